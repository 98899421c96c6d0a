// Morphing (core/algorithms/morph.h): straight-line interpolation of vertex positions between two
// states of a mesh, drawn on the connectivity the correspondence names, plus the easing curves and
// playback clocks that animate it. Guarantees: t is clamped to [0, 1] (NaN reads as 0); the
// endpoints are copied, not computed, so t = 0 reproduces the earlier shape and t = 1 the later
// one bit for bit; a deleted vertex of the drawn mesh keeps that mesh's stored position;
// every function is O(vertices) and allocates only the returned positions.
#include "core/algorithms/morph.h"

#include <cmath>

#include "core/errors.h"

namespace trilab {
namespace {

using Kind = MorphCorrespondence::Kind;

const char* kind_name(Kind kind) {
    switch (kind) {
        case Kind::SameVertices:
            return "SameVertices";
        case Kind::FromEarlier:
            return "FromEarlier";
        case Kind::ToLater:
            return "ToLater";
    }
    return "?";
}

/// t clamped to [0, 1]; NaN gives 0.
double clamp01(double t) {
    if (!(t > 0)) return 0;
    return t < 1 ? t : 1;
}

/// Positions of `drawn` at time t between `from` (t = 0) and `to` (t = 1), both indexed by
/// the vertex storage index of `drawn`.
std::vector<Point> interpolate(const HalfedgeMesh& drawn, const std::vector<Point>& from,
                               const std::vector<Point>& to, double t) {
    if (t == 0 && !drawn.has_garbage()) return from;
    if (t == 1 && !drawn.has_garbage()) return to;
    const std::vector<Point>& stored = drawn.positions();
    std::vector<Point> out(stored.size());
    const double s = 1 - t;
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (drawn.is_deleted(Vertex(Index(i))))
            out[i] = stored[i];
        else if (t == 0)
            out[i] = from[i];
        else if (t == 1)
            out[i] = to[i];
        else
            out[i] = s * from[i] + t * to[i];
    }
    return out;
}

}  // namespace

void check_correspondence(const HalfedgeMesh& before, const HalfedgeMesh& after,
                          const MorphCorrespondence& correspondence) {
    const std::string what = std::string("morph (") + kind_name(correspondence.kind) + "): ";
    const std::size_t n = correspondence.positions.size();
    switch (correspondence.kind) {
        case Kind::SameVertices:
            if (before.vertices_size() != after.vertices_size())
                throw InvalidArgument(
                    what + "the earlier mesh stores " + std::to_string(before.vertices_size()) +
                    " vertices but the later one " + std::to_string(after.vertices_size()));
            return;  // positions are not used
        case Kind::FromEarlier:
            if (n != after.vertices_size())
                throw InvalidArgument(what + std::to_string(n) +
                                      " start positions for a later mesh of " +
                                      std::to_string(after.vertices_size()) + " vertices");
            break;
        case Kind::ToLater:
            if (n != before.vertices_size())
                throw InvalidArgument(what + std::to_string(n) +
                                      " end positions for an earlier mesh of " +
                                      std::to_string(before.vertices_size()) + " vertices");
            break;
        default:
            throw InvalidArgument(what + "unknown correspondence kind");
    }
    for (std::size_t i = 0; i < n; ++i) {
        const Point& p = correspondence.positions[i];
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
            throw InvalidArgument(what + "position " + std::to_string(i) + " is not finite");
    }
}

MorphFrame morph_frame(const HalfedgeMesh& before, const HalfedgeMesh& after,
                       const MorphCorrespondence& correspondence, double t) {
    check_correspondence(before, after, correspondence);
    t = clamp01(t);
    MorphFrame frame;
    switch (correspondence.kind) {
        case Kind::SameVertices:
            frame.topology = &after;
            frame.positions = interpolate(after, before.positions(), after.positions(), t);
            break;
        case Kind::FromEarlier:
            frame.topology = &after;
            frame.positions = interpolate(after, correspondence.positions, after.positions(), t);
            break;
        case Kind::ToLater:
            if (t >= 1) {
                frame.topology = &after;
                frame.positions = after.positions();
            } else {
                frame.topology = &before;
                frame.positions =
                    interpolate(before, before.positions(), correspondence.positions, t);
            }
            break;
    }
    return frame;
}

double ease(Easing easing, double t) {
    t = clamp01(t);
    switch (easing) {
        case Easing::Linear:
            return t;
        case Easing::SmoothStep:
            return t * t * (3 - 2 * t);
        case Easing::EaseInOutCubic:
            if (t < 0.5) return 4 * t * t * t;
            {
                const double u = 2 - 2 * t;  // in [0, 1]
                return 1 - 0.5 * u * u * u;
            }
    }
    return t;
}

const char* easing_name(Easing easing) {
    return enum_id<Easing>(kEasings, easing);
}

Easing parse_easing(const std::string& name) {
    return parse_enum<Easing>(kEasings, name, "easing");
}

double playback_time(Playback playback, double elapsed, double duration) {
    if (!(duration > 0) || !std::isfinite(duration)) return 1;
    if (std::isnan(elapsed)) return 0;
    const double x = elapsed / duration;  // in periods; may be infinite
    switch (playback) {
        case Playback::Once:
            return clamp01(x);
        case Playback::Loop: {
            if (!std::isfinite(x)) return 0;
            const double f = x - std::floor(x);
            return f < 1 ? f : 0;  // guards rounding of tiny negative x
        }
        case Playback::PingPong: {
            if (!std::isfinite(x)) return 0;
            double f = x - 2 * std::floor(0.5 * x);  // in [0, 2]
            if (f >= 2) f = 0;
            return f <= 1 ? f : 2 - f;
        }
    }
    return clamp01(x);
}

const char* playback_name(Playback playback) {
    return enum_id<Playback>(kPlaybacks, playback);
}

Playback parse_playback(const std::string& name) {
    return parse_enum<Playback>(kPlaybacks, name, "playback");
}

}  // namespace trilab
