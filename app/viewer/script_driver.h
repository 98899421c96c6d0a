#pragma once
// ScriptDriver: scripted runs of the viewer (--frames with --op, --select, --brush, --lasso,
// --pick, --click, --sweep, --decompose, --figure, --orbit, --morph-t, --print-timing,
// --print-layout). It queues the same commands a user's clicks queue and moves the mouse as a
// user would; it decides when the last frame may be drawn (everything started has ended) and
// prints what scripts and tests read.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "app/viewer/tools.h"
#include "app/viewer/viewer_context.h"
#include "app/viewer/viewer_options.h"
#include "app/viewer/widgets.h"

struct GLFWwindow;

namespace trilab::viewer {

class SceneView;
class FrameOutput;

class ScriptDriver {
public:
    ScriptDriver(const ViewerOptions& options, ViewerContext& context, SceneView& scene,
                 Tools& tools, FrameOutput& output);
    ~ScriptDriver();
    ScriptDriver(const ScriptDriver&) = delete;
    ScriptDriver& operator=(const ScriptDriver&) = delete;

    /// Before a frame's UI: --select, --op, --decompose, --figure, --pick and --sweep in turn,
    /// each once what it waits for has ended.
    void advance();
    /// Before ImGui's frame: the mouse of --click and --lasso; after the UI: the commands a
    /// click queued; each frame's --brush step.
    void drive_mouse();
    void note_commands();
    void brush_step();
    /// Before the UI is rendered: the orbit's camera.
    void turn_camera();
    /// After each frame's swap: the sweep's, the orbit's and --print-timing's clocks.
    void frame_end(double frame_ms);
    /// The frame must be finished before it is timed.
    bool timing_frames() const;
    /// Whether the last frame may be drawn now (no job, preview, morph animation or scripted
    /// action still running). Finishes a playing morph, applies --morph-t.
    bool settled();
    /// The initial load was started by a --restore: --op waits for it.
    void restore_started() { initial_load_ended_ = false; }
    /// After the last frame: its log lines (the median frame time over `frames_timed`) and
    /// --print-timing.
    void finish(double median_frame_ms, std::size_t frames_timed);
    void print_layout(GLFWwindow* window) const;
    /// Quit now (a sweep ended, a scripted action failed) and the exit status (1 on failure).
    bool quit() const { return quit_; }
    int exit_status() const { return exit_status_; }

private:
    struct Sweep {
        bool active = false, waiting = false, started = false;
        bool lod = false;  ///< the level-of-detail slider ("decimate" with --param lod)
        Operation op, current;
        std::size_t param = 0;
        int next = 0;
        double t0 = 0;
        std::vector<double> ms;
    };
    struct ScriptedClicks {
        std::size_t next = 0;  ///< the click in progress
        int phase = 0;         ///< 0 find the widget, 1 hover, 2 press, 3 release, 4 report
        std::string target;    ///< what this press is for: the click's path or an opener
        bool opening = false;  ///< the press opens a section or menu on the way
        int openings = 0;      ///< for this click (bounded)
        /// Frames the target has been found disabled: a press waits a few for what is in
        /// flight to end (a job's result enables it), as a user would, before it fails.
        int disabled_frames = 0;
        int scrolls = 0;  ///< wheel steps taken to bring the target into view (bounded)
        float x = 0, y = 0;
        std::vector<WidgetNote> shown, drawing;  ///< last frame's widgets, this frame's
        std::vector<std::string> queued;         ///< commands the press queued
    };
    struct ScriptedBrush {
        int state = 0;  ///< 0 not started (or none), 1 dragging, 2 done
        glm::vec2 from{0.0f}, to{0.0f};
        int step = 0, steps = 24;
        int frames_waited = 0;  ///< frames drawn before it starts (the layout settles)
        double moved_at = -1;   ///< glfw time of the last move (-1: none waiting)
        std::vector<double> ms;
    };
    struct ScriptedLasso {
        int state = 0;                ///< 0 not started (or none), 1 drawing, 2 released, 3 done
        std::vector<glm::vec2> path;  ///< the mouse's window pixels, one per frame
        std::size_t step = 0;
        int frames_waited = 0;
    };
    struct Orbit {
        int frame = -1;  ///< -1: not started; 1..N: the orbit's frames; N + 1: resting
        Camera start;
        std::vector<double> ms;
        double motion_end = 0;  ///< glfw time at the end of the last orbit frame
        std::size_t proxy_frames = 0;
        bool done = false;
    };
    /// The initial load and --op are done and no job runs: scripted actions may start.
    bool ready() const;
    /// The orbit, its rest, the exact surface.
    bool motion_settled() const;
    void print_timing() const;
    void note_timing(double frame_ms);
    void log_last_frame(double median_frame_ms, std::size_t frames_timed);
    void advance_operations();
    bool next_selection();
    bool selections_pending() const;
    void start_sweep();
    void step_sweep(bool frame_shown);
    void drive_clicks();
    void fail_click(const std::string& why);
    bool clicks_pending() const { return clicks_.next < options_.clicks.size(); }
    void drive_lasso();
    void next_pick();
    bool picks_pending() const;
    void decompose();
    bool figure();
    std::vector<OperationPanelState*> operation_panels();

    const ViewerOptions& options_;
    ViewerContext& context_;
    Session& session_;
    SceneView& scene_;
    Tools& tools_;
    FrameOutput& output_;
    Sweep sweep_;
    ScriptedClicks clicks_;
    ScriptedBrush brush_;
    ScriptedLasso lasso_;
    Orbit orbit_;
    std::size_t next_select_ = 0, next_op_ = 0, next_pick_ = 0;
    bool initial_load_ended_ = true;  ///< options.mesh_path was read (or failed to be)
    bool initial_ops_done_ = false;   ///< every --op has been queued
    int decompose_state_ = 0;         ///< --decompose: 0 to do, 1 started, 2 done
    int figure_state_ = 0;            ///< --figure: 0 to do, 1 queued, 2 done
    bool morph_t_done_ = false;       ///< --morph-t has been applied
    double first_frame_ms_ = -1, exact_frame_ms_ = -1;  ///< --print-timing
    bool quit_ = false;
    int exit_status_ = 0;
};

}  // namespace trilab::viewer
