#pragma once
// Recipes: the typed operations of a history, from the loaded file on, as a JSON file that
// `trilab-cli replay` runs headless (docs/file-formats.md#recipes). Replaying a recipe on the
// same input gives the same bits as the session's states: every operation is deterministic
// (the same input and parameters give the same result, whatever the thread count).
#include <string>
#include <vector>

#include "app/history/history.h"
#include "core/halfedge_mesh.h"

namespace trilab {

struct Recipe {
    std::string source;  ///< the load entry's label and parameters ("Load bunny.obj")
    std::vector<Operation> operations;
};

/// The operations of the entries after the last entry up to the current one that has no
/// typed operation (the load), through the current entry. Throws InvalidArgument naming an
/// entry between them that has no typed operation (a viewer-made state such as a frequency
/// band or texture coordinates), which a recipe cannot replay.
Recipe recipe_of(const History& history);

/// The recipe as JSON: {"format": "trilab-recipe", "version": 1, "source": ...,
/// "operations": [{"operation": NAME, "text": ..., "parameters": {...typed...}}]}.
std::string recipe_json(const Recipe& recipe);
/// The typed parameters of `op` as a JSON object ({"iterations": 10, "operator":
/// "cotangent", ...}): the parameters that apply, as recipe_json() writes them.
std::string typed_parameters_json(const Operation& op);
/// Parses recipe_json()'s format; each operation is checked (check_operation). Throws
/// InvalidArgument naming `name`, the operation's position and the reason.
Recipe parse_recipe(const std::string& json, const std::string& name);

/// One operation run the way the viewer runs it (every step kept, morphs computed);
/// `changed` is false when the viewer would add no entry (the run stopped before its first
/// good step, or left the mesh as it was). Throws what run_operation throws.
struct ReplayStep {
    OperationResult result;
    bool changed = true;
};
ReplayStep run_recipe_step(const Operation& op, const HalfedgeMesh& mesh);

/// Runs every operation of `recipe` on `mesh` in order; returns the last state.
HalfedgeMesh replay(const Recipe& recipe, HalfedgeMesh mesh);

/// "" when `a` and `b` have the same storage sizes, connectivity and positions bit for bit;
/// otherwise the first difference ("positions differ at vertex 17").
std::string first_difference(const HalfedgeMesh& a, const HalfedgeMesh& b);

}  // namespace trilab
