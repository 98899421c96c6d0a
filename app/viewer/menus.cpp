// The menu bar (File, Edit, View, Tools, Algorithms, Rendering, Window, Help), the Rendering
// menu's items (also the right-click popup) and the panels' style; see panels.h.

#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/figure_panels.h"
#include "app/viewer/key_bindings.h"
#include "app/viewer/panel_helpers.h"
#include "app/viewer/panels.h"
#include "app/viewer/plots.h"
#include "app/viewer/tool.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/fairing.h"
#include "core/number_text.h"

namespace trilab::viewer {

using namespace ui;

namespace {

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
                                            VertexColoring::FrequencyMass,
                                            VertexColoring::GeodesicDistance,
                                            VertexColoring::RemovedBelow,
                                            VertexColoring::RemovedAbove,
                                            VertexColoring::MinAngle,
                                            VertexColoring::TriangleQuality,
                                            VertexColoring::SurfaceDistance};
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
                                "Frequency mass (geometry in the band)",
                                "Geodesic distance (from the picks)",
                                "Removed below the band's top (shape)",
                                "Removed above the band's top (detail, noise)",
                                "Triangle quality: smallest angle",
                                "Triangle quality: Q (1: equilateral)",
                                "Distance to a state or a file (Compare)"};
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

/// The items of the tools' panels listed in `menu`, in the tools' order: a toggle of the
/// panel (with its key's shortcut), or an action that applies its operation.
void panel_menu_items(const PanelEntries& entries, PanelMenu menu, bool busy,
                      CommandQueue& commands) {
    for (const PanelEntry& entry : entries) {
        if (entry.menu != menu) continue;
        if (entry.action) {
            if (menu_item(entry.title.c_str(), nullptr, false, !busy))
                commands.push_back(ApplyOperation{*entry.action});
        } else if (entry.shortcut >= 0) {
            shortcut_item(entry.title.c_str(), KeyAction(entry.shortcut), entry.open);
        } else {
            menu_item(entry.title.c_str(), nullptr, entry.open);
        }
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
                commands.push_back(ProjectTexCoords{settings.projection, settings.up});
            }
            if (menu_item("Spherical projection")) {
                settings.projection = TexCoordProjection::Spherical;
                commands.push_back(ProjectTexCoords{settings.projection, settings.up});
            }
        }
        end_menu();
    }
}

}  // namespace

void rendering_menu_items(RenderStyle& style, ViewSettings& settings, PanelState& panels,
                          const PanelEntries& entries, const RenderContext& render,
                          CommandQueue& commands) {
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
        if (const PanelEntry* edges = find_panel(entries, "collapsing-edges")) {
            menu_item("Collapsing edges", nullptr, edges->open);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("The edges the Decimation panel's next iteration collapses");
        }
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

void menu_bar(RenderStyle& style, ViewSettings& settings, PanelState& panels, const ToolList& tools,
              const MenuContext& context, const RenderContext& render, CommandQueue& commands) {
    PanelEntries entries;
    for (Tool* tool : tools)
        for (PanelEntry& entry : tool->panels()) entries.push_back(std::move(entry));
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
        if (menu_item("Open session...", nullptr, false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::OpenSession, "");
        if (menu_item("Save session...", nullptr, false, !context.busy))
            panels.file_browser.request(FileBrowserState::Purpose::SaveSession,
                                        context.document_path);
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
        panel_menu_items(entries, PanelMenu::Edit, context.busy, commands);
        end_menu();
    }
    view_menu(settings, commands);
    if (begin_menu("Tools")) {
        // Every tool from the registry: an action, or its section.
        panel_menu_items(entries, PanelMenu::Tools, context.busy, commands);
        end_menu();
    }
    if (begin_menu("Algorithms")) {
        panel_menu_items(entries, PanelMenu::Algorithms, context.busy, commands);
        end_menu();
    }
    if (begin_menu("Rendering")) {
        rendering_menu_items(style, settings, panels, entries, render, commands);
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
        reference_figures_menu(tools, context.busy, commands);
        menu_item("About trilab", nullptr, &panels.about_open);
        end_menu();
    }
    ImGui::EndMainMenuBar();
}

void reference_figures_menu(const ToolList& tools, bool busy, CommandQueue& commands) {
    if (!begin_menu("Reference figures")) return;
    ImGui::TextDisabled("the reference's figures: its models' stand-ins and its settings");
    for (const ReferenceFigure& f : reference_figures()) {
        const std::string label = f.name + "  " + f.title;
        if (menu_item(label.c_str(), nullptr, false, !busy)) {
            show_figure_in_panels(f, tools);
            commands.push_back(LoadFigure{f.name});
        }
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
            std::string tip = "the reference: " + f.reference + "\nhere: " + f.model_note;
            for (const std::string& s : f.setup) tip += "\nsetup: " + s;
            tip += "\nruns: " + f.operation;
            if (f.step > 0) tip += "\nstep: " + f.translation;
            ImGui::SetTooltip("%s", tip.c_str());
        }
    }
    end_menu();
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
                  const PanelEntries& entries, const RenderContext& render,
                  CommandQueue& commands) {
    if (panels.context_menu_requested) {
        ImGui::OpenPopup("##rendering_context");
        panels.context_menu_requested = false;
    }
    if (ImGui::BeginPopup("##rendering_context")) {
        rendering_menu_items(style, settings, panels, entries, render, commands);
        ImGui::EndPopup();
    }
}

}  // namespace trilab::viewer
