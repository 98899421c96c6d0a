#pragma once
// A region SPEC (issue 26): the selection an operation acts on, as trilab-cli's `--region SPEC`
// and the viewer's `--select SPEC` take it (one parser for both).
//
// SPEC is one of
//   sphere:X,Y,Z,R[,FEATHER]   vertices within R of the point (X, Y, Z)
//   geodesic:V,R[,FEATHER]     vertices within geodesic distance R of vertex V (heat method)
//   component:V                the connected component of vertex V
//   feature:K[,FEATHER]        the vertices within K rings of a feature (a sharp edge or a
//                              corner tag, core/features.h)
//   file:PATH                  a text file with one weight in [0, 1] per vertex per line (blank
//                              lines and lines starting with '#' are skipped), or a mesh file
//                              whose vertices carry a selection (PLY `selection`, OM custom
//                              property `selection`) with the same vertex count
// FEATHER (>= 0) feathers the region along the edges (feather_selection()). Vertex indices are
// the loaded mesh's (as `trilab-cli info` and `geodesic` count them).
#include <string>
#include <vector>

#include "core/algorithms/selection.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// A parsed SPEC, before any mesh is read.
struct RegionSpec {
    enum class Kind { Sphere, Geodesic, Component, File, Feature } kind = Kind::Sphere;
    std::vector<double> numbers;  ///< X,Y,Z,R[,F] / V,R[,F] / V / K[,F]
    std::string path;             ///< file:
    std::string text;             ///< the SPEC as given, for messages
};

/// Parses SPEC; throws InvalidArgument "--region: ..." naming the part that is wrong.
RegionSpec parse_region_spec(const std::string& text);

/// The region of `spec` on `mesh`; throws InvalidArgument "--region SPEC: ..." (a vertex out of
/// range, a file of the wrong length or with a bad weight, naming the line) or IoError.
Selection make_region(const HalfedgeMesh& mesh, const RegionSpec& spec);

}  // namespace trilab
