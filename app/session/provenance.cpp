// Provenance of a vertex along the history (app/session/provenance.h).
#include "app/session/provenance.h"

#include <cmath>
#include <limits>

#include "core/algorithms/decimation.h"
#include "core/algorithms/subdivision.h"

namespace trilab::viewer {
namespace {

/// Follows `v` of `after` back to `before` (one step): its index there and where the step
/// started it from. False when the step cannot be followed.
bool step_back(const HalfedgeMesh& before, const HalfedgeMesh& after, Vertex& v, Point& from) {
    if (!after.is_valid(v)) return false;
    const bool same_elements = after.topology_revision() == before.topology_revision() &&
                               after.vertices_size() == before.vertices_size();
    if (same_elements) {
        from = before.position(v);
        return true;
    }
    // Decimation first: its output may also carry an older subdivision's attributes.
    if (after.has_vertex_property(kDecimationSourceName)) {
        const auto source = after.get_vertex_property<Index>(kDecimationSourceName);
        const Vertex s(source[v]);
        if (before.is_valid(s) && after.vertices_size() < before.vertices_size()) {
            v = s;
            from = before.position(s);
            return true;
        }
    }
    if (after.has_vertex_property("v:subdivision_parents")) {
        const auto parents = after.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
        const SubdivisionParents& p = parents[v];
        Point sum = Point::Zero();
        int n = 0;
        for (int k = 0; k < 3; ++k)
            if (p[k] != kInvalidIndex && before.is_valid(Vertex(p[k]))) {
                sum += before.position(Vertex(p[k]));
                ++n;
            }
        if (n == 0 || after.vertices_size() <= before.vertices_size()) return false;
        v = Vertex(p[0]);
        from = sum / double(n);
        return true;
    }
    return false;
}

}  // namespace

std::vector<double> vertex_moves(const History& history, Vertex v) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> moved(history.size(), nan);
    if (history.size() == 0) return moved;
    std::size_t entry = history.current();
    HalfedgeMesh after = history.mesh(entry, history.info(entry).steps.size() - 1);
    if (!after.is_valid(v)) return moved;
    while (entry > 0) {
        const History::EntryInfo info = history.info(entry);
        const Point end = after.position(v);
        Point from = end;
        bool followed = true;
        // Back through the entry's steps, then to the previous entry's last step.
        for (std::size_t step = info.steps.size(); step-- > 0 && followed;) {
            HalfedgeMesh before =
                step > 0 ? history.mesh(entry, step - 1)
                         : history.mesh(entry - 1, history.info(entry - 1).steps.size() - 1);
            Point start;
            followed = step_back(before, after, v, start);
            if (followed && step == 0) from = start;
            after = std::move(before);
        }
        if (!followed) break;
        moved[entry] = (end - from).norm();
        --entry;
    }
    return moved;
}

}  // namespace trilab::viewer
