#include "app/viewer/panels.h"

#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>

#include "app/viewer/key_bindings.h"
#include "app/viewer/plots.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/fairing.h"
#include "core/number_text.h"

namespace trilab::viewer {
namespace {

void morph_controls(MorphState& morph, const History& history, double now);

constexpr const char* kErrorPopupTitle = "Error";

/// Pushes one style variable for the lifetime of the guard.
class ScopedStyleVar {
public:
    ScopedStyleVar(ImGuiStyleVar var, float value) { ImGui::PushStyleVar(var, value); }
    ScopedStyleVar(ImGuiStyleVar var, const ImVec2& value) { ImGui::PushStyleVar(var, value); }
    ~ScopedStyleVar() { ImGui::PopStyleVar(); }
    ScopedStyleVar(const ScopedStyleVar&) = delete;
    ScopedStyleVar& operator=(const ScopedStyleVar&) = delete;
};

/// A menu item that shows the key of `action` (the key bindings table's text). Reported to
/// the test hook as "shortcut:LABEL=KEYS".
bool shortcut_item(const char* label, KeyAction action, bool selected = false,
                   bool enabled = true) {
    const std::string keys = shortcut_text(action);
    const bool clicked = menu_item(label, keys.c_str(), selected, enabled);
    note_widget("shortcut:" + std::string(label) + "=" + keys);
    return clicked;
}
/// The same for an item that toggles `*selected`.
bool shortcut_item(const char* label, KeyAction action, bool* selected) {
    const std::string keys = shortcut_text(action);
    const bool clicked = menu_item(label, keys.c_str(), selected);
    note_widget("shortcut:" + std::string(label) + "=" + keys);
    return clicked;
}

/// Inside a dialog's Begin: Esc closes it while it has the focus (the viewer's key handler
/// also closes the dialogs, for presses ImGui 1.86 misses).
void close_on_escape(bool& open) {
    if (ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows) &&
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
        open = false;
}

/// Begins a dialog window (help, about, screenshot): centred when it appears, sized to its
/// content, kept inside the window, closed by Esc while focused. Call ImGui::End() after it
/// whatever it returns.
bool begin_dialog(const char* title, bool& open, ImGuiWindowFlags extra_flags = 0) {
    place_dialog();
    if (!ImGui::Begin(title, &open, ImGuiWindowFlags_AlwaysAutoResize | extra_flags)) return false;
    keep_dialog_inside();
    close_on_escape(open);
    return true;
}

ImVec4 notice_color(Notice::Level level) {
    return level == Notice::Level::Error ? ImVec4(1.0f, 0.45f, 0.40f, 1.0f)
                                         : ImVec4(0.70f, 0.85f, 0.70f, 1.0f);
}

}  // namespace

void apply_panel_style(ImGuiStyle& style) {
    ImGui::StyleColorsDark(&style);
    style.WindowRounding = 4.0f;
    style.FrameRounding = 3.0f;
    // A slider's grab is a thin, half-transparent bar: the value text on it stays legible.
    style.GrabMinSize = 4.0f;
    style.Colors[ImGuiCol_SliderGrab].w = 0.45f;
    style.Colors[ImGuiCol_SliderGrabActive].w = 0.6f;
}

namespace {

/// Rendering > Colour by vertex: every colouring; a change queues UpdateColoring.
void coloring_menu(ViewSettings& settings, CommandQueue& commands) {
    if (begin_menu("Colour by vertex")) {
        const VertexColoring colorings[] = {VertexColoring::None,
                                            VertexColoring::Normal,
                                            VertexColoring::K1,
                                            VertexColoring::K2,
                                            VertexColoring::Mean,
                                            VertexColoring::Gaussian,
                                            VertexColoring::ShapeIndex,
                                            VertexColoring::SubdivisionLevel,
                                            VertexColoring::SmoothingDistance,
                                            VertexColoring::Frequency,
                                            VertexColoring::FrequencyMass};
        const char* labels[] = {"None",
                                "Normal direction",
                                "First principal curvature",
                                "Second principal curvature",
                                "Mean curvature",
                                "Gaussian curvature",
                                "Shape index",
                                "Subdivision vertices",
                                "Smoothing distance",
                                "Frequency (the visualized eigenvector)",
                                "Frequency mass (geometry in the band)"};
        for (std::size_t i = 0; i < std::size(colorings); ++i) {
            if (menu_item(labels[i], nullptr, settings.coloring == colorings[i]) &&
                settings.coloring != colorings[i]) {
                settings.coloring = colorings[i];
                commands.push_back(UpdateColoring{});
            }
        }
        end_menu();
    }
}

/// Rendering > Texture: the texture mode, the image, and projections for a model without
/// texture coordinates.
void texture_menu(RenderStyle& style, ViewSettings& settings, PanelState& panels,
                  const RenderContext& render, CommandQueue& commands) {
    if (begin_menu("Texture")) {
        const TextureMode tmodes[] = {TextureMode::Off, TextureMode::Modulate,
                                      TextureMode::Replace};
        for (TextureMode m : tmodes) {
            const bool on = style.mode == RenderMode::Textured && style.texture_mode == m;
            const bool clicked =
                m == TextureMode::Off
                    ? shortcut_item(texture_mode_name(m), KeyAction::CycleTexture, on)
                    : menu_item(texture_mode_name(m), nullptr, on);
            if (clicked) {
                style.texture_mode = m;
                style.mode = m == TextureMode::Off ? RenderMode::Smooth : RenderMode::Textured;
            }
        }
        ImGui::Separator();
        if (menu_item("Checkerboard", nullptr, settings.use_checkerboard))
            settings.use_checkerboard = true;
        if (menu_item("Loaded image", nullptr, !settings.use_checkerboard,
                      render.has_loaded_texture))
            settings.use_checkerboard = false;
        if (menu_item("Load image..."))
            panels.file_browser.request(FileBrowserState::Purpose::LoadTexture, "");
        ImGui::Separator();
        if (render.has_texcoords) {
            ImGui::TextDisabled("the model has texture coordinates");
        } else {
            ImGui::TextDisabled("no texture coordinates: project them");
            if (menu_item("Planar projection")) {
                settings.projection = TexCoordProjection::Planar;
                commands.push_back(ProjectTexCoords{});
            }
            if (menu_item("Spherical projection")) {
                settings.projection = TexCoordProjection::Spherical;
                commands.push_back(ProjectTexCoords{});
            }
        }
        end_menu();
    }
}

}  // namespace

void rendering_menu_items(RenderStyle& style, ViewSettings& settings, PanelState& panels,
                          const RenderContext& render, CommandQueue& commands) {
    const RenderMode modes[] = {RenderMode::Wireframe, RenderMode::HiddenLine,
                                RenderMode::Flat,      RenderMode::Smooth,
                                RenderMode::Points,    RenderMode::Textured};
    for (RenderMode mode : modes)
        if (menu_item(render_mode_name(mode), nullptr, style.mode == mode)) style.mode = mode;
    ImGui::Separator();
    if (begin_menu("Wireframe overlay")) {
        if (menu_item("Automatic", nullptr, settings.wireframe == WireframeOverlay::Auto))
            settings.wireframe = WireframeOverlay::Auto;
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("on while the edges are long enough on the screen to tell apart");
        if (shortcut_item("On", KeyAction::ToggleWireframe,
                          settings.wireframe == WireframeOverlay::On))
            settings.wireframe = WireframeOverlay::On;
        if (shortcut_item("Off", KeyAction::ToggleWireframe,
                          settings.wireframe == WireframeOverlay::Off))
            settings.wireframe = WireframeOverlay::Off;
        end_menu();
    }
    shortcut_item("Back-face colour", KeyAction::ToggleBackFaceColor, &style.back_face_color);
    coloring_menu(settings, commands);
    texture_menu(style, settings, panels, render, commands);
    if (begin_menu("Vectors")) {
        menu_item("Face normals", nullptr, &style.face_normals);
        menu_item("Vertex normals", nullptr, &style.vertex_normals);
        menu_item("Collapsing edges", nullptr, &panels.decimation.show_collapsing_edges);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("The edges the Decimation panel's next iteration collapses");
        ImGui::SetNextItemWidth(10.0f * ImGui::GetFontSize());
        ImGui::SliderFloat("length", &style.vector_length, 0.002f, 0.2f, "%.3f",
                           ImGuiSliderFlags_Logarithmic);
        end_menu();
    }
    if (begin_menu("Lighting and colours")) {
        shortcut_item("Specular highlight", KeyAction::ToggleSpecular, &style.specular);
        shortcut_item("Fog", KeyAction::ToggleFog, &style.fog);
        ImGui::SetNextItemWidth(10.0f * ImGui::GetFontSize());
        ImGui::SliderFloat("fog amount", &style.fog_amount, 0.0f, 1.0f);
        ImGui::SetNextItemWidth(10.0f * ImGui::GetFontSize());
        ImGui::ColorEdit3("background", &style.background.x);
        ImGui::SetNextItemWidth(10.0f * ImGui::GetFontSize());
        ImGui::ColorEdit3("front", &style.front_color.x);
        ImGui::SetNextItemWidth(10.0f * ImGui::GetFontSize());
        ImGui::ColorEdit3("back", &style.back_color.x);
        ImGui::SetNextItemWidth(10.0f * ImGui::GetFontSize());
        ImGui::SliderFloat("line width", &style.wire_width, 0.5f, 4.0f, "%.1f px");
        ImGui::SetNextItemWidth(10.0f * ImGui::GetFontSize());
        ImGui::SliderFloat("point size", &style.point_size, 1.0f, 12.0f, "%.1f px");
        end_menu();
    }
    ImGui::Separator();
    if (shortcut_item("Fit view", KeyAction::FitView)) commands.push_back(FitView{});
    if (shortcut_item("Screenshot...", KeyAction::Screenshot)) panels.screenshot.open = true;
}

void menu_bar(RenderStyle& style, ViewSettings& settings, PanelState& panels,
              const MenuContext& context, const RenderContext& render, CommandQueue& commands) {
    if (!ImGui::BeginMainMenuBar()) return;
    panels.layout.menu_height = ImGui::GetWindowHeight();
    if (begin_menu("File")) {
        if (shortcut_item("Open...", KeyAction::OpenFile, false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::OpenMesh, context.document_path);
        const bool has_recent = context.recent_files && !context.recent_files->empty();
        if (begin_menu("Open recent", has_recent && !context.busy)) {
            for (const std::string& path : *context.recent_files)
                if (menu_item(path.c_str())) commands.push_back(LoadFile{path});
            end_menu();
        }
        if (menu_item("Revert", nullptr, false, context.has_file && !context.busy))
            commands.push_back(RevertFile{});
        if (shortcut_item("Save as...", KeyAction::SaveFile, false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::SaveMesh, context.document_path);
        ImGui::Separator();
        if (menu_item("Load texture...", nullptr, false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::LoadTexture, "");
        ImGui::Separator();
        if (shortcut_item("Quit", KeyAction::Quit)) commands.push_back(Quit{});
        end_menu();
    }
    if (begin_menu("Edit")) {
        if (shortcut_item("Undo", KeyAction::Undo, false, context.can_undo && !context.busy))
            commands.push_back(Undo{});
        if (shortcut_item("Redo", KeyAction::Redo, false, context.can_redo && !context.busy))
            commands.push_back(Redo{});
        ImGui::Separator();
        shortcut_item("History", KeyAction::ToggleHistory, &panels.history_open);
        shortcut_item("Morph", KeyAction::ToggleMorph, &panels.morph_open);
        shortcut_item("Record", KeyAction::ToggleRecord, &panels.record.open);
        end_menu();
    }
    view_menu(settings, commands);
    if (begin_menu("Tools")) {
        menu_item("Add noise", nullptr, &panels.tools.open);
        if (menu_item("Flip orientation", nullptr, false, !context.busy))
            commands.push_back(ApplyOperation{make_operation("flip")});
        menu_item("Weld coincident vertices...", nullptr, &panels.weld.open);
        end_menu();
    }
    if (begin_menu("Algorithms")) {
        // The operation panels arrive with their issues; listed so the menu shows the plan.
        menu_item("Fairing", nullptr, &panels.fairing.open);
        menu_item("Frequency decomposition", nullptr, &panels.frequency.open);
        menu_item("Subdivision", nullptr, &panels.subdivision.open);
        menu_item("Decimation", nullptr, &panels.decimation.open);
        end_menu();
    }
    if (begin_menu("Rendering")) {
        rendering_menu_items(style, settings, panels, render, commands);
        end_menu();
    }
    if (begin_menu("Window")) {
        menu_item("Sidebar", nullptr, &panels.sidebar_open);
        shortcut_item("Model information", KeyAction::PrintInfo, &panels.info_open);
        shortcut_item("Log", KeyAction::ToggleLog, &panels.log_open);
        end_menu();
    }
    if (begin_menu("Help")) {
        shortcut_item("Key bindings", KeyAction::ToggleHelp, &panels.help_open);
        menu_item("About trilab", nullptr, &panels.about_open);
        end_menu();
    }
    ImGui::EndMainMenuBar();
}

void view_menu(ViewSettings& settings, CommandQueue& commands) {
    if (!begin_menu("View")) return;
    if (menu_item("Default view")) commands.push_back(ResetView{});
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("look at the model's front with its up axis up, and fit it");
    if (begin_menu("Up axis")) {
        for (const EnumEntry<UpAxis>& e : kUpAxes) {
            if (menu_item(e.label, nullptr, settings.up == e.value) && settings.up != e.value) {
                settings.up = e.value;
                commands.push_back(ResetView{});
            }
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(
                    "the model's up axis (remembered): the default view keeps it up, and the "
                    "spherical texture projection puts its poles on it");
        }
        end_menu();
    }
    end_menu();
}

void context_menu(RenderStyle& style, ViewSettings& settings, PanelState& panels,
                  const RenderContext& render, CommandQueue& commands) {
    if (panels.context_menu_requested) {
        ImGui::OpenPopup("##rendering_context");
        panels.context_menu_requested = false;
    }
    if (ImGui::BeginPopup("##rendering_context")) {
        rendering_menu_items(style, settings, panels, render, commands);
        ImGui::EndPopup();
    }
}

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

void place_dialog(float width_em, float height_em) {
    const ImGuiIO& io = ImGui::GetIO();
    const float em = ImGui::GetFontSize(), margin = 0.5f * em;
    const ImVec2 most(std::max(1.0f, io.DisplaySize.x - 2.0f * margin),
                      std::max(1.0f, io.DisplaySize.y - 2.0f * margin));
    ImGui::SetNextWindowPos(ImVec2(0.5f * io.DisplaySize.x, 0.5f * io.DisplaySize.y),
                            ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
    if (width_em > 0 && height_em > 0)
        ImGui::SetNextWindowSize(
            ImVec2(std::min(width_em * em, most.x), std::min(height_em * em, most.y)),
            ImGuiCond_Appearing);
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), most);
}

void keep_dialog_inside() {
    const ImGuiIO& io = ImGui::GetIO();
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    const ImVec2 fixed(std::clamp(pos.x, 0.0f, std::max(0.0f, io.DisplaySize.x - size.x)),
                       std::clamp(pos.y, 0.0f, std::max(0.0f, io.DisplaySize.y - size.y)));
    if (fixed.x != pos.x || fixed.y != pos.y) ImGui::SetWindowPos(fixed);
}

bool begin_modal_dialog(const char* title, int flags, float width_em, float height_em) {
    place_dialog(width_em, height_em);
    if (!ImGui::BeginPopupModal(title, nullptr, flags)) return false;
    keep_dialog_inside();
    return true;
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
        ImGui::Text("%zu vertices   %zu faces   %s   %.1f ms", info.n_vertices, info.n_faces,
                    info.file_name.c_str(), info.frame_ms);
        if (notice.level != Notice::Level::None &&
            ImGui::GetItemRectMax().x + 3.0f * style.ItemSpacing.x < text_right) {
            ImGui::SameLine(0.0f, 3.0f * style.ItemSpacing.x);
            ImGui::PushClipRect(
                ImGui::GetCursorScreenPos(),
                ImVec2(ImGui::GetWindowPos().x + text_right, ImGui::GetWindowPos().y + region.h),
                true);
            ImGui::TextColored(notice_color(notice.level), "%s", notice.text.c_str());
            ImGui::PopClipRect();
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
            char label[256];
            std::snprintf(label, sizeof label, "%s%s%s (%.1f s)", job->name.c_str(),
                          job->stage.empty() ? "" : ": ", job->stage.c_str(), job->seconds);
            // Unknown progress: a bar that sweeps, so the user sees the program is alive.
            const float f = job->fraction >= 0.0 ? float(job->fraction)
                                                 : float(0.5 + 0.5 * std::sin(3.0 * job->seconds));
            ImGui::ProgressBar(f, ImVec2(job_w - cancel_w - 2.0f * style.ItemSpacing.x, 0.0f),
                               label);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", label);
            ImGui::SameLine();
            if (job->cancel_requested)
                ImGui::TextDisabled("cancelling");
            else if (button("Cancel##job"))
                commands.push_back(CancelJob{});
        }
    }
    ImGui::End();
}

void help_window(PanelState& panels) {
    if (!panels.help_open) return;
    if (begin_dialog("Key bindings", panels.help_open, ImGuiWindowFlags_NoCollapse)) {
        if (ImGui::BeginTable("bindings", 2,
                              ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
            for (const BindingHelpRow& row : binding_help_rows()) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(row.keys.c_str());
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(row.action.c_str());
            }
            ImGui::EndTable();
        }
    }
    ImGui::End();
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

namespace {
/// A typed value outside the declared range was replaced by `kept`: the text field lets go
/// (so it shows `kept` at once, like the slider), and the reason goes to `notes`.
void keep_typed_value(const ParamSpec& p, double typed, double kept,
                      std::vector<std::string>* notes) {
    ImGui::ClearActiveID();
    if (!notes) return;
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s: %g is outside %g .. %g; using %g", p.label.c_str(), typed,
                  p.min, p.max, kept);
    notes->push_back(buf);
}

/// The width of a widget with its label at the right: `wanted_em`, less in a narrow sidebar
/// (the label keeps `label_share` of the line), never under 4 em.
float widget_width(float wanted_em = 12.0f, float label_share = 0.4f) {
    const float em = ImGui::GetFontSize();
    const float avail = ImGui::GetContentRegionAvail().x;
    return std::max(4.0f * em, std::min(wanted_em * em, (1.0f - label_share) * avail));
}
}  // namespace

std::string default_note_text(const ParamSpec& p) {
    if (p.default_note.empty()) return "default";
    // The declaration speaks of the command line ("none (--percent and --iterations)"); the
    // panel names the same parameters by their labels.
    std::string text;
    for (std::size_t i = 0; i < p.default_note.size(); ++i) {
        if (p.default_note.compare(i, 2, "--") == 0) {
            ++i;
            continue;
        }
        text += p.default_note[i];
    }
    return text;
}

double clamp_to_declared(const ParamSpec& p, double x) {
    double kept = std::clamp(x, p.min, p.max);
    if (p.min_exclusive && kept <= p.min) {  // the smallest value above min the panel offers
        const double ui_low = p.ui_min != 0 || p.ui_max != 0 ? p.ui_min : p.min;
        kept = ui_low > p.min ? ui_low : std::nextafter(p.min, p.max);
    }
    return kept;
}

namespace {

/// One parameter's widgets: what they edit and how.
struct ParamWidget {
    const ParamSpec& p;
    ParamValue& v;
    double lo, hi;  ///< the slider's span
    float w;        ///< the widget width
    ImGuiSliderFlags flags;
    std::vector<std::string>* notes;
};

/// A combo box, as wide as its longest choice where it can be.
void choice_widget(const ParamWidget& pw) {
    const ParamSpec& p = pw.p;
    ParamValue& v = pw.v;
    const float w = pw.w;
    int current = 0;
    float widest = 0;  // the combo shows its longest choice whole where it can
    for (std::size_t c = 0; c < p.choices.size(); ++c) {
        if (p.choices[c].value == int(v.x)) current = int(c);
        widest = std::max(widest, ImGui::CalcTextSize(p.choices[c].label.c_str()).x);
    }
    const float fit = widest + ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().FramePadding.x;
    ImGui::SetNextItemWidth(
        std::max(w, std::min(fit, widget_width(fit / ImGui::GetFontSize(), 0.3f))));
    if (ImGui::BeginCombo(p.label.c_str(), p.choices[current].label.c_str())) {
        for (std::size_t c = 0; c < p.choices.size(); ++c)
            if (ImGui::Selectable(p.choices[c].label.c_str(), int(c) == current))
                v.x = p.choices[c].value;
        ImGui::EndCombo();
    }
}

/// A slider (or, over wide ranges, a typed field); an optional one with its check box.
void integer_widget(const ParamWidget& pw) {
    const ParamSpec& p = pw.p;
    ParamValue& v = pw.v;
    const double lo = pw.lo, hi = pw.hi;
    std::vector<std::string>* notes = pw.notes;
    // An optional number's check box carries its label: set, or the default.
    const std::string label = p.optional ? "##" + p.name : p.label;
    if (p.optional) {
        if (checkbox(p.label.c_str(), &v.on, (p.name + ":on").c_str()) && v.on)
            v.x = std::clamp(v.x, p.min, p.max);  // from "unset" to a value
        ImGui::SameLine();
    }
    if (!v.on) {  // unset: the run's default, said in words
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", default_note_text(p).c_str());
        ImGui::PopTextWrapPos();
        return;
    }
    ImGui::SetNextItemWidth(pw.w);
    if (hi - lo <= 1000) {
        int x = int(std::clamp(v.x, lo, hi));
        if (ImGui::SliderInt(label.c_str(), &x, int(lo), int(hi), "%d",
                             ImGuiSliderFlags_AlwaysClamp))
            v.x = x;
    } else {  // wide ranges (vertex counts): type the number
        long long x = std::llround(v.x);
        if (ImGui::InputScalar(label.c_str(), ImGuiDataType_S64, &x)) {
            v.x = std::clamp(double(x), p.min, p.max);
            if (v.x != double(x)) keep_typed_value(p, double(x), v.x, notes);
        }
    }
}

/// A typed field and a slider; a switchable one with its check box.
void number_widget(const ParamWidget& pw) {
    const ParamSpec& p = pw.p;
    ParamValue& v = pw.v;
    const double lo = pw.lo, hi = pw.hi;
    const float w = pw.w;
    std::vector<std::string>* notes = pw.notes;
    const bool switchable = p.kind == ParamKind::Switchable;
    if (switchable) {  // the check box carries the label
        checkbox(p.label.c_str(), &v.on, (p.name + ":on").c_str());
        ImGui::SameLine();
        if (!v.on) ImGui::BeginDisabled();
    }
    // Type any value ("2e-2" works) or drag the slider. A typed value outside the
    // declared range is clamped at once: the field lets go of it and shows the
    // value used, as do the slider and every message (keep_typed_value()).
    ImGui::SetNextItemWidth(w * 0.45f);
    double x = v.x;
    const bool typed = ImGui::InputDouble("##value", &x, 0.0, 0.0, "%g");
    note_widget(p.name + ":value");
    if (typed && std::isfinite(x)) {
        v.x = clamp_to_declared(p, x);
        // "0" on the way to "0.05" above an exclusive 0 is not a typing mistake.
        const bool on_the_way = p.min_exclusive && x == p.min;
        if (v.x != x && !on_the_way) keep_typed_value(p, x, v.x, notes);
    }
    // A slider where its span fits a float's (max-error has none: scale-dependent).
    if (std::abs(lo) < 1e30 && std::abs(hi) < 1e30) {
        ImGui::SameLine();
        float f = float(std::clamp(v.x, lo, hi));
        // Beyond the slider's span the slider shows the value itself, not its end.
        char beyond[64];
        std::snprintf(beyond, sizeof beyond, "%.4g", v.x);
        const bool outside = v.x < lo || v.x > hi;
        ImGui::SetNextItemWidth(w * 0.55f);
        const std::string label = switchable ? "##" + p.name : p.label;
        if (ImGui::SliderFloat(label.c_str(), &f, float(lo), float(hi), outside ? beyond : "%.4g",
                               pw.flags))
            v.x = f;
    } else if (!switchable) {
        ImGui::SameLine();
        ImGui::TextUnformatted(p.label.c_str());
    }
    v.x = clamp_to_declared(p, v.x);
    if (switchable && !v.on) ImGui::EndDisabled();
}

/// Two typed integers, the second not below the first.
void range_widget(const ParamWidget& pw) {
    const ParamSpec& p = pw.p;
    ParamValue& v = pw.v;
    int range[2] = {int(v.x), int(v.y)};
    ImGui::SetNextItemWidth(pw.w);
    if (ImGui::InputInt2(p.label.c_str(), range)) {
        v.x = std::clamp(double(range[0]), p.min, p.max);
        v.y = std::clamp(double(range[1]), v.x, p.max);
    }
}

}  // namespace

bool operation_widgets(Operation& op, const std::vector<std::string>& skip,
                       std::vector<std::string>* notes) {
    bool changed = false;
    const OperationDef& def = *op.def;
    const float w = widget_width();
    for (std::size_t i = 0; i < def.params.size(); ++i) {
        if (def.why_not(op.values, i)) continue;  // hidden: it does not apply
        const ParamSpec& p = def.params[i];
        if (std::find(skip.begin(), skip.end(), p.name) != skip.end()) continue;
        ParamValue& v = op.values[i];
        const ParamValue before = v;
        ImGui::PushID(p.name.c_str());
        const double lo = p.ui_min != 0 || p.ui_max != 0 ? p.ui_min : p.min;
        const double hi = p.ui_min != 0 || p.ui_max != 0 ? p.ui_max : p.max;
        const ImGuiSliderFlags flags =
            p.logarithmic ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None;
        const ParamWidget pw{p, v, lo, hi, w, flags, notes};
        switch (p.kind) {
            case ParamKind::Choice:
                choice_widget(pw);
                break;
            case ParamKind::Flag: {
                bool on = v.x != 0;
                if (checkbox(p.label.c_str(), &on)) v.x = on ? 1 : 0;
                break;
            }
            case ParamKind::Integer:
                integer_widget(pw);
                break;
            case ParamKind::Switchable:
            case ParamKind::Number:
                number_widget(pw);
                break;
            case ParamKind::Range:
                range_widget(pw);
                break;
        }
        note_widget(p.name);
        if (ImGui::IsItemHovered() && !p.help.empty()) ImGui::SetTooltip("%s", p.help.c_str());
        ImGui::PopID();
        if (v != before) {
            v.given = true;
            changed = true;
        }
    }
    return changed;
}

namespace {

const ImVec4 kErrorColor(1.0f, 0.45f, 0.40f, 1.0f);

/// Greyed text that wraps at the sidebar's edge.
template <class... Args>
void wrapped_disabled(const char* format, Args... args) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled(format, args...);
    ImGui::PopTextWrapPos();
}

/// Coloured text that wraps at the sidebar's edge.
template <class... Args>
void wrapped_colored(const ImVec4& color, const char* format, Args... args) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(color, format, args...);
    ImGui::PopTextWrapPos();
}

/// The parameters of an operation panel, its Apply button, and the preview's note.
void operation_panel_body(OperationPanelState& state, const char* apply, bool busy,
                          CommandQueue& commands) {
    std::vector<std::string> notes;
    if (operation_widgets(state.op, {}, &notes)) {
        state.dirty = true;
        state.input_note.clear();
    }
    if (!notes.empty()) state.input_note = notes.back();
    if (!state.input_note.empty()) wrapped_disabled("%s", state.input_note.c_str());
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
    if (!error.empty()) wrapped_colored(kErrorColor, "%s", error.c_str());
    if ((busy && !state.previewing) || !error.empty()) ImGui::BeginDisabled();
    if (button(apply)) commands.push_back(ApplyOperation{state.op});
    if ((busy && !state.previewing) || !error.empty()) ImGui::EndDisabled();
    if (state.previewing) {
        ImGui::SameLine();
        if (button("Cancel")) commands.push_back(CancelPreview{});
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("back to the state before (Esc)");
    }
    if (!state.preview_note.empty()) wrapped_disabled("%s", state.preview_note.c_str());
}

/// The largest stable explicit step of the mesh and operator; a larger explicit step in red
/// with the reason, and a button that switches to implicit integration. The warning's lines
/// are kept free while it is not shown, so that nothing below moves when it comes or goes.
void stability_guidance(FairingPanelState& state) {
    const double limit = state.max_stable_step;
    const bool taubin = int(state.op.value("operator").x) == int(FairingOperator::Taubin);
    const bool explicit_run =
        taubin || int(state.op.value("integration").x) == int(Integration::Explicit);
    // NaN until estimated: tested with isnan first, as an ordered comparison with NaN raises
    // FE_INVALID (the tests run with floating-point traps).
    const bool known = !std::isnan(limit) && limit > 0;
    const double step = taubin ? state.op.value("lambda").x : state.op.value("step").x;
    const char* what = taubin ? "lambda" : "step";
    if (known)
        wrapped_disabled("largest stable explicit %s: %.3g", what, limit);
    else
        wrapped_disabled("largest stable explicit %s: estimating...", what);
    note_widget("stable-step");
    char warning[160];
    std::snprintf(warning, sizeof warning, "%s %.3g is above it: the run would diverge and stop",
                  what, step);
    const float wrap = ImGui::GetContentRegionAvail().x;
    const ImVec2 text = ImGui::CalcTextSize(warning, nullptr, false, wrap);
    const ImGuiStyle& style = ImGui::GetStyle();
    const float reserved = text.y + (taubin ? 0.0f : style.ItemSpacing.y + ImGui::GetFrameHeight());
    if (!(known && explicit_run && step > limit)) {
        ImGui::Dummy(ImVec2(1.0f, reserved));
        return;
    }
    const float top = ImGui::GetCursorPosY();
    wrapped_colored(kErrorColor, "%s", warning);
    note_widget("unstable");
    if (!taubin && button("Use implicit integration")) {
        ParamValue& integration = state.op.value("integration");
        integration.x = int(Integration::Implicit);
        integration.given = true;
        state.dirty = true;
    }
    // Whatever the text's last line did, the rows below start where they always do.
    const float used = ImGui::GetCursorPosY() - top - style.ItemSpacing.y;
    if (used < reserved) ImGui::Dummy(ImVec2(1.0f, reserved - used - style.ItemSpacing.y));
}

/// Where the morph of a result is: one place, the Morph section.
void morph_hint() {
    wrapped_disabled("the morph of each result: the Morph section (M)");
}

}  // namespace

void subdivision_section(PanelState& panels, const SidebarContext& context,
                         CommandQueue& commands) {
    OperationPanelState& state = panels.subdivision;
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
            commands.push_back(ApplyOperation{make_operation("weld")});
        if (context.busy) ImGui::EndDisabled();
    }
    ImGui::Separator();
    wrapped_disabled("colour: Rendering > Colour by vertex > Subdivision vertices");
    morph_hint();
}

void fairing_section(PanelState& panels, const SidebarContext& context, CommandQueue& commands) {
    FairingPanelState& state = panels.fairing;
    SidebarSection section("Fairing", state.open);
    if (!section) return;
    stability_guidance(state);
    // What the mesh cannot do is switched off with the reason, never ignored.
    ParamValue& volume = state.op.value("preserve-volume");
    ParamValue& boundary = state.op.value("boundary");
    if (!context.closed) volume.x = 0;
    if (context.closed) boundary.x = int(BoundaryMode::Fixed);
    operation_panel_body(state, "Smooth", context.busy, commands);
    if (!context.closed) wrapped_disabled("open mesh: no volume to preserve");
    ImGui::Separator();
    morph_hint();
}

void decimation_section(PanelState& panels, const SidebarContext& context, CommandQueue& commands) {
    DecimationPanelState& d = panels.decimation;
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

void tools_section(PanelState& panels, bool busy, CommandQueue& commands) {
    if (SidebarSection noise("Tools: add noise", panels.tools.open); noise) {
        ImGui::TextWrapped("Moves the vertices along their normals.");
        operation_panel_body(panels.tools, "Apply", busy, commands);
    }
    if (SidebarSection weld("Tools: weld coincident vertices", panels.weld.open); weld) {
        ImGui::TextWrapped(
            "Joins coincident vertices where the mesh stays manifold (tolerance 0: exactly the "
            "same position); the log says what stays apart.");
        operation_panel_body(panels.weld, "Weld", busy, commands);
    }
}

FrequencyActions sidebar_sections(PanelState& panels, MorphState& morph,
                                  const SidebarContext& context, CommandQueue& commands) {
    const FrequencyDocument no_decomposition;
    tools_section(panels, context.busy, commands);
    fairing_section(panels, context, commands);
    const FrequencyActions frequency = frequency_window(
        panels.frequency, context.frequency ? *context.frequency : no_decomposition, context.busy);
    subdivision_section(panels, context, commands);
    decimation_section(panels, context, commands);
    if (context.history) morph_section(panels, morph, *context.history, context.now);
    record_section(panels, context.can_record, commands);
    info_section(panels, context.info ? *context.info : std::vector<std::string>{});
    ImGui::Spacing();
    wrapped_disabled(
        "The Tools and Algorithms menus open these sections; H the history, L the log.");
    return frequency;
}

namespace {
/// The morph slider and animation controls for the current history entry.
void morph_controls(MorphState& morph, const History& history, double now) {
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
    float t = float(morph.t);
    ImGui::SetNextItemWidth(widget_width(16.0f, 0.0f));
    if (ImGui::SliderFloat("##t", &t, 0.0f, 1.0f, "t = %.3f")) {
        morph.t = t;
        morph.playing = false;
    }
    if (!morph.playing) {
        if (button("Animate")) {
            morph.playing = true;
            morph.play_start = now;
        }
    } else if (button("Stop")) {
        morph.playing = false;
    }
    ImGui::SameLine();
    if (button("Before")) {
        morph.t = 0.0;
        morph.playing = false;
    }
    ImGui::SameLine();
    if (button("After")) {
        morph.t = 1.0;
        morph.playing = false;
    }
    float duration = float(morph.duration);
    ImGui::SetNextItemWidth(widget_width(8.0f));
    if (ImGui::SliderFloat("duration", &duration, 0.2f, 20.0f, "%.1f s",
                           ImGuiSliderFlags_Logarithmic))
        morph.duration = duration;
    const char* easings[] = {"linear", "smooth step", "ease in-out (cubic)"};
    int e = int(morph.easing);
    ImGui::SetNextItemWidth(widget_width(8.0f));
    if (ImGui::Combo("easing", &e, easings, 3)) morph.easing = Easing(e);
    const char* modes[] = {"once", "loop", "ping-pong"};
    int m = int(morph.playback);
    ImGui::SetNextItemWidth(widget_width(8.0f));
    if (ImGui::Combo("playback", &m, modes, 3)) morph.playback = Playback(m);
    if (info.steps.size() > 1) ImGui::TextDisabled("%zu steps, chained", info.steps.size());
}
}  // namespace

void morph_section(PanelState& panels, MorphState& morph, const History& history, double now) {
    SidebarSection section("Morph", panels.morph_open);
    if (!section) return;
    morph_controls(morph, history, now);
}

void record_section(PanelState& panels, bool can_record, CommandQueue& commands) {
    RecordState& r = panels.record;
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
            ImGui::TextDisabled("(apply an operation first)");
        }
    }
}

void screenshot_dialog(ScreenshotState& state, CommandQueue& commands) {
    if (!state.open) return;
    if (begin_dialog("Screenshot", state.open)) {
        ImGui::TextUnformatted("The scene without the panels, framed as the view, as PNG.");
        ImGui::SetNextItemWidth(20.0f * ImGui::GetFontSize());
        ImGui::InputText("file", &state.path);
        int size[2] = {state.width, state.height};
        ImGui::SetNextItemWidth(12.0f * ImGui::GetFontSize());
        if (ImGui::InputInt2("width, height", size)) {
            state.width = std::clamp(size[0], 1, 16384);
            state.height = std::clamp(size[1], 1, 16384);
        }
        checkbox("transparent background", &state.transparent);
        if (button("Save") && !state.path.empty())
            commands.push_back(
                TakeScreenshot{state.path, state.width, state.height, state.transparent});
    }
    ImGui::End();
}

void about_window(PanelState& panels) {
    if (!panels.about_open) return;
    if (begin_dialog("About trilab", panels.about_open)) {
        ImGui::TextUnformatted("trilab: a laboratory for triangle meshes");
        ImGui::Separator();
        ImGui::TextUnformatted("Half-edge core, OpenGL 3.3 renderer, Dear ImGui " IMGUI_VERSION);
        ImGui::TextUnformatted("Formats: .obj .off .ply .stl .om");
    }
    ImGui::End();
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

void info_section(PanelState& panels, const std::vector<std::string>& lines) {
    SidebarSection section("Model information", panels.info_open);
    if (!section) return;
    ImGui::PushTextWrapPos(0.0f);
    for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
    ImGui::PopTextWrapPos();
}

bool color_legend(const VertexColors& colors, ColoringOptions& options, LegendSlot& slot) {
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
        slot.width = ImGui::GetWindowWidth();
        slot.height = ImGui::GetWindowHeight();
    }
    ImGui::End();
    return changed;
}

void unsaved_changes_popup(UnsavedPrompt& prompt, CommandQueue& commands) {
    constexpr const char* kTitle = "Unsaved changes";
    if (prompt.open_requested) {
        ImGui::OpenPopup(kTitle);
        prompt.open_requested = false;
    }
    if (!begin_modal_dialog(kTitle, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::PushTextWrapPos(
        std::min(36.0f * ImGui::GetFontSize(), 0.8f * ImGui::GetIO().DisplaySize.x));
    ImGui::TextUnformatted(prompt.quitting
                               ? "The mesh has changes that are not saved to a file. Quit anyway?"
                               : "The mesh has changes that are not saved to a file. Open the "
                                 "other file anyway? (The changes stay in the history: Edit -> "
                                 "Undo brings them back.)");
    ImGui::PopTextWrapPos();
    if (!prompt.document_path.empty()) {
        if (button("Save (overwrite)")) {
            commands.push_back(SaveAndContinue{});
            ImGui::CloseCurrentPopup();
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("replace %s with the current mesh", prompt.document_path.c_str());
        ImGui::SameLine();
    }
    if (button("Save as...")) {
        commands.push_back(SaveAsAndContinue{});
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (button(prompt.quitting ? "Discard and quit" : "Discard and open")) {
        if (prompt.quitting)
            commands.push_back(Quit{true});
        else
            commands.push_back(LoadFile{prompt.path, true});
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

void error_popup(Notice& notice) {
    if (notice.popup_pending) {
        ImGui::OpenPopup(kErrorPopupTitle);
        notice.popup_pending = false;
    }
    if (!begin_modal_dialog(kErrorPopupTitle, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::PushTextWrapPos(
        std::min(40.0f * ImGui::GetFontSize(), 0.8f * ImGui::GetIO().DisplaySize.x));
    ImGui::TextColored(notice_color(Notice::Level::Error), "%s", notice.text.c_str());
    ImGui::PopTextWrapPos();
    if (button("OK") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

}  // namespace trilab::viewer
