// Denoising by normal filtering (core/algorithms/denoise.h): Zheng et al. 2011 (bilateral),
// Zhang et al. 2015 (guided), then Sun et al. 2007's vertex update.
//
// The run works on dense face numbers (the live faces in storage order) and keeps, for every
// face, the list N(i) of the faces that share a vertex with it (itself included; degenerate
// faces left out) with the spatial part of the weight, A_j / mean area · exp(−|c_i − c_j|² /
// 2σ_s²), fixed during the normal iterations (the positions do not move then). A normal
// iteration is then one pass over these lists; the guided filter first scores every patch N(j):
//  - D, the largest normal difference within the patch, is sqrt(2 − 2 · the smallest dot
//    product of two of its normals) (all pairs);
//  - R's sums and maxima over the patch's edges come from per-vertex sums and maxima of φ over
//    the edges at each vertex: the edges of patch N(j) whose two faces are in the patch are
//    those at j's three corners (a face at a corner is in the patch), the three edges of j
//    itself counted twice in the sum of the corners' sums (rarer edges between two faces of
//    the patch away from j's corners are left out);
// and each face takes the mean normal of the patch of smallest D · R among the patches that
// contain it (N(j) contains i exactly when N(i) contains j).
// The positions live in a vector of their own until the end, so that a cancellation or a
// refused option leaves the mesh as it was; going back to the last good vertex iteration is a
// copy of that iteration's positions (kept only while later iterations leave folds).
#include "core/algorithms/denoise.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

#include "core/algorithms/feature_detection.h"
#include "core/algorithms/selection.h"
#include "core/errors.h"
#include "core/features.h"
#include "core/geometry.h"
#include "core/number_text.h"
#include "core/parallel.h"

namespace trilab {
namespace {

constexpr Index kNone = std::numeric_limits<Index>::max();
/// Guards R = max φ / (ε + Σ φ) against a patch without any normal difference.
constexpr double kConsistencyEpsilon = 1e-9;
/// A face whose area vector is at most this times the mean edge length squared has no normal.
constexpr double kDegenerateArea = 1e-12;
/// The tangential relaxation's step in each vertex iteration (a fraction of the way to the
/// area-weighted mean of the centroids around the vertex, along its tangent plane).
constexpr double kTangentialStep = 0.1;
/// Meshes with at least this many faces are worked on in a spatial order of their faces.
constexpr std::size_t kOrderFaces = 1 << 16;
constexpr double kDegrees = 57.295779513082320876798154814105;
/// The side check (check_sides()): a neighbour's normal this far from a face's (degrees) is
/// another side of a crease, and replaces it when its plane leaves the points around the face
/// at most this share of the energy.
constexpr double kSideMinAngle = 60.0;
constexpr double kSideMaxAngle = 120.0;
constexpr double kSideEnergyRatio = 0.5;

void check_options(const HalfedgeMesh& mesh, const DenoiseOptions& o) {
    const auto iterations = [](int n, const char* name) {
        if (n < 0 || n > kMaxDenoiseIterations)
            throw InvalidArgument(std::string("denoise: ") + name + " must be from 0 to " +
                                  std::to_string(kMaxDenoiseIterations) + ", got " +
                                  std::to_string(n));
    };
    iterations(o.normal_iterations, "normal_iterations");
    iterations(o.vertex_iterations, "vertex_iterations");
    const auto sigma = [](double s, double max, const char* name, const char* unit) {
        if (!std::isfinite(s) || !(s > 0) || s > max)
            throw InvalidArgument(std::string("denoise: ") + name +
                                  " must be a number above 0 and at most " + number_text(max) +
                                  unit + ", got " + number_text(s));
    };
    sigma(o.sigma_s, kMaxDenoiseSigmaS, "sigma_s", " (multiples of the mean edge length)");
    sigma(o.sigma_r, kMaxDenoiseSigmaR, "sigma_r", "");
    if (o.method != DenoiseMethod::Bilateral && o.method != DenoiseMethod::Guided)
        throw InvalidArgument("denoise: method must be " +
                              enum_ids(EnumTableView(kDenoiseMethods)));
    if (mesh.n_faces() == 0)
        throw InvalidArgument("denoise: the mesh has no faces (nothing to denoise)");
    for (Vertex v : mesh.vertices())
        if (!mesh.position(v).allFinite())
            throw InvalidArgument("denoise: vertex " + std::to_string(v.idx()) +
                                  " has a non-finite position");
    if (o.region) check_selection(mesh, *o.region, "denoise: region");
    if (o.features != FeatureSource::Stored && o.features != FeatureSource::None &&
        o.features != FeatureSource::Auto)
        throw InvalidArgument("denoise: features must be " +
                              enum_ids(EnumTableView(kFeatureSources)));
    if (o.features == FeatureSource::Auto &&
        !(std::isfinite(o.feature_angle) && o.feature_angle > 0 && o.feature_angle <= 180))
        throw InvalidArgument("denoise: feature_angle must be in (0, 180] degrees, got " +
                              number_text(o.feature_angle));
}

/// v / |v|, or `fallback` when v has no finite positive length: one square root and one
/// division (as norm() and three divisions it took 7 % of a run on 1.1M faces).
inline Vector3 normalized_or(const Vector3& v, const Vector3& fallback) {
    const double n2 = v.squaredNorm();
    if (!(n2 > 0) || !(n2 <= std::numeric_limits<double>::max())) return fallback;
    return v * (1.0 / std::sqrt(n2));
}

/// The range kernel exp(−|n − m|² / 2σ_r²) = exp((n · m − 1) / σ_r²) of unit vectors, as a
/// function of their dot product: a table over [−1, 1], linearly interpolated, fine enough that
/// the relative error stays below 1e-5 (about 256 / σ_r² entries, from 1,025 to 2^20).
class RangeKernel {
public:
    explicit RangeKernel(double sigma_r) {
        const double a = 1.0 / (sigma_r * sigma_r);
        const double n = std::clamp(256.0 * a, 1024.0, double(1 << 20));
        steps_ = int(n);
        scale_ = 0.5 * double(steps_);
        table_.resize(std::size_t(steps_) + 2);
        for (int i = 0; i <= steps_ + 1; ++i)
            table_[std::size_t(i)] = std::exp((double(i) / scale_ - 2.0) * a);
    }
    double operator()(double dot) const {
        const double t = (std::clamp(dot, -1.0, 1.0) + 1.0) * scale_;
        const int i = std::min(int(t), steps_ - 1);
        const double f = t - double(i);
        return table_[std::size_t(i)] + f * (table_[std::size_t(i) + 1] - table_[std::size_t(i)]);
    }

private:
    int steps_ = 0;
    double scale_ = 0;
    std::vector<double> table_;
};

/// The whole run; one method per stage.
class Denoiser {
public:
    Denoiser(const HalfedgeMesh& mesh, const DenoiseOptions& o, Progress& progress)
        : mesh_(mesh), o_(o), progress_(progress), pos_(mesh.positions()) {}

    DenoiseReport run() {
        report_.mean_edge_length = mean_edge_length(mesh_);
        number_faces();
        pick_sigma_r();
        build_vertex_faces();
        find_sectors();
        build_neighbourhoods();
        turn_inverted_normals();
        filter_normals();
        update_vertices();
        finish_report();
        return report_;
    }

private:
    // ---- set-up --------------------------------------------------------------------------

    /// The live faces in the order of the Morton code of their centroids (quantized to 2^21
    /// steps per axis of the bounding box; ties by index): the faces sharing a vertex are then
    /// mostly near in every array, which on large meshes saves most of the cache misses of the
    /// neighbourhood passes (about a third of the time on a million faces).
    void order_faces() {
        BoundingBox box;
        for (Face f : mesh_.faces()) {
            face_order_.push_back(f);
            box.extend(face_centroid(mesh_, f));
        }
        if (face_order_.size() < kOrderFaces) return;  // fits in the cache as it is
        const Vector3 size = box.size();
        const double extent = std::max({size.x(), size.y(), size.z()});
        const double scale = extent > 0 ? double((1u << 21) - 1) / extent : 0.0;
        std::vector<std::pair<std::uint64_t, Index>> keys;
        keys.reserve(face_order_.size());
        for (Face f : face_order_) {
            const Vector3 q = (face_centroid(mesh_, f) - box.min) * scale;
            keys.push_back({morton(q), f.idx()});
        }
        std::sort(keys.begin(), keys.end());
        for (std::size_t k = 0; k < keys.size(); ++k) face_order_[k] = Face(keys[k].second);
        // The vertices too: live ones in Morton order first, then the deleted ones.
        keys.clear();
        for (Vertex v : mesh_.vertices())
            keys.push_back({morton((mesh_.position(v) - box.min) * scale), v.idx()});
        std::sort(keys.begin(), keys.end());
        const std::size_t nv = mesh_.vertices_size();
        old_of_new_.clear();
        old_of_new_.reserve(nv);
        new_of_old_.assign(nv, kNone);
        for (const auto& key : keys) {
            new_of_old_[key.second] = Index(old_of_new_.size());
            old_of_new_.push_back(key.second);
        }
        for (std::size_t v = 0; v < nv; ++v)
            if (new_of_old_[v] == kNone) {
                new_of_old_[v] = Index(old_of_new_.size());
                old_of_new_.push_back(Index(v));
            }
        pos_ = input_positions();
    }

    /// Our vertex number of storage index `v`, and back (the same without a vertex order).
    Index internal(Index v) const { return new_of_old_.empty() ? v : new_of_old_[v]; }
    Index storage(Index v) const { return old_of_new_.empty() ? v : old_of_new_[v]; }
    /// The input's positions in our vertex numbering.
    std::vector<Point> input_positions() const {
        const std::vector<Point>& p = mesh_.positions();
        if (old_of_new_.empty()) return p;
        std::vector<Point> out(p.size());
        for (std::size_t v = 0; v < p.size(); ++v) out[v] = p[old_of_new_[v]];
        return out;
    }

public:
    /// The positions in storage order (after run()).
    std::vector<Point> storage_positions() {
        if (old_of_new_.empty()) return std::move(pos_);
        std::vector<Point> out(pos_.size());
        for (std::size_t v = 0; v < pos_.size(); ++v) out[old_of_new_[v]] = pos_[v];
        return out;
    }

private:
    /// The Morton code of a point in [0, 2^21)^3 (its coordinates' bits interleaved).
    static std::uint64_t morton(const Vector3& q) {
        const auto spread = [](double c) {
            std::uint64_t x = std::uint64_t(std::clamp(c, 0.0, double((1u << 21) - 1)));
            x = (x | (x << 32)) & 0x1f00000000ffffull;
            x = (x | (x << 16)) & 0x1f0000ff0000ffull;
            x = (x | (x << 8)) & 0x100f00f00f00f00full;
            x = (x | (x << 4)) & 0x10c30c30c30c30c3ull;
            x = (x | (x << 2)) & 0x1249249249249249ull;
            return x;
        };
        return spread(q.x()) | (spread(q.y()) << 1) | (spread(q.z()) << 2);
    }

    /// Dense face numbers, corners, area vectors; which faces are degenerate and which active.
    void number_faces() {
        const double h = report_.mean_edge_length;
        degenerate_area_ = kDegenerateArea * h * h;
        order_faces();
        for (Face f : face_order_) {
            const auto c = mesh_.face_vertices(f);
            corners_.push_back({internal(c[0].idx()), internal(c[1].idx()), internal(c[2].idx())});
        }
        const std::size_t nf = corners_.size();
        area_vec_.resize(nf);
        normal_.assign(nf, Vector3::Zero());
        area_.assign(nf, 0.0);
        centroid_.resize(nf);
        active_.assign(nf, 0);
        double total_area = 0;
        for (std::size_t f = 0; f < nf; ++f) {
            area_vec_[f] = area_vector(pos_, f);
            centroid_[f] = centroid(pos_, f);
            const double len = area_vec_[f].norm();
            if (!(len > degenerate_area_)) {
                ++report_.degenerate_faces;
                continue;
            }
            normal_[f] = area_vec_[f] / len;
            area_[f] = 0.5 * len;
            total_area += area_[f];
            const auto& c = corners_[f];
            active_[f] = !o_.region || weight(c[0]) > 0 || weight(c[1]) > 0 || weight(c[2]) > 0;
            report_.filtered_faces += active_[f];
        }
        const std::size_t good = nf - report_.degenerate_faces;
        mean_area_ = good ? total_area / double(good) : 1.0;
        input_normal_ = normal_;
    }

    /// The noise level (the median of |n_f − n_g| over the interior edges between two active
    /// faces) and the range sigma: the given one, or kDenoiseSigmaRPerNoise times the noise
    /// level within the automatic bounds (DenoiseOptions::fixed_sigma_r). O(E).
    void pick_sigma_r() {
        std::vector<Index> dense(mesh_.faces_size(), kNone);
        for (std::size_t k = 0; k < face_order_.size(); ++k) dense[face_order_[k].idx()] = Index(k);
        std::vector<double> differences;
        differences.reserve(mesh_.n_edges());
        for (Edge e : mesh_.edges()) {
            const Halfedge h0 = HalfedgeMesh::halfedge(e, 0), h1 = HalfedgeMesh::halfedge(e, 1);
            if (mesh_.is_boundary(h0) || mesh_.is_boundary(h1)) continue;
            const Index f = dense[mesh_.face(h0).idx()], g = dense[mesh_.face(h1).idx()];
            if (active_[f] && active_[g]) differences.push_back((normal_[f] - normal_[g]).norm());
        }
        if (!differences.empty()) {
            const auto middle = differences.begin() + std::ptrdiff_t(differences.size() / 2);
            std::nth_element(differences.begin(), middle, differences.end());
            report_.noise_level = *middle;
        }
        sigma_r_ = o_.fixed_sigma_r ? o_.sigma_r
                                    : std::clamp(kDenoiseSigmaRPerNoise * report_.noise_level,
                                                 kDenoiseAutoSigmaRMin, kDenoiseAutoSigmaRMax);
        report_.sigma_r = sigma_r_;
        range_kernel_ = RangeKernel(sigma_r_);
    }

    /// For every vertex storage index, its non-degenerate faces (CSR).
    void build_vertex_faces() {
        const std::size_t nv = mesh_.vertices_size(), nf = corners_.size();
        vf_offset_.assign(nv + 1, 0);
        for (std::size_t f = 0; f < nf; ++f)
            if (has_normal(f))
                for (Index v : corners_[f]) ++vf_offset_[v + 1];
        for (std::size_t v = 0; v < nv; ++v) vf_offset_[v + 1] += vf_offset_[v];
        vf_.resize(vf_offset_[nv]);
        std::vector<Index> fill(vf_offset_.begin(), vf_offset_.end() - 1);
        for (std::size_t f = 0; f < nf; ++f)
            if (has_normal(f))
                for (Index v : corners_[f]) vf_[fill[v]++] = Index(f);
    }

    /// N(i) for every non-degenerate face, with the spatial weights.
    void build_neighbourhoods() {
        const std::size_t nf = corners_.size();
        const double sigma = o_.sigma_s * report_.mean_edge_length;
        const double inv_two_sigma2 = sigma > 0 ? 1.0 / (2 * sigma * sigma) : 0.0;
        nb_offset_.assign(nf + 1, 0);
        nb_.reserve(14 * nf);
        spatial_.reserve(14 * nf);
        std::vector<Index> mark(nf, kNone), blocked(sector_.empty() ? 0 : nf, kNone);
        for (std::size_t i = 0; i < nf; ++i) {
            nb_offset_[i] = Index(nb_.size());
            if (!has_normal(i)) continue;
            if (!sector_.empty()) block_other_sectors(Index(i), blocked);
            for (Index v : corners_[i])
                for (Index k = vf_offset_[v]; k < vf_offset_[v + 1]; ++k) {
                    const Index j = vf_[k];
                    if (mark[j] == Index(i) || (!blocked.empty() && blocked[j] == Index(i)))
                        continue;
                    mark[j] = Index(i);
                    nb_.push_back(j);
                    const double d2 = (centroid_[i] - centroid_[j]).squaredNorm();
                    spatial_.push_back(
                        float(area_[j] / mean_area_ * std::exp(-d2 * inv_two_sigma2)));
                }
        }
        nb_offset_[nf] = Index(nb_.size());
    }

    // ---- stored features -----------------------------------------------------------------

    /// With features (DenoiseOptions::features): the sharp edges cut the fan of faces around
    /// each vertex into sectors; sector_[3 f + c] is face f's sector at its corner c, and
    /// feature_vertex_ marks the vertices on a sharp edge and the tagged corners.
    void find_sectors() {
        if (o_.features == FeatureSource::None || !has_features(mesh_)) return;
        const std::size_t nf = corners_.size();
        std::vector<Index> dense(mesh_.faces_size(), kNone);
        for (std::size_t k = 0; k < nf; ++k) dense[face_order_[k].idx()] = Index(k);
        sector_.assign(3 * nf, 0);
        feature_vertex_.assign(mesh_.vertices_size(), 0);
        for (Edge e : mesh_.edges()) report_.feature_edges += sharpness(mesh_, e) > 0;
        std::vector<std::pair<Index, std::uint16_t>> fan;  // (dense face, sector)
        std::vector<Halfedge> out;                         // the outgoing halfedges
        std::vector<std::uint8_t> cut;                     // whether the fan is cut there
        for (Vertex v : mesh_.vertices()) {
            if (mesh_.is_isolated(v)) continue;
            const Index iv = internal(v.idx());
            feature_vertex_[iv] = is_corner_tagged(mesh_, v);
            fan.clear();
            out.clear();
            for (Halfedge h : mesh_.halfedges_around(v)) out.push_back(h);
            cut.assign(out.size(), 0);
            std::size_t sharp_edges = 0, last_sharp = 0;
            for (std::size_t k = 0; k < out.size(); ++k)
                if (sharpness(mesh_, HalfedgeMesh::edge(out[k])) > 0) {
                    cut[k] = 1;
                    ++sharp_edges;
                    last_sharp = k;
                }
            const bool inner = !mesh_.is_boundary(v);
            // A dart (one sharp edge, inside): its fan is also cut at the edge half way round,
            // so the faces on either side of the sharp edge stay apart up to its tip.
            if (inner && sharp_edges == 1) cut[(last_sharp + out.size() / 2) % out.size()] = 1;
            if (sharp_edges > 0) feature_vertex_[iv] = 1;
            std::uint16_t sector = 0;
            for (std::size_t k = 0; k < out.size(); ++k) {
                sector = std::uint16_t(sector + cut[k]);
                if (!mesh_.is_boundary(out[k]))
                    fan.push_back({dense[mesh_.face(out[k]).idx()], sector});
            }
            // Around an inner vertex the last sector runs on into the first.
            for (const auto& [f, sec] : fan) {
                const std::uint16_t label = inner && sec == sector ? 0 : sec;
                for (std::size_t c = 0; c < 3; ++c)
                    if (corners_[f][c] == iv) sector_[3 * std::size_t(f) + c] = label;
            }
        }
        for (std::uint8_t fv : feature_vertex_) report_.feature_vertices += fv;
    }

    /// blocked[j] = i for the faces j that share a corner with face i but lie in another
    /// sector there (across a sharp edge from it).
    void block_other_sectors(Index i, std::vector<Index>& blocked) const {
        for (std::size_t c = 0; c < 3; ++c) {
            const Index v = corners_[i][c];
            const std::uint16_t own = sector_[3 * std::size_t(i) + c];
            for (Index k = vf_offset_[v]; k < vf_offset_[v + 1]; ++k) {
                const Index j = vf_[k];
                for (std::size_t d = 0; d < 3; ++d)
                    if (corners_[j][d] == v && sector_[3 * std::size_t(j) + d] != own)
                        blocked[j] = i;
            }
        }
    }

    // ---- normal filtering ----------------------------------------------------------------

    /// A face whose normal points away from the mean normal of the faces around it was turned
    /// over by the noise (a tangential displacement folds a small triangle): no range kernel
    /// can bring it back (it is its own only similar neighbour), so its filtering starts from
    /// that mean instead. The face itself is untangled by the vertex update.
    /// Such a face's own normal says nothing about its neighbours', so it takes no part in
    /// their filtering (its spatial weight in the others' N(i) is 0): two adjacent turned-over
    /// faces no longer hold each other on a blend of both sides of a crease (fandisk at k = 0.7:
    /// theta about 0.4 degrees lower).
    void turn_inverted_normals() {
        std::vector<std::uint8_t> inverted(corners_.size(), 0);
        std::vector<Vector3> start = normal_;
        const auto turn = [&](std::size_t begin, std::size_t end) {
            std::size_t count = 0;
            for (std::size_t i = begin; i < end; ++i) {
                if (!active_[i]) continue;
                Vector3 mean = Vector3::Zero();
                for (Index k = nb_offset_[i]; k < nb_offset_[i + 1]; ++k)
                    if (nb_[k] != Index(i)) mean += area_[nb_[k]] * normal_[nb_[k]];
                if (mean.dot(normal_[i]) < 0) {
                    start[i] = normalized_or(mean, normal_[i]);
                    inverted[i] = 1;
                    ++count;
                }
            }
            return count;
        };
        report_.inverted_faces =
            parallel_reduce(std::size_t(0), corners_.size(), std::size_t(0), turn,
                            [](std::size_t a, std::size_t b) { return a + b; });
        normal_.swap(start);
        if (report_.inverted_faces == 0) return;
        parallel_for_blocks(0, corners_.size(), [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i)
                for (Index k = nb_offset_[i]; k < nb_offset_[i + 1]; ++k)
                    if (nb_[k] != Index(i) && inverted[nb_[k]]) spatial_[k] = 0;
        });
    }

    void filter_normals() {
        const std::size_t nf = corners_.size();
        const int total = o_.normal_iterations + o_.vertex_iterations;
        std::vector<Vector3> next(nf);
        if (o_.method == DenoiseMethod::Guided) prepare_guided();
        for (int it = 0; it < o_.normal_iterations; ++it) {
            progress_.check_cancelled();
            progress_.report(total ? double(it) / total : 0, "filtering the normals");
            const std::vector<Vector3>& range =
                o_.method == DenoiseMethod::Guided ? guidance() : normal_;
            filter_once(range, next);
            normal_.swap(next);
            ++report_.normal_iterations_done;
        }
        if (o_.side_check && report_.normal_iterations_done > 0) check_sides(next);
    }

    /// The side check (see the file comment of denoise.h): a face whose filtered normal is that
    /// of the other side of a crease gets the normal, among its neighbours', of the plane its
    /// vertices and those of its edge neighbours fit clearly better. One pass; each face reads
    /// the filtered normals only, so the result does not depend on the order. O(F · m).
    void check_sides(std::vector<Vector3>& out) {
        const double cos_near = std::cos(kSideMinAngle / kDegrees);
        const double cos_far = std::cos(kSideMaxAngle / kDegrees);
        report_.side_corrected_faces = parallel_reduce(
            std::size_t(0), corners_.size(), std::size_t(0),
            [&](std::size_t begin, std::size_t end) {
                std::size_t count = 0;
                for (std::size_t i = begin; i < end; ++i) {
                    out[i] = normal_[i];
                    if (!active_[i]) continue;
                    const Scatter scatter = local_scatter(i);
                    const Vector3& n = normal_[i];
                    double best = kSideEnergyRatio * scatter.energy(n);
                    Index pick = kNone;
                    for (Index k = nb_offset_[i]; k < nb_offset_[i + 1]; ++k) {
                        const Vector3& m = normal_[nb_[k]];
                        const double c = m.dot(n);
                        if (c > cos_near || c < cos_far) continue;
                        const double e = scatter.energy(m);
                        if (e < best) {
                            best = e;
                            pick = nb_[k];
                        }
                    }
                    if (pick != kNone) {
                        out[i] = normal_[pick];
                        ++count;
                    }
                }
                return count;
            },
            [](std::size_t a, std::size_t b) { return a + b; });
        normal_.swap(out);
    }

    /// The scatter matrix (about their mean) of face i's corners and of the far corners of its
    /// edge neighbours, at the input's positions: energy(n) = Σ (n · (p − mean))², how far the
    /// points lie off the best plane of normal n.
    struct Scatter {
        double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
        double energy(const Vector3& n) const {
            return xx * n.x() * n.x() + yy * n.y() * n.y() + zz * n.z() * n.z() +
                   2 * (xy * n.x() * n.y() + xz * n.x() * n.z() + yz * n.y() * n.z());
        }
    };
    Scatter local_scatter(std::size_t i) const {
        Point points[6];
        int m = 0;
        for (Index v : corners_[i]) points[m++] = pos_[v];
        Halfedge h = mesh_.halfedge(face_order_[i]);
        for (int k = 0; k < 3; ++k, h = mesh_.next(h)) {
            const Halfedge t = HalfedgeMesh::twin(h);
            if (!mesh_.is_boundary(t))
                points[m++] = pos_[internal(mesh_.to_vertex(mesh_.next(t)).idx())];
        }
        Point mean = Point::Zero();
        for (int k = 0; k < m; ++k) mean += points[k];
        mean /= double(m);
        Scatter s;
        for (int k = 0; k < m; ++k) {
            const Vector3 d = points[k] - mean;
            s.xx += d.x() * d.x();
            s.xy += d.x() * d.y();
            s.xz += d.x() * d.z();
            s.yy += d.y() * d.y();
            s.yz += d.y() * d.z();
            s.zz += d.z() * d.z();
        }
        return s;
    }

    /// One pass of the (joint) bilateral filter: the range kernel reads `range`.
    void filter_once(const std::vector<Vector3>& range, std::vector<Vector3>& out) const {
        parallel_for_blocks(0, corners_.size(), [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                if (!active_[i]) {
                    out[i] = normal_[i];
                    continue;
                }
                const Vector3 ri = range[i];
                Vector3 sum = Vector3::Zero();
                for (Index k = nb_offset_[i]; k < nb_offset_[i + 1]; ++k) {
                    const Index j = nb_[k];
                    const double w = double(spatial_[k]) * range_kernel_(ri.dot(range[j]));
                    sum += w * normal_[j];
                }
                out[i] = normalized_or(sum, normal_[i]);
            }
        });
    }

    /// The interior edges between two faces with normals, and each face's three of them.
    void prepare_guided() {
        const std::size_t nf = corners_.size();
        face_edges_.assign(nf, {kNone, kNone, kNone});
        std::vector<Index> dense(mesh_.faces_size(), kNone);
        for (std::size_t k = 0; k < face_order_.size(); ++k) dense[face_order_[k].idx()] = Index(k);
        for (Edge e : mesh_.edges()) {
            const Halfedge h0 = HalfedgeMesh::halfedge(e, 0), h1 = HalfedgeMesh::halfedge(e, 1);
            if (mesh_.is_boundary(h0) || mesh_.is_boundary(h1)) continue;
            const Index f = dense[mesh_.face(h0).idx()], g = dense[mesh_.face(h1).idx()];
            if (!has_normal(f) || !has_normal(g)) continue;
            const Index id = Index(edge_faces_.size());
            edge_faces_.push_back({f, g});
            edge_vertices_.push_back(
                {internal(mesh_.to_vertex(h0).idx()), internal(mesh_.to_vertex(h1).idx())});
            for (const Index x : {f, g})
                for (Index& slot : face_edges_[x])
                    if (slot == kNone) {
                        slot = id;
                        break;
                    }
        }
        // Per vertex its edges, in edge order (CSR).
        const std::size_t nv = mesh_.vertices_size();
        ve_offset_.assign(nv + 1, 0);
        for (const auto& ev : edge_vertices_)
            for (Index v : ev) ++ve_offset_[v + 1];
        for (std::size_t v = 0; v < nv; ++v) ve_offset_[v + 1] += ve_offset_[v];
        ve_.resize(ve_offset_[nv]);
        std::vector<Index> fill(ve_offset_.begin(), ve_offset_.end() - 1);
        for (std::size_t e = 0; e < edge_vertices_.size(); ++e)
            for (Index v : edge_vertices_[e]) ve_[fill[v]++] = Index(e);
        guidance_.assign(nf, Vector3::Zero());
        patch_mean_.assign(nf, Vector3::Zero());
        patch_score_.assign(nf, 0.0);
        vertex_best_.assign(mesh_.vertices_size(), kNone);
        packed_.assign(nf, {0, 0, 0, 0});
    }

    /// Every face's guidance normal from the current normals.
    const std::vector<Vector3>& guidance() {
        const std::size_t nf = corners_.size(), nv = mesh_.vertices_size();
        std::vector<double> phi(edge_faces_.size());
        std::vector<double> vsum(nv, 0.0), vmax(nv, 0.0);
        parallel_for_blocks(0, phi.size(), [&](std::size_t begin, std::size_t end) {
            for (std::size_t e = begin; e < end; ++e)
                phi[e] = (normal_[edge_faces_[e][0]] - normal_[edge_faces_[e][1]]).norm();
        });
        // Each vertex gathers its edges' φ in edge order: the sums of a scatter over the edges.
        parallel_for_blocks(0, nv, [&](std::size_t begin, std::size_t end) {
            for (std::size_t v = begin; v < end; ++v)
                for (Index k = ve_offset_[v]; k < ve_offset_[v + 1]; ++k) {
                    vsum[v] += phi[ve_[k]];
                    vmax[v] = std::max(vmax[v], phi[ve_[k]]);
                }
        });
        parallel_for_blocks(0, nf, [&](std::size_t begin, std::size_t end) {
            for (std::size_t f = begin; f < end; ++f) {
                const Vector3& n = normal_[f];
                packed_[f] = {float(n.x()), float(n.y()), float(n.z()),
                              float(area_[f] / mean_area_)};
            }
        });
        parallel_for_blocks(0, nf, [&](std::size_t begin, std::size_t end) {
            for (std::size_t j = begin; j < end; ++j) score_patch(j, phi, vsum, vmax);
        });
        if (!sector_.empty()) {  // features: N(i) is no longer every face at i's corners
            parallel_for_blocks(0, nf, [&](std::size_t begin, std::size_t end) {
                for (std::size_t i = begin; i < end; ++i) {
                    if (!active_[i]) continue;
                    Index best = kNone;
                    for (Index k = nb_offset_[i]; k < nb_offset_[i + 1]; ++k)
                        if (best == kNone || patch_score_[nb_[k]] < patch_score_[best])
                            best = nb_[k];
                    guidance_[i] = best == kNone ? normal_[i] : patch_mean_[best];
                }
            });
            return guidance_;
        }
        // The patches containing face i are N(j) for the faces j at its corners, so the best
        // one is the best of each corner's best (3 look-ups a face, not one per neighbour).
        parallel_for_blocks(0, nv, [&](std::size_t begin, std::size_t end) {
            for (std::size_t v = begin; v < end; ++v) {
                Index best = kNone;
                for (Index k = vf_offset_[v]; k < vf_offset_[v + 1]; ++k)
                    if (best == kNone || patch_score_[vf_[k]] < patch_score_[best]) best = vf_[k];
                vertex_best_[v] = best;
            }
        });
        parallel_for_blocks(0, nf, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                if (!active_[i]) continue;
                Index best = kNone;
                for (Index v : corners_[i]) {
                    const Index b = vertex_best_[v];
                    if (b != kNone && (best == kNone || patch_score_[b] < patch_score_[best]))
                        best = b;
                }
                guidance_[i] = best == kNone ? normal_[i] : patch_mean_[best];
            }
        });
        return guidance_;
    }

    /// The area-weighted mean normal (normalized) of the faces nb_[begin, end), and the smallest
    /// dot product of two of their normals (all pairs). The normals are copied side by side in
    /// single precision (plenty for D) into lanes of a fixed width (16 or 32; the usual patch
    /// has about 13 faces): each offset is then a fixed-length pass over independent lanes
    /// that the compiler vectorizes, not a chain of scalar minima (patch_normals_lanes()).
    std::pair<Vector3, double> patch_normals(Index begin, Index end) const {
        const Index m = end - begin;
        if (m <= 16) return patch_normals_lanes<16>(begin, end);
        if (m <= 32) return patch_normals_lanes<32>(begin, end);
        Vector3 mean = Vector3::Zero();
        double min_dot = 1;
        for (Index a = begin; a < end; ++a) {
            mean += area_[nb_[a]] * normal_[nb_[a]];
            for (Index b = a + 1; b < end; ++b)
                min_dot = std::min(min_dot, normal_[nb_[a]].dot(normal_[nb_[b]]));
        }
        return {mean, min_dot};
    }

    /// Four single-precision lanes (GCC and Clang vector extension: SSE, NEON or scalar code).
    typedef float Lanes4 __attribute__((vector_size(16)));

    /// The normals are written twice over, x[t] = x[t mod m] for t < 2 · Lanes: lane b of
    /// offset s is the pair (b, b + s), and the offsets 1 to m / 2 cover every pair of the m
    /// normals (offsets s and m − s give the same pairs; the lanes past m repeat pairs).
    template <int Lanes>
    std::pair<Vector3, double> patch_normals_lanes(Index begin, Index end) const {
        constexpr int kGroupCount = Lanes / 4;
        alignas(16) float x[2 * Lanes], y[2 * Lanes], z[2 * Lanes];
        float mx = 0, my = 0, mz = 0;
        const int m = int(end - begin);
        for (int a = 0; a < m; ++a) {
            const std::array<float, 4>& n = packed_[nb_[begin + Index(a)]];
            x[a] = n[0];
            y[a] = n[1];
            z[a] = n[2];
            mx += n[3] * n[0];
            my += n[3] * n[1];
            mz += n[3] * n[2];
        }
        for (int t = m; t < 2 * Lanes; ++t) {
            x[t] = x[t - m];
            y[t] = y[t - m];
            z[t] = z[t - m];
        }
        Lanes4 vx[kGroupCount], vy[kGroupCount], vz[kGroupCount], low[kGroupCount];
        for (int g = 0; g < kGroupCount; ++g) {
            std::memcpy(&vx[g], x + 4 * g, sizeof(Lanes4));
            std::memcpy(&vy[g], y + 4 * g, sizeof(Lanes4));
            std::memcpy(&vz[g], z + 4 * g, sizeof(Lanes4));
            low[g] = Lanes4{1, 1, 1, 1};
        }
        for (int offset = 1; offset <= m / 2; ++offset) {
            for (int g = 0; g < kGroupCount; ++g) {
                Lanes4 sx, sy, sz;
                std::memcpy(&sx, x + 4 * g + offset, sizeof(Lanes4));
                std::memcpy(&sy, y + 4 * g + offset, sizeof(Lanes4));
                std::memcpy(&sz, z + 4 * g + offset, sizeof(Lanes4));
                const Lanes4 d = vx[g] * sx + vy[g] * sy + vz[g] * sz;
                low[g] = d < low[g] ? d : low[g];
            }
        }
        for (int g = 1; g < kGroupCount; ++g) low[0] = low[g] < low[0] ? low[g] : low[0];
        const float smallest =
            std::min(std::min(low[0][0], low[0][1]), std::min(low[0][2], low[0][3]));
        return {Vector3(mx, my, mz), double(smallest)};
    }

    /// Patch N(j)'s consistency D · R and its area-weighted mean normal.
    void score_patch(std::size_t j, const std::vector<double>& phi, const std::vector<double>& vsum,
                     const std::vector<double>& vmax) {
        const Index begin = nb_offset_[j], end = nb_offset_[j + 1];
        if (begin == end) return;
        const auto [mean, min_dot] = patch_normals(begin, end);
        patch_mean_[j] = normalized_or(mean, normal_[j]);
        const auto& c = corners_[j];
        double sum = vsum[c[0]] + vsum[c[1]] + vsum[c[2]];
        for (Index e : face_edges_[j])
            if (e != kNone) sum -= phi[e];
        const double max = std::max({vmax[c[0]], vmax[c[1]], vmax[c[2]]});
        const double d = std::sqrt(std::max(0.0, 2 - 2 * min_dot));
        patch_score_[j] = d * max / (kConsistencyEpsilon + std::max(0.0, sum));
    }

    // ---- vertex update -------------------------------------------------------------------

    void update_vertices() {
        const std::size_t nf = corners_.size();
        const int total = o_.normal_iterations + o_.vertex_iterations;
        // Faces already on the far side of their filtered normals (turned over by the noise)
        // are the vertex update's to untangle, not its folds.
        inverted_at_start_.assign(nf, 0);
        current_area_.assign(nf, 0.0);
        for (std::size_t f = 0; f < nf; ++f)
            inverted_at_start_[f] = has_normal(f) && !(area_vec_[f].dot(normal_[f]) > 0);
        std::vector<Point> next = pos_, good;
        int good_iterations = 0;
        std::size_t folded = 0;
        for (int it = 0; it < o_.vertex_iterations; ++it) {
            progress_.check_cancelled();
            progress_.report(double(o_.normal_iterations + it) / total, "moving the vertices");
            parallel_for_blocks(0, nf, [&](std::size_t begin, std::size_t end) {
                for (std::size_t f = begin; f < end; ++f) {
                    centroid_[f] = centroid(pos_, f);
                    current_area_[f] = area_vector(pos_, f).norm();
                }
            });
            move_vertices(next);
            if (!finite_) {
                stop(it, 0, good_iterations, good);
                return;
            }
            repair_inverted(next);
            pos_.swap(next);
            folded = count_folds();
            if (folded == 0) {
                good_iterations = it + 1;
                good.clear();  // pos_ is the good state
            } else if (good.empty() && it > 0 && good_iterations == it) {
                good = next;  // the state before this iteration
            }
            report_.vertex_iterations_done = it + 1;
        }
        if (folded == 0) return;
        // The last iteration left folds (the ones before may, on the way to untangling the
        // faces the noise turned over): keep its state but where it folds, there going back
        // towards the last state without folds.
        const std::vector<Point> base = good_iterations == 0 ? input_positions() : good;
        if (good_iterations == 0 || !good.empty()) {
            hold_folds(pos_, base);
            folded = count_folds();
        }
        if (folded > 0) stop(o_.vertex_iterations - 1, folded, good_iterations, good);
    }

    /// Goes back to the state after `good_iterations` iterations (`good`, or the input when
    /// `good` is empty and no iteration was good) and says why.
    void stop(int iteration, std::size_t folded, int good_iterations, std::vector<Point>& good) {
        report_.stopped_early = true;
        report_.folded_faces = folded;
        report_.vertex_iterations_done = good_iterations;
        if (good_iterations == 0)
            pos_ = input_positions();
        else if (!good.empty())
            pos_.swap(good);
        const std::string kept = "kept the state after vertex iteration " +
                                 std::to_string(good_iterations) + " of " +
                                 std::to_string(o_.vertex_iterations);
        if (!finite_)
            report_.stop_reason = "vertex iteration " + std::to_string(iteration + 1) +
                                  " gave a non-finite position; " + kept;
        else
            report_.stop_reason = "the vertex update folded " +
                                  count_text(folded, "face", "faces") +
                                  " (turned away from its filtered normal, or flat); " + kept +
                                  " (try fewer vertex iterations, or a larger sigma_r)";
    }

    /// next = the positions after one step of Sun et al.'s update.
    void move_vertices(std::vector<Point>& next) {
        const auto block = [&](std::size_t begin, std::size_t end) {
            bool ok = true;
            for (std::size_t v = begin; v < end; ++v) {
                next[v] = pos_[v];
                const Index fb = vf_offset_[v], fe = vf_offset_[v + 1];
                const double w = weight(Index(v));
                if (fb == fe || !(w > 0)) continue;
                Vector3 delta = Vector3::Zero(), n = Vector3::Zero();
                Point mean = Point::Zero();
                double area = 0;
                for (Index k = fb; k < fe; ++k) {
                    const Index f = vf_[k];
                    delta += normal_[f] * normal_[f].dot(centroid_[f] - pos_[v]);
                    const double a = current_area_[f];
                    mean += a * centroid_[f];
                    area += a;
                    n += normal_[f];
                }
                delta /= double(fe - fb);
                // The tangential relaxation (not on features: it would pull a crease's
                // vertices off its line and round a corner).
                if (area > 0 && (feature_vertex_.empty() || !feature_vertex_[v])) {
                    n = normalized_or(n, Vector3::Zero());
                    Vector3 t = mean / area - pos_[v];
                    t -= n * n.dot(t);
                    delta += kTangentialStep * t;
                }
                next[v] = o_.region ? Point(pos_[v] + w * delta) : Point(pos_[v] + delta);
                ok = ok && next[v].allFinite();
            }
            return ok;
        };
        finite_ = parallel_reduce(std::size_t(0), mesh_.vertices_size(), true, block,
                                  [](bool a, bool b) { return a && b; });
    }

    /// Whether area vector `a` of face f is a fold: no area, or on the far side of the face's
    /// filtered normal (and the face did not start there).
    bool folds(const Vector3& a, std::size_t f) const {
        return !(a.norm() > degenerate_area_) ||
               (!inverted_at_start_[f] && !(a.dot(normal_[f]) > 0));
    }

    /// Unfolds `next` towards `base`, a state without folds: the corners of a face that `next`
    /// folds go half way back to their places in `base`, up to kHalvings times, then all the
    /// way back; again until no face folds (at worst every vertex is back in `base`). Counts
    /// the vertices held back in the report. O(F) a round.
    void hold_folds(std::vector<Point>& next, const std::vector<Point>& base) {
        constexpr int kHalvings = 4;
        std::vector<Index> marked, held;
        for (int round = 0; round <= kHalvings + int(corners_.size()); ++round) {
            marked.clear();
            for (std::size_t f = 0; f < corners_.size(); ++f)
                if (has_normal(f) && folds(area_vector(next, f), f))
                    for (Index v : corners_[f]) marked.push_back(v);
            if (marked.empty()) break;
            std::sort(marked.begin(), marked.end());
            marked.erase(std::unique(marked.begin(), marked.end()), marked.end());
            for (Index v : marked) {
                next[v] = round < kHalvings ? Point(0.5 * (base[v] + next[v])) : base[v];
                held.push_back(v);
            }
        }
        std::sort(held.begin(), held.end());
        report_.held_vertices = std::size_t(std::unique(held.begin(), held.end()) - held.begin());
    }

    /// Untangles the faces that `next` leaves on the far side of their filtered normals: each
    /// corner of such a face moves to the mean of its neighbours, along the plane of the mean
    /// filtered normal of its faces (a tangential step: it does not pull the surface in).
    void repair_inverted(std::vector<Point>& next) {
        // Each block lists its faces' corners (scratch of its own), then the lists are joined.
        std::vector<std::vector<Index>> found(block_count(0, corners_.size()));
        parallel_for_blocks(0, corners_.size(), [&](std::size_t begin, std::size_t end) {
            std::vector<Index>& list = found[begin / kBlock];
            for (std::size_t f = begin; f < end; ++f) {
                if (!has_normal(f) || area_vector(next, f).dot(normal_[f]) > 0) continue;
                for (Index v : corners_[f]) list.push_back(v);
            }
        });
        std::vector<Index> marked;
        for (const auto& list : found) marked.insert(marked.end(), list.begin(), list.end());
        if (marked.empty()) return;
        std::sort(marked.begin(), marked.end());
        marked.erase(std::unique(marked.begin(), marked.end()), marked.end());
        std::vector<Point> moved(marked.size());
        for (std::size_t k = 0; k < marked.size(); ++k) {
            const Index v = marked[k];
            moved[k] = next[v];
            const double w = weight(v);
            if (!(w > 0)) continue;
            Vector3 n = Vector3::Zero();
            for (Index i = vf_offset_[v]; i < vf_offset_[v + 1]; ++i) n += normal_[vf_[i]];
            n = normalized_or(n, Vector3::Zero());
            Point mean = Point::Zero();
            int count = 0;
            for (Vertex u : mesh_.vertices_around(Vertex(storage(v)))) {
                mean += next[internal(u.idx())];
                ++count;
            }
            if (count == 0) continue;
            Vector3 d = mean / double(count) - next[v];
            d -= n * n.dot(d);
            moved[k] = next[v] + w * d;
        }
        for (std::size_t k = 0; k < marked.size(); ++k) next[marked[k]] = moved[k];
    }

    /// Faces that pos_ folds: on the far side of their filtered normal (and not at the start),
    /// or without area.
    std::size_t count_folds() const {
        return parallel_reduce(
            std::size_t(0), corners_.size(), std::size_t(0),
            [&](std::size_t begin, std::size_t end) {
                std::size_t count = 0;
                for (std::size_t f = begin; f < end; ++f)
                    if (has_normal(f)) count += folds(area_vector(pos_, f), f);
                return count;
            },
            [](std::size_t a, std::size_t b) { return a + b; });
    }

    void finish_report() {
        for (std::size_t f = 0; f < corners_.size(); ++f)
            if (has_normal(f) && inverted_at_start_[f] &&
                !(area_vector(pos_, f).dot(normal_[f]) > 0))
                ++report_.inverted_left_faces;
        double sum = 0, max = 0;
        std::size_t n = 0;
        for (std::size_t f = 0; f < corners_.size(); ++f) {
            if (!active_[f]) continue;
            const Vector3 &a = normal_[f], &b = input_normal_[f];
            const double angle = std::atan2(a.cross(b).norm(), a.dot(b)) * kDegrees;
            sum += angle;
            max = std::max(max, angle);
            ++n;
        }
        report_.mean_normal_change_degrees = n ? sum / double(n) : 0;
        report_.max_normal_change_degrees = max;
        const std::vector<Point>& input = mesh_.positions();
        for (Vertex v : mesh_.vertices()) {
            const double d = (pos_[internal(v.idx())] - input[v.idx()]).norm();
            report_.max_displacement = std::max(report_.max_displacement, d);
            report_.moved_vertices += d > 0;
        }
    }

    // ---- small helpers -------------------------------------------------------------------

    Vector3 area_vector(const std::vector<Point>& p, std::size_t f) const {
        const auto& c = corners_[f];
        return (p[c[1]] - p[c[0]]).cross(p[c[2]] - p[c[0]]);
    }
    Point centroid(const std::vector<Point>& p, std::size_t f) const {
        const auto& c = corners_[f];
        return (p[c[0]] + p[c[1]] + p[c[2]]) / 3.0;
    }
    bool has_normal(std::size_t f) const { return area_[f] > 0; }
    double weight(Index v) const { return o_.region ? double((*o_.region)[storage(v)]) : 1.0; }

    const HalfedgeMesh& mesh_;
    const DenoiseOptions& o_;
    Progress& progress_;
    DenoiseReport report_;
    double sigma_r_ = 0;
    RangeKernel range_kernel_{1.0};  ///< replaced by pick_sigma_r()
    std::vector<Point> pos_;
    std::vector<Face> face_order_;  ///< dense face number -> face
    /// Our vertex numbers (a spatial order on large meshes) <-> storage indices; empty: the same.
    std::vector<Index> new_of_old_, old_of_new_;
    std::vector<std::array<Index, 3>> corners_;
    std::vector<Vector3> area_vec_, normal_, input_normal_;
    std::vector<Point> centroid_;
    std::vector<double> area_, current_area_;
    std::vector<std::uint8_t> active_, inverted_at_start_;
    double mean_area_ = 1, degenerate_area_ = 0;
    std::vector<Index> vf_offset_, vf_, nb_offset_, nb_;
    std::vector<float> spatial_;
    // guided
    std::vector<std::array<Index, 2>> edge_faces_, edge_vertices_;
    std::vector<Index> ve_offset_, ve_;  ///< per vertex its edges (prepare_guided())
    std::vector<std::array<Index, 3>> face_edges_;
    std::vector<Vector3> guidance_, patch_mean_;
    std::vector<double> patch_score_;
    /// Per face its normal and area over the mean area, in single precision side by side (the
    /// patches' gathers read 16 bytes a face).
    std::vector<std::array<float, 4>> packed_;
    std::vector<Index> vertex_best_;  ///< per vertex, the face of best patch score around it
    /// Features: each face corner's sector around its vertex, and the feature vertices (empty
    /// without features).
    std::vector<std::uint16_t> sector_;
    std::vector<std::uint8_t> feature_vertex_;
    bool finite_ = true;
};

}  // namespace

DenoiseReport denoise(HalfedgeMesh& mesh, const DenoiseOptions& options, Progress& progress) {
    check_options(mesh, options);
    if (options.features == FeatureSource::Auto) {
        FeatureDetectionOptions d;
        d.angle_deg = options.feature_angle;
        detect_features(mesh, d);
    }
    Denoiser run(mesh, options, progress);
    const DenoiseReport report = run.run();
    if (report.vertex_iterations_done > 0) {
        mesh.set_positions(run.storage_positions());
        if (mesh.get_vertex_property<Vector3>("v:normal")) compute_vertex_normals(mesh);
    }
    return report;
}

DenoiseReport denoise(HalfedgeMesh& mesh, const DenoiseOptions& options) {
    NullProgress progress;
    return denoise(mesh, options, progress);
}

}  // namespace trilab
