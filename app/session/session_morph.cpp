// The morph playback; see session_morph.h.
#include "app/session/session_morph.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace trilab::viewer {

bool SessionMorph::execute(const Command& command) {
    MorphState& morph = core_.morph;
    if (auto* play = std::get_if<PlayMorph>(&command)) {
        if (play->play && !morph.playing) {
            // A pass from the start, on the session's clock.
            morph.playing = true;
            morph.play_start = core_.now();
        } else if (!play->play) {
            morph.playing = false;
        }
    } else if (auto* at = std::get_if<ShowMorphAt>(&command)) {
        morph.t = std::isfinite(at->t) ? std::clamp(at->t, 0.0, 1.0) : 1.0;
        morph.playing = false;
    } else if (auto* a = std::get_if<SetMorphAnimation>(&command)) {
        if (std::isfinite(a->duration) && a->duration > 0) morph.duration = a->duration;
        morph.easing = a->easing;
        morph.playback = a->playback;
    } else {
        return false;
    }
    return true;
}

void SessionMorph::reset(bool moves) {
    const MorphState& m = core_.morph;
    core_.morph = MorphState{1.0, false, m.duration, m.easing, m.playback, 0.0, moves};
}

void SessionMorph::update() {
    MorphState& morph = core_.morph;
    const std::size_t entry = core_.document.history.current();
    if (morph.playing) {
        morph.t = playback_time(morph.playback, core_.now() - morph.play_start, morph.duration);
        if (morph.playback == Playback::Once && morph.t >= 1.0) morph.playing = false;
    }
    const bool morphing = entry > 0 && (morph.playing || morph.t < 1.0);
    if (!morphing) {
        if (core_.shown.kind != Shown::Kind::Document) core_.show_document();
        return;
    }
    try {
        MorphFrame frame = core_.document.history.morph(entry, ease(morph.easing, morph.t));
        Shown& shown = core_.shown;
        shown.kind = Shown::Kind::Morph;
        shown.mesh = frame.topology;
        shown.positions = std::move(frame.positions);
        shown.level = nullptr;
        core_.bump();
    } catch (const std::exception& e) {
        reset(morph.moves);
        core_.notify_error(std::string("morph: ") + e.what());
        core_.show_document();
    }
}

}  // namespace trilab::viewer
