#pragma once
// PointerTrail: the mouse's events as the window system delivered them, in order, with the
// position each happened at. ImGui 1.86 reads the mouse once a frame (its position then,
// and whether a button went down since the last frame), so a press, a drag and a release
// that all happen during one slow frame (an exact frame of a 17.8M-face mesh takes 2 s in a
// software renderer) reach it as a click where the cursor is by then. The viewer replays the
// trail instead: the press where it happened, the drag along its path. Pure logic: the GLFW
// callbacks feed it (viewer.cpp); tests feed it directly.
#include <vector>

#include <glm/glm.hpp>

namespace trilab::viewer {

struct PointerEvent {
    enum class Kind { Move, Press, Release };
    Kind kind = Kind::Move;
    int button = 0;    ///< GLFW's button number (Press, Release)
    glm::vec2 pos{0};  ///< window coordinates, where it happened
};

class PointerTrail {
public:
    /// The cursor moved to (x, y), window coordinates.
    void move(double x, double y);
    /// A button went down (`pressed`) or up, where the cursor was last seen.
    void button(int button, bool pressed);
    /// The events since the last take(), oldest first (at most kMaxEvents: the oldest moves
    /// of a longer trail are merged).
    std::vector<PointerEvent> take();

    static constexpr std::size_t kMaxEvents = 4096;

private:
    std::vector<PointerEvent> events_;
    glm::vec2 last_{0};
};

/// What the view does with one frame's trail for the left button: where a press happened,
/// the path the cursor took while the button was down, and whether it was released.
struct LeftDrag {
    bool pressed = false;    ///< a press of the left button is in the trail
    glm::vec2 press_pos{0};  ///< where (window coordinates)
    /// The cursor's positions while the left button was down (after the press, or through the
    /// whole trail when it was down before), release position included.
    std::vector<glm::vec2> path;
    bool released = false;  ///< a release of the left button is in the trail
};
LeftDrag left_drag(const std::vector<PointerEvent>& events, bool down_before);

}  // namespace trilab::viewer
