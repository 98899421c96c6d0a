#pragma once
// SessionMorph: the current history entry's morph, played on the session's clock: the
// commands that play, stop, scrub and set up the animation (PlayMorph, ShowMorphAt,
// SetMorphAnimation), and each frame's shown state (a morph frame, or the document at rest).
#include "app/session/commands.h"
#include "app/session/session_core.h"

namespace trilab::viewer {

class SessionMorph {
public:
    explicit SessionMorph(SessionCore& core) : core_(core) {}

    /// Carries out a morph command; false: not one.
    bool execute(const Command& command);
    /// Advances the playback and shows its frame (or the document once it ends).
    void update();
    /// The playback at rest at the end of a new current entry that moves (or not) its vertices.
    void reset(bool moves);

private:
    SessionCore& core_;
};

}  // namespace trilab::viewer
