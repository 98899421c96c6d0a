#include "app/history/history.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <unordered_set>
#include <utility>

#include "core/errors.h"

namespace trilab {

namespace {

std::string format_bytes(std::size_t bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
    double value = double(bytes);
    int unit = 0;
    while (value >= 1024.0 && unit < 4) {
        value /= 1024.0;
        ++unit;
    }
    char buf[64];
    if (unit == 0)
        std::snprintf(buf, sizeof buf, "%zu bytes", bytes);
    else
        std::snprintf(buf, sizeof buf, "%.1f %s", value, units[unit]);
    return buf;
}

using MeshPtr = std::shared_ptr<const HalfedgeMesh>;

struct Step {
    std::uint64_t id = 0;  ///< unique in the history's lifetime
    /// The mesh after the step. Its arrays are shared (copy-on-write, core/property.h) with
    /// the step before wherever they hold the same values.
    MeshPtr mesh;
    MorphCorrespondence correspondence;
};

struct Entry {
    std::string label, parameters;
    Operation operation;  ///< the typed operation (none for loads and viewer-made states)
    double ms = 0;
    std::vector<Step> steps;
    std::size_t bytes = 0;
};

std::string entry_name(const Entry& e) {
    std::string s = "\"" + e.label + "\"";
    if (!e.parameters.empty()) s += " (" + e.parameters + ")";
    return s;
}

}  // namespace

// ---- the implementation -------------------------------------------------------------------

struct History::Impl {
    explicit Impl(std::size_t budget_bytes) : budget(budget_bytes) {}

    std::size_t budget;
    std::vector<Entry> entries;
    std::size_t current = 0;
    std::uint64_t next_id = 1;
    std::size_t total_bytes = 0;
    HalfedgeMesh empty;  ///< current_mesh() of an empty history

    MeshPtr current_state;  ///< the last step of the current entry

    const Entry& entry(std::size_t index, const char* what) const {
        if (index >= entries.size())
            throw InvalidArgument(std::string("History::") + what + ": entry " +
                                  std::to_string(index) + " does not exist (the history has " +
                                  std::to_string(entries.size()) + ")");
        return entries[index];
    }

    const Step& current_step() const { return entries[current].steps.back(); }

    void set_current(std::size_t index) {
        current = index;
        current_state = entries[index].steps.back().mesh;
    }

    const HalfedgeMesh& current_mesh() const { return current_state ? *current_state : empty; }

    /// Recounts every entry's bytes: each block of values (core/property.h) counts once,
    /// with the oldest entry that holds it; correspondences count with their step.
    void recount() {
        std::unordered_set<const void*> counted;
        total_bytes = 0;
        for (Entry& e : entries) {
            e.bytes = 0;
            for (const Step& s : e.steps) {
                e.bytes += s.correspondence.positions.size() * sizeof(Point);
                for (const HalfedgeMesh::MemoryBlock& b : s.mesh->memory_blocks())
                    if (counted.insert(b.id).second) e.bytes += b.bytes;
            }
            total_bytes += e.bytes;
        }
    }

    std::vector<std::string> trim() {
        std::vector<std::string> messages;
        while (total_bytes > budget && current > 0) {
            const std::size_t before = total_bytes;
            Entry dropped = std::move(entries.front());
            entries.erase(entries.begin());
            --current;
            recount();
            const std::size_t freed = before - std::min(before, total_bytes);
            std::string msg = "History: dropped the oldest entry " + entry_name(dropped) +
                              " to stay within the memory budget of " + format_bytes(budget) +
                              "; freed " + format_bytes(freed);
            if (freed == 0) msg += " (its mesh is still shared by later entries)";
            messages.push_back(msg + ".");
        }
        if (!messages.empty()) set_current(current);  // indices moved
        return messages;
    }
};

std::size_t History::default_budget() {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page_size = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || page_size <= 0) return std::size_t(2) << 30;  // unknown: 2 GiB
    return std::size_t(pages) * std::size_t(page_size) / 4;
}

History::History(std::size_t budget_bytes) : impl_(std::make_shared<Impl>(budget_bytes)) {}

void History::reset(HalfedgeMesh mesh, std::string label, std::string parameters, double ms) {
    Entry e;
    e.label = std::move(label);
    e.parameters = std::move(parameters);
    e.ms = ms;
    Step s;
    s.id = impl_->next_id++;
    s.mesh = std::make_shared<const HalfedgeMesh>(std::move(mesh));
    e.steps.push_back(std::move(s));

    Impl& im = *impl_;
    im.entries.clear();
    im.entries.push_back(std::move(e));
    im.set_current(0);
    im.recount();
}

std::vector<std::string> History::push(std::string label, std::string parameters, double ms,
                                       std::vector<HalfedgeMesh> step_meshes,
                                       std::vector<MorphCorrespondence> correspondences,
                                       Operation operation) {
    Impl& im = *impl_;
    const std::string where = "History::push \"" + label + "\": ";
    if (im.entries.empty())
        throw InvalidArgument(where + "the history is empty (reset it with a first mesh)");
    if (step_meshes.empty()) throw InvalidArgument(where + "an entry needs at least one step");
    if (step_meshes.size() != correspondences.size())
        throw InvalidArgument(where + std::to_string(step_meshes.size()) + " steps but " +
                              std::to_string(correspondences.size()) + " correspondences");
    for (std::size_t k = 0; k < step_meshes.size(); ++k) {
        const HalfedgeMesh& before = k == 0 ? im.current_mesh() : step_meshes[k - 1];
        try {
            check_correspondence(before, step_meshes[k], correspondences[k]);
        } catch (const InvalidArgument& e) {
            throw InvalidArgument(where + "step " + std::to_string(k) + ": " + e.what());
        }
    }

    // Build the entry aside; the history changes only once it is complete.
    Entry e;
    e.label = std::move(label);
    e.parameters = std::move(parameters);
    e.operation = std::move(operation);
    e.ms = ms;
    const HalfedgeMesh* predecessor = &im.current_mesh();
    for (std::size_t k = 0; k < step_meshes.size(); ++k) {
        HalfedgeMesh& mesh = step_meshes[k];
        Step s;
        s.id = im.next_id++;
        s.correspondence = std::move(correspondences[k]);
        // Steps that keep the vertices share every array their predecessor holds the same
        // values in (most are shared already when the step was made from a copy).
        if (s.correspondence.kind == MorphCorrespondence::Kind::SameVertices)
            mesh.share_equal_arrays(*predecessor);
        s.mesh = std::make_shared<const HalfedgeMesh>(std::move(mesh));
        predecessor = s.mesh.get();
        e.steps.push_back(std::move(s));
    }

    im.entries.reserve(im.current + 2);  // so that push_back cannot throw after the erase
    im.entries.erase(im.entries.begin() + std::ptrdiff_t(im.current) + 1, im.entries.end());
    im.entries.push_back(std::move(e));
    im.set_current(im.entries.size() - 1);
    im.recount();
    return im.trim();
}

std::vector<std::string> History::trim_to_budget() {
    return impl_->trim();
}

bool History::can_undo() const {
    return !impl_->entries.empty() && impl_->current > 0;
}

bool History::can_redo() const {
    return impl_->current + 1 < impl_->entries.size();
}

void History::undo() {
    if (can_undo()) jump(impl_->current - 1);
}

void History::redo() {
    if (can_redo()) jump(impl_->current + 1);
}

void History::jump(std::size_t index) {
    impl_->entry(index, "jump");
    if (index == impl_->current) return;
    impl_->set_current(index);
}

std::size_t History::size() const {
    return impl_->entries.size();
}

std::size_t History::current() const {
    return impl_->current;
}

History::EntryInfo History::info(std::size_t index) const {
    const Entry& e = impl_->entry(index, "info");
    EntryInfo out;
    out.label = e.label;
    out.parameters = e.parameters;
    out.operation = e.operation;
    out.ms = e.ms;
    out.bytes = e.bytes;
    for (const Step& s : e.steps)
        out.steps.push_back({s.mesh->n_vertices(), s.mesh->n_faces(), s.correspondence.kind});
    return out;
}

const HalfedgeMesh& History::current_mesh() const {
    return impl_->current_mesh();
}

HalfedgeMesh History::mesh(std::size_t index, std::size_t step) const {
    const Entry& e = impl_->entry(index, "mesh");
    if (step >= e.steps.size())
        throw InvalidArgument("History::mesh: entry " + std::to_string(index) + " has " +
                              std::to_string(e.steps.size()) + " steps, not step " +
                              std::to_string(step));
    return *e.steps[step].mesh;
}

MorphFrame History::morph(std::size_t index, double t) const {
    const Impl& im = *impl_;
    const Entry& e = im.entry(index, "morph");
    if (index == 0)
        throw InvalidArgument("History::morph: entry 0 has no earlier state to morph from");
    if (!(t >= 0.0)) t = 0.0;  // NaN too
    if (t > 1.0) t = 1.0;
    const std::size_t n = e.steps.size();
    const double scaled = t * double(n);
    const std::size_t k = std::min(std::size_t(scaled), n - 1);
    const double local = std::min(1.0, scaled - double(k));

    const Step& before = k == 0 ? im.entries[index - 1].steps.back() : e.steps[k - 1];
    const Step& after = e.steps[k];
    // Both states live in their entries until the next change, so the frame's topology does.
    return morph_frame(*before.mesh, *after.mesh, after.correspondence, local);
}

std::size_t History::bytes() const {
    return impl_->total_bytes;
}

std::size_t History::budget() const {
    return impl_->budget;
}

void History::set_budget(std::size_t bytes) {
    impl_->budget = bytes;
}

}  // namespace trilab
