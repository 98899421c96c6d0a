#pragma once
// The viewer's command-line options (main.cpp reads them; kUsage there lists them).
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace trilab::viewer {

/// Command-line options (see kUsage in main.cpp).
struct ViewerOptions {
    std::string mesh_path;   ///< empty: the built-in default model
    int frames = 0;          ///< > 0: render that many frames, then return 0
    int close_after = 0;     ///< > 0: press the window's close button after that many frames
    std::string screenshot;  ///< non-empty: write the last frame (before the swap) as PNG
    /// Print "framebuffer W H", "view X Y W H" and one `window "TITLE" X Y W H` line per
    /// visible window after the last frame (framebuffer pixels).
    bool print_layout = false;
    float ui_scale = 0;     ///< > 0: the UI (font) scale instead of the monitor's
    std::string wireframe;  ///< "on", "off" or "auto" (default)
    double morph_t = -1;    ///< in [0, 1]: show the current entry's morph at this time
    int width = 1280;       ///< window size in screen coordinates
    int height = 800;
    std::string mode;   ///< initial render mode name (render_mode_name()), empty: default
    std::string color;  ///< initial vertex colouring name (coloring_name()), empty: none
    /// --op (repeatable): operations applied after loading, in order, each once the one
    /// before has finished.
    std::vector<std::string> operations;
    std::string save_session;  ///< --save-session: write the session there after the last frame
    bool restore = false;      ///< --restore: restore the newest crash journal without asking
    bool no_recovery = false;  ///< --no-recovery: no crash journal, no recovery question
    std::string show;          ///< panels to open at start, comma-separated
    int memory_budget_mb = 0;  ///< the history's budget; 0: a quarter of the RAM
    std::string decompose;     ///< "K" or "K:LO:HI": Frequency panel Decompose (and a band)
    std::string up;            ///< "y" or "z": the up axis for this run; empty: the remembered one
    /// --sweep OP --param NAME --range FROM:TO:COUNT: preview OP with NAME at COUNT evenly
    /// spaced values, print "sweep: previews=N median_ms=X max_ms=Y" and exit.
    std::string sweep_op, sweep_param;
    /// --click "SECTION/LABEL" (repeatable): widgets to press, in order, after --op.
    std::vector<std::string> clicks;
    /// --pick X,Y (repeatable): window pixels to pick once the model is shown; the second
    /// measures from the first.
    std::vector<std::string> picks;
    double sweep_from = 0, sweep_to = 0;
    int sweep_count = 0;
    /// --select SPEC (repeatable): selections set once the model is shown (issue 26).
    std::vector<std::string> selections;
    std::string brush;          ///< --brush "X0,Y0:X1,Y1[:R]": a scripted brush drag
    std::string lasso;          ///< --lasso "X0,Y0:X1,Y1:X2,Y2[:...][:through]": one lasso
    std::string figure;         ///< --figure NAME: a reference figure's mesh and settings
    int orbit_frames = 0;       ///< --orbit N: one scripted turn around the model in N frames
    bool print_timing = false;  ///< --print-timing: first and first exact frame times
};

/// Reads --lasso's "X0,Y0:X1,Y1:X2,Y2[:...][:through]" into the polygon's window pixels (at
/// least three finite points) and whether it selects through the model. Returns "" on
/// success, else what is wrong (the caller names the option).
std::string parse_lasso_script(const std::string& text, std::vector<glm::vec2>& points,
                               bool& through);

}  // namespace trilab::viewer
