#include "app/viewer/pointer_trail.h"

namespace trilab::viewer {

void PointerTrail::move(double x, double y) {
    last_ = glm::vec2(float(x), float(y));
    // A long trail keeps its presses and releases; consecutive moves merge into the newest.
    if (events_.size() >= kMaxEvents && events_.back().kind == PointerEvent::Kind::Move) {
        events_.back().pos = last_;
        return;
    }
    events_.push_back({PointerEvent::Kind::Move, 0, last_});
}

void PointerTrail::button(int button, bool pressed) {
    events_.push_back(
        {pressed ? PointerEvent::Kind::Press : PointerEvent::Kind::Release, button, last_});
}

std::vector<PointerEvent> PointerTrail::take() {
    std::vector<PointerEvent> out;
    out.swap(events_);
    return out;
}

LeftDrag left_drag(const std::vector<PointerEvent>& events, bool down_before) {
    LeftDrag drag;
    bool down = down_before;
    for (const PointerEvent& e : events) {
        if (e.kind == PointerEvent::Kind::Press && e.button == 0) {
            if (drag.pressed) drag.path.clear();  // a second press: the newest drag counts
            drag.pressed = true;
            drag.released = false;
            drag.press_pos = e.pos;
            down = true;
        } else if (e.kind == PointerEvent::Kind::Release && e.button == 0) {
            if (down) drag.path.push_back(e.pos);
            drag.released = true;
            down = false;
        } else if (e.kind == PointerEvent::Kind::Move && down) {
            drag.path.push_back(e.pos);
        }
    }
    return drag;
}

}  // namespace trilab::viewer
