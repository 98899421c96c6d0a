#pragma once
// A region SPEC (issue 26): the selection an operation acts on, as trilab-cli's `--region SPEC`
// and the viewer's `--select SPEC` take it (one parser for both).
//
// SPEC is one of
//   sphere:X,Y,Z,R[,FEATHER]   vertices within R of the point (X, Y, Z)
//   geodesic:V,R[,FEATHER]     vertices within geodesic distance R of vertex V (heat method)
//   component:V                the connected component of vertex V
//   threshold:QUANTITY,LO,HI   vertices whose value of the colouring QUANTITY (a name of
//                              core/algorithms/coloring.h coloring_name(): k1, k2, mean,
//                              gaussian, shape-index, subdivision, geodesic-distance, ...)
//                              is in [LO, HI]; vertices without a value are outside. The
//                              colourings that need a field from elsewhere (a spectral
//                              decomposition, an earlier state) are refused, naming why
//   feature:K[,FEATHER]        the vertices within K rings of a feature (a sharp edge or a
//                              corner tag, core/features.h)
//   file:PATH                  a text file with one weight in [0, 1] per vertex per line (blank
//                              lines and lines starting with '#' are skipped), or a mesh file
//                              whose vertices carry a selection (PLY `selection`, OM custom
//                              property `selection`) with the same vertex count
// FEATHER (>= 0) feathers the region along the edges (feather_selection()). Vertex indices are
// the loaded mesh's (as `trilab-cli info` and `geodesic` count them).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/algorithms/selection.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// A parsed SPEC, before any mesh is read.
struct RegionSpec {
    enum class Kind { Sphere, Geodesic, Component, File, Threshold, Feature } kind = Kind::Sphere;
    std::vector<double> numbers;  ///< X,Y,Z,R[,F] / V,R[,F] / V / LO,HI / K[,F]
    std::string quantity;         ///< threshold: the colouring's name
    std::string path;             ///< file:
    std::string text;             ///< the SPEC as given, for messages
};

/// The largest weight file (file:PATH with one weight per line) read for a mesh of `vertices`
/// vertex storage slots: 1 MiB plus 64 bytes a vertex, at most max_readable_file_bytes().
/// Weight files are read from regular files only (core/io/file_util.h read_file_bytes): a
/// device (/dev/zero), a FIFO or a directory is refused before it is read.
std::uint64_t weight_file_budget(std::size_t vertices);

/// Parses SPEC; throws InvalidArgument "--region: ..." naming the part that is wrong.
RegionSpec parse_region_spec(const std::string& text);

/// The region of `spec` on `mesh`; throws InvalidArgument "--region SPEC: ..." (a vertex out of
/// range, a file of the wrong length or with a bad weight, naming the line) or IoError.
Selection make_region(const HalfedgeMesh& mesh, const RegionSpec& spec);

}  // namespace trilab
