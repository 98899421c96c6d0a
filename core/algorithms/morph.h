#pragma once
// Morphing between two states of a mesh, defined once for every operation.
//
// An operation that turns mesh A (before) into mesh B (after) records how their vertices
// correspond, in one of three ways:
//  - SameVertices: B has A's vertices (a geometry-only change); the morph interpolates
//    A's positions to B's on B's connectivity.
//  - FromEarlier: B's connectivity is new (subdivision); `positions` gives, for every vertex
//    of B (storage index), where it starts on A's surface (e.g. a new vertex at its parent
//    edge's midpoint). The morph draws B with positions going from `positions` to B's.
//  - ToLater: B is coarser (decimation); `positions` gives, for every vertex of A, where it
//    ends on B's surface (a collapsed vertex at its collapse target). The morph draws A (a
//    geomorph on the finer mesh) with positions going from A's to `positions`, and B itself
//    at t = 1.
// morph_frame() evaluates any of them at t in [0, 1]; t = 0 gives A's shape and t = 1 B's.
#include <string>
#include <vector>

#include "core/enum_table.h"
#include "core/halfedge_mesh.h"

namespace trilab {

struct MorphCorrespondence {
    enum class Kind { SameVertices, FromEarlier, ToLater };
    Kind kind = Kind::SameVertices;
    /// FromEarlier: one start position per vertex of the later mesh (storage index).
    /// ToLater: one end position per vertex of the earlier mesh (storage index).
    std::vector<Point> positions;
};

/// What to draw at one moment of a morph: which mesh's connectivity, with which positions
/// (one per vertex storage index of that mesh).
struct MorphFrame {
    const HalfedgeMesh* topology = nullptr;
    std::vector<Point> positions;
};

/// The morph from `before` to `after` at t (clamped to [0, 1]). Throws InvalidArgument when
/// the correspondence does not fit the meshes (sizes), naming what is wrong.
MorphFrame morph_frame(const HalfedgeMesh& before, const HalfedgeMesh& after,
                       const MorphCorrespondence& correspondence, double t);
/// Checks that `correspondence` fits the meshes; throws InvalidArgument otherwise.
void check_correspondence(const HalfedgeMesh& before, const HalfedgeMesh& after,
                          const MorphCorrespondence& correspondence);

enum class Easing { Linear, SmoothStep, EaseInOutCubic };
/// The one table of Easing (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<Easing> kEasings[] = {
    {Easing::Linear, "linear", "Linear"},
    {Easing::SmoothStep, "smooth-step", "Smooth step"},
    {Easing::EaseInOutCubic, "ease-in-out-cubic", "Cubic"},
};
/// The eased time for t in [0, 1] (ease(e, 0) = 0, ease(e, 1) = 1, monotone).
double ease(Easing easing, double t);
/// "linear", "smooth-step", "ease-in-out-cubic".
const char* easing_name(Easing easing);
/// The easing of that name (as easing_name() writes it). Throws InvalidArgument listing them.
Easing parse_easing(const std::string& name);

/// Playback of an animation of `duration` seconds: the morph time at `elapsed` seconds,
/// once (clamped), looping, or ping-pong.
enum class Playback { Once, Loop, PingPong };
/// The one table of Playback (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<Playback> kPlaybacks[] = {
    {Playback::Once, "once", "Once"},
    {Playback::Loop, "loop", "Loop"},
    {Playback::PingPong, "ping-pong", "Ping-pong"},
};
/// A duration <= 0 (or not finite) gives 1, the end of the morph; a NaN elapsed time gives 0.
double playback_time(Playback playback, double elapsed, double duration);
/// "once", "loop", "ping-pong".
const char* playback_name(Playback playback);
/// The playback of that name (as playback_name() writes it). Throws InvalidArgument otherwise.
Playback parse_playback(const std::string& name);

}  // namespace trilab
