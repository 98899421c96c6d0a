#include "app/history/history.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
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
using Step = History::StepRecord;
using Record = History::EntryRecord;

/// An entry: its immutable record (shared with snapshots) and the memory it holds alone.
struct Entry {
    std::shared_ptr<const Record> record;
    std::size_t bytes = 0;
};

/// A step id unique in this process (the journal tells states apart by it).
std::uint64_t draw_step_id() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

/// A step of `mesh`: one that keeps the vertices shares every array `predecessor` (if any)
/// holds the same values in (most are shared already when the step was made from a copy).
Step make_step(HalfedgeMesh mesh, MorphCorrespondence correspondence,
               const HalfedgeMesh* predecessor) {
    Step s;
    s.id = draw_step_id();
    if (predecessor && correspondence.kind == MorphCorrespondence::Kind::SameVertices)
        mesh.share_equal_arrays(*predecessor);
    s.mesh = std::make_shared<const HalfedgeMesh>(std::move(mesh));
    s.correspondence = std::make_shared<const MorphCorrespondence>(std::move(correspondence));
    return s;
}

std::string entry_name(const Entry& e) {
    std::string s = "\"" + e.record->label + "\"";
    if (!e.record->parameters.empty()) s += " (" + e.record->parameters + ")";
    return s;
}

}  // namespace

// ---- the implementation -------------------------------------------------------------------

struct History::Impl {
    explicit Impl(std::size_t budget_bytes) : budget(budget_bytes) {}

    std::size_t budget;
    std::vector<Entry> entries;
    std::size_t current = 0;
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

    void set_current(std::size_t index) {
        current = index;
        current_state = entries[index].record->steps.back().mesh;
    }

    const HalfedgeMesh& current_mesh() const { return current_state ? *current_state : empty; }

    /// Recounts every entry's bytes: each block of values (core/property.h) counts once,
    /// with the oldest entry that holds it; correspondences count with their step.
    void recount() {
        std::unordered_set<const void*> counted;
        total_bytes = 0;
        for (Entry& e : entries) {
            e.bytes = 0;
            for (const Step& s : e.record->steps) {
                e.bytes += s.correspondence->positions.size() * sizeof(Point);
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
    auto e = std::make_shared<Record>();
    e->label = std::move(label);
    e->parameters = std::move(parameters);
    e->ms = ms;
    Step s;
    s.id = draw_step_id();
    s.mesh = std::make_shared<const HalfedgeMesh>(std::move(mesh));
    s.correspondence = std::make_shared<const MorphCorrespondence>();
    e->steps.push_back(std::move(s));

    Impl& im = *impl_;
    im.entries.clear();
    im.entries.push_back(Entry{std::move(e), 0});
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
    auto e = std::make_shared<Record>();
    e->label = std::move(label);
    e->parameters = std::move(parameters);
    e->operation = std::move(operation);
    e->ms = ms;
    const HalfedgeMesh* predecessor = &im.current_mesh();
    for (std::size_t k = 0; k < step_meshes.size(); ++k) {
        e->steps.push_back(
            make_step(std::move(step_meshes[k]), std::move(correspondences[k]), predecessor));
        predecessor = e->steps.back().mesh.get();
    }

    im.entries.reserve(im.current + 2);  // so that push_back cannot throw after the erase
    im.entries.erase(im.entries.begin() + std::ptrdiff_t(im.current) + 1, im.entries.end());
    im.entries.push_back(Entry{std::move(e), 0});
    im.set_current(im.entries.size() - 1);
    im.recount();
    return im.trim();
}

History::Snapshot History::snapshot() const {
    Snapshot s;
    s.entries.reserve(impl_->entries.size());
    for (const Entry& e : impl_->entries) s.entries.push_back(e.record);
    s.current = impl_->current;
    return s;
}

std::vector<std::string> History::restore(std::vector<EntryRecord> entries, std::size_t current) {
    if (entries.empty()) throw InvalidArgument("History::restore: no entries");
    if (current >= entries.size())
        throw InvalidArgument("History::restore: current entry " + std::to_string(current) +
                              " does not exist (" + std::to_string(entries.size()) + " entries)");
    std::vector<Entry> built;
    built.reserve(entries.size());
    const HalfedgeMesh* predecessor = nullptr;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        EntryRecord& in = entries[i];
        const std::string where =
            "History::restore: entry " + std::to_string(i) + " \"" + in.label + "\"";
        if (in.steps.empty()) throw InvalidArgument(where + " has no steps");
        auto e = std::make_shared<Record>();
        e->label = std::move(in.label);
        e->parameters = std::move(in.parameters);
        e->operation = std::move(in.operation);
        e->ms = in.ms;
        for (std::size_t k = 0; k < in.steps.size(); ++k) {
            StepRecord& s = in.steps[k];
            if (!s.mesh || !s.correspondence)
                throw InvalidArgument(where + ": step " + std::to_string(k) + " is empty");
            if (predecessor) {
                try {
                    check_correspondence(*predecessor, *s.mesh, *s.correspondence);
                } catch (const InvalidArgument& error) {
                    throw InvalidArgument(where + ": step " + std::to_string(k) + ": " +
                                          error.what());
                }
            }
            e->steps.push_back(make_step(HalfedgeMesh(*s.mesh), *s.correspondence, predecessor));
            predecessor = e->steps.back().mesh.get();
        }
        built.push_back(Entry{std::move(e), 0});
    }
    Impl& im = *impl_;
    im.entries = std::move(built);
    im.set_current(current);
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
    const Entry& entry = impl_->entry(index, "info");
    const Record& e = *entry.record;
    EntryInfo out;
    out.label = e.label;
    out.parameters = e.parameters;
    out.operation = e.operation;
    out.ms = e.ms;
    out.bytes = entry.bytes;
    for (const Step& s : e.steps)
        out.steps.push_back({s.mesh->n_vertices(), s.mesh->n_faces(), s.correspondence->kind});
    return out;
}

const HalfedgeMesh& History::current_mesh() const {
    return impl_->current_mesh();
}

HalfedgeMesh History::mesh(std::size_t index, std::size_t step) const {
    const Record& e = *impl_->entry(index, "mesh").record;
    if (step >= e.steps.size())
        throw InvalidArgument("History::mesh: entry " + std::to_string(index) + " has " +
                              std::to_string(e.steps.size()) + " steps, not step " +
                              std::to_string(step));
    return *e.steps[step].mesh;
}

MorphFrame History::morph(std::size_t index, double t) const {
    const Impl& im = *impl_;
    const Record& e = *im.entry(index, "morph").record;
    if (index == 0)
        throw InvalidArgument("History::morph: entry 0 has no earlier state to morph from");
    if (!(t >= 0.0)) t = 0.0;  // NaN too
    if (t > 1.0) t = 1.0;
    const std::size_t n = e.steps.size();
    const double scaled = t * double(n);
    const std::size_t k = std::min(std::size_t(scaled), n - 1);
    const double local = std::min(1.0, scaled - double(k));

    const Step& before = k == 0 ? im.entries[index - 1].record->steps.back() : e.steps[k - 1];
    const Step& after = e.steps[k];
    // Both states live in their entries until the next change, so the frame's topology does.
    return morph_frame(*before.mesh, *after.mesh, *after.correspondence, local);
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
