#include "app/history/history.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <variant>

#include "core/errors.h"

namespace trilab {

namespace {

// ---- attribute types the history can compare, copy and size -----------------------------
// Attributes of other types cannot be compared through the mesh's interface: a step that
// carries one is stored as a full mesh, and it is counted at kUnknownElementBytes.

template <class... Ts>
struct TypeList {};

using KnownTypes = TypeList<Eigen::Vector3d, Eigen::Vector2d, Eigen::Vector4d, Eigen::Vector3f,
                            Eigen::Vector2f, Eigen::Vector4f, double, float, std::int8_t,
                            std::uint8_t, std::int16_t, std::uint16_t, std::int32_t, std::uint32_t,
                            std::int64_t, std::uint64_t, Vertex, Halfedge, Edge, Face>;

constexpr std::size_t kUnknownElementBytes = 16;

template <class T>
constexpr bool has_no_padding() {
    if constexpr (std::is_base_of_v<Eigen::MatrixBase<T>, T>)
        return sizeof(T) == std::size_t(T::SizeAtCompileTime) * sizeof(typename T::Scalar);
    else if constexpr (std::is_arithmetic_v<T>)
        return true;
    else
        return sizeof(T) == sizeof(Index);  // the handle types: one Index each
}

template <class L>
struct ArrayVariantOf;
template <class... Ts>
struct ArrayVariantOf<TypeList<Ts...>> {
    using type = std::variant<std::vector<Ts>...>;
};
/// One attribute array of any known type.
using AnyArray = ArrayVariantOf<KnownTypes>::type;

enum class ElementKind { Vertex, Halfedge, Edge, Face };
constexpr ElementKind kAllKinds[] = {ElementKind::Vertex, ElementKind::Halfedge, ElementKind::Edge,
                                     ElementKind::Face};

/// The connectivity arrays: a step shares a base only when these are equal.
bool is_connectivity(const std::string& name) {
    static const char* const names[] = {"v:halfedge", "v:deleted",  "h:to",
                                        "h:next",     "h:prev",     "h:face",
                                        "e:deleted",  "f:halfedge", "f:deleted"};
    return std::find(std::begin(names), std::end(names), name) != std::end(names);
}

std::vector<std::string> property_names(const HalfedgeMesh& m, ElementKind kind) {
    switch (kind) {
        case ElementKind::Vertex:
            return m.vertex_property_names();
        case ElementKind::Halfedge:
            return m.halfedge_property_names();
        case ElementKind::Edge:
            return m.edge_property_names();
        case ElementKind::Face:
            return m.face_property_names();
    }
    return {};
}

std::size_t storage_size(const HalfedgeMesh& m, ElementKind kind) {
    switch (kind) {
        case ElementKind::Vertex:
            return m.vertices_size();
        case ElementKind::Halfedge:
            return m.halfedges_size();
        case ElementKind::Edge:
            return m.edges_size();
        case ElementKind::Face:
            return m.faces_size();
    }
    return 0;
}

/// The array of that name and type (nullptr when there is none of that type).
template <class T>
const std::vector<T>* typed_array(const HalfedgeMesh& m, ElementKind kind,
                                  const std::string& name) {
    switch (kind) {
        case ElementKind::Vertex: {
            auto p = m.get_vertex_property<T>(name);
            return p ? &p.vector() : nullptr;
        }
        case ElementKind::Halfedge: {
            auto p = m.get_halfedge_property<T>(name);
            return p ? &p.vector() : nullptr;
        }
        case ElementKind::Edge: {
            auto p = m.get_edge_property<T>(name);
            return p ? &p.vector() : nullptr;
        }
        case ElementKind::Face: {
            auto p = m.get_face_property<T>(name);
            return p ? &p.vector() : nullptr;
        }
    }
    return nullptr;
}

template <class T>
std::vector<T>* typed_array(HalfedgeMesh& m, ElementKind kind, const std::string& name) {
    return const_cast<std::vector<T>*>(typed_array<T>(std::as_const(m), kind, name));
}

/// sizeof the element type of the attribute, or 0 when its type is not a known one.
template <class... Ts>
std::size_t element_bytes(const HalfedgeMesh& m, ElementKind kind, const std::string& name,
                          TypeList<Ts...>) {
    std::size_t bytes = 0;
    (void)((typed_array<Ts>(m, kind, name) ? (bytes = sizeof(Ts), true) : false) || ...);
    return bytes;
}

/// Bit-for-bit equality (so -0.0 differs from 0.0 and equal NaNs are equal).
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    static_assert(has_no_padding<T>(), "memcmp needs a type without padding");
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

enum class Comparison { UnknownType, TypeMismatch, Equal, Different };

template <class T>
bool compare_as(const HalfedgeMesh& a, const HalfedgeMesh& b, ElementKind kind,
                const std::string& name, Comparison& out) {
    const std::vector<T>* x = typed_array<T>(a, kind, name);
    if (!x) return false;
    const std::vector<T>* y = typed_array<T>(b, kind, name);
    out = !y                  ? Comparison::TypeMismatch
          : same_bits(*x, *y) ? Comparison::Equal
                              : Comparison::Different;
    return true;
}

template <class... Ts>
Comparison compare_attribute(const HalfedgeMesh& a, const HalfedgeMesh& b, ElementKind kind,
                             const std::string& name, TypeList<Ts...>) {
    Comparison out = Comparison::UnknownType;
    (void)(compare_as<Ts>(a, b, kind, name, out) || ...);
    return out;
}

template <class T>
bool copy_as(const HalfedgeMesh& m, ElementKind kind, const std::string& name, AnyArray& out) {
    const std::vector<T>* x = typed_array<T>(m, kind, name);
    if (!x) return false;
    out = *x;
    return true;
}

template <class... Ts>
AnyArray copy_attribute(const HalfedgeMesh& m, ElementKind kind, const std::string& name,
                        TypeList<Ts...>) {
    AnyArray out;
    (void)(copy_as<Ts>(m, kind, name, out) || ...);
    return out;
}

/// An attribute array that differs from the base's (e.g. normals recomputed after a move).
struct AttributeOverride {
    ElementKind kind;
    std::string name;
    AnyArray values;
};

std::size_t array_bytes(const AnyArray& a) {
    return std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, a);
}

/// An estimate of a mesh's memory: storage size x bytes per element, over every array.
std::size_t mesh_bytes(const HalfedgeMesh& m) {
    std::size_t total = 0;
    for (ElementKind kind : kAllKinds) {
        std::size_t per_element = 0;
        for (const std::string& name : property_names(m, kind)) {
            const std::size_t b = element_bytes(m, kind, name, KnownTypes{});
            per_element += b ? b : kUnknownElementBytes;
        }
        total += per_element * storage_size(m, kind);
    }
    return total;
}

/// Whether `mesh` can be stored as positions (plus attribute overrides) over `base`: equal
/// storage sizes and live counts, the same attribute names in the same order, equal
/// connectivity arrays bit for bit, and every other attribute of a known type (equal, or
/// recorded in `overrides`). Any attribute of an unknown type makes the answer false.
bool shares_structure(const HalfedgeMesh& mesh, const HalfedgeMesh& base,
                      std::vector<AttributeOverride>& overrides) {
    overrides.clear();
    for (ElementKind kind : kAllKinds)
        if (storage_size(mesh, kind) != storage_size(base, kind)) return false;
    if (mesh.n_vertices() != base.n_vertices() || mesh.n_edges() != base.n_edges() ||
        mesh.n_faces() != base.n_faces())
        return false;
    for (ElementKind kind : kAllKinds) {
        const std::vector<std::string> names = property_names(mesh, kind);
        if (names != property_names(base, kind)) return false;
        for (const std::string& name : names) {
            if (kind == ElementKind::Vertex && name == "v:position") continue;
            switch (compare_attribute(mesh, base, kind, name, KnownTypes{})) {
                case Comparison::UnknownType:
                case Comparison::TypeMismatch:
                    return false;
                case Comparison::Equal:
                    break;
                case Comparison::Different:
                    if (is_connectivity(name)) return false;
                    overrides.push_back(
                        {kind, name, copy_attribute(mesh, kind, name, KnownTypes{})});
                    break;
            }
        }
    }
    return true;
}

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
    std::uint64_t id = 0;  ///< unique in the history's lifetime (key of morph()'s states)
    /// The whole mesh, or null for a shared step.
    MeshPtr full;
    /// A shared step: the full mesh whose connectivity and attributes it shares (the base of
    /// its predecessor, or the predecessor itself), its own positions and the attribute
    /// arrays that differ from the base's.
    MeshPtr base;
    std::vector<Point> positions;
    std::vector<AttributeOverride> overrides;
    MorphCorrespondence correspondence;
    std::size_t vertices = 0, faces = 0;

    /// The full mesh that holds this step's connectivity and attributes.
    const MeshPtr& structure() const { return full ? full : base; }
    /// Memory this step holds on its own (its base not included).
    std::size_t own_bytes() const {
        std::size_t b = correspondence.positions.size() * sizeof(Point);
        if (full) return b + mesh_bytes(*full);
        b += positions.size() * sizeof(Point);
        for (const AttributeOverride& o : overrides) b += array_bytes(o.values);
        return b;
    }
};

struct Entry {
    std::string label, parameters;
    Operation operation;  ///< the typed operation (none for loads and viewer-made states)
    double ms = 0;
    std::vector<Step> steps;
    std::size_t bytes = 0;
};

/// The state after a shared step: a copy of its base with its positions and overrides.
HalfedgeMesh reconstruct(const Step& step) {
    HalfedgeMesh m = *step.base;
    m.positions() = step.positions;
    for (const AttributeOverride& o : step.overrides) {
        std::visit(
            [&](const auto& values) {
                using T = typename std::decay_t<decltype(values)>::value_type;
                *typed_array<T>(m, o.kind, o.name) = values;
            },
            o.values);
    }
    return m;
}

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

    // The current state, rebuilt eagerly on every change so that current_mesh() only reads,
    // and the states morph() rebuilt since the last change (kept so that the topology of a
    // frame stays valid, and so that playback does not rebuild them frame after frame).
    MeshPtr current_state;
    mutable std::unordered_map<std::uint64_t, MeshPtr> morph_states;

    const Entry& entry(std::size_t index, const char* what) const {
        if (index >= entries.size())
            throw InvalidArgument(std::string("History::") + what + ": entry " +
                                  std::to_string(index) + " does not exist (the history has " +
                                  std::to_string(entries.size()) + ")");
        return entries[index];
    }

    const Step& current_step() const { return entries[current].steps.back(); }

    /// The state after `step` for morph(): its full mesh, the current state, or a
    /// reconstruction kept until the next change.
    MeshPtr morph_state(const Step& step) const {
        if (step.full) return step.full;
        if (&step == &current_step()) return current_state;
        MeshPtr& slot = morph_states[step.id];
        if (!slot) slot = std::make_shared<const HalfedgeMesh>(reconstruct(step));
        return slot;
    }

    /// After every change of the entries or of the current one: makes entry `index` the
    /// current one, with its state (`built`: that state when the caller has it at hand), and
    /// drops morph()'s states. Builds first, so a failure leaves everything as it was.
    void set_current(std::size_t index, MeshPtr built = nullptr) {
        const Step& s = entries[index].steps.back();
        MeshPtr state = s.full  ? s.full
                        : built ? std::move(built)
                                : std::make_shared<const HalfedgeMesh>(reconstruct(s));
        morph_states.clear();
        current = index;
        current_state = std::move(state);
    }

    const HalfedgeMesh& current_mesh() const { return current_state ? *current_state : empty; }

    /// Recounts every entry's bytes: full meshes and shared steps' own arrays count with
    /// their entry; a base counts with the oldest entry that holds it (its owner, or, once
    /// the owner was dropped, the oldest entry whose shared steps keep it alive).
    void recount() {
        std::unordered_set<const HalfedgeMesh*> counted;
        total_bytes = 0;
        for (Entry& e : entries) {
            e.bytes = 0;
            for (const Step& s : e.steps) {
                e.bytes += s.own_bytes();
                if (s.full) counted.insert(s.full.get());
            }
            for (const Step& s : e.steps)
                if (!s.full && counted.insert(s.base.get()).second) e.bytes += mesh_bytes(*s.base);
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
        if (!messages.empty()) set_current(current, current_state);  // indices moved
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
    s.vertices = mesh.n_vertices();
    s.faces = mesh.n_faces();
    s.full = std::make_shared<const HalfedgeMesh>(std::move(mesh));
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
    MeshPtr last_state;  // the state after the last step, when already at hand
    MeshPtr predecessor = im.current_step().structure();
    for (std::size_t k = 0; k < step_meshes.size(); ++k) {
        HalfedgeMesh& mesh = step_meshes[k];
        Step s;
        s.id = im.next_id++;
        s.vertices = mesh.n_vertices();
        s.faces = mesh.n_faces();
        s.correspondence = std::move(correspondences[k]);
        const bool last = k + 1 == step_meshes.size();
        if (s.correspondence.kind == MorphCorrespondence::Kind::SameVertices &&
            shares_structure(mesh, *predecessor, s.overrides)) {
            s.base = predecessor;
            if (last) {
                s.positions = mesh.positions();
                last_state = std::make_shared<const HalfedgeMesh>(std::move(mesh));
            } else {
                s.positions = std::move(mesh.positions());  // the mesh is not needed again
            }
        } else {
            s.full = std::make_shared<const HalfedgeMesh>(std::move(mesh));
        }
        predecessor = s.structure();
        e.steps.push_back(std::move(s));
    }

    im.entries.reserve(im.current + 2);  // so that push_back cannot throw after the erase
    im.entries.erase(im.entries.begin() + std::ptrdiff_t(im.current) + 1, im.entries.end());
    im.entries.push_back(std::move(e));
    // A shared last step's incoming mesh is the current state exactly (its arrays equal the
    // base's, its positions and overrides are the step's): keep it rather than rebuild it.
    im.set_current(im.entries.size() - 1, std::move(last_state));
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
    for (const Step& s : e.steps) out.steps.push_back({s.vertices, s.faces, s.correspondence.kind});
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
    const Step& s = e.steps[step];
    return s.full ? *s.full : reconstruct(s);
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
    // Both states stay alive (full meshes in their entries, reconstructions in morph_states)
    // until the next change, so the frame's topology does too.
    const MeshPtr a = im.morph_state(before);
    const MeshPtr b = im.morph_state(after);
    return morph_frame(*a, *b, after.correspondence, local);
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
