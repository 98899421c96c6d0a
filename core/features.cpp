#include "core/features.h"

#include <cmath>

#include "core/errors.h"
#include "core/number_text.h"

namespace trilab {

bool has_features(const HalfedgeMesh& mesh) {
    if (const auto s = mesh.get_edge_property<float>(kSharpnessProperty))
        for (Edge e : mesh.edges())
            if (s[e] > 0.0f) return true;
    if (const auto c = mesh.get_vertex_property<std::uint8_t>(kCornerProperty))
        for (Vertex v : mesh.vertices())
            if (c[v] != 0) return true;
    return false;
}

void clear_features(HalfedgeMesh& mesh) {
    if (mesh.has_edge_property(kSharpnessProperty)) mesh.remove_edge_property(kSharpnessProperty);
    if (mesh.has_vertex_property(kCornerProperty)) mesh.remove_vertex_property(kCornerProperty);
}

EdgeProperty<float> sharpness_property(HalfedgeMesh& mesh) {
    if (mesh.has_edge_property(kSharpnessProperty) &&
        !mesh.get_edge_property<float>(kSharpnessProperty))
        throw InvalidArgument(std::string("edge property '") + kSharpnessProperty +
                              "' exists with a type other than float");
    return mesh.edge_property<float>(kSharpnessProperty, 0.0f);
}

VertexProperty<std::uint8_t> corner_property(HalfedgeMesh& mesh) {
    if (mesh.has_vertex_property(kCornerProperty) &&
        !mesh.get_vertex_property<std::uint8_t>(kCornerProperty))
        throw InvalidArgument(std::string("vertex property '") + kCornerProperty +
                              "' exists with a type other than uint8");
    return mesh.vertex_property<std::uint8_t>(kCornerProperty, 0);
}

void set_sharpness(HalfedgeMesh& mesh, Edge e, float s) {
    if (!e.is_valid() || e.idx() >= mesh.edges_size() || mesh.is_deleted(e))
        throw InvalidArgument("set_sharpness: edge " + std::to_string(e.idx()) +
                              " does not exist (the mesh has " + std::to_string(mesh.edges_size()) +
                              " edges)");
    if (!valid_sharpness(s))
        throw InvalidArgument("set_sharpness: sharpness of edge " + std::to_string(e.idx()) +
                              " must be >= 0 or inf (got " + number_text(s) + ")");
    sharpness_property(mesh)[e] = s;
}

float sharpness(const HalfedgeMesh& mesh, Edge e) {
    const auto s = mesh.get_edge_property<float>(kSharpnessProperty);
    return s ? s[e] : 0.0f;
}

bool is_corner_tagged(const HalfedgeMesh& mesh, Vertex v) {
    const auto c = mesh.get_vertex_property<std::uint8_t>(kCornerProperty);
    return c && c[v] != 0;
}

std::string check_features(const HalfedgeMesh& mesh) {
    if (mesh.has_edge_property(kSharpnessProperty)) {
        const auto s = mesh.get_edge_property<float>(kSharpnessProperty);
        if (!s) return std::string("edge property '") + kSharpnessProperty + "' is not float";
        const std::vector<float>& v = s.vector();
        if (v.size() != mesh.edges_size())
            return "sharpness array has " + std::to_string(v.size()) + " values for " +
                   std::to_string(mesh.edges_size()) + " edges";
        for (std::size_t e = 0; e < v.size(); ++e)
            if (!valid_sharpness(v[e]))
                return "edge " + std::to_string(e) + ": sharpness " + number_text(v[e]) +
                       " is not >= 0 (or inf)";
    }
    if (mesh.has_vertex_property(kCornerProperty)) {
        const auto c = mesh.get_vertex_property<std::uint8_t>(kCornerProperty);
        if (!c) return std::string("vertex property '") + kCornerProperty + "' is not uint8";
        const std::vector<std::uint8_t>& v = c.vector();
        if (v.size() != mesh.vertices_size())
            return "corner tag array has " + std::to_string(v.size()) + " values for " +
                   std::to_string(mesh.vertices_size()) + " vertices";
        for (std::size_t i = 0; i < v.size(); ++i)
            if (v[i] > 1)
                return "vertex " + std::to_string(i) + ": corner tag " + std::to_string(v[i]) +
                       " is not 0 or 1";
    }
    return {};
}

const char* vertex_class_name(VertexClass c) {
    switch (c) {
        case VertexClass::Smooth:
            return "smooth";
        case VertexClass::Dart:
            return "dart";
        case VertexClass::Crease:
            return "crease";
        case VertexClass::Corner:
            return "corner";
    }
    return "smooth";
}

VertexClassification classify_vertices(const HalfedgeMesh& mesh, bool boundary_is_sharp) {
    VertexClassification out;
    out.classes.assign(mesh.vertices_size(), VertexClass::Smooth);
    std::vector<std::uint8_t> count(mesh.vertices_size(), 0);
    const auto s = mesh.get_edge_property<float>(kSharpnessProperty);
    for (Edge e : mesh.edges()) {
        const bool sharp = (s && s[e] > 0.0f) || (boundary_is_sharp && mesh.is_boundary(e));
        if (!sharp) continue;
        for (int k = 0; k < 2; ++k) {
            std::uint8_t& c = count[mesh.to_vertex(mesh.halfedge(e, k)).idx()];
            if (c < 3) ++c;
        }
    }
    const auto tag = mesh.get_vertex_property<std::uint8_t>(kCornerProperty);
    for (Vertex v : mesh.vertices()) {
        const bool tagged = tag && tag[v] != 0;
        const VertexClass c = tagged ? VertexClass::Corner : VertexClass(count[v.idx()]);
        out.classes[v.idx()] = c;
        switch (c) {
            case VertexClass::Smooth:
                ++out.smooth;
                break;
            case VertexClass::Dart:
                ++out.darts;
                break;
            case VertexClass::Crease:
                ++out.creases;
                break;
            case VertexClass::Corner:
                ++out.corners;
                if (tagged && count[v.idx()] < 3) ++out.tagged_corners;
                break;
        }
    }
    return out;
}

std::string feature_save_note(const HalfedgeMesh& mesh, bool format_keeps_features) {
    if (format_keeps_features || !has_features(mesh)) return {};
    std::size_t edges = 0, corners = 0;
    if (const auto s = mesh.get_edge_property<float>(kSharpnessProperty))
        for (Edge e : mesh.edges()) edges += s[e] > 0.0f ? 1 : 0;
    if (const auto c = mesh.get_vertex_property<std::uint8_t>(kCornerProperty))
        for (Vertex v : mesh.vertices()) corners += c[v] != 0 ? 1 : 0;
    return "features not saved (the format has no edges): " +
           count_text(edges, "sharp edge", "sharp edges") + ", " +
           count_text(corners, "corner tag", "corner tags") + " dropped; use .ply or .om";
}

}  // namespace trilab
