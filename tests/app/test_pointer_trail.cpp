// The pointer trail (app/viewer/pointer_trail.h): the mouse's events in order, where each
// happened, and the left drag the view replays from them (issue 38 item 5).
#include <catch2/catch.hpp>

#include "app/viewer/pointer_trail.h"

using namespace trilab::viewer;

TEST_CASE("A press, a drag and a release in one frame keep the press where it happened",
          "[pointer]") {
    PointerTrail trail;
    trail.move(100, 200);
    trail.button(0, true);  // pressed at (100, 200)
    for (int i = 1; i <= 6; ++i) trail.move(100 + 40 * i, 200);
    trail.button(0, false);  // released at (340, 200): where the cursor is by then
    const LeftDrag drag = left_drag(trail.take(), false);
    CHECK(drag.pressed);
    CHECK(drag.released);
    CHECK(drag.press_pos == glm::vec2(100, 200));
    REQUIRE(drag.path.size() == 7);  // six moves and the release
    CHECK(drag.path.front() == glm::vec2(140, 200));
    CHECK(drag.path.back() == glm::vec2(340, 200));
    CHECK(trail.take().empty());  // taken once
}

TEST_CASE("A drag's path continues across frames and ignores other buttons", "[pointer]") {
    PointerTrail trail;
    trail.move(10, 10);
    trail.button(1, true);  // right button: not the view's turn
    trail.move(20, 10);
    const LeftDrag none = left_drag(trail.take(), false);
    CHECK_FALSE(none.pressed);
    CHECK(none.path.empty());
    // The left button was down before this frame: every move is on its path.
    trail.move(30, 10);
    trail.move(40, 12);
    const LeftDrag held = left_drag(trail.take(), true);
    CHECK_FALSE(held.pressed);
    CHECK_FALSE(held.released);
    CHECK(held.path.size() == 2);
    // A second press in one frame: the newest drag counts.
    trail.button(0, true);
    trail.move(50, 10);
    trail.button(0, false);
    trail.move(60, 10);
    trail.button(0, true);
    trail.move(70, 10);
    const LeftDrag second = left_drag(trail.take(), false);
    CHECK(second.pressed);
    CHECK_FALSE(second.released);
    CHECK(second.press_pos == glm::vec2(60, 10));
    CHECK(second.path == std::vector<glm::vec2>{glm::vec2(70, 10)});
}

TEST_CASE("A very long trail merges its moves and keeps its buttons", "[pointer]") {
    PointerTrail trail;
    trail.button(0, true);
    for (int i = 0; i < 10000; ++i) trail.move(i, 0);
    trail.button(0, false);
    const std::vector<PointerEvent> events = trail.take();
    CHECK(events.size() <= PointerTrail::kMaxEvents + 1);
    const LeftDrag drag = left_drag(events, false);
    CHECK(drag.pressed);
    CHECK(drag.released);
    CHECK(drag.path.back() == glm::vec2(9999, 0));
}
