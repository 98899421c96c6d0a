#pragma once
// History: the one snapshot stack that every operation pushes to, driving undo, redo and the
// morphs between states (the design card's "single undo/snapshot stack for morphing").
//
// An entry is one operation (load, revert, noise, ...) with its label, parameters, timing and
// one or more steps (iterations); each step holds the mesh after it and how it morphs from
// the previous state (core/algorithms/morph.h). Steps share unchanged data through the mesh's
// copy-on-write arrays (core/property.h): a step made from a copy of the mesh before it
// shares every array it did not change, and a step that keeps the vertices is also made to
// share every array whose values equal its predecessor's bit for bit. So a geometry-only step
// costs its positions (and whatever else it changed, e.g. normals). A memory budget (default a
// quarter of the RAM) drops the oldest entries, with a message, rather than running out of
// memory. Undo and redo move a cursor; pushing after an undo drops the redo entries.
//
// Accounting. Every block of array values counts once, with the oldest entry that holds it;
// a step's correspondence positions count with it. Dropping an entry frees what no later
// entry shares.
//
// Threads: the const functions only read, so a job may read the current mesh while the render
// thread calls morph(); the non-const functions need exclusive access.
// Copies of a History share one stack.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/ops/operation.h"
#include "core/algorithms/morph.h"
#include "core/halfedge_mesh.h"

namespace trilab {

class History {
public:
    struct StepInfo {
        std::size_t vertices = 0, faces = 0;
        MorphCorrespondence::Kind kind = MorphCorrespondence::Kind::SameVertices;
    };
    struct EntryInfo {
        std::string label, parameters;
        /// The typed operation that made the entry (empty `def` for loads and states the
        /// viewer made itself); the text above is for people.
        Operation operation;
        double ms = 0;
        std::vector<StepInfo> steps;
        std::size_t bytes = 0;  ///< memory this entry holds on its own
    };

    /// One state as the history holds it: immutable, shared (a snapshot, a journal and the
    /// history itself may hold the same state).
    struct StepRecord {
        std::uint64_t id = 0;  ///< unique among the steps of this process's histories
        std::shared_ptr<const HalfedgeMesh> mesh;
        std::shared_ptr<const MorphCorrespondence> correspondence;
    };
    /// One entry as the history holds it: immutable once pushed.
    struct EntryRecord {
        std::string label, parameters;
        Operation operation;  ///< empty `def` for loads and viewer-made states
        double ms = 0;
        std::vector<StepRecord> steps;
    };
    /// The whole history at one moment, sharing every entry with it (copying one costs a
    /// pointer per entry): what a session writer or the crash journal reads, on any thread.
    struct Snapshot {
        std::vector<std::shared_ptr<const EntryRecord>> entries;
        std::size_t current = 0;
    };

    explicit History(std::size_t budget_bytes = default_budget());
    static std::size_t default_budget();  ///< a quarter of the physical memory

    /// Starts a new history with `mesh` as its first entry (a load). Clears everything.
    void reset(HalfedgeMesh mesh, std::string label, std::string parameters = "", double ms = 0);
    /// Appends an entry after the current one (dropping any redo entries) and makes it the
    /// current one. Each step's correspondence must fit its predecessor (check_correspondence:
    /// step 0 against the current state, step k against step k - 1); throws InvalidArgument
    /// otherwise, with the history unchanged, as also for an empty history, no steps, or
    /// step and correspondence counts that differ. Then drops the oldest entries (never the
    /// current one) while bytes() exceeds the budget, and returns one message per dropped
    /// entry naming it and the bytes freed.
    std::vector<std::string> push(std::string label, std::string parameters, double ms,
                                  std::vector<HalfedgeMesh> step_meshes,
                                  std::vector<MorphCorrespondence> correspondences,
                                  Operation operation = {});

    /// The history as it is now (see Snapshot); O(entries).
    Snapshot snapshot() const;
    /// Replaces the whole history with `entries` (a session file, a journal) and makes entry
    /// `current` the current one. Each step's mesh and correspondence are taken as they are
    /// (ids are drawn anew); the correspondences are checked as push() checks them (entry 0's
    /// first step has no predecessor). Throws InvalidArgument naming the entry and step, with
    /// the history unchanged, for no entries, an entry without steps, a bad correspondence or
    /// `current` out of range. Then trims to the budget as push() does (messages returned).
    std::vector<std::string> restore(std::vector<EntryRecord> entries, std::size_t current);

    bool can_undo() const;
    bool can_redo() const;
    /// Moves to the previous / next entry; does nothing where there is none.
    void undo();
    void redo();
    /// Makes entry `index` the current one. Throws InvalidArgument when there is no such entry.
    void jump(std::size_t index);

    /// The number of entries (0 before the first reset) and the current entry's index. Entry
    /// indices shift down when the budget drops the oldest entries.
    std::size_t size() const;
    std::size_t current() const;
    /// Throws InvalidArgument when there is no such entry (so do mesh() and morph()).
    EntryInfo info(std::size_t index) const;
    /// The mesh of the current state (the last step of the current entry); an empty mesh
    /// before the first reset. The reference stays valid until the next reset, push, undo,
    /// redo, jump or trim.
    const HalfedgeMesh& current_mesh() const;
    /// The mesh after step `step` of entry `index` (a copy: cheap, its arrays are shared).
    HalfedgeMesh mesh(std::size_t index, std::size_t step) const;
    /// The morph of entry `index` (>= 1) from the state before it (t = 0) through its steps
    /// to its last step (t = 1): the steps are chained, each taking an equal share of t
    /// (clamped to [0, 1]), and the step that t falls in is evaluated by morph_frame. The
    /// frame's topology points into the History: the mesh of one of the two states of that
    /// step, itself (its positions and attributes are that state's), which stays valid until
    /// the next reset, push, undo, redo, jump or trim. Calls for the same step return the same
    /// pointer until then (a new pointer means new connectivity to upload).
    MorphFrame morph(std::size_t index, double t) const;

    /// The memory the entries hold (the sum of info(i).bytes).
    std::size_t bytes() const;
    std::size_t budget() const;
    /// Sets the budget; it applies at the next push, or now through trim_to_budget().
    void set_budget(std::size_t bytes);
    /// Drops the oldest entries (never the current one) while bytes() exceeds the budget;
    /// one message per dropped entry, as push returns.
    std::vector<std::string> trim_to_budget();

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace trilab
