// Soft selections (core/algorithms/selection.h). Rings are one pass over the edges per ring
// (dilation: max, erosion: min, from the weights before the pass); the feather is one
// multi-source Dijkstra over the edge graph from the vertices of positive weight.
#include "core/algorithms/selection.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/algorithms/components.h"
#include "core/algorithms/geodesic.h"
#include "core/errors.h"
#include "core/number_text.h"

namespace trilab {
namespace {

void check_vertex(const HalfedgeMesh& mesh, Vertex v, const char* who) {
    if (!v.is_valid() || !mesh.is_valid(v))
        throw InvalidArgument(std::string(who) + ": vertex " +
                              (v.is_valid() ? std::to_string(v.idx()) : std::string("-1")) +
                              " is out of range (the mesh has " +
                              std::to_string(mesh.vertices_size()) + " vertices)");
    if (mesh.is_deleted(v))
        throw InvalidArgument(std::string(who) + ": vertex " + std::to_string(v.idx()) +
                              " is deleted");
}

void check_radius(double r, const char* who, const char* name) {
    if (!std::isfinite(r) || r < 0)
        throw InvalidArgument(std::string(who) + ": " + name +
                              " must be a finite number >= 0, got " + number_text(r));
}

void check_rings(int rings, const char* who) {
    if (rings < 0)
        throw InvalidArgument(std::string(who) + ": rings must be >= 0, got " +
                              std::to_string(rings));
}

/// One pass of a dilation (take = max) or erosion (take = min) over the edges.
template <class Take>
void ring_pass(const HalfedgeMesh& mesh, Selection& s, Take take) {
    const Selection before = s;
    for (Edge e : mesh.edges()) {
        const Halfedge h = HalfedgeMesh::halfedge(e, 0);
        const Index a = mesh.from_vertex(h).idx(), b = mesh.to_vertex(h).idx();
        s[a] = take(s[a], before[b]);
        s[b] = take(s[b], before[a]);
    }
}

}  // namespace

void check_selection(const HalfedgeMesh& mesh, const Selection& selection,
                     const std::string& what) {
    if (selection.size() != mesh.vertices_size())
        throw InvalidArgument(what + ": expected one weight per vertex (" +
                              std::to_string(mesh.vertices_size()) + "), got " +
                              std::to_string(selection.size()));
    for (std::size_t i = 0; i < selection.size(); ++i) {
        const float w = selection[i];
        if (!std::isfinite(w) || w < 0.0f || w > 1.0f)
            throw InvalidArgument(what + ": vertex " + std::to_string(i) +
                                  ": expected a weight from 0 to 1, got " + number_text(w));
    }
}

std::size_t count_selected(const Selection& selection) {
    return std::size_t(
        std::count_if(selection.begin(), selection.end(), [](float w) { return w > 0.0f; }));
}

bool selects_everything(const HalfedgeMesh& mesh, const Selection& selection) {
    if (selection.size() != mesh.vertices_size()) return false;
    for (Vertex v : mesh.vertices())
        if (selection[v.idx()] != 1.0f) return false;
    return true;
}

Selection empty_selection(const HalfedgeMesh& mesh) {
    return Selection(mesh.vertices_size(), 0.0f);
}

Selection full_selection(const HalfedgeMesh& mesh) {
    Selection s = empty_selection(mesh);
    for (Vertex v : mesh.vertices()) s[v.idx()] = 1.0f;
    return s;
}

Selection sphere_selection(const HalfedgeMesh& mesh, const Point& center, double radius) {
    check_radius(radius, "sphere selection", "radius");
    if (!center.allFinite()) throw InvalidArgument("sphere selection: the centre must be finite");
    Selection s = empty_selection(mesh);
    const double r2 = radius * radius;
    for (Vertex v : mesh.vertices())
        if ((mesh.position(v) - center).squaredNorm() <= r2) s[v.idx()] = 1.0f;
    return s;
}

Selection geodesic_selection(const HalfedgeMesh& mesh, Vertex center, double radius) {
    check_vertex(mesh, center, "geodesic selection");
    check_radius(radius, "geodesic selection", "radius");
    Selection s = empty_selection(mesh);
    if (mesh.is_isolated(center)) {
        s[center.idx()] = 1.0f;
        return s;
    }
    const std::vector<double> d = geodesic_distances(mesh, {center});
    for (Vertex v : mesh.vertices())
        if (d[v.idx()] <= radius) s[v.idx()] = 1.0f;
    return s;
}

Selection component_selection(const HalfedgeMesh& mesh, Vertex v) {
    check_vertex(mesh, v, "component selection");
    Selection s = empty_selection(mesh);
    if (mesh.is_isolated(v)) {
        s[v.idx()] = 1.0f;
        return s;
    }
    const ComponentLabels labels = label_face_components(mesh);
    const Index c = labels.of_vertex[v.idx()];
    for (Vertex w : mesh.vertices())
        if (labels.of_vertex[w.idx()] == c) s[w.idx()] = 1.0f;
    return s;
}

Selection threshold_selection(const HalfedgeMesh& mesh, const std::vector<double>& values,
                              double threshold, ThresholdSide side) {
    if (values.size() != mesh.vertices_size())
        throw InvalidArgument("threshold selection: expected one value per vertex (" +
                              std::to_string(mesh.vertices_size()) + "), got " +
                              std::to_string(values.size()));
    if (!std::isfinite(threshold))
        throw InvalidArgument("threshold selection: the threshold must be finite, got " +
                              number_text(threshold));
    Selection s = empty_selection(mesh);
    for (Vertex v : mesh.vertices()) {
        const double x = values[v.idx()];
        if (side == ThresholdSide::Above ? x > threshold : x < threshold) s[v.idx()] = 1.0f;
    }
    return s;
}

void grow_selection(const HalfedgeMesh& mesh, Selection& selection, int rings) {
    check_selection(mesh, selection, "grow selection");
    check_rings(rings, "grow selection");
    for (int r = 0; r < rings; ++r)
        ring_pass(mesh, selection, [](float a, float b) { return std::max(a, b); });
}

void shrink_selection(const HalfedgeMesh& mesh, Selection& selection, int rings) {
    check_selection(mesh, selection, "shrink selection");
    check_rings(rings, "shrink selection");
    for (int r = 0; r < rings; ++r)
        ring_pass(mesh, selection, [](float a, float b) { return std::min(a, b); });
}

void invert_selection(const HalfedgeMesh& mesh, Selection& selection) {
    check_selection(mesh, selection, "invert selection");
    for (Vertex v : mesh.vertices()) selection[v.idx()] = 1.0f - selection[v.idx()];
}

void feather_selection(const HalfedgeMesh& mesh, Selection& selection, double width) {
    check_selection(mesh, selection, "feather selection");
    check_radius(width, "feather selection", "width");
    if (width == 0) return;
    std::vector<Vertex> sources;
    for (Vertex v : mesh.vertices())
        if (selection[v.idx()] > 0.0f) sources.push_back(v);
    if (sources.empty()) return;
    const std::vector<double> d = edge_graph_distances(mesh, sources);
    for (Vertex v : mesh.vertices()) {
        const double t = d[v.idx()] / width;
        if (!(t < 1.0)) continue;  // at or beyond the width (or unreachable): no change
        const double falloff = 1.0 - t * t * (3.0 - 2.0 * t);
        float& w = selection[v.idx()];
        w = std::max(w, std::clamp(float(falloff), 0.0f, 1.0f));
    }
}

std::optional<Selection> stored_selection(const HalfedgeMesh& mesh) {
    const auto p = mesh.get_vertex_property<float>(kSelectionProperty);
    if (!p) return std::nullopt;
    return p.vector();
}

void store_selection(HalfedgeMesh& mesh, const Selection& selection) {
    check_selection(mesh, selection, "store selection");
    auto p = mesh.vertex_property<float>(kSelectionProperty, 0.0f);
    p.vector() = selection;
}

}  // namespace trilab
