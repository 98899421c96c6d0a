#pragma once
// Building a HalfedgeMesh from a polygon soup, as file readers produce it.
//
// The soup may be anything a file holds: polygons of any size, non-manifold edges and
// vertices, inconsistent orientation, duplicated faces, unused vertices. Nothing is lost:
//  - polygons with more than three corners are triangulated in their best-fit plane
//    (core/triangulate.h: ear clipping up to 16 corners, a monotone partition above, in
//    O(n log n); a fan for a polygon that crosses itself, noted in the report);
//  - a face with a repeated vertex index (or fewer than three corners) is the only kind that
//    is dropped: it has no area and no orientation;
//  - a face that would give an edge a third face, or a second face on the same side (an
//    inconsistent orientation or a duplicate) is added detached, with its own copies of its
//    vertices, as OpenMesh's importer does;
//  - a vertex whose faces form several fans is split into one copy per fan;
//  - vertices that no face uses are kept (isolated) and counted.
// Everything done is counted in the LoadReport. Complexity: linear in the soup size (plus
// O(n log n) per polygon of n > 16 corners), with no copy of a triangle soup's corners
// (mesh_builder.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// Faces as vertex-index lists with optional attributes, in the order a file gives them.
struct PolygonSoup {
    std::vector<Point> positions;
    /// Corner vertex indices of all faces, concatenated.
    std::vector<Index> corners;
    /// Face f has corners [face_offsets[f], face_offsets[f + 1]); size n_faces + 1.
    std::vector<std::size_t> face_offsets{0};
    /// Optional per-vertex attributes: empty, or one value per position.
    std::vector<Vector3> normals;
    std::vector<Color> colors;
    std::vector<TexCoord> texcoords;
    /// Per-vertex scalar "v:distance" (double; PLY property `distance`, e.g. a geodesic
    /// distance, core/algorithms/geodesic.h).
    std::vector<double> distances;
    /// Per-vertex selection weight "v:selection" (float in [0, 1]; PLY property `selection`,
    /// core/algorithms/selection.h).
    std::vector<float> selections;
    /// Optional per-corner texture coordinates: empty, or one per entry of `corners`.
    std::vector<TexCoord> corner_texcoords;
    /// Optional sharp edges (core/features.h): two vertex indices and a sharpness (>= 0, or
    /// inf). Each becomes "e:sharpness" of the mesh edge joining those vertices (and of the
    /// edges joining their copies); one that names no edge of the mesh is dropped and counted
    /// in the report's notes. Listing the same pair twice keeps the last value.
    struct SharpEdge {
        Index a = 0, b = 0;
        float sharpness = 0;
    };
    std::vector<SharpEdge> sharp_edges;
    /// Optional corner tags "v:corner" (core/features.h): empty, or one per position (0 or 1).
    std::vector<std::uint8_t> corner_tags;

    std::size_t n_faces() const { return face_offsets.size() - 1; }
    /// Appends a face; `uv`, when given, holds one texture coordinate per corner.
    void add_face(const std::vector<Index>& face, const std::vector<TexCoord>& uv = {});
};

/// What loading a file did, for `trilab-cli info` and the viewer's log.
struct LoadReport {
    std::string file;
    std::string format;
    std::size_t file_vertices = 0;               ///< vertices declared / read from the file
    std::size_t file_faces = 0;                  ///< faces read from the file
    std::size_t polygons_triangulated = 0;       ///< faces with more than three corners
    std::size_t triangles_from_polygons = 0;     ///< triangles those polygons became
    std::size_t degenerate_faces_dropped = 0;    ///< faces with a repeated vertex or < 3 corners
    std::size_t detached_faces = 0;              ///< added with their own vertex copies
    std::size_t nonmanifold_vertices_split = 0;  ///< vertices with several fans
    std::size_t vertex_copies_added = 0;         ///< copies made for detached faces and fans
    std::size_t isolated_vertices = 0;           ///< vertices used by no face (kept)
    std::size_t merged_vertices = 0;             ///< duplicate corners merged (STL)
    std::vector<std::string> notes;              ///< anything else worth telling the user

    /// One line per non-zero count, for logs.
    std::vector<std::string> lines() const;
};

/// Checks what build_mesh needs of a soup before it builds anything: fewer vertices than
/// 32-bit indices number, face offsets matching the corner list, every corner index in range,
/// finite positions, attribute arrays of the right sizes. Throws InvalidArgument naming the
/// face and corner (or the vertex, or the attribute). Linear in the soup size.
void check_polygon_soup(const PolygonSoup& soup);

/// Builds a valid HalfedgeMesh from `soup` (see the file comment). Attributes in the soup
/// become "v:normal", "v:color", "v:texcoord" and "h:texcoord" (the texture coordinate of
/// the corner at to_vertex(h) in face(h)), "e:sharpness" and "v:corner". Throws InvalidArgument
/// naming the face and corner if a corner index is out of range or an attribute array has the wrong
/// size; the report is filled in on success.
HalfedgeMesh build_mesh(const PolygonSoup& soup, LoadReport& report);
/// The same, consuming the soup: a triangle soup's face offsets are released once the
/// triangles are known and the positions move into the mesh (no copy), lowering the peak
/// memory of a large load by about a third of the soup. The result is identical.
HalfedgeMesh build_mesh(PolygonSoup&& soup, LoadReport& report);

/// The inverse: every live face as a triangle, with per-vertex attributes; vertices are
/// numbered in storage order with deleted ones skipped.
PolygonSoup to_soup(const HalfedgeMesh& mesh);

namespace detail {
/// Test hook: how many threads build_mesh (and the PLY reader's face decoding) may use for
/// a large soup (1 or 2; 2 by default, where the machine has two). With 1, every stage runs
/// its one-thread pass, the reference the two-thread passes are compared with element for
/// element.
void set_build_threads(int n);
int build_threads();
}  // namespace detail

}  // namespace trilab
