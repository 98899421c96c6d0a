// Session files and journals (app/history/session_file.h). Reading is in two passes: the
// chunks are parsed and checked into a model (references, types, sizes; nothing big is
// allocated, the arrays stay views into the file's bytes), then the states are built, each
// from the last built state of the same layout (sharing its arrays copy-on-write) with the
// arrays that differ decoded, validated (core/validate.h), and handed to History::restore.
#include "app/history/session_file.h"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <unordered_map>

#include "app/history/chunk_io.h"
#include "app/history/session_encoder.h"
#include "app/history/session_types.h"
#include "core/errors.h"
#include "core/io/file_util.h"
#include "core/system_memory.h"
#include "core/validate.h"

namespace trilab {

namespace st = session_types;

// ---- writing --------------------------------------------------------------------------------

SessionWriteReport write_session(const std::string& path, const History::Snapshot& snapshot,
                                 const SessionExtras& extras) {
    if (snapshot.entries.empty())
        throw InvalidArgument("write_session " + path + ": the history is empty");
    for (std::size_t i = 0; i < snapshot.entries.size(); ++i)
        for (const History::StepRecord& s : snapshot.entries[i]->steps)
            if (s.mesh->has_garbage())
                throw InvalidArgument("write_session " + path + ": entry " + std::to_string(i) +
                                      " holds a state with deleted elements (not collected)");
    SessionWriteReport report;
    write_file_atomically(path, [&](std::ostream& os) {
        SessionEncoder enc(
            [&os](const char* data, std::size_t size) { os.write(data, std::streamsize(size)); });
        enc.file_header(false);
        for (std::size_t i = 0; i < snapshot.entries.size(); ++i)
            enc.entry(std::uint32_t(i), *snapshot.entries[i]);
        enc.current(std::uint32_t(snapshot.current));
        if (!extras.viewer_settings.empty()) enc.viewer_settings(extras.viewer_settings);
        if (!extras.texture_path.empty() || !extras.texture_bytes.empty())
            enc.texture(extras.texture_path, extras.texture_bytes);
        enc.end(std::uint32_t(snapshot.entries.size()));
        report.bytes = enc.bytes();
        report.arrays = enc.arrays();
        report.states = enc.states();
        report.skipped = enc.skipped();
    });
    report.entries = snapshot.entries.size();
    return report;
}

// ---- the model of a file ---------------------------------------------------------------------

namespace {

constexpr std::uint64_t kMaxElements = std::uint64_t(1) << 31;
constexpr std::size_t kMaxName = 4096;

struct BlobRef {
    std::uint32_t code = 0;
    std::uint64_t count = 0;
    std::string_view data;  ///< the encoded values
    std::size_t chunk_bytes = 0;
};
struct PropRef {
    std::uint8_t container = 0;
    std::string name;
    std::uint32_t code = 0;
    std::string default_bytes;
    std::uint32_t blob = 0;
};
struct StateRef {
    std::uint64_t nv = 0, ne = 0, nf = 0;
    std::vector<PropRef> props;
    std::size_t chunk_bytes = 0;
};
struct StepRef {
    std::uint32_t state = 0;
    MorphCorrespondence::Kind kind = MorphCorrespondence::Kind::SameVertices;
    std::uint32_t blob = kNoBlob;
};
struct EntryRef {
    SessionEntrySummary summary;
    std::vector<StepRef> steps;
};

/// Checks that `data` holds exactly `count` values of type `code`.
void check_values(std::uint32_t code, std::uint64_t count, std::string_view data,
                  const char* what) {
    const std::size_t size = st::element_size(code);
    if (size) {
        if (count > data.size() / size || count * size != data.size())
            throw ChunkError(std::string(what) + ": " + std::to_string(count) + " values of " +
                             std::to_string(size) + " bytes in " + std::to_string(data.size()) +
                             " bytes");
        return;
    }
    ByteReader r(data);
    if (count > data.size() / 4)
        throw ChunkError(std::string(what) + ": " + std::to_string(count) + " strings in " +
                         std::to_string(data.size()) + " bytes");
    for (std::uint64_t i = 0; i < count; ++i) r.str(what);
    r.finish(what);
}

std::size_t container_count(const StateRef& s, int c) {
    switch (c) {
        case st::Vertices:
            return std::size_t(s.nv);
        case st::Halfedges:
            return std::size_t(2 * s.ne);
        case st::Edges:
            return std::size_t(s.ne);
        default:
            return std::size_t(s.nf);
    }
}

/// The chunks read so far, as the history they describe.
class Model {
public:
    explicit Model(bool is_journal) : journal(is_journal) {}

    /// Applies chunk `c`; throws ChunkError (the model is then as before the chunk).
    void apply(const ChunkView& c);
    /// Whether chunk type `type` completes a record (a journal's prefix may end after it).
    static bool is_commit(std::uint32_t type) {
        return type != session_chunk::kArray && type != session_chunk::kState;
    }

    bool journal = false;
    bool ended = false;
    std::unordered_map<std::uint32_t, BlobRef> blobs;
    std::unordered_map<std::uint32_t, StateRef> states;
    std::vector<EntryRef> entries;
    std::size_t current = 0;
    SessionExtras extras;
    std::size_t records = 0;
    std::uint32_t pid = 0;
    std::string program;
    std::set<std::uint32_t> counted_blobs, counted_states;

private:
    void array(ByteReader& r, std::size_t bytes);
    void state(ByteReader& r, std::size_t bytes);
    void entry(ByteReader& r, std::size_t bytes);
    Operation operation(ByteReader& r);
    std::size_t new_bytes(const EntryRef& e);
};

void Model::array(ByteReader& r, std::size_t bytes) {
    const std::uint32_t id = r.u32("array id");
    BlobRef b;
    b.code = r.u32("array type");
    b.count = r.u64("array length");
    if (b.code < st::kFirstCode || b.code > st::kLastCode)
        throw ChunkError("array " + std::to_string(id) + ": unknown type code " +
                         std::to_string(b.code));
    if (blobs.count(id)) throw ChunkError("array " + std::to_string(id) + " is defined twice");
    b.data = r.view(r.left(), "array values");
    check_values(b.code, b.count, b.data, "array values");
    b.chunk_bytes = bytes;
    blobs.emplace(id, b);
}

void Model::state(ByteReader& r, std::size_t bytes) {
    const std::uint32_t id = r.u32("state id");
    StateRef s;
    s.nv = r.u64("vertex count");
    s.ne = r.u64("edge count");
    s.nf = r.u64("face count");
    if (s.nv > kMaxElements || s.ne > kMaxElements / 2 || s.nf > kMaxElements)
        throw ChunkError("state " + std::to_string(id) + ": element counts out of range");
    if (states.count(id)) throw ChunkError("state " + std::to_string(id) + " is defined twice");
    const std::uint32_t n = r.u32("property count");
    if (n > r.left() / 14) throw ChunkError("property count " + std::to_string(n) + " too large");
    std::set<std::pair<int, std::string>> names;
    for (std::uint32_t i = 0; i < n; ++i) {
        PropRef p;
        p.container = r.u8("property container");
        p.name = r.str("property name", kMaxName);
        p.code = r.u32("property type");
        p.default_bytes = r.str("property default", kMaxName);
        p.blob = r.u32("property array");
        const std::string what = "property '" + p.name + "'";
        if (p.container > st::Faces) throw ChunkError(what + ": bad container");
        if (!names.insert({p.container, p.name}).second) throw ChunkError(what + " is given twice");
        const auto b = blobs.find(p.blob);
        if (b == blobs.end())
            throw ChunkError(what + ": array " + std::to_string(p.blob) + " is not defined");
        if (b->second.code != p.code) throw ChunkError(what + ": its array has another type");
        if (b->second.count != container_count(s, p.container))
            throw ChunkError(what + ": " + std::to_string(b->second.count) + " values for " +
                             std::to_string(container_count(s, p.container)) + " elements");
        check_values(p.code, 1, p.default_bytes, "property default");
        s.props.push_back(std::move(p));
    }
    r.finish("properties");
    s.chunk_bytes = bytes;
    states.emplace(id, std::move(s));
}

Operation Model::operation(ByteReader& r) {
    const std::string name = r.str("operation name", kMaxName);
    const std::uint32_t n = r.u32("parameter count");
    if (n > r.left() / 22) throw ChunkError("parameter count " + std::to_string(n) + " too large");
    Operation op;
    if (!name.empty()) {
        try {
            op = make_operation(name);
        } catch (const Error& e) {
            throw ChunkError(e.what());
        }
    } else if (n != 0) {
        throw ChunkError("parameters without an operation");
    }
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::string param = r.str("parameter name", kMaxName);
        ParamValue v;
        v.x = r.f64("parameter value");
        v.y = r.f64("parameter value");
        v.on = r.u8("parameter switch") != 0;
        v.given = r.u8("parameter given") != 0;
        try {
            op.value(param) = v;
        } catch (const Error& e) {
            throw ChunkError(name + ": " + e.what());
        }
    }
    if (op.def) {
        try {
            check_operation(op);
        } catch (const Error& e) {
            throw ChunkError("operation " + name + ": " + e.what());
        }
    }
    return op;
}

std::size_t Model::new_bytes(const EntryRef& e) {
    std::size_t bytes = 0;
    const auto blob = [&](std::uint32_t id) {
        if (id != kNoBlob && counted_blobs.insert(id).second) bytes += blobs.at(id).chunk_bytes;
    };
    for (const StepRef& s : e.steps) {
        if (counted_states.insert(s.state).second) {
            const StateRef& state = states.at(s.state);
            bytes += state.chunk_bytes;
            for (const PropRef& p : state.props) blob(p.blob);
        }
        blob(s.blob);
    }
    return bytes;
}

void Model::entry(ByteReader& r, std::size_t bytes) {
    const std::uint32_t index = r.u32("entry index");
    EntryRef e;
    e.summary.label = r.str("entry label", kMaxName);
    e.summary.parameters = r.str("entry parameters", kMaxName);
    e.summary.ms = r.f64("entry time");
    e.summary.operation = operation(r);
    const std::uint32_t n = r.u32("step count");
    if (n == 0 || n > r.left() / 9) throw ChunkError("bad step count " + std::to_string(n));
    for (std::uint32_t k = 0; k < n; ++k) {
        StepRef s;
        s.state = r.u32("step state");
        const std::uint8_t kind = r.u8("step correspondence");
        s.blob = r.u32("step correspondence array");
        const auto state = states.find(s.state);
        if (state == states.end())
            throw ChunkError("step " + std::to_string(k) + ": state " + std::to_string(s.state) +
                             " is not defined");
        if (kind > 2) throw ChunkError("step " + std::to_string(k) + ": bad correspondence kind");
        s.kind = MorphCorrespondence::Kind(kind);
        if (s.blob != kNoBlob) {
            const auto b = blobs.find(s.blob);
            if (b == blobs.end() || b->second.code != st::kPointCode)
                throw ChunkError("step " + std::to_string(k) +
                                 ": its correspondence array is not a defined point array");
        }
        e.summary.steps.push_back({std::size_t(state->second.nv), std::size_t(state->second.nf)});
        e.steps.push_back(s);
    }
    r.finish("entry");
    if (index > entries.size())
        throw ChunkError("entry index " + std::to_string(index) + " after " +
                         std::to_string(entries.size()) + " entries");
    e.summary.bytes = bytes + new_bytes(e);
    entries.resize(index);
    entries.push_back(std::move(e));
    current = index;
}

void Model::apply(const ChunkView& c) {
    if (ended) throw ChunkError("a chunk after the end chunk");
    ByteReader r(c.payload);
    const std::size_t bytes = c.end - c.offset;
    const auto need_entries = [&](const char* what) {
        if (entries.empty()) throw ChunkError(std::string(what) + " before the first entry");
    };
    switch (c.type) {
        case session_chunk::kArray:
            array(r, bytes);
            return;
        case session_chunk::kState:
            state(r, bytes);
            return;
        case session_chunk::kEntry:
            entry(r, bytes);
            break;
        case session_chunk::kCurrent: {
            const std::uint32_t i = r.u32("current entry");
            r.finish("current entry");
            need_entries("a current entry");
            if (i >= entries.size())
                throw ChunkError("current entry " + std::to_string(i) + " of " +
                                 std::to_string(entries.size()));
            current = i;
            break;
        }
        case session_chunk::kDrop: {
            const std::uint32_t n = r.u32("dropped entries");
            r.finish("dropped entries");
            need_entries("dropping entries");
            if (n >= entries.size() || n > current)
                throw ChunkError("dropping " + std::to_string(n) + " of " +
                                 std::to_string(entries.size()) + " entries");
            entries.erase(entries.begin(), entries.begin() + std::ptrdiff_t(n));
            current -= n;
            break;
        }
        case session_chunk::kKeep: {
            const std::uint32_t n = r.u32("kept entries");
            r.finish("kept entries");
            need_entries("keeping entries");
            if (n == 0 || n > entries.size() || current >= n)
                throw ChunkError("keeping " + std::to_string(n) + " of " +
                                 std::to_string(entries.size()) + " entries");
            entries.resize(n);
            break;
        }
        case session_chunk::kView: {
            std::string text = r.str("viewer settings");
            r.finish("viewer settings");
            extras.viewer_settings = std::move(text);
            return;
        }
        case session_chunk::kTexture: {
            std::string path = r.str("texture path", kMaxName);
            const std::uint64_t n = r.u64("texture size");
            if (n != r.left()) throw ChunkError("texture size disagrees with the chunk");
            extras.texture_bytes = std::string(r.view(std::size_t(n), "texture bytes"));
            extras.texture_path = std::move(path);
            return;
        }
        case session_chunk::kJournal: {
            if (!journal) throw ChunkError("a journal chunk in a session file");
            const std::uint32_t p = r.u32("process id");
            r.u64("process start");
            std::string name = r.str("program", kMaxName);
            r.finish("journal header");
            pid = p;
            program = std::move(name);
            return;
        }
        case session_chunk::kEnd: {
            if (journal) throw ChunkError("an end chunk in a journal");
            const std::uint32_t n = r.u32("entry count");
            r.u32("array count");
            r.u32("state count");
            r.finish("end");
            if (n != entries.size())
                throw ChunkError("the end chunk counts " + std::to_string(n) + " entries, " +
                                 std::to_string(entries.size()) + " were read");
            ended = true;
            return;
        }
        default:
            throw ChunkError("unknown chunk type");
    }
    ++records;
}

// ---- building the states ---------------------------------------------------------------------

template <class T>
T decode_one(std::string_view bytes) {
    if constexpr (std::is_same_v<T, std::string>) {
        ByteReader r(bytes);
        return r.str("value");
    } else {
        T v;
        std::memcpy(static_cast<void*>(&v), bytes.data(), sizeof(T));
        return v;
    }
}

template <class T>
std::vector<T> decode_values(const BlobRef& b) {
    if constexpr (std::is_same_v<T, std::string>) {
        std::vector<T> out;
        out.reserve(std::size_t(b.count));
        ByteReader r(b.data);
        for (std::uint64_t i = 0; i < b.count; ++i) out.push_back(r.str("value"));
        return out;
    } else {
        std::vector<T> out(std::size_t(b.count));
        if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), b.data.data(), b.data.size());
        return out;
    }
}

const char* const kBuiltins[] = {"v:position", "v:halfedge", "v:deleted", "h:to",
                                 "h:next",     "h:prev",     "h:face",    "e:deleted",
                                 "f:halfedge", "f:deleted"};

class Builder {
public:
    explicit Builder(const Model& model) : model_(model) {}
    /// The mesh of state `id` (built once).
    std::shared_ptr<const HalfedgeMesh> mesh(std::uint32_t id);
    MorphCorrespondence correspondence(const StepRef& s) const {
        MorphCorrespondence c;
        c.kind = s.kind;
        if (s.blob != kNoBlob) c.positions = decode_values<Point>(model_.blobs.at(s.blob));
        return c;
    }

private:
    struct Built {
        std::shared_ptr<const HalfedgeMesh> mesh;
        std::vector<std::uint32_t> blobs;  ///< per property
    };
    void assign(HalfedgeMesh& m, const PropRef& p) const;
    void check(const HalfedgeMesh& m, const StateRef& s);

    const Model& model_;
    std::unordered_map<std::uint32_t, Built> built_;
    std::map<std::string, std::uint32_t> last_of_layout_;            ///< layout -> last state built
    std::unordered_map<std::uint32_t, std::uint32_t> first_holder_;  ///< blob -> state
    std::set<std::vector<std::uint32_t>> validated_;                 ///< connectivity blobs checked
};

void Builder::assign(HalfedgeMesh& m, const PropRef& p) const {
    st::visit(p.code, [&](auto tag) {
        using T = typename decltype(tag)::type;
        PropertyArray<T>* a = st::find_array<T>(m, p.container, p.name);
        if (!a) {
            for (const std::string& n : st::array_names(m, p.container))
                if (n == p.name)
                    throw ChunkError("property '" + p.name + "' has the wrong type for it");
            a = st::add_array<T>(m, p.container, p.name, decode_one<T>(p.default_bytes));
        }
        a->assign(decode_values<T>(model_.blobs.at(p.blob)));
    });
}

void Builder::check(const HalfedgeMesh& m, const StateRef& s) {
    std::vector<std::uint32_t> connectivity;
    std::size_t builtins = 0;
    for (const PropRef& p : s.props)
        for (const char* b : kBuiltins)
            if (p.name == b) {
                ++builtins;
                connectivity.push_back(p.blob);
            }
    if (builtins != std::size(kBuiltins))
        throw ChunkError("a state lacks some of the built-in arrays (connectivity, positions)");
    for (std::uint8_t d : m.get_vertex_property<std::uint8_t>("v:deleted").vector())
        if (d) throw ChunkError("a state has deleted vertices");
    for (std::uint8_t d : m.get_edge_property<std::uint8_t>("e:deleted").vector())
        if (d) throw ChunkError("a state has deleted edges");
    for (std::uint8_t d : m.get_face_property<std::uint8_t>("f:deleted").vector())
        if (d) throw ChunkError("a state has deleted faces");
    if (validated_.count(connectivity)) return;
    const ValidationResult v = validate(m);
    if (!v) throw ChunkError("a state's connectivity is invalid: " + v.message);
    validated_.insert(connectivity);
}

std::shared_ptr<const HalfedgeMesh> Builder::mesh(std::uint32_t id) {
    const auto done = built_.find(id);
    if (done != built_.end()) return done->second.mesh;
    const StateRef& s = model_.states.at(id);
    std::string layout =
        std::to_string(s.nv) + "," + std::to_string(s.ne) + "," + std::to_string(s.nf);
    for (const PropRef& p : s.props)
        layout += "|" + std::to_string(p.container) + p.name + ":" + std::to_string(p.code);
    HalfedgeMesh m;
    const Built* base = nullptr;
    const auto last = last_of_layout_.find(layout);
    if (last != last_of_layout_.end()) base = &built_.at(last->second);
    if (base) {
        m = *base->mesh;  // shares every array; the ones that differ are replaced below
    } else {
        m.resize_elements(std::size_t(s.nv), std::size_t(s.ne), std::size_t(s.nf));
    }
    Built b;
    std::set<std::uint32_t> share_with;
    for (std::size_t i = 0; i < s.props.size(); ++i) {
        const PropRef& p = s.props[i];
        b.blobs.push_back(p.blob);
        if (base && base->blobs[i] == p.blob) continue;
        assign(m, p);
        const auto holder = first_holder_.find(p.blob);
        if (holder != first_holder_.end()) share_with.insert(holder->second);
    }
    check(m, s);
    // Arrays first held by another state (not the base): share their values again.
    for (std::uint32_t other : share_with) m.share_equal_arrays(*built_.at(other).mesh);
    for (const PropRef& p : s.props) first_holder_.emplace(p.blob, id);
    b.mesh = std::make_shared<const HalfedgeMesh>(std::move(m));
    last_of_layout_[layout] = id;
    return built_.emplace(id, std::move(b)).first->second.mesh;
}

/// Refuses a model whose arrays would not fit in the memory this process may still use.
void check_memory(const Model& model) {
    std::uint64_t bytes = 0;
    for (const auto& [id, b] : model.blobs) bytes += b.data.size();
    const std::uint64_t available = available_memory_bytes();
    if (bytes > available)
        throw ChunkError("its arrays need " + std::to_string(bytes >> 20) + " MiB, only " +
                         std::to_string(available >> 20) + " MiB may still be allocated");
}

std::string chunk_where(std::size_t index, const ChunkView* c, std::size_t offset) {
    return "chunk " + std::to_string(index) + " (" + (c ? chunk_name(c->type) + " " : "") +
           "at byte " + std::to_string(offset) + ")";
}

/// Parses every chunk of `bytes` after the header into `model`. A session stops at the first
/// error (thrown as IoError); a journal keeps the model of its last complete record.
void parse(std::string_view bytes, const std::string& name, Model& model, SessionContents& out) {
    // Model::apply changes nothing when it throws, and arrays and states read after the last
    // record are referenced by no entry: the model at a failure is its last record's.
    std::size_t offset = kFileHeaderBytes, index = 0, committed = kFileHeaderBytes;
    while (offset < bytes.size() || (!model.journal && !model.ended)) {
        ChunkView c;
        bool have = false;
        try {
            c = read_chunk(bytes, offset);
            have = true;
            model.apply(c);
        } catch (const ChunkError& e) {
            const std::string reason =
                chunk_where(index, have ? &c : nullptr, offset) + ": " + e.what();
            if (!model.journal) throw IoError(name, 0, reason);
            out.stop_reason = reason;
            out.bytes_discarded = bytes.size() - committed;
            out.complete = false;
            return;
        }
        offset = c.end;
        ++index;
        if (model.journal && Model::is_commit(c.type)) committed = offset;
    }
    if (model.journal && committed != bytes.size()) {
        // Only arrays and states after the last record: an entry cut short before its record.
        out.stop_reason = "the last record is incomplete";
        out.bytes_discarded = bytes.size() - committed;
        out.complete = false;
    }
}

void check_header(std::string_view bytes, const std::string& name, bool journal) {
    if (bytes.size() < kFileHeaderBytes)
        throw IoError(name, 0,
                      "not a trilab " + std::string(journal ? "journal" : "session") + ": " +
                          std::to_string(bytes.size()) + " bytes, shorter than the 16-byte header");
    const char* magic = journal ? kJournalMagic : kSessionMagic;
    if (std::memcmp(bytes.data(), magic, 8) != 0)
        throw IoError(name, 0,
                      "not a trilab " + std::string(journal ? "journal" : "session") +
                          " (the header does not start with " + std::string(magic) + ")");
    ByteReader r(bytes.substr(8, 8));
    const std::uint32_t version = r.u32("version");
    const std::uint32_t zero = r.u32("header flags");
    if (version != kSessionFormatVersion || zero != 0)
        throw IoError(name, 0,
                      "format version " + std::to_string(version) + " (this trilab reads " +
                          std::to_string(kSessionFormatVersion) + ")");
}

/// Builds the history of `model` into `out`; a journal keeps the entries before the first that
/// fails to build.
void build(const Model& model, const std::string& name, std::size_t budget, SessionContents& out) {
    try {
        check_memory(model);
    } catch (const ChunkError& e) {
        throw IoError(name, 0, e.what());
    }
    Builder builder(model);
    std::vector<History::EntryRecord> records;
    const HalfedgeMesh* predecessor = nullptr;
    for (std::size_t i = 0; i < model.entries.size(); ++i) {
        const EntryRef& e = model.entries[i];
        History::EntryRecord r;
        r.label = e.summary.label;
        r.parameters = e.summary.parameters;
        r.operation = e.summary.operation;
        r.ms = e.summary.ms;
        const HalfedgeMesh* before = predecessor;
        try {
            for (std::size_t k = 0; k < e.steps.size(); ++k) {
                History::StepRecord s;
                s.mesh = builder.mesh(e.steps[k].state);
                auto c =
                    std::make_shared<const MorphCorrespondence>(builder.correspondence(e.steps[k]));
                if (before) check_correspondence(*before, *s.mesh, *c);
                s.correspondence = std::move(c);
                before = s.mesh.get();
                r.steps.push_back(std::move(s));
            }
        } catch (const std::exception& error) {
            const std::string reason =
                "entry " + std::to_string(i) + " \"" + e.summary.label + "\": " + error.what();
            if (!model.journal || i == 0) throw IoError(name, 0, reason);
            out.stop_reason = reason;
            out.complete = false;
            break;
        }
        predecessor = before;
        records.push_back(std::move(r));
        out.entries.push_back(e.summary);
    }
    const std::size_t current = std::min(model.current, records.size() - 1);
    out.history = History(budget);
    out.messages = out.history.restore(std::move(records), current);
}

SessionContents read_bytes(std::string_view bytes, const std::string& name, std::size_t budget,
                           bool journal) {
    check_header(bytes, name, journal);
    SessionContents out;
    out.journal = journal;
    out.file_bytes = bytes.size();
    Model model(journal);
    parse(bytes, name, model, out);
    if (model.entries.empty())
        throw IoError(name, 0,
                      journal ? "no complete entry to restore" +
                                    (out.stop_reason.empty() ? "" : " (" + out.stop_reason + ")")
                              : "no entries");
    out.extras = model.extras;
    out.records = model.records;
    out.pid = model.pid;
    out.program = model.program;
    build(model, name, budget, out);
    return out;
}

}  // namespace

// ---- reading ---------------------------------------------------------------------------------

SessionContents read_session_bytes(std::string_view bytes, const std::string& name,
                                   std::size_t budget_bytes) {
    return read_bytes(bytes, name, budget_bytes, false);
}

SessionContents read_journal_bytes(std::string_view bytes, const std::string& name,
                                   std::size_t budget_bytes) {
    return read_bytes(bytes, name, budget_bytes, true);
}

SessionContents read_session(const std::string& path, std::size_t budget_bytes) {
    const std::string bytes = read_file_bytes(path);
    return read_session_bytes(bytes, path, budget_bytes);
}

SessionContents read_journal(const std::string& path, std::size_t budget_bytes) {
    const std::string bytes = read_file_bytes(path);
    return read_journal_bytes(bytes, path, budget_bytes);
}

SessionContents read_session_or_journal(const std::string& path, std::size_t budget_bytes) {
    const std::string bytes = read_file_bytes(path);
    const bool journal = bytes.size() >= 8 && std::memcmp(bytes.data(), kJournalMagic, 8) == 0;
    return read_bytes(bytes, path, budget_bytes, journal);
}

}  // namespace trilab
