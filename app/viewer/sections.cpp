// The sections the tools draw: Tools, Fairing, Subdivision, Decimation, Morph, Record, Model
// information and Inspector, each an ID scope of its own; sidebar_sections() draws every
// tool's in the tools' order; see panels.h.

#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "app/ops/spectrum_op.h"
#include "app/viewer/key_bindings.h"
#include "app/viewer/panel_helpers.h"
#include "app/viewer/panels.h"
#include "app/viewer/plots.h"
#include "app/viewer/tool.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/fairing.h"
#include "core/algorithms/transfer_function.h"
#include "core/algorithms/weld.h"
#include "core/errors.h"
#include "core/number_text.h"

namespace trilab::viewer {

using namespace ui;

namespace {
void morph_controls(const MorphState& morph, const History& history, CommandQueue& commands);
}  // namespace

void operation_panel_body(OperationPanelState& state, const char* apply, bool busy,
                          CommandQueue& commands) {
    if (!state.region_note.empty()) wrapped_disabled("%s", state.region_note.c_str());
    std::vector<std::string> notes;
    if (operation_widgets(state.op, &notes)) {
        state.dirty = true;
        state.input_note.clear();
    }
    if (!notes.empty()) state.input_note = notes.back();
    std::string error;
    try {
        check_operation(state.op);
    } catch (const Error& e) {
        error = e.what();
    }
    // Live: every change previews at once; slow inputs preview when the drag is released.
    if (state.dirty && error.empty() && (state.live || !ImGui::IsAnyItemActive())) {
        commands.push_back(PreviewOperation{state.op});
        state.dirty = false;
    }
    if ((busy && !state.previewing) || !error.empty()) ImGui::BeginDisabled();
    if (button(apply)) commands.push_back(ApplyOperation{state.op});
    if ((busy && !state.previewing) || !error.empty()) ImGui::EndDisabled();
    if (state.previewing) {
        ImGui::SameLine();
        if (button("Cancel")) commands.push_back(CancelPreview{});
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("back to the state before (Esc)");
    }
    // The panel's one message on the Apply row (issue 38, item 13: a message that comes never
    // moves what is below): an error first, then a typed value that was clamped, then the
    // preview's note; as much as fits, the whole in the tooltip.
    const std::string message = !error.empty()              ? panel_words(error)
                                : !state.input_note.empty() ? state.input_note
                                                            : state.preview_note;
    if (!message.empty()) {
        ImGui::SameLine();
        ImGui::AlignTextToFramePadding();
        fitted_text(!error.empty() ? kErrorColor : ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled),
                    message);
    }
}

void morph_hint() {
    wrapped_disabled("the morph of each result: the Morph section (M)");
}

namespace {

/// The largest stable explicit step of the mesh and operator on one row that never changes
/// height (issue 38, item 13): a larger explicit step turns it red with the reason, and a
/// button on the same row switches to implicit integration.
void stability_guidance(FairingPanelState& state) {
    const double limit = state.max_stable_step;
    const FairingOptions o = options_of<FairingOptions>(state.op);
    const bool taubin = o.op == FairingOperator::Taubin;
    const bool explicit_run = taubin || o.integration == Integration::Explicit;
    // NaN until estimated: tested with isnan first, as an ordered comparison with NaN raises
    // FE_INVALID (the tests run with floating-point traps).
    const bool known = !std::isnan(limit) && limit > 0;
    const double step = taubin ? o.taubin_lambda : o.step;
    const char* what = taubin ? "lambda" : "step";
    const bool unstable = known && explicit_run && step > limit;
    ImGui::AlignTextToFramePadding();
    char text[200];
    if (!known) {
        std::snprintf(text, sizeof text, "largest stable explicit %s: estimating...", what);
    } else if (!unstable) {
        std::snprintf(text, sizeof text, "largest stable explicit %s: %.3g", what, limit);
    } else {
        std::snprintf(text, sizeof text,
                      "%s %.3g is above the largest stable %.3g: the run would diverge and stop",
                      what, step, limit);
    }
    if (unstable && !taubin) {
        // The button at the row's right end, the text in what is left of the row.
        const char* label = "Use implicit";
        const float button_w =
            ImGui::CalcTextSize(label).x + 2.0f * ImGui::GetStyle().FramePadding.x;
        ImGui::PushItemWidth(-1.0f);
        const float room =
            ImGui::GetContentRegionAvail().x - button_w - ImGui::GetStyle().ItemSpacing.x;
        const std::string shown = fit_text(
            text, room, [](const std::string& t) { return ImGui::CalcTextSize(t.c_str()).x; });
        ImGui::TextColored(kErrorColor, "%s", shown.c_str());
        note_widget("unstable");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
        ImGui::PopItemWidth();
        ImGui::SameLine(ImGui::GetContentRegionMax().x - button_w);
        if (button(label, 0.0f, "Use implicit integration")) {
            FairingOptions implicit = options_of<FairingOptions>(state.op);
            implicit.integration = Integration::Implicit;
            set_options(state.op, implicit);
            state.dirty = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("switch to implicit integration: stable at any step");
        return;
    }
    fitted_text(unstable ? kErrorColor : ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled), text);
    note_widget(unstable ? "unstable" : "stable-step");
}

}  // namespace

void subdivision_section(OperationPanelState& state, const SidebarContext& context,
                         CommandQueue& commands) {
    SidebarSection section("Subdivision", state.open);
    if (!section) return;
    operation_panel_body(state, "Subdivide", context.busy, commands);
    if (context.open_seams) {
        // Sqrt3 flips the old edges: along an unwelded seam the two sides stay apart, and
        // the surface creases there (README "Subdivision").
        wrapped_colored(ImVec4(1.0f, 0.80f, 0.35f, 1.0f),
                        "The mesh has coincident boundary edges (unwelded seams): Sqrt3 leaves "
                        "creases along them. Weld them first:");
        if (context.busy) ImGui::BeginDisabled();
        if (button("Weld coincident vertices"))
            commands.push_back(ApplyOperation{operation_of(WeldOptions{})});
        if (context.busy) ImGui::EndDisabled();
    }
    ImGui::Separator();
    wrapped_disabled("colour: Rendering > Colour by vertex > Subdivision vertices");
    morph_hint();
}

void fairing_section(FairingPanelState& state, const SidebarContext& context,
                     CommandQueue& commands) {
    SidebarSection section("Fairing", state.open);
    if (!section) return;
    stability_guidance(state);
    // What the mesh cannot do is switched off with the reason, never ignored.
    FairingOptions o = options_of<FairingOptions>(state.op);
    if (!context.closed) o.preserve_volume = false;
    if (context.closed) o.boundary = BoundaryMode::Fixed;
    set_options(state.op, o);
    operation_panel_body(state, "Smooth", context.busy, commands);
    if (!context.closed) wrapped_disabled("open mesh: no volume to preserve");
    // The spectral lens: the filter these settings are on this mesh's frequencies.
    ImGui::Separator();
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted("Transfer curve: what each frequency is multiplied by");
    ImGui::PopTextWrapPos();
    const TransferPlotRequest request =
        transfer_plot(options_of<FairingOptions>(state.op), state.lens);
    if (request == TransferPlotRequest::Decompose && !context.busy) {
        // The lens's own decomposition: the 100 lowest frequencies of the panel's operator.
        SpectrumOptions spectrum;
        spectrum.k = 100;
        spectrum.spectral.op = laplacian_of(options_of<FairingOptions>(state.op).op);
        commands.push_back(Decompose{operation_of(spectrum)});
    }
    if (request == TransferPlotRequest::ShowDivergingRun && !context.busy)
        commands.push_back(ShowDivergingRun{state.op});
    ImGui::Separator();
    morph_hint();
}

void decimation_section(DecimationPanelState& d, const SidebarContext& context,
                        CommandQueue& commands) {
    SidebarSection section("Decimation", d.open);
    if (!section) return;
    const bool busy = context.busy;
    operation_panel_body(d, "Decimate", busy, commands);
    // Level of detail: a slider over the progressive mesh of the current state.
    ImGui::SetNextItemOpen(d.lod_open, ImGuiCond_Always);
    d.lod_open = ImGui::CollapsingHeader("Level of detail");
    note_widget("section:Level of detail", WidgetNote::Kind::Header, "Level of detail");
    if (d.lod_open) {
        WidgetSection lod_section("Level of detail", false);
        if (!d.lod_ready) {
            if (busy || d.lod_building) ImGui::BeginDisabled();
            if (button("Build levels")) commands.push_back(BuildLevelOfDetail{d.op});
            if (busy || d.lod_building) ImGui::EndDisabled();
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(
                    "decimate down to 1 %% with this cost and these "
                    "constraints, recording every collapse");
        } else {
            ImGui::SetNextItemWidth(widget_width());
            if (ImGui::SliderFloat("lod (% of vertices)", &d.lod_percent, 100.0f, 1.0f, "%.1f %%",
                                   ImGuiSliderFlags_AlwaysClamp))
                commands.push_back(ShowLevelOfDetail{double(d.lod_percent)});
            note_widget("lod");
            if (button("Apply level")) commands.push_back(ApplyLevelOfDetail{});
            ImGui::SameLine();
            if (button("Cancel##lod")) commands.push_back(CancelPreview{});
        }
        if (!d.lod_note.empty()) wrapped_disabled("%s", d.lod_note.c_str());
    }
    checkbox("show collapsing edges", &d.show_collapsing_edges);
    if (d.show_collapsing_edges) {
        ImGui::SameLine();
        ImGui::TextDisabled("(%zu)", context.collapsing_edges);
    }
    ImGui::Separator();
    morph_hint();
}

std::vector<OperationPanelState> tool_panels(const std::vector<const OperationDef*>& owned) {
    std::vector<OperationPanelState> tools;
    for (const OperationDef* def : operation_defs())
        if (std::find(owned.begin(), owned.end(), def) == owned.end())
            tools.emplace_back(def->name);
    return tools;
}

std::string tool_section_title(const OperationDef& def) {
    std::string label = def.label;
    if (!label.empty() && label[0] >= 'A' && label[0] <= 'Z') label[0] = char(label[0] - 'A' + 'a');
    return "Tools: " + label;
}

const PanelEntry* find_panel(const PanelEntries& entries, const std::string& name) {
    for (const PanelEntry& entry : entries)
        if (entry.name == name) return &entry;
    return nullptr;
}

void open_panels(PanelState& panels, const PanelEntries& entries, const std::string& list) {
    // The window's own panels and dialogs; every tool's panel by its entry's name.
    const std::pair<const char*, bool*> names[] = {{"help", &panels.help_open},
                                                   {"about", &panels.about_open},
                                                   {"screenshot", &panels.screenshot.open},
                                                   {"history", &panels.history_open},
                                                   {"log", &panels.log_open},
                                                   {"info", &panels.info_open}};
    for (std::size_t pos = 0; pos < list.size();) {
        std::size_t comma = list.find(',', pos);
        if (comma == std::string::npos) comma = list.size();
        const std::string panel = list.substr(pos, comma - pos);
        pos = comma + 1;
        if (panel == "all" || panel == "tools") {  // every panel (not the dialogs), every tool
            const bool all = panel == "all";
            if (all) panels.history_open = panels.log_open = panels.info_open = true;
            for (const PanelEntry& entry : entries)
                if (entry.open && (all ? entry.in_all : entry.in_tools)) *entry.open = true;
            continue;
        }
        bool* flag = nullptr;
        for (const auto& [name, open] : names)
            if (panel == name) flag = open;
        if (const PanelEntry* entry = find_panel(entries, panel); entry && entry->open)
            flag = entry->open;
        if (!flag) {
            std::string known = "all, tools";
            for (const auto& [name, open] : names) known += std::string(", ") + name;
            for (const PanelEntry& entry : entries)
                if (entry.open && !entry.action) known += ", " + entry.name;
            throw InvalidArgument("--show: unknown panel '" + panel + "' (" + known + ")");
        }
        *flag = true;
    }
}

void tools_section(std::vector<OperationPanelState>& tools, bool busy, CommandQueue& commands) {
    for (OperationPanelState& tool : tools) {
        if (tool.op.def->params.empty()) continue;  // a menu action (Tools > Flip orientation)
        const std::string title = tool_section_title(*tool.op.def);
        if (SidebarSection section(title.c_str(), tool.open); section) {
            ImGui::TextWrapped("%s", panel_words(tool.op.def->summary).c_str());
            operation_panel_body(tool, "Apply", busy, commands);
        }
    }
}

void sidebar_sections(const ToolList& tools, const SidebarContext& context,
                      CommandQueue& commands) {
    for (Tool* tool : tools) tool->section(context, commands);
    ImGui::Spacing();
    wrapped_disabled(
        "The Tools and Algorithms menus open these sections; H the history, L the log.");
}

namespace {
/// The morph slider and animation controls for the current history entry.
void morph_controls(const MorphState& morph, const History& history, CommandQueue& commands) {
    const std::size_t entry = history.current();
    if (entry == 0) {
        ImGui::TextDisabled("morph: the first state has nothing before it");
        return;
    }
    const History::EntryInfo info = history.info(entry);
    if (!morph.moves) {  // a load, a revert, texture coordinates: no vertex moves
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("morph: %s moves no vertex", info.label.c_str());
        ImGui::PopTextWrapPos();
        return;
    }
    ImGui::PushTextWrapPos(0.0f);
    ImGui::Text("%s %s: before -> after", info.label.c_str(), info.parameters.c_str());
    ImGui::PopTextWrapPos();
    // The morph is the session's: every control queues a command (one clock, one owner).
    float t = float(morph.t);
    ImGui::SetNextItemWidth(widget_width(16.0f, 0.0f));
    if (ImGui::SliderFloat("##t", &t, 0.0f, 1.0f, "t = %.3f"))
        commands.push_back(ShowMorphAt{double(t)});
    // One width for both, so that Before and After stay where they are when a play ends.
    const float play_width =
        ImGui::CalcTextSize("Animate").x + 2 * ImGui::GetStyle().FramePadding.x;
    if (!morph.playing) {
        if (button("Animate", play_width)) commands.push_back(PlayMorph{true});
    } else if (button("Stop", play_width)) {
        commands.push_back(PlayMorph{false});
    }
    ImGui::SameLine();
    if (button("Before")) commands.push_back(ShowMorphAt{0.0});
    ImGui::SameLine();
    if (button("After")) commands.push_back(ShowMorphAt{1.0});
    SetMorphAnimation animation{morph.duration, morph.easing, morph.playback};
    bool changed = false;
    float duration = float(morph.duration);
    ImGui::SetNextItemWidth(widget_width(8.0f));
    if (ImGui::SliderFloat("duration", &duration, 0.2f, 20.0f, "%.1f s",
                           ImGuiSliderFlags_Logarithmic)) {
        animation.duration = duration;
        changed = true;
    }
    const char* easings[] = {"linear", "smooth step", "ease in-out (cubic)"};
    int e = int(morph.easing);
    ImGui::SetNextItemWidth(widget_width(8.0f));
    if (ImGui::Combo("easing", &e, easings, 3)) {
        animation.easing = Easing(e);
        changed = true;
    }
    const char* modes[] = {"once", "loop", "ping-pong"};
    int m = int(morph.playback);
    ImGui::SetNextItemWidth(widget_width(8.0f));
    if (ImGui::Combo("playback", &m, modes, 3)) {
        animation.playback = Playback(m);
        changed = true;
    }
    if (changed) commands.push_back(animation);
    if (info.steps.size() > 1) ImGui::TextDisabled("%zu steps, chained", info.steps.size());
}
}  // namespace

void morph_section(bool& open, const MorphState& morph, const History& history,
                   CommandQueue& commands) {
    SidebarSection section("Morph", open);
    if (!section) return;
    morph_controls(morph, history, commands);
}

void record_section(RecordState& r, bool can_record, const std::string& why_not,
                    CommandQueue& commands) {
    if (r.running) r.open = true;  // the progress and Cancel stay visible
    SidebarSection section("Record", r.open);
    if (!section) return;
    ImGui::TextWrapped("Writes the morph of the current entry as PNG frames, framed as the view.");
    const float w = widget_width(10.0f);
    if (r.running) ImGui::BeginDisabled();
    ImGui::SetNextItemWidth(w);
    if (ImGui::InputInt("frames", &r.frames)) r.frames = std::clamp(r.frames, 2, 100000);
    ImGui::SetNextItemWidth(w);
    if (ImGui::InputInt("per second", &r.fps)) r.fps = std::clamp(r.fps, 1, 240);
    ImGui::Text("duration %.2f s", double(r.frames) / r.fps);
    int size[2] = {r.width, r.height};
    ImGui::SetNextItemWidth(w);
    if (ImGui::InputInt2("width, height", size)) {
        r.width = std::clamp(size[0], 16, 8192);
        r.height = std::clamp(size[1], 16, 8192);
    }
    ImGui::SetNextItemWidth(w);
    ImGui::InputText("folder", &r.folder);
    ImGui::SetNextItemWidth(w);
    ImGui::InputText("name", &r.name);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s/%s_0000.png ...", r.folder.c_str(), r.name.c_str());
    ImGui::PopTextWrapPos();
    checkbox("also an MP4", &r.mp4);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("needs ffmpeg on the PATH");
    if (r.running) ImGui::EndDisabled();
    if (r.running) {
        ImGui::ProgressBar(float(r.next) / float(r.frames), ImVec2(w, 0.0f));
        ImGui::SameLine();
        if (button("Cancel##record")) commands.push_back(CancelRecording{});
    } else {
        if (!can_record) ImGui::BeginDisabled();
        if (button("Record")) commands.push_back(StartRecording{});
        if (!can_record) {
            ImGui::EndDisabled();
            ImGui::SameLine();
            ImGui::TextDisabled("(%s)", why_not.empty() ? "nothing to record" : why_not.c_str());
        }
    }
}

void info_section(bool& open, const std::vector<std::string>& lines) {
    SidebarSection section("Model information", open);
    if (!section) return;
    ImGui::PushTextWrapPos(0.0f);
    for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
    ImGui::PopTextWrapPos();
}

void inspector_section(bool& open, const InspectorView& view, CommandQueue& commands) {
    SidebarSection section("Inspector", open);
    if (!section) return;
    if (!view.has_picks) {
        wrapped_disabled(
            "Click the model to pick the vertex, edge and face under the cursor; Ctrl+click a "
            "second point to measure the distance to it; double click to turn around that "
            "point.");
        return;
    }
    if (button("Clear picks")) commands.push_back(ClearPicks{});
    ImGui::SameLine();
    if (button("Centre view here")) commands.push_back(CentreOnPick{});
    if (!view.note.empty()) wrapped_disabled(view.note.c_str());
    for (std::size_t g = 0; g < view.groups.size(); ++g) {
        const InspectorView::Group& group = view.groups[g];
        ImGui::PushID(int(g));
        ImGui::Separator();
        ImGui::TextUnformatted(group.title.c_str());
        // Two columns without a table where the sidebar is wide enough, else each label over
        // its value; values break at spaces only (a number never splits: "0." / "038977"),
        // labels too, and nothing is cut at an edge.
        const float em = ImGui::GetFontSize();
        const float x0 = ImGui::GetCursorPosX(), avail = ImGui::GetContentRegionAvail().x;
        const bool columns = avail >= 24.0f * em;
        const float label_width = columns ? std::min(10.0f * em, 0.4f * avail) : avail;
        const auto measure = [](const std::string& t) { return ImGui::CalcTextSize(t.c_str()).x; };
        for (const InspectorView::Row& row : group.rows) {
            const float y = ImGui::GetCursorPosY();
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
            for (const std::string& line :
                 wrap_at_spaces(row.label, label_width - 0.5f * em, measure))
                ImGui::TextUnformatted(line.c_str());
            ImGui::PopStyleColor();
            const float label_end = ImGui::GetCursorPosY();
            const float value_x = columns ? x0 + label_width : x0 + em;
            if (columns) ImGui::SetCursorPosY(y);
            for (const std::string& line :
                 wrap_at_spaces(row.text, x0 + avail - value_x, measure)) {
                ImGui::SetCursorPosX(value_x);
                ImGui::TextUnformatted(line.c_str());
            }
            ImGui::SetCursorPos(ImVec2(x0, std::max(label_end, ImGui::GetCursorPosY())));
        }
        ImGui::Dummy(ImVec2(0.0f, 0.0f));
        ImGui::PopID();
    }
    if (view.moved_by_entry.size() > 1) {
        ImGui::Separator();
        ImGui::TextUnformatted("Moved by each entry");
        ImGui::PlotHistogram("##provenance", view.moved_by_entry.data(),
                             int(view.moved_by_entry.size()), 0, nullptr, 0.0f, FLT_MAX,
                             ImVec2(widget_width(16.0f, 0.0f), 3.0f * ImGui::GetFrameHeight()));
        ImGui::TextDisabled("entries 0..%zu, the current one is %zu",
                            view.moved_by_entry.size() - 1, view.current_entry);
    }
}

}  // namespace trilab::viewer
