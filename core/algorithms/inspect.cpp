// The inspector (core/algorithms/inspect.h): every number from the function that computes it
// elsewhere, then the fields the panel and the CLI print.
#include "core/algorithms/inspect.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <thread>

#include "core/algorithms/components.h"
#include "core/algorithms/curvature.h"
#include "core/algorithms/laplacian.h"
#include "core/algorithms/mesh_distance.h"
#include "core/algorithms/mesh_quality.h"
#include "core/algorithms/texcoords.h"
#include "core/errors.h"
#include "core/geometry.h"
#include "core/mesh_builder.h"
#include "core/number_text.h"
#include "core/parallel.h"

namespace trilab {

namespace {

constexpr double kPi = 3.14159265358979323846;

template <class H>
void check_element(const HalfedgeMesh& mesh, H h, const char* function, const char* what,
                   std::size_t live, const char* plural) {
    if (!mesh.is_valid(h) || mesh.is_deleted(h))
        throw InvalidArgument(std::string(function) + ": " + what + " " +
                              (h.is_valid() ? std::to_string(h.idx()) : std::string("(invalid)")) +
                              " is not in the mesh (" + count_text(live, what, plural) +
                              ", indices 0 to " + std::to_string(live == 0 ? 0 : live - 1) + ")");
}

// Other live vertices with faces at exactly v's position (coincident.h's exact rule).
std::size_t coincident_copies(const HalfedgeMesh& mesh, Vertex v) {
    const Point& p = mesh.position(v);
    if (!p.allFinite() || mesh.is_isolated(v)) return 0;
    std::size_t n = 0;
    for (Vertex w : mesh.vertices())
        if (w != v && mesh.position(w) == p && !mesh.is_isolated(w)) ++n;
    return n;
}

// Interior angle at a of the triangle (a, b, c), in radians (atan2: 0..pi, also degenerate).
double corner_angle(const Point& a, const Point& b, const Point& c) {
    const Vector3 u = b - a, w = c - a;
    return std::atan2(u.cross(w).norm(), u.dot(w));
}

// Six significant digits, written as number_text() writes numbers ("0.123457", "1e+09").
std::string short_text(double v) {
    if (!std::isfinite(v)) return number_text(v);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return number_text(std::strtod(buf, nullptr));
}

std::string vector_text(const Vector3& v) {
    return short_text(v.x()) + " " + short_text(v.y()) + " " + short_text(v.z());
}

std::string snake(std::string s) {
    for (char& c : s) {
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'))) c = '_';
    }
    return s;
}

InspectionField number_field(std::string key, std::string label, double v,
                             const std::string& unit = "") {
    return {std::move(key), std::move(label), short_text(v) + unit, {v}};
}
InspectionField index_field(std::string key, std::string label, Index i) {
    return {std::move(key), std::move(label), std::to_string(i), {double(i)}};
}
InspectionField flag_field(std::string key, std::string label, bool b) {
    return {std::move(key), std::move(label), b ? "yes" : "no", {b ? 1.0 : 0.0}};
}
InspectionField vector_field(std::string key, std::string label, const Vector3& v) {
    return {std::move(key), std::move(label), vector_text(v), {v.x(), v.y(), v.z()}};
}
InspectionField words_field(std::string key, std::string label, std::string text) {
    return {std::move(key), std::move(label), std::move(text), {}};
}

// The faces at v and at its neighbours (in index order) as a mesh of their own: the vertex's
// curvatures and Laplacian rows depend on nothing farther (the second-order hinges of the edges
// at v and opposite it lie in these faces), so they are computed there in O(ring) instead of
// over the whole mesh. v's fan and its neighbours' fans are complete in the patch.
struct Patch {
    HalfedgeMesh mesh;
    Vertex v;  ///< v in the patch
};
Patch local_patch(const HalfedgeMesh& mesh, Vertex v) {
    std::vector<Face> faces;
    std::vector<Vertex> ring{v};
    for (Vertex w : mesh.vertices_around(v)) ring.push_back(w);
    for (Vertex u : ring)
        for (Face f : mesh.faces_around(u)) faces.push_back(f);
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    PolygonSoup soup;
    std::vector<Vertex> used;
    for (Face f : faces)
        for (Vertex u : mesh.face_vertices(f)) used.push_back(u);
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    const auto local = [&](Vertex u) {
        return Index(std::lower_bound(used.begin(), used.end(), u) - used.begin());
    };
    for (Vertex u : used) soup.positions.push_back(mesh.position(u));
    for (Face f : faces) {
        const auto c = mesh.face_vertices(f);
        soup.add_face({local(c[0]), local(c[1]), local(c[2])});
    }
    LoadReport report;
    Patch patch{build_mesh(soup, report), Vertex(local(v))};
    return patch;
}

}  // namespace

VertexInspection inspect_vertex(const HalfedgeMesh& mesh, Vertex v,
                                const InspectionInputs& inputs) {
    check_element(mesh, v, "inspect_vertex", "vertex", mesh.n_vertices(), "vertices");
    VertexInspection r;
    r.vertex = v;
    r.position = mesh.position(v);
    r.normal = vertex_normal(mesh, v);
    r.isolated = mesh.is_isolated(v);
    r.valence = r.isolated ? 0 : mesh.valence(v);
    r.boundary = !r.isolated && mesh.is_boundary(v);
    r.texture_seam = on_texture_seam(mesh, mesh.get_halfedge_property<TexCoord>("h:texcoord"), v);
    r.coincident_copies = coincident_copies(mesh, v);

    const Index i = v.idx();
    if (r.isolated) {
        r.laplacian_fixed = true;
    } else {
        // The colourings' compute_curvatures() and the fairing's build_laplacian(), on the
        // vertex's neighbourhood (local_patch(): the same faces in the same order).
        const Patch patch = local_patch(mesh, v);
        const Index pi = patch.v.idx();
        const VertexCurvatures c = compute_curvatures(patch.mesh);
        r.curvature_valid = c.valid[pi] != 0;
        r.k1 = c.k1[pi];
        r.k2 = c.k2[pi];
        r.mean = c.mean[pi];
        r.gaussian = c.gaussian[pi];
        r.shape_index = c.shape_index[pi];
        // |(L X)_v| under each fairing operator (default options: the boundary fixed).
        // ImprovedUmbrella measures lengths in units of the mean edge length, the whole mesh's.
        const double unit = mean_edge_length(mesh), patch_unit = mean_edge_length(patch.mesh);
        for (std::size_t k = 0; k < std::size(kLaplacianOperators); ++k) {
            const LaplacianOperator op = kLaplacianOperators[k].value;
            const Laplacian lap = build_laplacian(patch.mesh, op);
            const Index row = lap.map.row_of[pi];
            if (row == kInvalidIndex || lap.fixed[row]) {
                r.laplacian_fixed = true;
                continue;
            }
            Vector3 lx = Vector3::Zero();
            for (Eigen::Index col = 0; col < lap.L.outerSize(); ++col)
                for (SparseMatrix::InnerIterator it(lap.L, col); it; ++it)
                    if (it.row() == Eigen::Index(row))
                        lx += it.value() * patch.mesh.position(lap.map.vertex_of[col]);
            double scale = 1;
            if (op == LaplacianOperator::ImprovedUmbrella && patch_unit > 0 && unit > 0)
                scale = (unit / patch_unit) * (unit / patch_unit);
            r.laplacian_length[k] = scale * lx.norm();
        }
    }

    const std::size_t n = mesh.vertices_size();
    for (const NamedVertexField& f : inputs.fields) {
        const double value = f.values && f.values->size() == n
                                 ? (*f.values)[i]
                                 : std::numeric_limits<double>::quiet_NaN();
        r.field_values.emplace_back(f.name, value);
    }
    if (inputs.reference && inputs.reference->size() == n) {
        // smoothing_distance() (core/algorithms/coloring.h) at one vertex.
        const double d = (mesh.position(v) - (*inputs.reference)[i]).dot(r.normal);
        r.smoothing_distance = std::isfinite(d) ? d : 0.0;
    }
    if (inputs.displacement && inputs.displacement->size() == n)
        r.displacement = (*inputs.displacement)[i];

    const auto level = mesh.get_vertex_property<int>("v:subdivision_level");
    const auto stencil = mesh.get_vertex_property<int>("v:subdivision_stencil");
    const auto parents = mesh.get_vertex_property<SubdivisionParents>("v:subdivision_parents");
    if (level || stencil) {
        SubdivisionOrigin o;
        if (level) o.level = level[v];
        if (stencil) o.stencil = SubdivisionStencil(stencil[v]);
        o.even = is_even_stencil(o.stencil);
        if (parents)
            for (int k = 0; k < 3; ++k)
                if (parents[v][k] != kInvalidIndex) o.parents.push_back(parents[v][k]);
        r.subdivision = o;
    }
    if (const auto source = mesh.get_vertex_property<Index>(kDecimationSourceName))
        r.decimation_source = source[v];
    const auto sharp = mesh.get_edge_property<float>(kSharpnessProperty);
    const auto corner = mesh.get_vertex_property<std::uint8_t>(kCornerProperty);
    if (sharp || corner) {
        VertexInspection::FeatureRole f;
        if (sharp)
            for (Halfedge h : mesh.halfedges_around(v))
                if (sharp[HalfedgeMesh::edge(h)] > 0.0f) ++f.sharp_edges;
        f.tagged = corner && corner[v] != 0;
        f.cls = f.tagged || f.sharp_edges >= 3 ? VertexClass::Corner
                : f.sharp_edges == 2           ? VertexClass::Crease
                : f.sharp_edges == 1           ? VertexClass::Dart
                                               : VertexClass::Smooth;
        r.feature = f;
    }
    return r;
}

std::string feature_role_text(const VertexInspection::FeatureRole& role) {
    const std::string edges =
        std::to_string(role.sharp_edges) + " sharp edge" + (role.sharp_edges == 1 ? "" : "s");
    switch (role.cls) {
        case VertexClass::Corner:
            return role.tagged ? "corner: tagged (Loop keeps it where it is)"
                               : "corner: " + edges + " meet (Loop keeps it where it is)";
        case VertexClass::Crease:
            return "crease: " + edges +
                   " (Loop's crease rule: 3/4 itself, 1/8 each end along them)";
        case VertexClass::Dart:
            return "dart: 1 sharp edge ending here (the smooth rule)";
        case VertexClass::Smooth:
            break;
    }
    return "smooth: no sharp edge";
}

EdgeInspection inspect_edge(const HalfedgeMesh& mesh, Edge e, const DecimationOptions& options) {
    check_element(mesh, e, "inspect_edge", "edge", mesh.n_edges(), "edges");
    EdgeInspection r;
    r.edge = e;
    r.ends = {mesh.vertex(e, 0), mesh.vertex(e, 1)};
    r.length = edge_length(mesh, e);
    r.boundary = mesh.is_boundary(e);
    if (!r.boundary) {
        const Vector3 n0 = face_normal(mesh, mesh.face(HalfedgeMesh::halfedge(e, 0)));
        const Vector3 n1 = face_normal(mesh, mesh.face(HalfedgeMesh::halfedge(e, 1)));
        if (n0.squaredNorm() > 0 && n1.squaredNorm() > 0)
            r.dihedral_angle = std::acos(std::clamp(n0.dot(n1), -1.0, 1.0)) * 180.0 / kPi;
    }
    r.cotangent_weight = cotangent_weight(mesh, e);
    if (const auto sharp = mesh.get_edge_property<float>(kSharpnessProperty))
        r.sharpness = sharp[e];
    r.selected_cost = options.cost;
    for (const auto& entry : kDecimationCosts) {
        DecimationOptions o = options;
        o.cost = entry.value;
        r.costs.push_back({entry.value, explain_collapse(mesh, e, o)});
    }
    return r;
}

FaceInspection inspect_face(const HalfedgeMesh& mesh, Face f) {
    check_element(mesh, f, "inspect_face", "face", mesh.n_faces(), "faces");
    FaceInspection r;
    r.face = f;
    r.corners = mesh.face_vertices(f);
    const Point& a = mesh.position(r.corners[0]);
    const Point& b = mesh.position(r.corners[1]);
    const Point& c = mesh.position(r.corners[2]);
    r.area = face_area(mesh, f);
    r.normal = face_normal(mesh, f);
    // Two angles by atan2, the third pi minus them (they sum to 180 degrees, as curvature.cpp).
    const double a0 = corner_angle(a, b, c), a1 = corner_angle(b, c, a);
    r.angles = {a0 * 180.0 / kPi, a1 * 180.0 / kPi, (kPi - a0 - a1) * 180.0 / kPi};
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    r.aspect_ratio = r.area > 0 ? std::sqrt(3.0) * longest * longest / (4.0 * r.area)
                                : std::numeric_limits<double>::infinity();
    r.quality = triangle_quality(mesh, f);
    const ComponentLabels labels = label_face_components(mesh);
    r.component = labels.of_face[f.idx()];
    r.components = labels.components.size();
    return r;
}

Face nearest_face(const HalfedgeMesh& mesh, const Point& p) {
    const Index nf = Index(mesh.faces_size());
    if (mesh.n_faces() == 0) return Face();
    struct Best {
        double d2 = std::numeric_limits<double>::infinity();
        Index f = kInvalidIndex;
    };
    const auto& fh = mesh.face_halfedge_array();
    const auto& next = mesh.halfedge_next_array();
    const auto& to = mesh.halfedge_to_array();
    const auto& x = mesh.positions();
    const auto scan = [&](Index begin, Index end, Best& best) {
        for (Index f = begin; f < end; ++f) {
            if (mesh.is_deleted(Face(f))) continue;
            const Halfedge h0 = fh[f], h1 = next[h0.idx()], h2 = next[h1.idx()];
            const Point& a = x[to[h0.idx()].idx()];
            const Point& b = x[to[h1.idx()].idx()];
            const Point& c = x[to[h2.idx()].idx()];
            const double d2 = (closest_point_on_triangle(p, a, b, c) - p).squaredNorm();
            if (d2 < best.d2 || best.f == kInvalidIndex) best = {d2, f};
        }
    };
    const unsigned hw = std::max(1u, unsigned(trilab::thread_count()));
    const unsigned threads = nf < 200000 ? 1u : std::min(hw, 16u);
    std::vector<Best> best(threads);
    std::vector<std::thread> pool;
    const Index chunk = Index((std::size_t(nf) + threads - 1) / threads);
    for (unsigned t = 1; t < threads; ++t) {
        const Index begin = std::min(nf, Index(t * std::size_t(chunk)));
        const Index end = std::min(nf, Index(begin + std::size_t(chunk)));
        pool.emplace_back([&, t, begin, end] { scan(begin, end, best[t]); });
    }
    scan(0, std::min(nf, chunk), best[0]);
    for (std::thread& t : pool) t.join();
    Best result;
    for (const Best& b : best)  // chunks in index order: a tie keeps the smaller index
        if (b.f != kInvalidIndex && (result.f == kInvalidIndex || b.d2 < result.d2)) result = b;
    return Face(result.f);
}

Vertex nearest_corner(const HalfedgeMesh& mesh, Face f, const Point& p) {
    check_element(mesh, f, "nearest_corner", "face", mesh.n_faces(), "faces");
    Vertex best;
    double d2 = std::numeric_limits<double>::infinity();
    for (Vertex v : mesh.face_vertices(f)) {
        const double d = (mesh.position(v) - p).squaredNorm();
        if (!best.is_valid() || d < d2) {
            best = v;
            d2 = d;
        }
    }
    return best;
}

Edge nearest_side(const HalfedgeMesh& mesh, Face f, const Point& p) {
    check_element(mesh, f, "nearest_side", "face", mesh.n_faces(), "faces");
    Edge best;
    double d2 = std::numeric_limits<double>::infinity();
    for (Halfedge h : mesh.halfedges_of(f)) {
        const Point& a = mesh.position(mesh.from_vertex(h));
        const Point& b = mesh.position(mesh.to_vertex(h));
        const Vector3 ab = b - a;
        const double len2 = ab.squaredNorm();
        const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
        const double d = (a + t * ab - p).squaredNorm();
        if (!best.is_valid() || d < d2) {
            best = HalfedgeMesh::edge(h);
            d2 = d;
        }
    }
    return best;
}

std::vector<InspectionField> inspection_fields(const VertexInspection& v) {
    std::vector<InspectionField> out;
    out.push_back(index_field("vertex", "Vertex", v.vertex.idx()));
    out.push_back(vector_field("position", "Position", v.position));
    out.push_back(vector_field("normal", "Normal", v.normal));
    out.push_back(index_field("valence", "Valence", v.valence));
    out.push_back(flag_field("boundary", "On the boundary", v.boundary));
    out.push_back(flag_field("texture_seam", "On a texture seam", v.texture_seam));
    out.push_back(
        index_field("coincident_copies", "Coincident copies (seam)", Index(v.coincident_copies)));
    if (v.curvature_valid) {
        out.push_back(number_field("k1", "k1 (larger principal curvature)", v.k1));
        out.push_back(number_field("k2", "k2 (smaller principal curvature)", v.k2));
        out.push_back(number_field("mean_curvature", "Mean curvature", v.mean));
        out.push_back(number_field("gaussian_curvature", "Gaussian curvature", v.gaussian));
        out.push_back(number_field("shape_index", "Shape index", v.shape_index));
    } else {
        const std::string why =
            v.isolated ? "none (isolated vertex)"
                       : (v.boundary ? "none (boundary vertex)" : "none (degenerate fan)");
        out.push_back(words_field("k1", "k1 (larger principal curvature)", why));
        out.push_back(words_field("k2", "k2 (smaller principal curvature)", why));
        out.push_back(words_field("mean_curvature", "Mean curvature", why));
        out.push_back(words_field("gaussian_curvature", "Gaussian curvature", why));
        out.push_back(words_field("shape_index", "Shape index", why));
    }
    for (std::size_t k = 0; k < std::size(kLaplacianOperators); ++k) {
        const auto& op = kLaplacianOperators[k];
        const std::string key = "laplacian_" + snake(op.id);
        const std::string label = std::string("|Laplacian|, ") + op.label;
        if (v.laplacian_fixed)
            out.push_back({key, label, "0 (fixed: boundary or isolated)", {0.0}});
        else
            out.push_back(number_field(key, label, v.laplacian_length[k]));
    }
    for (const auto& [name, value] : v.field_values) {
        if (std::isnan(value))
            out.push_back(words_field("field_" + snake(name), name, "none"));
        else
            out.push_back(number_field("field_" + snake(name), name, value));
    }
    if (v.smoothing_distance)
        out.push_back(number_field("smoothing_distance", "Smoothing distance (along the normal)",
                                   *v.smoothing_distance));
    if (v.displacement) {
        InspectionField f =
            vector_field("band_displacement", "Displacement by the band", *v.displacement);
        f.text += " (length " + short_text(v.displacement->norm()) + ")";
        out.push_back(f);
    }
    if (v.feature)
        out.push_back({"feature_class",
                       "Feature class",
                       feature_role_text(*v.feature),
                       {double(int(v.feature->cls)), double(v.feature->sharp_edges)}});
    if (v.subdivision) {
        const SubdivisionOrigin& o = *v.subdivision;
        out.push_back(index_field("subdivision_level", "Subdivision level", Index(o.level)));
        if (o.stencil != SubdivisionStencil::Unknown) {
            out.push_back({"subdivision_even",
                           "Even or odd",
                           o.even ? "even (an old vertex)" : "odd (new)",
                           {o.even ? 1.0 : 0.0}});
            out.push_back({"subdivision_stencil",
                           "Stencil",
                           subdivision_stencil_label(o.stencil),
                           {double(int(o.stencil))}});
            InspectionField parents{"subdivision_parents", "Parents (previous level)", "", {}};
            for (Index p : o.parents) {
                if (!parents.text.empty()) parents.text += ", ";
                parents.text += std::to_string(p);
                parents.numbers.push_back(double(p));
            }
            if (parents.text.empty()) parents.text = "none";
            out.push_back(parents);
        }
    }
    if (v.decimation_source)
        out.push_back(
            index_field("decimation_source", "Vertex before decimation", *v.decimation_source));
    return out;
}

namespace {

std::string refusal_label(CollapseRefusal r) {
    switch (r) {
        case CollapseRefusal::None:
            return "allowed";
        case CollapseRefusal::NoDirection:
            return "refused: neither end may move (boundary, seam or coincident vertex)";
        case CollapseRefusal::MaxError:
            return "refused by the maximum error";
        case CollapseRefusal::IndependentSet:
            return "refused by the independent set";
        case CollapseRefusal::Topology:
            return "refused by the topology (link condition)";
        case CollapseRefusal::TextureSeam:
            return "refused: the removed vertex is on a texture seam";
        case CollapseRefusal::NormalFlip:
            return "refused by the normal flip";
        case CollapseRefusal::Roundness:
            return "refused by the roundness";
    }
    return "?";
}

// "refuses"/"allows"/"off (... )" followed by the comparison.
std::string verdict(bool on, bool refuses, const std::string& comparison) {
    if (!on) return "off (" + comparison + ")";
    return (refuses ? "refuses: " : "allows: ") + comparison;
}

}  // namespace

std::vector<InspectionField> inspection_fields(const EdgeInspection& e) {
    std::vector<InspectionField> out;
    out.push_back(index_field("edge", "Edge", e.edge.idx()));
    out.push_back({"ends",
                   "Ends",
                   std::to_string(e.ends[0].idx()) + ", " + std::to_string(e.ends[1].idx()),
                   {double(e.ends[0].idx()), double(e.ends[1].idx())}});
    out.push_back(number_field("length", "Length", e.length));
    out.push_back(flag_field("boundary", "On the boundary", e.boundary));
    if (e.dihedral_angle)
        out.push_back(number_field("dihedral_angle", "Dihedral angle (between the normals)",
                                   *e.dihedral_angle, " deg"));
    else
        out.push_back(words_field("dihedral_angle", "Dihedral angle (between the normals)",
                                  e.boundary ? "none (boundary edge)" : "none (degenerate face)"));
    out.push_back(number_field("cotangent_weight", "Cotangent weight", e.cotangent_weight));
    if (e.sharpness) {
        const float s = *e.sharpness;
        const std::string text = std::isinf(s) ? "infinite (a crease at every level)"
                                 : s > 0.0f
                                     ? short_text(double(s)) + " (semi-sharp: the sharp rule for " +
                                           std::to_string(int(std::floor(s))) + " level" +
                                           (std::floor(s) == 1.0f ? "" : "s") + ", then blended)"
                                     : "0 (smooth)";
        out.push_back({"sharpness", "Sharpness", text, {double(s)}});
    }
    for (const CostInspection& c : e.costs) {
        const std::string id = snake(decimation_cost_name(c.cost));
        const std::string name = enum_label<DecimationCost>(kDecimationCosts, c.cost);
        const CollapseExplanation& x = c.collapse;
        if (!x.possible) {
            out.push_back(
                words_field(id + "_cost", "Collapse cost, " + name, "none: neither end may move"));
            continue;
        }
        out.push_back({id + "_cost",
                       "Collapse cost, " + name,
                       short_text(x.cost) + " (vertex " + std::to_string(x.removed.idx()) +
                           " into " + std::to_string(x.kept.idx()) + ")",
                       {x.cost, double(x.removed.idx()), double(x.kept.idx())}});
    }
    const auto selected =
        std::find_if(e.costs.begin(), e.costs.end(),
                     [&](const CostInspection& c) { return c.cost == e.selected_cost; });
    if (selected == e.costs.end()) return out;
    const CollapseExplanation& x = selected->collapse;
    out.push_back({"collapse",
                   "Collapse now",
                   refusal_label(x.refusal),
                   {x.refusal == CollapseRefusal::None ? 1.0 : 0.0}});
    out.push_back(words_field("refusal", "First refusal", collapse_refusal_name(x.refusal)));
    if (!x.possible) return out;
    out.push_back(vector_field("target", "Kept vertex goes to", x.target));
    out.push_back({"topology",
                   "Link condition",
                   x.topology_ok ? "allows" : "refuses",
                   {x.topology_ok ? 1.0 : 0.0}});
    if (x.texture_seam) out.push_back(flag_field("texture_seam_refuses", "Texture seam", true));
    out.push_back(
        {"normal_flip",
         "Normal flip",
         verdict(x.normal_flip_on, x.normal_flip_refuses,
                 x.degenerate_face
                     ? "a face would degenerate"
                     : "largest normal change " + short_text(x.largest_normal_change) + " deg " +
                           (x.largest_normal_change > x.max_normal_angle ? ">" : "<=") + " limit " +
                           short_text(x.max_normal_angle) + " deg"),
         {x.largest_normal_change, x.max_normal_angle, x.normal_flip_refuses ? 1.0 : 0.0}});
    out.push_back({"roundness",
                   "Roundness",
                   verdict(x.roundness_on, x.roundness_refuses,
                           "roundness reached " + short_text(x.roundness) +
                               (x.roundness < x.min_roundness ? " < " : " >= ") + "limit " +
                               short_text(x.min_roundness)),
                   {x.roundness, x.min_roundness, x.roundness_refuses ? 1.0 : 0.0}});
    out.push_back({"independent_set",
                   "Independent set",
                   verdict(x.independent_set_on, x.independent_set_refuses,
                           x.independent_set_refuses ? "an end is locked" : "no end is locked"),
                   {x.independent_set_refuses ? 1.0 : 0.0}});
    out.push_back({"max_error",
                   "Maximum error",
                   verdict(x.max_error_on, x.max_error_refuses,
                           "error " + short_text(x.error) +
                               (x.max_error_on ? (x.max_error_refuses ? " > " : " <= ") +
                                                     std::string("limit ") + short_text(x.max_error)
                                               : std::string())),
                   {x.error, x.max_error, x.max_error_refuses ? 1.0 : 0.0}});
    return out;
}

std::vector<InspectionField> inspection_fields(const FaceInspection& f) {
    std::vector<InspectionField> out;
    out.push_back(index_field("face", "Face", f.face.idx()));
    out.push_back(
        {"corners",
         "Corners",
         std::to_string(f.corners[0].idx()) + ", " + std::to_string(f.corners[1].idx()) + ", " +
             std::to_string(f.corners[2].idx()),
         {double(f.corners[0].idx()), double(f.corners[1].idx()), double(f.corners[2].idx())}});
    out.push_back(number_field("area", "Area", f.area));
    out.push_back({"angles",
                   "Angles",
                   short_text(f.angles[0]) + ", " + short_text(f.angles[1]) + ", " +
                       short_text(f.angles[2]) + " deg",
                   {f.angles[0], f.angles[1], f.angles[2]}});
    out.push_back(vector_field("normal", "Normal", f.normal));
    out.push_back(number_field("aspect_ratio", "Aspect ratio (1: equilateral)", f.aspect_ratio));
    out.push_back(number_field("quality", "Quality Q (1: equilateral)", f.quality));
    out.push_back({"component",
                   "Component",
                   std::to_string(f.component) + " of " + std::to_string(f.components),
                   {double(f.component), double(f.components)}});
    return out;
}

}  // namespace trilab
