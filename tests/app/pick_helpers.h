#pragma once
// Picking in the session tests: PickAt, and the pick it made (nullopt for a miss).
#include <cstdint>
#include <optional>

#include "app/session/session.h"

namespace trilab::viewer {

/// Executes PickAt{ray, 0, second} on `s`: the hit (the new first or second pick), or nullopt
/// when the ray missed (the picks are cleared) or the pick failed.
inline std::optional<Pick> pick(Session& s, const Ray& ray, bool second) {
    const std::uint64_t version = s.picking().picks().version;
    s.execute(PickAt{ray, 0.0, second});
    const PickSet& picks = s.picking().picks();
    if (picks.version == version || picks.picks.empty()) return std::nullopt;
    return picks.picks.back();
}

}  // namespace trilab::viewer
