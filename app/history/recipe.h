#pragma once
// Recipes: the typed operations and the selections of a history, from the loaded file on, as a
// JSON file that `trilab-cli replay` runs headless (docs/file-formats.md#recipes). Replaying a
// recipe on the same input gives the same bits as the session's states: every operation is
// deterministic (the same input and parameters give the same result, whatever the thread
// count), and each operation runs on the selection the viewer ran it on.
#include <optional>
#include <string>
#include <vector>

#include "app/history/history.h"
#include "core/algorithms/selection.h"
#include "core/halfedge_mesh.h"

namespace trilab {

/// One step of a recipe: an operation (on the current selection, or on its own region), or a
/// selection made in the viewer (issue 38, item 1: recipes replay selections).
struct RecipeStep {
    enum class Kind { RunOperation, SetSelection };
    /// How a selection step gives its weights: a region SPEC evaluated on the mesh at that
    /// point (app/ops/region_spec.h), the weights themselves, or no selection at all.
    enum class From { Spec, Weights, Clear };
    Kind kind = Kind::RunOperation;
    Operation operation;  ///< Kind::RunOperation
    /// Kind::RunOperation: a region SPEC this step runs on instead of the current selection ("":
    /// the current selection, as the viewer runs it). Kind::SetSelection with From::Spec: the
    /// SPEC of the selection.
    std::string region;
    From from = From::Spec;
    Selection weights;  ///< From::Weights: one per vertex storage index
    std::string text;   ///< for people: the history entry's label and parameters

    RecipeStep() = default;
    RecipeStep(Operation op) : operation(std::move(op)) {}  // NOLINT: a plain operation step
    bool operator==(const RecipeStep& o) const {
        return kind == o.kind && operation == o.operation && region == o.region && from == o.from &&
               weights == o.weights;
    }
    bool operator!=(const RecipeStep& o) const { return !(*this == o); }
};

struct Recipe {
    std::string source;  ///< the load entry's label and parameters ("Load bunny.obj")
    std::vector<RecipeStep> steps;
    /// The number of operation steps.
    std::size_t operations() const;
    /// The number of selection steps.
    std::size_t selections() const;
};

/// The steps of the entries after the last load up to the current entry, through the current
/// entry. A load is entry 0 or an entry without a typed operation whose first step brings
/// positions of its own (a file opened, Revert, a figure's model). Each entry becomes:
///  - an entry with a typed operation: an operation step (run on the selection at that point,
///    as the viewer ran it);
///  - a selection entry (one step that keeps the connectivity and positions of the state
///    before it and changes its "v:selection", or is labelled as the viewer labels selections:
///    Select, Brush, Lasso, Grow/Shrink/Invert/Feather/Clear selection): a selection step, as
///    its SPEC when the entry is "Select SPEC" and the SPEC gives exactly the stored weights
///    again (a file: SPEC never), otherwise as the weights themselves, or a clear;
///  - anything else (a state the viewer made itself, such as texture coordinates): refused,
///    InvalidArgument naming the entry's index, label and parameters.
Recipe recipe_of(const History& history);

/// The recipe as JSON: {"format": "trilab-recipe", "version": 2, "source": ..., "operations":
/// [{"operation": NAME, "text": ..., "parameters": {...typed...}[, "region": SPEC]},
///  {"selection": "spec", "spec": SPEC, "text": ...},
///  {"selection": "weights", "vertices": N, "indices": [...], "weights": [...], "text": ...},
///  {"selection": "clear", "text": ...}]} (the weights listed where positive, in shortest
/// round-trip form, so they read back bit for bit).
std::string recipe_json(const Recipe& recipe);
/// The typed parameters of `op` as a JSON object ({"iterations": 10, "operator":
/// "cotangent", ...}): the parameters that apply, as recipe_json() writes them.
std::string typed_parameters_json(const Operation& op);
/// Parses recipe_json()'s format (version 1, operations only, or 2); each operation is checked
/// (check_operation), each SPEC parsed (parse_region_spec), each weight list checked (indices
/// in range and increasing, weights in (0, 1]). Throws InvalidArgument naming `name`, the
/// step's position and the reason; an unknown kind of step is refused, never skipped.
Recipe parse_recipe(const std::string& json, const std::string& name);

/// One operation run the way the viewer runs it (every step kept, morphs computed) on
/// `region` of `mesh` (nullptr: the whole mesh); `changed` is false when the viewer would add
/// no entry (the run stopped before its first good step, or left the mesh as it was). Throws
/// what run_operation throws (an empty region included).
struct ReplayStep {
    OperationResult result;
    bool changed = true;
};
ReplayStep run_recipe_step(const Operation& op, const HalfedgeMesh& mesh,
                           const Selection* region = nullptr);

/// The region an operation step runs on at `mesh`, as the viewer gives it: the step's own
/// SPEC where it has one, else the mesh's stored selection ("v:selection"); nullopt (the whole
/// mesh) without a selection, when it selects everything, or when the operation takes no
/// region and the step names none.
std::optional<Selection> recipe_region(const RecipeStep& step, const HalfedgeMesh& mesh);

/// Applies one selection step to `mesh` (stores or removes its "v:selection"). Throws
/// InvalidArgument naming `where` for weights of another vertex count, or what make_region
/// throws.
void apply_selection_step(const RecipeStep& step, HalfedgeMesh& mesh, const std::string& where);

/// Runs every step of `recipe` on `mesh` in order; returns the last state. Throws
/// InvalidArgument naming the step (its position and text) that cannot be replayed.
HalfedgeMesh replay(const Recipe& recipe, HalfedgeMesh mesh);

/// "" when `a` and `b` have the same storage sizes, connectivity and positions bit for bit;
/// otherwise the first difference ("positions differ at vertex 17").
std::string first_difference(const HalfedgeMesh& a, const HalfedgeMesh& b);

}  // namespace trilab
