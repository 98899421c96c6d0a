#pragma once
// Face orientation: reversing it, and telling when a closed mesh is oriented inwards.
//
// A closed mesh whose faces wind clockwise seen from outside has a negative signed volume
// (formula 1.15 of the reference report): the viewer then sees only back faces, and every
// outward normal points in. flip_orientation() reverses every face (the half-edge mesh stays
// valid: each face keeps its vertices and edges, the halfedges change sides); a file whose
// closed mesh has a negative volume gets a note in its load report saying so (read_mesh()).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"

namespace trilab {

/// flip_orientation()'s options: its region, and the mesh's components when known.
struct FlipOptions {
    /// The region (core/algorithms/selection.h): one weight per vertex storage index, or
    /// nullptr for the whole mesh. Orientation belongs to a connected component (flipping part
    /// of one would leave an edge whose faces disagree, which no half-edge mesh can hold), so
    /// every component with a vertex of positive weight is flipped whole and the others are
    /// left untouched, bit for bit. Not owned.
    const std::vector<float>* region = nullptr;
    /// With a region: this mesh's components as label_components() numbers them (one label
    /// per vertex storage index), when the caller has them already (the viewer keeps its
    /// current state's, computed for its statistics), so that the flip need not find them;
    /// nullptr: the touched components are found while they are flipped, by a flood from the
    /// region's vertices over their edges only (HalfedgeMesh::reverse_orientation_from()), so
    /// a region on a small component costs less than the whole flip. They must be this mesh's
    /// (same topology). Not owned.
    const std::vector<Index>* components = nullptr;
};

/// What flip_orientation() did.
struct FlipReport {
    std::size_t faces = 0;  ///< faces reversed (every live face)
    /// The signed volume before and after (empty for an open mesh): after = -before.
    std::optional<double> volume_before, volume_after;
    bool normals_negated = false;  ///< a stored "v:normal" was negated
    std::size_t components = 0;    ///< with a region: the components flipped (0 without)
};

/// Reverses the orientation of every face (HalfedgeMesh::reverse_orientation(): vertex,
/// edge and face indices are kept; per-corner "h:texcoord" values stay on their corners) and
/// negates a stored "v:normal", so shading agrees with the new winding. Boundaries, isolated
/// and deleted elements are handled; the mesh stays valid (validate()). With a region only the
/// components it touches are flipped (FlipOptions::region; the volumes are then the whole
/// mesh's). Throws InvalidArgument for a region that does not fit (check_selection()) or
/// components of the wrong size.
/// O(vertices + halfedges); with a region and no labels, O(vertices + faces + the touched
/// components' halfedges).
FlipReport flip_orientation(HalfedgeMesh& mesh, const FlipOptions& options = {});

/// The load-report note for a closed mesh with a negative signed volume (below -1e-9 of its
/// bounding-box diagonal cubed, so rounding on a flat closed mesh does not count): names the
/// volume and says how to flip it (the viewer's Tools -> Flip orientation, `trilab-cli flip
/// IN OUT`). Empty for open meshes and positive volumes. O(faces).
std::string inward_orientation_note(const HalfedgeMesh& mesh);

}  // namespace trilab
