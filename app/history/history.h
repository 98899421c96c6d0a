#pragma once
// History: the one snapshot stack that every operation pushes to, driving undo, redo and the
// morphs between states (the design card's "single undo/snapshot stack for morphing").
//
// An entry is one operation (load, revert, noise, ...) with its label, parameters, timing and
// one or more steps (iterations); each step holds the mesh after it and how it morphs from
// the previous state (core/morph.h). Entries share unchanged data: a geometry-only step
// stores only its positions and shares the connectivity and attributes of the mesh it came
// from. A memory budget (default a quarter of the RAM) drops the oldest entries, with a
// message, rather than running out of memory. Undo and redo move a cursor; pushing after an
// undo drops the redo entries.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/halfedge_mesh.h"
#include "core/morph.h"

namespace trilab {

class History {
public:
    struct StepInfo {
        std::size_t vertices = 0, faces = 0;
        MorphCorrespondence::Kind kind = MorphCorrespondence::Kind::SameVertices;
    };
    struct EntryInfo {
        std::string label, parameters;
        double ms = 0;
        std::vector<StepInfo> steps;
        std::size_t bytes = 0;  ///< memory this entry holds on its own
    };

    explicit History(std::size_t budget_bytes = default_budget());
    static std::size_t default_budget();  ///< a quarter of the physical memory

    /// Starts a new history with `mesh` as its first entry (a load). Clears everything.
    void reset(HalfedgeMesh mesh, std::string label, std::string parameters = "",
               double ms = 0);
    /// Appends an entry after the current one (dropping any redo entries). Each step's
    /// correspondence must fit its predecessor (check_correspondence); throws InvalidArgument
    /// otherwise, with the history unchanged. Returns messages about entries dropped to stay
    /// within the budget.
    std::vector<std::string> push(std::string label, std::string parameters, double ms,
                                  std::vector<HalfedgeMesh> step_meshes,
                                  std::vector<MorphCorrespondence> correspondences);

    bool can_undo() const;
    bool can_redo() const;
    void undo();
    void redo();
    /// Makes entry `index` the current one.
    void jump(std::size_t index);

    std::size_t size() const;
    std::size_t current() const;
    EntryInfo info(std::size_t index) const;
    /// The mesh of the current state (the last step of the current entry).
    const HalfedgeMesh& current_mesh() const;
    /// The mesh after step `step` of entry `index`.
    HalfedgeMesh mesh(std::size_t index, std::size_t step) const;
    /// The morph of entry `index` (>= 1) from the state before it (t = 0) through its steps
    /// to its last step (t = 1): the steps are chained, each taking an equal share of t. The
    /// frame's topology points into the History and stays valid until it next changes.
    MorphFrame morph(std::size_t index, double t) const;

    std::size_t bytes() const;
    std::size_t budget() const;
    void set_budget(std::size_t bytes);

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace trilab
