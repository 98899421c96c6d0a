#pragma once
// The inspector: everything trilab knows about one vertex, edge or face, as numbers and as a
// list of labelled fields that the viewer's panel and `trilab-cli inspect` both print.
//
// Every number comes from the code that computes it elsewhere, so the inspector and the rest
// of trilab always agree: the curvatures from compute_curvatures() (the colourings' arrays),
// the Laplacian vectors from build_laplacian(), an edge's collapse cost and the answers of the
// decimator's constraints from explain_collapse() (the decimator's own checks, see
// core/algorithms/decimation.h), a face's component from label_face_components(), the
// subdivision and decimation provenance from the attributes those operations leave on their
// output ("v:subdivision_level", "v:subdivision_stencil", "v:subdivision_parents",
// "v:decimation_source").
//
// No GL, no ImGui. Every function throws InvalidArgument naming the element when the handle
// is out of range or deleted, and leaves the mesh as it was (all take it const).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/algorithms/decimation.h"
#include "core/algorithms/subdivision.h"
#include "core/features.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// One line of the inspector: what the panel shows and what the CLI's JSON holds.
struct InspectionField {
    std::string key;              ///< snake_case, for JSON ("mean_curvature")
    std::string label;            ///< words a user reads ("Mean curvature")
    std::string text;             ///< the value formatted (core/number_text.h), units included
    std::vector<double> numbers;  ///< the value as numbers (empty for words, e.g. "none")
};

/// A per-vertex scalar field from outside the mesh (the current colouring, an eigenvector),
/// indexed by vertex storage index; not owned.
struct NamedVertexField {
    std::string name;                             ///< shown as the label ("Frequency 3")
    const std::vector<double>* values = nullptr;  ///< size vertices_size(); NaN: no value
};

/// What inspect_vertex() reports besides the mesh's own data. Pointers are not owned and may
/// be null; an array whose size is not mesh.vertices_size() is reported as unavailable.
struct InspectionInputs {
    std::vector<NamedVertexField> fields;
    /// Positions before smoothing (the reference of the smoothing-distance colouring).
    const std::vector<Point>* reference = nullptr;
    /// A per-vertex displacement (the part of the position the current band carries).
    const std::vector<Vector3>* displacement = nullptr;
};

/// Where a vertex came from in the subdivision step that made the mesh (the attributes
/// "v:subdivision_stencil" and "v:subdivision_parents", core/algorithms/subdivision.h).
struct SubdivisionOrigin {
    int level = 0;  ///< "v:subdivision_level": the iteration that created the vertex
    SubdivisionStencil stencil = SubdivisionStencil::Unknown;
    bool even = false;           ///< an old vertex of the coarser mesh
    std::vector<Index> parents;  ///< vertex indices in the coarser mesh
};

struct VertexInspection {
    Vertex vertex;
    Point position = Point::Zero();
    Vector3 normal = Vector3::Zero();  ///< vertex_normal(): area weighted, unit (0 if none)
    unsigned valence = 0;
    bool isolated = false;
    bool boundary = false;
    bool texture_seam = false;          ///< its corners carry different "h:texcoord"
    std::size_t coincident_copies = 0;  ///< other vertices at exactly its position
    // Curvatures (compute_curvatures(); 0 and curvature_valid false at boundary vertices).
    bool curvature_valid = false;
    double k1 = 0, k2 = 0, mean = 0, gaussian = 0, shape_index = 0;
    /// |(L X)_v| under each LaplacianOperator (order of kLaplacianOperators), with the default
    /// LaplacianOptions (boundary fixed: 0 there, and laplacian_fixed is true).
    std::array<double, 4> laplacian_length{};
    bool laplacian_fixed = false;
    /// The value of each InspectionInputs::fields entry (NaN where it has none).
    std::vector<std::pair<std::string, double>> field_values;
    std::optional<double> smoothing_distance;  ///< (p - reference) . n, as the colouring
    std::optional<Vector3> displacement;       ///< from InspectionInputs::displacement
    std::optional<SubdivisionOrigin> subdivision;
    std::optional<Index> decimation_source;  ///< "v:decimation_source": index in the input
    /// Its role among the features (core/features.h), when the mesh stores sharpness or
    /// corner tags: the class Loop's crease rules give it, and why.
    struct FeatureRole {
        VertexClass cls = VertexClass::Smooth;
        unsigned sharp_edges = 0;  ///< its edges of sharpness > 0
        bool tagged = false;       ///< tagged a corner
    };
    std::optional<FeatureRole> feature;
};

/// Words for a vertex's feature role: its class and why ("corner: 3 sharp edges meet ...").
std::string feature_role_text(const VertexInspection::FeatureRole& role);

/// The decimator's view of one edge under one cost (explain_collapse()).
struct CostInspection {
    DecimationCost cost = DecimationCost::Quadric;
    CollapseExplanation collapse;
};

struct EdgeInspection {
    Edge edge;
    std::array<Vertex, 2> ends;  ///< vertex(e, 0), vertex(e, 1)
    double length = 0;
    bool boundary = false;
    /// Angle between the two faces' normals in degrees (0 flat, 180 folded back); absent on a
    /// boundary edge or when a face is degenerate.
    std::optional<double> dihedral_angle;
    double cotangent_weight = 0;  ///< cotangent_weight(): (cot alpha + cot beta) / 2
    /// Its sharpness (core/features.h), when the mesh stores sharpness.
    std::optional<float> sharpness;
    /// The collapse under each DecimationCost (kDecimationCosts order), with the constraints
    /// of the options passed in; `costs[options.cost]` is what a run would do.
    std::vector<CostInspection> costs;
    DecimationCost selected_cost = DecimationCost::Quadric;  ///< options.cost
};

struct FaceInspection {
    Face face;
    std::array<Vertex, 3> corners;
    double area = 0;
    std::array<double, 3> angles{};  ///< degrees, at corners[0..2]
    Vector3 normal = Vector3::Zero();
    /// Longest edge over the shortest altitude, times sqrt(3)/2: 1 for an equilateral
    /// triangle, growing without bound towards a sliver; infinity when degenerate.
    double aspect_ratio = 0;
    /// Frey and Borouchaki's shape measure (core/algorithms/mesh_quality.h): 1 for an
    /// equilateral triangle, 0 for a degenerate one.
    double quality = 0;
    Index component = kInvalidIndex;  ///< label_face_components() numbering
    std::size_t components = 0;       ///< how many the mesh has
};

/// Inspects a live vertex. The curvatures and Laplacian lengths come from compute_curvatures()
/// and build_laplacian() run on the faces around the vertex and its neighbours (all they
/// depend on; the improved umbrella rescaled to the whole mesh's mean edge length), so they
/// equal the colourings' and the fairing's values: O(ring) plus O(V + E) for the coincident
/// copies and the mean edge length.
VertexInspection inspect_vertex(const HalfedgeMesh& mesh, Vertex v,
                                const InspectionInputs& inputs = {});

/// Inspects a live edge: geometry and the decimator's answers (explain_collapse()) under
/// `options`' constraints for each cost. O(V + F) (the decimator's quadrics and coincident
/// vertices of the whole mesh).
EdgeInspection inspect_edge(const HalfedgeMesh& mesh, Edge e,
                            const DecimationOptions& options = {});

/// Inspects a live face. O(V + F) (the components).
FaceInspection inspect_face(const HalfedgeMesh& mesh, Face f);

/// The live face closest to `p` (exact: point-triangle distances over every face, on several
/// threads); invalid when the mesh has no faces. Ties go to the smallest index. O(F / threads).
Face nearest_face(const HalfedgeMesh& mesh, const Point& p);
/// The corner of `f` nearest to `p`, and the edge of `f` nearest to `p` (for a pick).
Vertex nearest_corner(const HalfedgeMesh& mesh, Face f, const Point& p);
Edge nearest_side(const HalfedgeMesh& mesh, Face f, const Point& p);

/// The fields to show, in order (the panel's lines, the CLI's text and JSON keys).
std::vector<InspectionField> inspection_fields(const VertexInspection& v);
std::vector<InspectionField> inspection_fields(const EdgeInspection& e);
std::vector<InspectionField> inspection_fields(const FaceInspection& f);

}  // namespace trilab
