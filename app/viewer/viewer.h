#pragma once
// Viewer: the trilab window. Owns the GLFW window and GL context, the ImGui layer and the
// frame loop, and the owners of everything else: the shared context (the session, the view,
// the command queue, the panels), the scene (SceneView: what is drawn), the tools (each with
// its derived displays, overlays and mouse handling), the scripted-run driver and the picture
// output. Panels and tools queue commands; the viewer carries out the window's own commands
// and hands the rest to the session, so loading, fitting and quitting happen in one place.
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/frame_output.h"
#include "app/viewer/pointer_trail.h"
#include "app/viewer/scene_view.h"
#include "app/viewer/script_driver.h"
#include "app/viewer/tools.h"
#include "app/viewer/viewer_context.h"
#include "app/viewer/viewer_options.h"

struct GLFWwindow;

namespace trilab::viewer {

class Viewer {
public:
    /// Opens the window, creates the GL context and ImGui, uploads the default model and,
    /// when options.mesh_path is set, loads that file (a load error becomes a notice, not an
    /// exception). Throws trilab::Error when no window or GL 3.3 core context can be had or
    /// the shaders fail.
    explicit Viewer(ViewerOptions options);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    /// Runs until the window closes, Quit, or options.frames frames. Returns the exit status:
    /// 0, or 1 when the screenshot cannot be written or a scripted action failed.
    int run();

private:
    struct GlfwLibrary;
    struct WindowDeleter {
        void operator()(GLFWwindow* window) const;
    };
    struct ImGuiLayer;
    /// A key press as GLFW reported it. Shortcuts are read from these rather than from
    /// ImGui's key state, which (before ImGui 1.87) misses a press and release that fall
    /// into the same frame.
    struct KeyPress {
        int key;
        int mods;
    };

    static GLFWwindow* create_window(const ViewerOptions& options, Viewer* viewer);
    static Viewer* from(GLFWwindow* window);
    static void wake(GLFWwindow* window);

    /// Before a frame: finished jobs, what the session did, the scripted actions; returns
    /// whether it waited for a job (a scripted run's initial load).
    bool prepare_frame();
    /// One frame's UI, its commands and the scene (not swapped yet); returns whether
    /// commands ran.
    bool draw_frame();
    /// The mouse in the view (the tools first, then the camera), dropped files, the keys.
    /// Turns the view along a left drag's path (pointer_trail.h), past the click's slop.
    void turn_along(const std::vector<glm::vec2>& path, const glm::vec2& origin);
    void handle_input();
    void draw_ui();
    void render_scene();
    /// Carries out a command: the window's own here, the document's in the session.
    void execute(const Command& command);
    /// Follows what the session did: recolour, fit, title, recent files, texture, the
    /// unsaved-changes question's next step.
    void follow_session();
    /// Whether a Quit may go ahead now; when changes are unsaved it asks instead (false).
    bool confirm_quit();
    /// Opens the unsaved-changes question before quitting or opening `path`.
    void ask_before_discarding(bool quitting, const std::string& path, bool recover = false);
    void fit_view();
    /// The default view for the up axis (View > Default view, View > Up axis), fitted; a new
    /// up axis is remembered, and spherical texture coordinates the viewer projected follow it.
    void reset_view();
    /// Model and scene information, for the Info panel and the `I` key.
    std::vector<std::string> scene_info() const;
    /// The median wall time of the most recent frames; with `simplified` set, of those among
    /// them that drew the stand-in (true) or the exact surface (false) only.
    double frame_ms(std::optional<bool> simplified = std::nullopt) const;

    // Sessions and the crash journal (viewer_session.cpp).
    /// The view, panels and texture a session file stores beside the history.
    SessionExtras session_extras() const;
    /// Applies an opened session's extras (settings that cannot be applied become log notes).
    void apply_session_extras(const SessionExtras& extras);
    /// Starts the journal and looks for the journals of viewers that did not exit cleanly:
    /// --restore restores the newest, an interactive run asks, a scripted run logs it.
    void start_recovery();
    /// Each frame: the settings into the journal when they changed (at most once a second),
    /// and the journal's warning, once.
    void journal_settings();
    /// --save-session: writes the session now; returns an error message or "".
    std::string save_session_now();

    ViewerOptions options_;
    std::unique_ptr<GlfwLibrary> glfw_;
    std::unique_ptr<GLFWwindow, WindowDeleter> window_;
    std::unique_ptr<ImGuiLayer> imgui_;
    ViewerContext context_;
    std::unique_ptr<SceneView> scene_;
    Tools tools_;
    std::unique_ptr<FrameOutput> output_;
    std::unique_ptr<ScriptDriver> script_;
    RecentFiles recent_;
    Preferences preferences_;                 ///< remembered settings (interactive sessions only)
    std::vector<KeyPress> key_presses_;       ///< since the last frame
    std::vector<std::string> dropped_paths_;  ///< files dropped on the window since the last frame
    PointerTrail pointer_trail_;  ///< the mouse's events since the last frame (GLFW's callbacks)
    bool left_down_ = false;      ///< the left button is down, by the trail's events
    glm::vec2 drag_last_{0.0f};   ///< the left drag's last position (view coordinates)
    glm::vec2 press_pos_{0.0f};   ///< where the left button went down (a click picks)
    bool turning_ = false;        ///< the left drag has moved past the click's slop
    bool drag_in_view_ = false;   ///< the mouse drag began in the view
    bool quit_ = false;
    std::string journaled_settings_;     ///< the settings text last given to the journal
    double settings_journaled_at_ = -1;  ///< Session::now() of that
    /// Wall time of the most recent frames (events excluded), for a median that ignores the
    /// slow first frame (shader compilation, font upload).
    /// Each with whether it drew the stand-in (the status bar times frames of the kind on the
    /// screen: turning a large mesh is not timed by its last exact frame).
    std::array<std::pair<double, bool>, 15> frame_times_ms_{};
    std::size_t n_frame_times_ = 0;
};

}  // namespace trilab::viewer
