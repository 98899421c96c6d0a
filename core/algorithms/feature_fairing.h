#pragma once
// Sliding features in fairing (issue 39, item 4): the crease vertices of the mesh's feature
// graph (core/features.h: two sharp edges, no corner tag) smooth along their feature curve with
// the 1-D Laplacian of the curve, x_i <- x_i + t·(w_a x_a + w_b x_b - x_i) over their two curve
// neighbours a and b, while corners (three or more sharp edges, or tagged), the ends of open
// curves (darts' vertices), boundary vertices and the region's weight-0 vertices stay where
// they are. The surface operator treats every feature vertex as a fixed row (so nothing smooths
// across a crease); the curve's own step then moves the crease vertices (FairingRun calls
// step() once per iteration, core/algorithms/fairing.cpp). This is the curve analogue of the
// surface diffusion (Desbrun, Meyer, Schröder, Barr 1999 for the implicit form; Taubin 1995 for
// λ|μ): umbrella, second order and Taubin use the uniform weights 1/2, 1/2; curvature flow and
// the improved umbrella the 1-D cotangent form, weights proportional to 1/length (the discrete
// curvature flow of a polyline), refreshed every iteration. Explicit integration takes one
// explicit 1-D step (Taubin: its λ then its μ step), stable for t <= 1; implicit integration
// (or an explicit step above 1, which would be unstable on the curve) solves
// (D + t·K) x' = D x over the moving curve vertices with sparse Cholesky (SPD: the curve's
// Laplacian is symmetric in its weighted form), the fixed curve vertices on the right-hand side.
// In an implicit run the surface rows see the curve vertices at the iteration's start (their
// fixed rows), the curve rows see only the curve: a block Gauss-Seidel split of the joint
// system, stable for any step.
// Complexity: O(V + E) to build; per step O(C) explicit, O(C) to factor and solve implicit
// (the system is a union of paths and cycles), C the crease vertices.
#include <cstddef>
#include <string>
#include <vector>

#include "core/enum_table.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// What the feature vertices do under fairing: stay where they are, or (crease vertices) slide
/// along their feature curve with the curve's 1-D Laplacian (corners and curve ends fixed).
enum class FeatureMode { Fixed, Slide };
/// The one table of FeatureMode (core/enum_table.h): identifier and label of each value.
inline constexpr EnumEntry<FeatureMode> kFeatureModes[] = {
    {FeatureMode::Fixed, "fixed", "Fixed"},
    {FeatureMode::Slide, "slide", "Slide along their curves"},
};
const char* feature_mode_name(FeatureMode mode);  ///< "fixed", "slide"
FeatureMode parse_feature_mode(const std::string& name);

/// How a curve step is taken (from the fairing options).
struct CurveStep {
    double t = 0.5;                ///< the step (Taubin: λ), umbrella units
    double mu = 0;                 ///< Taubin's μ (< 0) for a second explicit step; 0: none
    bool implicit = false;         ///< backward Euler on the curve
    bool length_weighted = false;  ///< 1/length weights (curvature flow, improved umbrella)
};

/// The crease vertices of a mesh's features and their curve neighbours, by vertex index.
class FeatureCurveFairing {
public:
    /// The crease vertices of `mesh` that slide: two sharp edges, no corner tag, not on the
    /// boundary, and a positive weight in `region` where given (one weight per vertex storage
    /// index). A mesh without features gives none. O(V + E).
    FeatureCurveFairing(const HalfedgeMesh& mesh, const std::vector<float>* region);

    /// The sliding vertices (ascending storage indices).
    const std::vector<Index>& moving() const { return moving_; }
    /// Renumbers every vertex through `map` (old storage index -> new, e.g. a weld's
    /// vertex_map); a sliding vertex whose new index another one already has stays fixed.
    void remap(const std::vector<Index>& map);

    /// One step: reads the positions P and writes the sliding vertices' new positions into
    /// `out` (every other entry untouched). Returns false when a result is not finite (`out`
    /// then untouched).
    bool step(const CurveStep& s, const std::vector<Point>& P, std::vector<Point>& out) const;

private:
    struct Row {
        Index v, a, b;  ///< the vertex and its two curve neighbours
    };
    std::vector<Row> rows_;
    std::vector<Index> moving_;
};

}  // namespace trilab
