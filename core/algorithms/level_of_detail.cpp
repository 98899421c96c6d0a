// Level of detail over a progressive mesh (core/algorithms/level_of_detail.h): the progressive
// mesh of a slider, and LevelOfDetail's constructor (its checks and drawing order) and moves.
#include "core/algorithms/level_of_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"
#include "core/mesh_builder.h"
#include "core/number_text.h"

namespace trilab {

namespace {

// ceil(percent / 100 * vertices), up to a rounding error of the product (1 % of 300
// vertices keeps 3, not 4).
std::size_t kept_vertices(double percent, std::size_t vertices) {
    const double x = percent / 100.0 * double(vertices);
    return std::min(vertices, std::size_t(std::max(0.0, std::ceil(x - 1e-6))));
}

}  // namespace

ProgressiveBuild build_progressive_mesh(const HalfedgeMesh& mesh, const DecimationOptions& options,
                                        double min_percent, Progress& progress) {
    if (!(min_percent > 0 && min_percent <= 100))
        throw InvalidArgument("build_progressive_mesh: min_percent must be in (0, 100], got " +
                              number_text(min_percent));
    std::size_t surface = 0;
    for (Vertex v : mesh.vertices())
        if (!mesh.is_isolated(v)) ++surface;
    DecimationOptions o = options;
    o.target_vertices = std::max<std::size_t>(1, kept_vertices(min_percent, surface));
    o.iterations = 1;
    o.independent_set = false;
    o.levels = DecimationLevels::None;
    o.record_geomorph = false;
    o.record_progressive = true;
    DecimationResult r = decimate(mesh, o, progress);
    return ProgressiveBuild{std::move(r.progressive), r.report};
}

namespace {

bool has_corner(const std::array<Vertex, 3>& c, Vertex v) {
    return c[0] == v || c[1] == v || c[2] == v;
}

[[noreturn]] void bad_progressive(std::size_t collapse, const std::string& what) {
    throw InvalidArgument("LevelOfDetail: inconsistent progressive mesh at collapse " +
                          std::to_string(collapse) + ": " + what);
}

// The constructor in four stages: the fine mesh checked (valences), a dry run of every
// collapse (checks, corners, prefix sums, the fixed-point scale), the drawing order, and the
// copy of everything into that order.

/// The fine mesh's counts: valence per vertex, faces, vertices with faces, live vertices,
/// the largest valence (at least 1).
struct FineMesh {
    std::vector<std::uint32_t> valence;
    std::size_t faces = 0, vertices = 0, live_vertices = 0;
    std::uint64_t max_valence = 1;
};

/// Checks the progressive mesh's sizes and its fine mesh: corners of live faces are distinct
/// live vertices.
FineMesh check_fine_mesh(const ProgressiveMesh& pm) {
    const std::size_t nv = pm.positions.size(), nf = pm.faces.size();
    if (pm.vertex_alive.size() != nv || pm.face_alive.size() != nf)
        throw InvalidArgument("LevelOfDetail: the progressive mesh's sizes disagree (" +
                              std::to_string(nv) + " positions, " +
                              std::to_string(pm.vertex_alive.size()) + " vertex flags, " +
                              std::to_string(nf) + " faces, " +
                              std::to_string(pm.face_alive.size()) + " face flags)");
    if (nv >= kInvalidIndex || nf >= (std::size_t(1) << 30))
        throw InvalidArgument("LevelOfDetail: too many vertices or faces");
    FineMesh fine;
    fine.valence.assign(nv, 0);
    for (std::size_t f = 0; f < nf; ++f) {
        if (!pm.face_alive[f]) continue;
        const auto& c = pm.faces[f];
        for (Vertex v : c)
            if (!v.is_valid() || v.idx() >= nv || !pm.vertex_alive[v.idx()])
                throw InvalidArgument("LevelOfDetail: face " + std::to_string(f) +
                                      " has a corner that is not a live vertex");
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
            throw InvalidArgument("LevelOfDetail: face " + std::to_string(f) + " repeats a corner");
        for (Vertex v : c) ++fine.valence[v.idx()];
        ++fine.faces;
    }
    for (std::size_t v = 0; v < nv; ++v) {
        if (fine.valence[v] > 0) ++fine.vertices;
        if (pm.vertex_alive[v]) ++fine.live_vertices;
        fine.max_valence = std::max<std::uint64_t>(fine.max_valence, fine.valence[v]);
    }
    return fine;
}

/// What the dry run of the collapses gives the level of detail: per ring entry the corner of
/// the moved face that held the removed vertex; prefix sums over the steps of ring faces and
/// of faces removed; fixed-point units per unit of face normal.
struct CollapseRecord {
    std::vector<std::uint8_t> ring_corner;
    std::vector<std::uint64_t> ring_prefix, removed_prefix;
    double normal_scale = 1;
};

/// A dry run of every collapse (so that set_level() can trust the record): its vertices are
/// live and where it says, the faces it names are live and at its vertices, its ring lists
/// every face at the kept vertex once, and the removed vertex has no face left.
class CollapseDryRun {
public:
    CollapseDryRun(const ProgressiveMesh& pm, FineMesh& fine)
        : pm_(pm),
          fine_(fine),
          corners_(pm.faces),
          face_on_(pm.face_alive),
          vertex_on_(pm.vertex_alive),
          at_(pm.positions) {}

    CollapseRecord run() {
        const std::size_t nc = pm_.collapses.size();
        if (nc > fine_.vertices) bad_progressive(nc, "more collapses than vertices with faces");
        CollapseRecord r;
        r.ring_corner.assign(pm_.ring_faces.size(), 0);
        r.ring_prefix.assign(nc + 1, 0);
        r.removed_prefix.assign(nc + 1, 0);
        for (std::size_t v = 0; v < pm_.positions.size(); ++v)
            if (fine_.valence[v] > 0) extend(pm_.positions[v]);
        for (std::size_t k = 0; k < nc; ++k) {
            const VertexSplit& s = pm_.collapses[k];
            const std::uint32_t removed_faces = collapse(k, r.ring_corner);
            fine_.max_valence =
                std::max<std::uint64_t>(fine_.max_valence, s.ring_end - s.moved_begin);
            r.ring_prefix[k + 1] = r.ring_prefix[k] + (s.ring_end - s.moved_begin);
            r.removed_prefix[k + 1] = r.removed_prefix[k] + removed_faces;
        }
        // Fixed point: a component of a face normal is at most diagonal^2 in size and a vertex
        // has at most max_valence faces at any level, so the sums stay below 2^61.
        const double diagonal2 = fine_.faces > 0 ? (hi_ - lo_).squaredNorm() : 0.0;
        r.normal_scale =
            diagonal2 > 0 ? std::ldexp(1.0, 61) / (double(fine_.max_valence) * diagonal2) : 1.0;
        return r;
    }

private:
    void extend(const Point& p) {
        if (!p.allFinite())
            throw InvalidArgument("LevelOfDetail: the progressive mesh has a non-finite position");
        lo_ = lo_.cwiseMin(p);
        hi_ = hi_.cwiseMax(p);
    }

    /// Checks and applies collapse k; records the corners of its moved faces. Returns the
    /// number of faces it removes.
    std::uint32_t collapse(std::size_t k, std::vector<std::uint8_t>& ring_corner) {
        const std::size_t nv = pm_.positions.size(), nf = pm_.faces.size();
        const std::size_t nr = pm_.ring_faces.size();
        std::vector<std::uint32_t>& valence = fine_.valence;
        const VertexSplit& s = pm_.collapses[k];
        const Vertex r = s.removed, q = s.kept;
        if (!r.is_valid() || !q.is_valid() || r.idx() >= nv || q.idx() >= nv || r == q ||
            !vertex_on_[r.idx()] || !vertex_on_[q.idx()])
            bad_progressive(k, "its vertices are not two live vertices");
        if (!(s.moved_begin <= s.moved_end && s.moved_end <= s.ring_end && s.ring_end <= nr))
            bad_progressive(k, "its ring range is out of order or out of range");
        if (at_[r.idx()] != s.removed_position || at_[q.idx()] != s.kept_before)
            bad_progressive(k, "its positions before the collapse are not the vertices'");
        at_[q.idx()] = s.kept_after;
        std::uint32_t removed_faces = 0;
        for (Face f : s.faces) {
            if (!f.is_valid()) continue;
            if (f.idx() >= nf || !face_on_[f.idx()] || !has_corner(corners_[f.idx()], r) ||
                !has_corner(corners_[f.idx()], q))
                bad_progressive(k, "a face it removes is not a live face at its edge");
            face_on_[f.idx()] = 0;
            for (Vertex v : corners_[f.idx()]) --valence[v.idx()];
            ++removed_faces;
        }
        if (removed_faces == 0) bad_progressive(k, "it removes no face");
        for (std::uint32_t i = s.moved_begin; i < s.ring_end; ++i) {
            const Face f = pm_.ring_faces[i];
            const bool moved = i < s.moved_end;
            if (!f.is_valid() || f.idx() >= nf || !face_on_[f.idx()])
                bad_progressive(k, "a face of its ring is not live");
            auto& c = corners_[f.idx()];
            if (!has_corner(c, moved ? r : q) || has_corner(c, moved ? q : r))
                bad_progressive(k, "a face of its ring is not at the vertex it names");
            if (moved) {
                const int j = c[0] == r ? 0 : c[1] == r ? 1 : 2;
                ring_corner[i] = std::uint8_t(j);
                c[j] = q;
                --valence[r.idx()];
                ++valence[q.idx()];
            }
        }
        if (valence[r.idx()] != 0 || valence[q.idx()] != s.ring_end - s.moved_begin)
            bad_progressive(k, "its ring does not list the faces at its vertices");
        vertex_on_[r.idx()] = 0;
        extend(s.kept_after);
        extend(s.kept_before);
        return removed_faces;
    }

    const ProgressiveMesh& pm_;
    FineMesh& fine_;
    std::vector<std::array<Vertex, 3>> corners_;
    std::vector<std::uint8_t> face_on_, vertex_on_;
    std::vector<Point> at_;
    Point lo_ = Point::Constant(std::numeric_limits<double>::infinity()), hi_ = -lo_;
};

/// 10 bits to every third bit of 30.
std::uint32_t spread_bits(std::uint32_t x) {
    std::uint32_t r = 0;
    for (int i = 0; i < 10; ++i) r |= ((x >> i) & 1u) << (3 * i);
    return r;
}

/// The Hilbert index of the cell x (10 bits an axis) (Skilling, "Programming the Hilbert
/// curve", AIP Conf. Proc. 707, 2004: axes to the transposed index, whose bits interleave).
std::uint32_t hilbert_code(std::uint32_t x[3]) {
    for (std::uint32_t q = 1u << 9; q > 1; q >>= 1) {
        const std::uint32_t p = q - 1;
        for (int i = 0; i < 3; ++i) {
            if (x[i] & q) {
                x[0] ^= p;
            } else {
                const std::uint32_t t = (x[0] ^ x[i]) & p;
                x[0] ^= t;
                x[i] ^= t;
            }
        }
    }
    x[1] ^= x[0];
    x[2] ^= x[1];
    std::uint32_t t = 0;
    for (std::uint32_t q = 1u << 9; q > 1; q >>= 1)
        if (x[2] & q) t ^= q - 1;
    for (int axis = 0; axis < 3; ++axis) x[axis] ^= t;
    std::uint32_t code = 0;
    for (int axis = 0; axis < 3; ++axis) code |= spread_bits(x[axis]) << (2 - axis);
    return code;
}

/// The level of detail's numbering and the fine mesh's, both ways (see LevelOfDetail).
struct DrawingOrder {
    std::vector<Index> face_of, fine_face, vertex_of, fine_vertex;
};

/// Drawing order: faces along a Hilbert curve through their centroids (10 bits an axis,
/// ties in index order), vertices in the order the faces first use them, then isolated
/// vertices, then vertices deleted in the input (never live).
DrawingOrder drawing_order(const ProgressiveMesh& pm, std::size_t fine_faces) {
    const std::size_t nv = pm.positions.size(), nf = pm.faces.size();
    Point lo = Point::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t f = 0; f < nf; ++f)
        if (pm.face_alive[f])
            for (Vertex v : pm.faces[f]) {
                lo = lo.cwiseMin(pm.positions[v.idx()]);
                hi = hi.cwiseMax(pm.positions[v.idx()]);
            }
    const Vector3 extent = (hi - lo).cwiseMax(Vector3::Constant(1e-300));
    std::vector<std::uint64_t> keys;
    keys.reserve(fine_faces);
    for (std::size_t f = 0; f < nf; ++f) {
        if (!pm.face_alive[f]) continue;
        const auto& c = pm.faces[f];
        const Point centre =
            (pm.positions[c[0].idx()] + pm.positions[c[1].idx()] + pm.positions[c[2].idx()]) / 3.0;
        std::uint32_t x[3];
        for (int axis = 0; axis < 3; ++axis) {
            const double t = (centre[axis] - lo[axis]) / extent[axis];
            x[axis] = std::uint32_t(std::min(1023.0, std::max(0.0, t * 1024.0)));
        }
        keys.push_back(std::uint64_t(hilbert_code(x)) << 32 | f);
    }
    std::sort(keys.begin(), keys.end());
    DrawingOrder o;
    o.face_of.assign(nf, kInvalidIndex);
    o.fine_face.resize(fine_faces);
    o.vertex_of.assign(nv, kInvalidIndex);
    o.fine_vertex.reserve(nv);
    const auto add_vertex = [&](Index v) {
        o.vertex_of[v] = Index(o.fine_vertex.size());
        o.fine_vertex.push_back(v);
    };
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const Index f = Index(keys[i] & 0xffffffffu);
        o.face_of[f] = Index(i);
        o.fine_face[i] = f;
        for (Vertex v : pm.faces[f])
            if (o.vertex_of[v.idx()] == kInvalidIndex) add_vertex(v.idx());
    }
    for (Index v = 0; v < nv; ++v)
        if (pm.vertex_alive[v] && o.vertex_of[v] == kInvalidIndex) add_vertex(v);
    for (Index v = 0; v < nv; ++v)
        if (!pm.vertex_alive[v]) add_vertex(v);
    return o;
}

}  // namespace

LevelOfDetail::LevelOfDetail(const ProgressiveMesh& pm) {
    FineMesh fine = check_fine_mesh(pm);
    fine_faces_ = fine.faces;
    fine_vertices_ = fine.vertices;
    live_at_fine_ = fine.live_vertices;
    CollapseRecord record = CollapseDryRun(pm, fine).run();
    ring_prefix_ = std::move(record.ring_prefix);
    removed_prefix_ = std::move(record.removed_prefix);
    normal_scale_ = record.normal_scale;
    DrawingOrder order = drawing_order(pm, fine_faces_);
    face_of_ = std::move(order.face_of);
    fine_face_ = std::move(order.fine_face);
    vertex_of_ = std::move(order.vertex_of);
    fine_vertex_ = std::move(order.fine_vertex);
    take_in_drawing_order(pm, record.ring_corner);
    normal_sum_.assign(pm.positions.size(), NormalSum{0, 0, 0});
    vertex_changed_.assign(pm.positions.size(), 0);
    recompute_normals();
    all_changed_ = true;
    fine_faces_state_ = faces_;
    fine_positions_state_ = positions_;
    fine_normals_state_ = normal_sum_;
    fine_vertex_alive_state_ = vertex_alive_;
}

void LevelOfDetail::take_in_drawing_order(const ProgressiveMesh& pm,
                                          const std::vector<std::uint8_t>& ring_corner) {
    const std::size_t nv = pm.positions.size(), nc = pm.collapses.size();
    positions_.resize(nv);
    vertex_alive_.resize(nv);
    for (Index v = 0; v < nv; ++v) {
        positions_[v] = pm.positions[fine_vertex_[v]];
        vertex_alive_[v] = pm.vertex_alive[fine_vertex_[v]];
    }
    faces_.resize(fine_faces_);
    face_alive_.assign(fine_faces_, 1);
    for (Index f = 0; f < fine_faces_; ++f) {
        const auto& c = pm.faces[fine_face_[f]];
        faces_[f] = {vertex_of_[c[0].idx()], vertex_of_[c[1].idx()], vertex_of_[c[2].idx()]};
    }
    steps_.resize(nc);
    ring_.resize(pm.ring_faces.size());
    for (std::size_t k = 0; k < nc; ++k) {
        const VertexSplit& s = pm.collapses[k];
        Step& step = steps_[k];
        step.kept = vertex_of_[s.kept.idx()];
        step.removed = vertex_of_[s.removed.idx()];
        for (int i = 0; i < 2; ++i)
            step.dead[i] = s.faces[i].is_valid() ? face_of_[s.faces[i].idx()] : kInvalidIndex;
        step.ring_begin = s.moved_begin;
        step.moved_end = s.moved_end;
        step.ring_end = s.ring_end;
        step.kept_before = s.kept_before;
        step.kept_after = s.kept_after;
        for (std::uint32_t i = s.moved_begin; i < s.ring_end; ++i)
            ring_[i] = (face_of_[pm.ring_faces[i].idx()] << 2) | ring_corner[i];
    }
}

void LevelOfDetail::face_normal(Index f, int sign) {
    const auto& c = faces_[f];
    const Point& p0 = positions_[c[0]];
    const Vector3 n = (positions_[c[1]] - p0).cross(positions_[c[2]] - p0) * normal_scale_;
    // Any rounding gives exact sums as long as a face adds and removes the same integers.
    const std::int64_t q[3] = {sign * std::int64_t(n.x()), sign * std::int64_t(n.y()),
                               sign * std::int64_t(n.z())};
    for (Index v : c) {
        NormalSum& sum = normal_sum_[v];
        sum[0] += q[0];
        sum[1] += q[1];
        sum[2] += q[2];
    }
}

void LevelOfDetail::recompute_normals() {
    std::fill(normal_sum_.begin(), normal_sum_.end(), NormalSum{0, 0, 0});
    for (Index f = 0; f < faces_.size(); ++f)
        if (face_alive_[f]) face_normal(f, 1);
}

Vector3 LevelOfDetail::vertex_normal(Index v) const {
    const NormalSum& s = normal_sum_[v];
    const Vector3 n{double(s[0]), double(s[1]), double(s[2])};
    const double len = n.norm();
    return len > 0 ? Vector3(n / len) : Vector3::Zero();
}

void LevelOfDetail::collapse_step(const Step& s, bool normals, bool track) {
    if (normals) {
        for (std::uint32_t i = s.ring_begin; i < s.ring_end; ++i) face_normal(ring_[i] >> 2, -1);
        for (Index f : s.dead)
            if (f != kInvalidIndex) face_normal(f, -1);
    }
    if (track) {
        for (std::uint32_t i = s.ring_begin; i < s.ring_end; ++i) mark_vertices(ring_[i] >> 2);
        for (Index f : s.dead)
            if (f != kInvalidIndex) mark_vertices(f);
    }
    for (Index f : s.dead)
        if (f != kInvalidIndex) face_alive_[f] = 0;
    for (std::uint32_t i = s.ring_begin; i < s.moved_end; ++i)
        faces_[ring_[i] >> 2][ring_[i] & 3] = s.kept;
    positions_[s.kept] = s.kept_after;
    vertex_alive_[s.removed] = 0;
    if (normals)
        for (std::uint32_t i = s.ring_begin; i < s.ring_end; ++i) face_normal(ring_[i] >> 2, 1);
}

void LevelOfDetail::split_step(const Step& s, bool normals, bool track) {
    if (normals)
        for (std::uint32_t i = s.ring_begin; i < s.ring_end; ++i) face_normal(ring_[i] >> 2, -1);
    for (std::uint32_t i = s.ring_begin; i < s.moved_end; ++i)
        faces_[ring_[i] >> 2][ring_[i] & 3] = s.removed;
    positions_[s.kept] = s.kept_before;
    vertex_alive_[s.removed] = 1;
    for (Index f : s.dead)
        if (f != kInvalidIndex) face_alive_[f] = 1;
    if (normals) {
        for (std::uint32_t i = s.ring_begin; i < s.ring_end; ++i) face_normal(ring_[i] >> 2, 1);
        for (Index f : s.dead)
            if (f != kInvalidIndex) face_normal(f, 1);
    }
    if (track) {
        for (std::uint32_t i = s.ring_begin; i < s.ring_end; ++i) mark_vertices(ring_[i] >> 2);
        for (Index f : s.dead)
            if (f != kInvalidIndex) mark_vertices(f);
    }
}

void LevelOfDetail::set_level(std::size_t level) {
    level = std::min(level, steps_.size());
    if (level == level_) return;
    if (level < level_ && 2 * level < level_ - level) {
        // Far towards the fine mesh: from the fine state, fewer steps.
        faces_ = fine_faces_state_;
        positions_ = fine_positions_state_;
        normal_sum_ = fine_normals_state_;
        vertex_alive_ = fine_vertex_alive_state_;
        std::fill(face_alive_.begin(), face_alive_.end(), std::uint8_t(1));
        level_ = 0;
        clear_changes();
        all_changed_ = true;
        triangles_stale_ = live_vertices_stale_ = true;
        if (level == 0) return;
    }
    // Updating the normals step by step touches every ring face twice; recomputing them
    // touches every live face of the new level once (and scans the others).
    const std::size_t a = std::min(level, level_), b = std::max(level, level_);
    const std::uint64_t stepwise =
        2 * (ring_prefix_[b] - ring_prefix_[a]) + (removed_prefix_[b] - removed_prefix_[a]);
    const std::uint64_t all = fine_faces_ - removed_prefix_[level] + fine_faces_ / 8;
    const bool normals = stepwise <= all;
    if (!normals && !all_changed_) {
        clear_changes();
        all_changed_ = true;
    }
    const bool track = !all_changed_;
    while (level_ < level) collapse_step(steps_[level_++], normals, track);
    while (level_ > level) split_step(steps_[--level_], normals, track);
    if (!normals) recompute_normals();
    triangles_stale_ = live_vertices_stale_ = true;
}

const std::vector<std::array<Index, 3>>& LevelOfDetail::triangles() const {
    if (triangles_stale_) {
        triangles_.resize(n_triangles());
        std::size_t n = 0;
        for (Index f = 0; f < faces_.size(); ++f)
            if (face_alive_[f]) triangles_[n++] = faces_[f];
        triangles_stale_ = false;
    }
    return triangles_;
}

const std::vector<Index>& LevelOfDetail::live_vertices() const {
    if (live_vertices_stale_) {
        live_vertices_.resize(n_live_vertices());
        std::size_t n = 0;
        for (Index v = 0; v < vertex_alive_.size(); ++v)
            if (vertex_alive_[v]) live_vertices_[n++] = v;
        live_vertices_stale_ = false;
    }
    return live_vertices_;
}

void LevelOfDetail::clear_changes() {
    for (Index v : changed_vertices_) vertex_changed_[v] = 0;
    changed_vertices_.clear();
    all_changed_ = false;
}

std::size_t LevelOfDetail::level_for_percent(double percent) const {
    if (!(percent >= 0 && percent <= 100))
        throw InvalidArgument("level of detail: percent must be from 0 to 100, got " +
                              number_text(percent));
    const std::size_t keep = kept_vertices(percent, fine_vertices_);
    return std::min(fine_vertices_ - keep, max_level());
}

double LevelOfDetail::percent_at_level(std::size_t level) const {
    if (fine_vertices_ == 0) return 100;
    level = std::min(level, max_level());
    return 100.0 * double(fine_vertices_ - level) / double(fine_vertices_);
}

HalfedgeMesh LevelOfDetail::mesh() const {
    PolygonSoup soup;
    std::vector<Index> index(positions_.size(), kInvalidIndex);
    for (Index fine = 0; fine < vertex_of_.size(); ++fine) {
        const Index v = vertex_of_[fine];
        if (!vertex_alive_[v]) continue;
        index[v] = Index(soup.positions.size());
        soup.positions.push_back(positions_[v]);
    }
    for (Index fine = 0; fine < face_of_.size(); ++fine) {
        const Index f = face_of_[fine];
        if (f == kInvalidIndex || !face_alive_[f]) continue;
        const auto& c = faces_[f];
        soup.add_face({index[c[0]], index[c[1]], index[c[2]]});
    }
    LoadReport report;
    return build_mesh(soup, report);
}

}  // namespace trilab
