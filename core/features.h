#pragma once
// The feature graph of a mesh: sharp edges and corner vertices, stored as mesh properties.
//
//  - "e:sharpness" (float, one per edge): 0 smooth, a positive value semi-sharp, +infinity
//    infinitely sharp. As in OpenSubdiv (DeRose, Kass, Truong 1998; Sdc::Crease), a sharpness
//    s uses the sharp rules for the first floor(s) subdivision levels and blends at the last,
//    the children of an edge get s - 1 per level (0 once s <= 1), and a value of 10 or more
//    (OpenSubdiv's SHARPNESS_INFINITE) never decays: it acts as +infinity.
//  - "v:corner" (std::uint8_t, one per vertex): 1 tags the vertex as a corner (an infinitely
//    sharp vertex: it never moves under approximating subdivision); 0 otherwise.
//
// Both are ordinary properties: copying a mesh shares them copy-on-write, garbage collection
// and renumbering move them with their elements, an edge split gives both halves the split
// edge's sharpness. validate() (core/validate.h) checks them through check_features(). PLY
// (an `edge` element vertex1, vertex2, crease) and OM (custom properties "sharpness" and
// "corner") save and load them; OBJ, OFF and STL cannot (feature_save_note()).
//
// Vertex classes, as OpenSubdiv's Sdc::Crease::DetermineVertexVertexRule computes them: a
// vertex with a corner tag, or with three or more sharp edges (sharpness > 0) is a corner;
// with two a crease; with one a dart; otherwise smooth. Boundary edges count as sharp where
// the caller asks (subdivision always does: OpenSubdiv's boundary edges are infinitely sharp).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/enum_table.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// The edge property of sharpness values (float).
inline constexpr const char* kSharpnessProperty = "e:sharpness";
/// The vertex property of corner tags (std::uint8_t, 0 or 1).
inline constexpr const char* kCornerProperty = "v:corner";
/// Infinite sharpness.
inline constexpr float kInfiniteSharpness = std::numeric_limits<float>::infinity();
/// Sharpness at and above which an edge acts as infinitely sharp (OpenSubdiv 3.5's
/// Sdc::Crease::SHARPNESS_INFINITE).
inline constexpr float kSharpnessActsInfinite = 10.0f;

/// Which features an operation uses (subdivision, decimation): those stored in the mesh, none,
/// or those detected by angle first (core/algorithms/feature_detection.h).
enum class FeatureSource { Stored, None, Auto };
/// The one table of FeatureSource (core/enum_table.h): "stored", "none", "auto".
inline constexpr EnumEntry<FeatureSource> kFeatureSources[] = {
    {FeatureSource::Stored, "stored", "stored in the mesh"},
    {FeatureSource::None, "none", "none"},
    {FeatureSource::Auto, "auto", "detected by angle"},
};

/// Whether `s` is a valid sharpness: finite and >= 0, or +infinity.
inline bool valid_sharpness(float s) {
    return s >= 0.0f;  // false for NaN and negative values; +inf passes
}
/// The sharpness of an edge's children after one subdivision level (OpenSubdiv's uniform
/// creasing method, its default): 0 stays 0, >= 10 stays, s > 1 becomes s - 1, else 0.
inline float child_sharpness(float s) {
    if (!(s > 0.0f)) return 0.0f;
    if (s >= kSharpnessActsInfinite) return s;
    return s > 1.0f ? s - 1.0f : 0.0f;
}

/// Whether the mesh has any feature: a live edge of sharpness > 0 or a tagged live vertex.
/// O(E + V) when the properties exist, O(1) otherwise.
bool has_features(const HalfedgeMesh& mesh);
/// Removes both properties.
void clear_features(HalfedgeMesh& mesh);
/// The sharpness property, created (all 0) when missing. Throws InvalidArgument when a
/// property of that name has another type.
EdgeProperty<float> sharpness_property(HalfedgeMesh& mesh);
/// The corner property, created (all 0) when missing; throws as above.
VertexProperty<std::uint8_t> corner_property(HalfedgeMesh& mesh);
/// Sets the sharpness of edge `e`. Throws InvalidArgument (mesh unchanged) for an edge index
/// past the end or deleted, or a sharpness that is negative or NaN.
void set_sharpness(HalfedgeMesh& mesh, Edge e, float sharpness);
/// The sharpness of a live edge (0 when the mesh has no sharpness property).
float sharpness(const HalfedgeMesh& mesh, Edge e);
/// Whether vertex v is tagged a corner.
bool is_corner_tagged(const HalfedgeMesh& mesh, Vertex v);

/// "" when the features are consistent, else the first problem: a property of the wrong type,
/// an array of the wrong size, a sharpness that is negative or NaN (naming the edge), a
/// corner tag other than 0 or 1 (naming the vertex). Used by validate(). O(E + V).
std::string check_features(const HalfedgeMesh& mesh);

enum class VertexClass : std::uint8_t { Smooth = 0, Dart = 1, Crease = 2, Corner = 3 };
/// "smooth", "dart", "crease", "corner".
const char* vertex_class_name(VertexClass c);

struct VertexClassification {
    /// One per vertex storage index (deleted and isolated vertices: Smooth).
    std::vector<VertexClass> classes;
    std::size_t smooth = 0, darts = 0, creases = 0, corners = 0;
    /// Corners that are so because of a tag (the others have three or more sharp edges).
    std::size_t tagged_corners = 0;
};
/// Classifies every live vertex (see the file comment); boundary edges count as sharp when
/// `boundary_is_sharp`. O(V + E).
VertexClassification classify_vertices(const HalfedgeMesh& mesh, bool boundary_is_sharp);

/// The line a save report gives when writing `mesh` to a format that cannot hold its features
/// (`format_keeps_features` false) would drop them; "" when nothing is dropped.
std::string feature_save_note(const HalfedgeMesh& mesh, bool format_keeps_features);

}  // namespace trilab
