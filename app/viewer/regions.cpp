// The fixed regions of the layout: the sidebar and its section headers, the History column,
// the log, the status bar and the colour legend; see panels.h.

#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>
#include <functional>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/key_bindings.h"
#include "app/viewer/panel_helpers.h"
#include "app/viewer/panels.h"
#include "app/viewer/plots.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/fairing.h"
#include "core/number_text.h"

namespace trilab::viewer {

using namespace ui;

bool begin_region(const char* title, const Rect& r, bool* open, char resizable, float& width,
                  float& height, int extra_flags) {
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(r.w, r.h), ImGuiCond_Always);
    // Only the inner edge moves: the other dimension is held by the constraint.
    const ImGuiIO& io = ImGui::GetIO();
    const bool horizontal = resizable == 'l' || resizable == 'r';
    ImGui::SetNextWindowSizeConstraints(
        horizontal ? ImVec2(0.0f, r.h) : ImVec2(r.w, 0.0f),
        horizontal ? ImVec2(io.DisplaySize.x, r.h) : ImVec2(r.w, io.DisplaySize.y));
    ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                             ImGuiWindowFlags_NoSavedSettings |
                             ImGuiWindowFlags_NoBringToFrontOnFocus | extra_flags;
    if (resizable == 0) flags |= ImGuiWindowFlags_NoResize;
    ScopedStyleVar rounding(ImGuiStyleVar_WindowRounding, 0.0f);
    const bool visible = ImGui::Begin(title, open, flags);
    // A drag of an edge has resized the window: keep the new size (the layout clamps it).
    // A drag of the outer edge moved it; it snaps back next frame.
    const ImVec2 size = ImGui::GetWindowSize();
    if (horizontal && size.x != r.w) width = size.x;
    if (resizable == 't' && size.y != r.h) height = size.y;
    return visible;
}

void end_region() {
    ImGui::End();
}

bool begin_sidebar(const Rect& r, LayoutState& layout) {
    float height = r.h;
    return begin_region("Sidebar", r, nullptr, 'r', layout.sidebar_width, height,
                        ImGuiWindowFlags_NoTitleBar);
}

SidebarSection::SidebarSection(const char* label, bool& open) : open_(section_header(label, open)) {
    if (open_) scope_.emplace(label, true);
}

bool section_header(const char* label, bool& open) {
    // Remember whether the section was open last frame, in the window's storage: a section
    // opened from a menu or a key (not by its header) is scrolled into view.
    ImGuiStorage* storage = ImGui::GetStateStorage();
    const ImGuiID id = ImGui::GetID((std::string(label) + "##was-open").c_str());
    const int was = storage->GetInt(id, -1);
    ImGui::SetNextItemOpen(open, ImGuiCond_Always);
    const bool clicked_open = ImGui::CollapsingHeader(label);
    note_widget(std::string("section:") + label, WidgetNote::Kind::Header, label);
    const bool by_click = clicked_open != open;
    open = clicked_open;
    if (open && was == 0 && !by_click) ImGui::SetScrollHereY(0.0f);
    storage->SetInt(id, open ? 1 : 0);
    if (open) ImGui::Spacing();
    return open;
}

std::string status_text(const StatusInfo& info) {
    char text[512];
    if (!info.loading.empty())
        std::snprintf(text, sizeof(text), "loading %s   %zu faces   %.1f ms", info.loading.c_str(),
                      info.n_faces, info.frame_ms);
    else
        std::snprintf(text, sizeof(text), "%zu vertices   %zu faces   %s   %.1f ms%s%s",
                      info.n_vertices, info.n_faces, info.file_name.c_str(), info.frame_ms,
                      info.simplified.empty() ? "" : "   ", info.simplified.c_str());
    return text;
}

void status_bar(const StatusInfo& info, const Notice& notice, const JobInfo* job,
                const Rect& region, CommandQueue& commands) {
    const ImGuiStyle& style = ImGui::GetStyle();
    const float em = ImGui::GetFontSize();
    ImGui::SetNextWindowPos(ImVec2(region.x, region.y));
    ImGui::SetNextWindowSize(ImVec2(region.w, region.h));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                   ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                   ImGuiWindowFlags_NoBringToFrontOnFocus;
    const float pad_y = std::max(0.0f, 0.5f * (region.h - ImGui::GetFrameHeight()));
    ScopedStyleVar padding(ImGuiStyleVar_WindowPadding, ImVec2(style.FramePadding.x * 2.0f, pad_y));
    ScopedStyleVar rounding(ImGuiStyleVar_WindowRounding, 0.0f);
    ScopedStyleVar border(ImGuiStyleVar_WindowBorderSize, 0.0f);
    ScopedStyleVar min_size(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));  // not 32 px
    if (ImGui::Begin("Status", nullptr, flags)) {
        // The running job takes the right end: name, time, progress, Cancel.
        const float job_w = job ? std::min(30.0f * em, 0.55f * region.w) : 0.0f;
        const float text_right = region.w - job_w - 2.0f * style.FramePadding.x;
        ImGui::AlignTextToFramePadding();
        ImGui::TextUnformatted(status_text(info).c_str());
        if (notice.level != Notice::Level::None &&
            ImGui::GetItemRectMax().x + 3.0f * style.ItemSpacing.x < text_right) {
            ImGui::SameLine(0.0f, 3.0f * style.ItemSpacing.x);
            // As much as fits, ending in "..." (the whole text in the tooltip and the log).
            const float room = ImGui::GetWindowPos().x + text_right - ImGui::GetCursorScreenPos().x;
            const std::string shown = fit_text(notice.text, room, [](const std::string& t) {
                return ImGui::CalcTextSize(t.c_str()).x;
            });
            ImGui::TextColored(notice_color(notice.level), "%s", shown.c_str());
            if (ImGui::IsItemHovered()) {  // the whole text (the bar may clip it) and details
                ImGui::BeginTooltip();
                ImGui::TextUnformatted(notice.text.c_str());
                for (const std::string& line : notice.details) ImGui::TextUnformatted(line.c_str());
                ImGui::EndTooltip();
            }
        }
        if (job) {
            ImGui::SameLine(region.w - job_w);
            const float cancel_w = ImGui::CalcTextSize("cancelling").x + 2 * style.FramePadding.x;
            const float bar_w = job_w - cancel_w - 2.0f * style.ItemSpacing.x;
            const std::string label =
                job_label(*job, bar_w - 2.0f * style.FramePadding.x,
                          [](const std::string& t) { return ImGui::CalcTextSize(t.c_str()).x; });
            // Unknown progress: a bar that sweeps, so the user sees the program is alive.
            const float f = job->fraction >= 0.0 ? float(job->fraction)
                                                 : float(0.5 + 0.5 * std::sin(3.0 * job->seconds));
            ImGui::ProgressBar(f, ImVec2(bar_w, 0.0f), label.c_str());
            note_widget("job-progress", WidgetNote::Kind::Other, label.c_str());
            if (ImGui::IsItemHovered()) {  // the whole text, whatever the bar shows
                ImGui::BeginTooltip();
                ImGui::TextUnformatted(
                    job_label(*job, 1e9f, [](const std::string&) { return 0.0f; }).c_str());
                ImGui::EndTooltip();
            }
            ImGui::SameLine();
            if (job->cancel_requested)
                ImGui::TextDisabled("cancelling");
            else if (button("Cancel##job"))
                commands.push_back(CancelJob{});
        }
    }
    ImGui::End();
}

std::string job_label(const JobInfo& job, float width,
                      const std::function<float(const std::string&)>& text_width) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, " (%.1f s)", job.seconds);
    // The most that fits, dropping whole parts from the end (they stay in the tooltip): never
    // a text cut at the bar's edge.
    const std::string candidates[] = {
        job.stage.empty() ? job.name + seconds : job.name + ": " + job.stage + seconds,
        job.name + seconds, job.name, job.stage.empty() ? job.name : job.stage};
    for (const std::string& c : candidates)
        if (text_width(c) <= width) return c;
    // Not even the name: its first words that fit, marked as shortened.
    std::string words = job.name;
    while (!words.empty() && text_width(words + "...") > width) {
        const std::size_t space = words.find_last_of(' ');
        words = space == std::string::npos ? std::string() : words.substr(0, space);
    }
    return words.empty() ? std::string() : words + "...";
}

std::string fit_text(const std::string& text, float width,
                     const std::function<float(const std::string&)>& text_width) {
    if (text_width(text) <= width) return text;
    // The longest start (at a UTF-8 character boundary) that fits with the ellipsis.
    std::size_t lo = 0, hi = text.size();
    const auto boundary = [&](std::size_t n) {
        while (n > 0 && n < text.size() && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80)
            --n;
        return n;
    };
    while (lo < hi) {
        const std::size_t mid = boundary((lo + hi + 1) / 2);
        if (mid <= lo) break;
        if (text_width(text.substr(0, mid) + "...") <= width)
            lo = mid;
        else
            hi = mid - 1;
    }
    std::size_t n = boundary(lo);
    // End at a word's end when one is close: "... use a sma..." reads worse than "... use a...".
    const std::size_t space = text.rfind(' ', n);
    if (space != std::string::npos && space > 0 && n - space < 12) n = space;
    while (n > 0 && text[n - 1] == ' ') --n;
    return n == 0 ? std::string() : text.substr(0, n) + "...";
}

std::vector<std::string> wrap_at_spaces(
    const std::string& text, float width,
    const std::function<float(const std::string&)>& text_width) {
    std::vector<std::string> lines;
    std::string line;
    std::size_t i = 0;
    while (i <= text.size()) {
        std::size_t end = text.find(' ', i);
        if (end == std::string::npos) end = text.size();
        const std::string word = text.substr(i, end - i);
        const std::string joined = line.empty() ? word : line + " " + word;
        if (!line.empty() && text_width(joined) > width) {
            lines.push_back(line);
            line = word;
        } else {
            line = joined;
        }
        i = end + 1;
    }
    if (!line.empty() || lines.empty()) lines.push_back(line);
    return lines;
}

void history_window(PanelState& panels, const History& history, bool busy, const Rect& region,
                    CommandQueue& commands) {
    if (!panels.history_open) return;
    float height = region.h;
    if (begin_region("History", region, &panels.history_open, 'l', panels.layout.history_width,
                     height)) {
        ImGui::TextWrapped("%s, %.1f MB of the %.0f MB budget",
                           count_text(history.size(), "entry", "entries").c_str(),
                           history.bytes() / 1e6, history.budget() / 1e6);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "When the history grows past its budget the oldest entries are "
                "dropped (with a message in the log).");
        ImGui::Separator();
        for (std::size_t i = 0; i < history.size(); ++i) {
            const History::EntryInfo e = history.info(i);
            char label[512];
            std::snprintf(label, sizeof(label), "%zu  %s %s%s##entry%zu", i, e.label.c_str(),
                          e.parameters.c_str(), i > history.current() ? " (redo)" : "", i);
            const bool current = i == history.current();
            if (ImGui::Selectable(label, current) && !current && !busy)
                commands.push_back(JumpTo{i});
            if (ImGui::IsItemHovered()) {
                ImGui::BeginTooltip();
                ImGui::Text("%zu  %s %s", i, e.label.c_str(), e.parameters.c_str());
                ImGui::Text("%zu step%s, %.1f ms, %.2f MB", e.steps.size(),
                            e.steps.size() == 1 ? "" : "s", e.ms, e.bytes / 1e6);
                if (!e.steps.empty())
                    ImGui::Text("%zu vertices, %zu faces", e.steps.back().vertices,
                                e.steps.back().faces);
                ImGui::EndTooltip();
            }
        }
    }
    end_region();
}

void log_window(PanelState& panels, const Log& log, const Rect& region) {
    if (!panels.log_open) return;
    float width = region.w;
    if (begin_region("Log", region, &panels.log_open, 't', width, panels.layout.log_height)) {
        const std::vector<LogEntry> entries = log.entries();
        ImGui::PushTextWrapPos(0.0f);
        for (const LogEntry& e : entries) {
            if (e.level == LogEntry::Level::Error)
                ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.40f, 1.0f), "%s", e.text.c_str());
            else if (e.level == LogEntry::Level::Warning)
                ImGui::TextColored(ImVec4(1.0f, 0.80f, 0.35f, 1.0f), "%s", e.text.c_str());
            else
                ImGui::TextUnformatted(e.text.c_str());
        }
        ImGui::PopTextWrapPos();
        if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
    }
    end_region();
}

namespace {

/// Under the colour bar of a scalar colouring: smooth colours, bands, isolines or both, and
/// their count. Edits the render style only (no recolouring).
void scalar_display_controls(RenderStyle& style) {
    const ScalarDisplay displays[] = {ScalarDisplay::Smooth, ScalarDisplay::Bands,
                                      ScalarDisplay::Isolines, ScalarDisplay::BandsAndIsolines};
    const char* labels[] = {"smooth", "bands", "isolines", "bands + isolines"};
    int current = 0;
    for (int i = 0; i < 4; ++i)
        if (style.scalar_display == displays[i]) current = i;
    ImGui::SetNextItemWidth(8.0f * ImGui::GetFontSize());
    const bool open = ImGui::BeginCombo("##display", labels[current]);
    note_widget("legend: display");
    if (open) {
        for (int i = 0; i < 4; ++i) {
            if (ImGui::Selectable(labels[i], i == current)) style.scalar_display = displays[i];
            note_widget(std::string("legend: display ") + labels[i]);
        }
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Bands cut the range into N equal steps; isolines are drawn at the N - 1 "
            "values between them, over the shading");
    if (style.scalar_display != ScalarDisplay::Smooth) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(6.0f * ImGui::GetFontSize());
        if (style.scalar_display == ScalarDisplay::Isolines) {  // counted as lines
            int lines = style.scalar_steps - 1;
            if (ImGui::SliderInt("##lines", &lines, kMinScalarSteps - 1, kMaxScalarSteps - 1,
                                 "%d lines", ImGuiSliderFlags_AlwaysClamp))
                style.scalar_steps = lines + 1;
            note_widget("legend: lines");
        } else {
            ImGui::SliderInt("##steps", &style.scalar_steps, kMinScalarSteps, kMaxScalarSteps,
                             "%d bands", ImGuiSliderFlags_AlwaysClamp);
            note_widget("legend: bands");
        }
    }
}

}  // namespace

bool color_legend(const VertexColors& colors, ColoringOptions& options, RenderStyle& style,
                  LegendSlot& slot) {
    slot.width = slot.height = 0;
    if (!colors.has_legend) return false;
    // In its fixed region (layout.h): the bottom right of the view, at most the slot's size.
    ImGui::SetNextWindowPos(ImVec2(slot.right, slot.bottom), ImGuiCond_Always, ImVec2(1.0f, 1.0f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(slot.max_width, slot.max_height));
    bool changed = false;
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration |
                                   ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove;
    if (ImGui::Begin("##legend", nullptr, flags)) {
        const float padding = 2.0f * ImGui::GetStyle().WindowPadding.x;
        changed = legend_contents(colors, options, slot.max_width - padding);
        if (colors.kind != ColorMapKind::Categorical && !colors.values.empty())
            scalar_display_controls(style);
        slot.width = ImGui::GetWindowWidth();
        slot.height = ImGui::GetWindowHeight();
    }
    ImGui::End();
    return changed;
}

}  // namespace trilab::viewer
