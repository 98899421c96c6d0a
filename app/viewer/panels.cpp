#include "app/viewer/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "app/viewer/key_bindings.h"
#include "app/viewer/plots.h"
#include "core/algorithms/fairing.h"

namespace trilab::viewer {
namespace {

void morph_controls(MorphState& morph, const History& history, double now);
void note_widget(const std::string& id);

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

/// ImGui::BeginMenu; a closed menu's header is reported to the test hook as "menu:LABEL".
bool begin_menu(const char* label, bool enabled = true) {
    const bool open = ImGui::BeginMenu(label, enabled);
    if (!open) note_widget(std::string("menu:") + label);
    return open;
}

/// A menu item that shows the key of `action` (the key bindings table's text). Reported to
/// the test hook as "shortcut:LABEL=KEYS".
bool shortcut_item(const char* label, KeyAction action, bool selected = false,
                   bool enabled = true) {
    const std::string keys = shortcut_text(action);
    const bool clicked = ImGui::MenuItem(label, keys.c_str(), selected, enabled);
    note_widget("shortcut:" + std::string(label) + "=" + keys);
    return clicked;
}
/// The same for an item that toggles `*selected`.
bool shortcut_item(const char* label, KeyAction action, bool* selected) {
    const std::string keys = shortcut_text(action);
    const bool clicked = ImGui::MenuItem(label, keys.c_str(), selected);
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

void rendering_menu_items(RenderStyle& style, ViewSettings& settings, PanelState& panels,
                          const RenderContext& render, CommandQueue& commands) {
    const RenderMode modes[] = {RenderMode::Wireframe, RenderMode::HiddenLine,
                                RenderMode::Flat,      RenderMode::Smooth,
                                RenderMode::Points,    RenderMode::Textured};
    for (RenderMode mode : modes)
        if (ImGui::MenuItem(render_mode_name(mode), nullptr, style.mode == mode)) style.mode = mode;
    ImGui::Separator();
    if (begin_menu("Wireframe overlay")) {
        if (ImGui::MenuItem("Automatic", nullptr, settings.wireframe == WireframeOverlay::Auto))
            settings.wireframe = WireframeOverlay::Auto;
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("on while the edges are long enough on the screen to tell apart");
        if (shortcut_item("On", KeyAction::ToggleWireframe,
                          settings.wireframe == WireframeOverlay::On))
            settings.wireframe = WireframeOverlay::On;
        if (shortcut_item("Off", KeyAction::ToggleWireframe,
                          settings.wireframe == WireframeOverlay::Off))
            settings.wireframe = WireframeOverlay::Off;
        ImGui::EndMenu();
    }
    shortcut_item("Back-face colour", KeyAction::ToggleBackFaceColor, &style.back_face_color);
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
            if (ImGui::MenuItem(labels[i], nullptr, settings.coloring == colorings[i]) &&
                settings.coloring != colorings[i]) {
                settings.coloring = colorings[i];
                commands.push_back(UpdateColoring{});
            }
        }
        ImGui::EndMenu();
    }
    if (begin_menu("Texture")) {
        const TextureMode tmodes[] = {TextureMode::Off, TextureMode::Modulate,
                                      TextureMode::Replace};
        for (TextureMode m : tmodes) {
            const bool on = style.mode == RenderMode::Textured && style.texture_mode == m;
            const bool clicked =
                m == TextureMode::Off
                    ? shortcut_item(texture_mode_name(m), KeyAction::CycleTexture, on)
                    : ImGui::MenuItem(texture_mode_name(m), nullptr, on);
            if (clicked) {
                style.texture_mode = m;
                style.mode = m == TextureMode::Off ? RenderMode::Smooth : RenderMode::Textured;
            }
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Checkerboard", nullptr, settings.use_checkerboard))
            settings.use_checkerboard = true;
        if (ImGui::MenuItem("Loaded image", nullptr, !settings.use_checkerboard,
                            render.has_loaded_texture))
            settings.use_checkerboard = false;
        if (ImGui::MenuItem("Load image..."))
            panels.file_browser.request(FileBrowserState::Purpose::LoadTexture, "");
        ImGui::Separator();
        if (render.has_texcoords) {
            ImGui::TextDisabled("the model has texture coordinates");
        } else {
            ImGui::TextDisabled("no texture coordinates: project them");
            if (ImGui::MenuItem("Planar projection")) {
                settings.projection = TexCoordProjection::Planar;
                commands.push_back(ProjectTexCoords{});
            }
            if (ImGui::MenuItem("Spherical projection")) {
                settings.projection = TexCoordProjection::Spherical;
                commands.push_back(ProjectTexCoords{});
            }
        }
        ImGui::EndMenu();
    }
    if (begin_menu("Vectors")) {
        ImGui::MenuItem("Face normals", nullptr, &style.face_normals);
        ImGui::MenuItem("Vertex normals", nullptr, &style.vertex_normals);
        ImGui::MenuItem("Collapsing edges", nullptr, &panels.decimation.show_collapsing_edges);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("The edges the Decimation panel's next iteration collapses");
        ImGui::SetNextItemWidth(10.0f * ImGui::GetFontSize());
        ImGui::SliderFloat("length", &style.vector_length, 0.002f, 0.2f, "%.3f",
                           ImGuiSliderFlags_Logarithmic);
        ImGui::EndMenu();
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
        ImGui::EndMenu();
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
                if (ImGui::MenuItem(path.c_str())) commands.push_back(LoadFile{path});
            ImGui::EndMenu();
        }
        if (ImGui::MenuItem("Revert", nullptr, false, context.has_file && !context.busy))
            commands.push_back(RevertFile{});
        if (shortcut_item("Save as...", KeyAction::SaveFile, false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::SaveMesh, context.document_path);
        ImGui::Separator();
        if (ImGui::MenuItem("Load texture...", nullptr, false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::LoadTexture, "");
        ImGui::Separator();
        if (shortcut_item("Quit", KeyAction::Quit)) commands.push_back(Quit{});
        ImGui::EndMenu();
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
        ImGui::EndMenu();
    }
    view_menu(settings, commands);
    if (begin_menu("Tools")) {
        ImGui::MenuItem("Add noise", nullptr, &panels.tools.open);
        if (ImGui::MenuItem("Flip orientation", nullptr, false, !context.busy))
            commands.push_back(ApplyOperation{make_operation("flip")});
        ImGui::MenuItem("Weld coincident vertices...", nullptr, &panels.weld.open);
        ImGui::EndMenu();
    }
    if (begin_menu("Algorithms")) {
        // The operation panels arrive with their issues; listed so the menu shows the plan.
        ImGui::MenuItem("Fairing", nullptr, &panels.fairing.open);
        ImGui::MenuItem("Frequency decomposition", nullptr, &panels.frequency.open);
        ImGui::MenuItem("Subdivision", nullptr, &panels.subdivision.open);
        ImGui::MenuItem("Decimation", nullptr, &panels.decimation.open);
        ImGui::EndMenu();
    }
    if (begin_menu("Rendering")) {
        rendering_menu_items(style, settings, panels, render, commands);
        ImGui::EndMenu();
    }
    if (begin_menu("Window")) {
        ImGui::MenuItem("Sidebar", nullptr, &panels.sidebar_open);
        shortcut_item("Model information", KeyAction::PrintInfo, &panels.info_open);
        shortcut_item("Log", KeyAction::ToggleLog, &panels.log_open);
        ImGui::EndMenu();
    }
    if (begin_menu("Help")) {
        shortcut_item("Key bindings", KeyAction::ToggleHelp, &panels.help_open);
        ImGui::MenuItem("About trilab", nullptr, &panels.about_open);
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

void view_menu(ViewSettings& settings, CommandQueue& commands) {
    if (!begin_menu("View")) return;
    if (ImGui::MenuItem("Default view")) commands.push_back(ResetView{});
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("look at the model's front with its up axis up, and fit it");
    if (begin_menu("Up axis")) {
        for (const EnumEntry<UpAxis>& e : kUpAxes) {
            if (ImGui::MenuItem(e.label, nullptr, settings.up == e.value) &&
                settings.up != e.value) {
                settings.up = e.value;
                commands.push_back(ResetView{});
            }
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(
                    "the model's up axis (remembered): the default view keeps it up, and the "
                    "spherical texture projection puts its poles on it");
        }
        ImGui::EndMenu();
    }
    ImGui::EndMenu();
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

bool section_header(const char* label, bool& open) {
    // Remember whether the section was open last frame, in the window's storage: a section
    // opened from a menu or a key (not by its header) is scrolled into view.
    ImGuiStorage* storage = ImGui::GetStateStorage();
    const ImGuiID id = ImGui::GetID((std::string(label) + "##was-open").c_str());
    const int was = storage->GetInt(id, -1);
    ImGui::SetNextItemOpen(open, ImGuiCond_Always);
    const bool clicked_open = ImGui::CollapsingHeader(label);
    note_widget(std::string("section:") + label);
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
            else if (ImGui::Button("Cancel##job"))
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
        ImGui::TextWrapped("%zu entries, %.1f MB of the %.0f MB budget", history.size(),
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
WidgetRectHook widget_rect_hook;  // tests only; see set_widget_rect_hook()

/// Reports the last item's rectangle to the test hook, when one is set.
void note_widget(const std::string& id) {
    if (!widget_rect_hook) return;
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    widget_rect_hook(id, a.x, a.y, b.x, b.y);
}

/// The width of a widget with its label at the right: `wanted_em`, less in a narrow sidebar
/// (the label keeps `label_share` of the line), never under 4 em.
float widget_width(float wanted_em = 12.0f, float label_share = 0.4f) {
    const float em = ImGui::GetFontSize();
    const float avail = ImGui::GetContentRegionAvail().x;
    return std::max(4.0f * em, std::min(wanted_em * em, (1.0f - label_share) * avail));
}
}  // namespace

void set_widget_rect_hook(WidgetRectHook hook) {
    widget_rect_hook = std::move(hook);
}

void note_widget_rect(const std::string& id, float x0, float y0, float x1, float y1) {
    if (widget_rect_hook) widget_rect_hook(id, x0, y0, x1, y1);
}

bool operation_widgets(Operation& op, const std::vector<std::string>& skip) {
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
        switch (p.kind) {
            case ParamKind::Choice: {
                int current = 0;
                float widest = 0;  // the combo shows its longest choice whole where it can
                for (std::size_t c = 0; c < p.choices.size(); ++c) {
                    if (p.choices[c].value == int(v.x)) current = int(c);
                    widest = std::max(widest, ImGui::CalcTextSize(p.choices[c].label.c_str()).x);
                }
                const float fit =
                    widest + ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().FramePadding.x;
                ImGui::SetNextItemWidth(
                    std::max(w, std::min(fit, widget_width(fit / ImGui::GetFontSize(), 0.3f))));
                if (ImGui::BeginCombo(p.label.c_str(), p.choices[current].label.c_str())) {
                    for (std::size_t c = 0; c < p.choices.size(); ++c)
                        if (ImGui::Selectable(p.choices[c].label.c_str(), int(c) == current))
                            v.x = p.choices[c].value;
                    ImGui::EndCombo();
                }
                break;
            }
            case ParamKind::Flag: {
                bool on = v.x != 0;
                if (ImGui::Checkbox(p.label.c_str(), &on)) v.x = on ? 1 : 0;
                break;
            }
            case ParamKind::Integer: {
                if (p.optional) {
                    if (ImGui::Checkbox("##set", &v.on) && v.on)
                        v.x = std::clamp(v.x, p.min, p.max);  // from "unset" to a value
                    note_widget(p.name + ":on");
                    ImGui::SameLine();
                }
                if (!v.on) {  // unset: the run's default, said in words
                    ImGui::TextDisabled(
                        "%s: %s", p.label.c_str(),
                        p.default_note.empty() ? "default" : p.default_note.c_str());
                    break;
                }
                ImGui::SetNextItemWidth(w);
                if (hi - lo <= 1000) {
                    int x = int(std::clamp(v.x, lo, hi));
                    if (ImGui::SliderInt(p.label.c_str(), &x, int(lo), int(hi), "%d",
                                         ImGuiSliderFlags_AlwaysClamp))
                        v.x = x;
                } else {  // wide ranges (vertex counts): type the number
                    long long x = std::llround(v.x);
                    if (ImGui::InputScalar(p.label.c_str(), ImGuiDataType_S64, &x))
                        v.x = std::clamp(double(x), p.min, p.max);
                }
                break;
            }
            case ParamKind::Switchable:
            case ParamKind::Number: {
                if (p.kind == ParamKind::Switchable) {
                    ImGui::Checkbox("##on", &v.on);
                    note_widget(p.name + ":on");
                    ImGui::SameLine();
                    if (!v.on) ImGui::BeginDisabled();
                }
                // Type any value ("2e-2" works) or drag the slider.
                ImGui::SetNextItemWidth(w * 0.45f);
                double x = v.x;
                if (ImGui::InputDouble("##value", &x, 0.0, 0.0, "%g") && std::isfinite(x)) v.x = x;
                // A slider where its span fits a float's (max-error has none: scale-dependent).
                if (std::abs(lo) < 1e30 && std::abs(hi) < 1e30) {
                    ImGui::SameLine();
                    float f = float(std::clamp(v.x, lo, hi));
                    ImGui::SetNextItemWidth(w * 0.55f);
                    if (ImGui::SliderFloat(p.label.c_str(), &f, float(lo), float(hi), "%.4g",
                                           flags))
                        v.x = f;
                } else {
                    ImGui::SameLine();
                    ImGui::TextUnformatted(p.label.c_str());
                }
                v.x = std::clamp(v.x, p.min, p.max);
                if (p.min_exclusive && v.x <= p.min) v.x = std::max(lo, p.min + 1e-9);
                if (p.kind == ParamKind::Switchable && !v.on) ImGui::EndDisabled();
                break;
            }
            case ParamKind::Range: {
                int range[2] = {int(v.x), int(v.y)};
                ImGui::SetNextItemWidth(w);
                if (ImGui::InputInt2(p.label.c_str(), range)) {
                    v.x = std::clamp(double(range[0]), p.min, p.max);
                    v.y = std::clamp(double(range[1]), v.x, p.max);
                }
                break;
            }
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
/// The parameters of an operation panel, its Apply button, and the morph of the current
/// entry.
void operation_panel_body(OperationPanelState& state, const char* apply, bool busy,
                          CommandQueue& commands) {
    if (operation_widgets(state.op)) state.dirty = true;
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
    if (!error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.40f, 1.0f), "%s", error.c_str());
    if ((busy && !state.previewing) || !error.empty()) ImGui::BeginDisabled();
    if (ImGui::Button(apply)) commands.push_back(ApplyOperation{state.op});
    note_widget(apply);
    if ((busy && !state.previewing) || !error.empty()) ImGui::EndDisabled();
    if (state.previewing) {
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) commands.push_back(CancelPreview{});
        note_widget("Cancel");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("back to the state before (Esc)");
    }
    if (!state.preview_note.empty()) ImGui::TextDisabled("%s", state.preview_note.c_str());
}

/// The largest stable explicit step of the mesh and operator; a larger explicit step in red
/// with the reason, and a button that switches to implicit integration.
void stability_guidance(FairingPanelState& state) {
    const double limit = state.max_stable_step;
    const bool taubin = int(state.op.value("operator").x) == int(FairingOperator::Taubin);
    const bool explicit_run =
        taubin || int(state.op.value("integration").x) == int(Integration::Explicit);
    // NaN until estimated: tested with isnan first, as an ordered comparison with NaN raises
    // FE_INVALID (the tests run with floating-point traps).
    if (std::isnan(limit) || limit <= 0) {
        ImGui::TextDisabled("largest stable explicit step: estimating...");
        return;
    }
    const double step = taubin ? state.op.value("lambda").x : state.op.value("step").x;
    ImGui::TextDisabled("largest stable explicit %s: %.3g", taubin ? "lambda" : "step", limit);
    note_widget("stable-step");
    if (explicit_run && step > limit) {
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.40f, 1.0f),
                           "%s %.3g is above it: the run would diverge and stop",
                           taubin ? "lambda" : "step", step);
        note_widget("unstable");
        if (!taubin) {
            if (ImGui::Button("Use implicit integration")) {
                ParamValue& integration = state.op.value("integration");
                integration.x = int(Integration::Implicit);
                integration.given = true;
                state.dirty = true;
            }
            note_widget("Use implicit integration");
        }
    }
}

}  // namespace

void subdivision_section(PanelState& panels, MorphState& morph, const History& history, bool busy,
                         double now, CommandQueue& commands) {
    OperationPanelState& state = panels.subdivision;
    if (!section_header("Subdivision", state.open)) return;
    operation_panel_body(state, "Subdivide", busy, commands);
    ImGui::Separator();
    morph_controls(morph, history, now);
    ImGui::TextDisabled("colour: Rendering > Colour by vertex > Subdivision vertices");
}

void fairing_section(PanelState& panels, MorphState& morph, const History& history, bool closed,
                     bool busy, double now, CommandQueue& commands) {
    FairingPanelState& state = panels.fairing;
    if (!section_header("Fairing", state.open)) return;
    stability_guidance(state);
    // What the mesh cannot do is switched off with the reason, never ignored.
    ParamValue& volume = state.op.value("preserve-volume");
    ParamValue& boundary = state.op.value("boundary");
    if (!closed) volume.x = 0;
    if (closed) boundary.x = int(BoundaryMode::Fixed);
    operation_panel_body(state, "Smooth", busy, commands);
    if (!closed) ImGui::TextDisabled("open mesh: no volume to preserve");
    ImGui::Separator();
    morph_controls(morph, history, now);
}

void decimation_section(PanelState& panels, MorphState& morph, const History& history, bool busy,
                        double now, std::size_t collapsing_edges, CommandQueue& commands) {
    DecimationPanelState& d = panels.decimation;
    if (!section_header("Decimation", d.open)) return;
    {
        operation_panel_body(d, "Decimate", busy, commands);
        // Level of detail: a slider over the progressive mesh of the current state.
        if (ImGui::CollapsingHeader("Level of detail")) {
            if (!d.lod_ready) {
                if (busy || d.lod_building) ImGui::BeginDisabled();
                if (ImGui::Button("Build levels")) commands.push_back(BuildLevelOfDetail{d.op});
                note_widget("Build levels");
                if (busy || d.lod_building) ImGui::EndDisabled();
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip(
                        "decimate down to 1 %% with this cost and these "
                        "constraints, recording every collapse");
            } else {
                ImGui::SetNextItemWidth(widget_width());
                if (ImGui::SliderFloat("lod (% of vertices)", &d.lod_percent, 100.0f, 1.0f,
                                       "%.1f %%", ImGuiSliderFlags_AlwaysClamp))
                    commands.push_back(ShowLevelOfDetail{double(d.lod_percent)});
                note_widget("lod");
                if (ImGui::Button("Apply level")) commands.push_back(ApplyLevelOfDetail{});
                note_widget("Apply level");
                ImGui::SameLine();
                if (ImGui::Button("Cancel##lod")) commands.push_back(CancelPreview{});
            }
            if (!d.lod_note.empty()) ImGui::TextDisabled("%s", d.lod_note.c_str());
        }
        ImGui::Checkbox("show collapsing edges", &d.show_collapsing_edges);
        if (d.show_collapsing_edges) {
            ImGui::SameLine();
            ImGui::TextDisabled("(%zu)", collapsing_edges);
        }
        ImGui::Separator();
        morph_controls(morph, history, now);
    }
}

void tools_section(PanelState& panels, bool busy, CommandQueue& commands) {
    if (section_header("Tools: add noise", panels.tools.open)) {
        ImGui::TextWrapped("Moves the vertices along their normals.");
        operation_panel_body(panels.tools, "Apply", busy, commands);
    }
    if (section_header("Tools: weld coincident vertices", panels.weld.open)) {
        ImGui::TextWrapped(
            "Joins coincident vertices where the mesh stays manifold (tolerance 0: exactly the "
            "same position); the log says what stays apart.");
        operation_panel_body(panels.weld, "Weld", busy, commands);
    }
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
        if (ImGui::Button("Animate")) {
            morph.playing = true;
            morph.play_start = now;
        }
        note_widget("Animate");
    } else if (ImGui::Button("Stop")) {
        morph.playing = false;
    }
    ImGui::SameLine();
    if (ImGui::Button("Before")) {
        morph.t = 0.0;
        morph.playing = false;
    }
    ImGui::SameLine();
    if (ImGui::Button("After")) {
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
    if (!section_header("Morph", panels.morph_open)) return;
    morph_controls(morph, history, now);
}

void record_section(PanelState& panels, bool can_record, CommandQueue& commands) {
    RecordState& r = panels.record;
    if (r.running) r.open = true;  // the progress and Cancel stay visible
    if (!section_header("Record", r.open)) return;
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
    ImGui::Checkbox("also an MP4", &r.mp4);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("needs ffmpeg on the PATH");
    if (r.running) ImGui::EndDisabled();
    if (r.running) {
        ImGui::ProgressBar(float(r.next) / float(r.frames), ImVec2(w, 0.0f));
        ImGui::SameLine();
        if (ImGui::Button("Cancel##record")) commands.push_back(CancelRecording{});
    } else {
        if (!can_record) ImGui::BeginDisabled();
        if (ImGui::Button("Record")) commands.push_back(StartRecording{});
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
        ImGui::Checkbox("transparent background", &state.transparent);
        if (ImGui::Button("Save") && !state.path.empty())
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
    if (!section_header("Model information", panels.info_open)) return;
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
        if (ImGui::Button("Save (overwrite)")) {
            commands.push_back(SaveAndContinue{});
            ImGui::CloseCurrentPopup();
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("replace %s with the current mesh", prompt.document_path.c_str());
        ImGui::SameLine();
    }
    if (ImGui::Button("Save as...")) {
        commands.push_back(SaveAsAndContinue{});
        ImGui::CloseCurrentPopup();
    }
    note_widget("Save as...");
    ImGui::SameLine();
    if (ImGui::Button(prompt.quitting ? "Discard and quit" : "Discard and open")) {
        if (prompt.quitting)
            commands.push_back(Quit{true});
        else
            commands.push_back(LoadFile{prompt.path, true});
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
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
    if (ImGui::Button("OK") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
        ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

}  // namespace trilab::viewer
