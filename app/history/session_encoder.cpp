// SessionEncoder (app/history/session_encoder.h): arrays, states and entries as chunks.
#include "app/history/session_encoder.h"

#include <unordered_set>

#include "app/history/session_types.h"

namespace trilab {

namespace st = session_types;

namespace {

/// The bytes of one value: its memory, or u32 length + bytes for a string.
template <class T>
void put_value(ByteWriter& w, const T& v) {
    if constexpr (std::is_same_v<T, std::string>)
        w.str(v);
    else
        w.raw(&v, sizeof(T));
}

}  // namespace

void SessionEncoder::emit(std::uint32_t type, const std::string& head, const void* tail,
                          std::size_t tail_size) {
    bytes_ += write_chunk(sink_, type, head, tail, tail_size);
}

void SessionEncoder::file_header(bool journal) {
    ByteWriter w;
    w.raw(journal ? kJournalMagic : kSessionMagic, 8);
    w.u32(kSessionFormatVersion);
    w.u32(0);
    sink_(w.bytes().data(), w.bytes().size());
    bytes_ += w.bytes().size();
}

template <class T>
std::uint32_t SessionEncoder::array(const PropertyArray<T>& a, std::uint32_t code) {
    const auto found = blobs_.find(a.values_id());
    if (found != blobs_.end()) return found->second;
    const std::uint32_t id = next_blob_++;
    const std::vector<T>& values = a.data();
    ByteWriter head;
    head.u32(id);
    head.u32(code);
    head.u64(values.size());
    if constexpr (std::is_same_v<T, std::string>) {
        for (const std::string& s : values) head.str(s);
        emit(session_chunk::kArray, head.bytes());
    } else {
        emit(session_chunk::kArray, head.bytes(), values.data(), values.size() * sizeof(T));
    }
    blobs_.emplace(a.values_id(), id);
    return id;
}

std::uint32_t SessionEncoder::positions(const std::vector<Point>& p) {
    const auto found = blobs_.find(&p);
    if (found != blobs_.end()) return found->second;
    const std::uint32_t id = next_blob_++;
    ByteWriter head;
    head.u32(id);
    head.u32(st::kPointCode);
    head.u64(p.size());
    emit(session_chunk::kArray, head.bytes(), p.data(), p.size() * sizeof(Point));
    blobs_.emplace(&p, id);
    return id;
}

std::uint32_t SessionEncoder::state(const History::StepRecord& step) {
    const auto found = states_.find(step.id);
    if (found != states_.end()) return found->second;
    const HalfedgeMesh& m = *step.mesh;
    ByteWriter props;
    std::uint32_t count = 0;
    for (int c = st::Vertices; c <= st::Faces; ++c) {
        for (const std::string& name : st::array_names(m, c)) {
            bool stored = false;
            for (std::uint32_t code = st::kFirstCode; code <= st::kLastCode && !stored; ++code) {
                st::visit(code, [&](auto tag) {
                    using T = typename decltype(tag)::type;
                    const PropertyArray<T>* a = st::find_array<T>(m, c, name);
                    if (!a) return;
                    const std::uint32_t blob = array(*a, code);
                    props.u8(std::uint8_t(c));
                    props.str(name);
                    props.u32(code);
                    ByteWriter d;
                    put_value(d, a->default_value());
                    props.str(d.bytes());
                    props.u32(blob);
                    ++count;
                    stored = true;
                });
            }
            if (!stored) {
                const std::string what = name + " (a type session files do not store)";
                bool known = false;
                for (const std::string& s : skipped_) known = known || s == what;
                if (!known) skipped_.push_back(what);
            }
        }
    }
    const std::uint32_t id = next_state_++;
    ByteWriter head;
    head.u32(id);
    head.u64(m.vertices_size());
    head.u64(m.edges_size());
    head.u64(m.faces_size());
    head.u32(count);
    head.raw(props.bytes().data(), props.bytes().size());
    emit(session_chunk::kState, head.bytes());
    states_.emplace(step.id, id);
    return id;
}

void SessionEncoder::entry(std::uint32_t index, const History::EntryRecord& e) {
    std::vector<std::uint32_t> state_ids, corr_ids;
    for (const History::StepRecord& s : e.steps) {
        state_ids.push_back(state(s));
        corr_ids.push_back(
            s.correspondence->positions.empty() ? kNoBlob : positions(s.correspondence->positions));
    }
    ByteWriter w;
    w.u32(index);
    w.str(e.label);
    w.str(e.parameters);
    w.f64(e.ms);
    const OperationDef* def = e.operation.def;
    w.str(def ? def->name : std::string());
    w.u32(def ? std::uint32_t(def->params.size()) : 0);
    if (def) {
        for (std::size_t i = 0; i < def->params.size(); ++i) {
            const ParamValue& v = e.operation.values[i];
            w.str(def->params[i].name);
            w.f64(v.x);
            w.f64(v.y);
            w.u8(v.on ? 1 : 0);
            w.u8(v.given ? 1 : 0);
        }
    }
    w.u32(std::uint32_t(e.steps.size()));
    for (std::size_t k = 0; k < e.steps.size(); ++k) {
        w.u32(state_ids[k]);
        w.u8(std::uint8_t(e.steps[k].correspondence->kind));
        w.u32(corr_ids[k]);
    }
    emit(session_chunk::kEntry, w.bytes());
}

void SessionEncoder::current(std::uint32_t index) {
    ByteWriter w;
    w.u32(index);
    emit(session_chunk::kCurrent, w.bytes());
}

void SessionEncoder::drop_front(std::uint32_t count) {
    ByteWriter w;
    w.u32(count);
    emit(session_chunk::kDrop, w.bytes());
}

void SessionEncoder::keep(std::uint32_t count) {
    ByteWriter w;
    w.u32(count);
    emit(session_chunk::kKeep, w.bytes());
}

void SessionEncoder::viewer_settings(const std::string& text) {
    ByteWriter w;
    w.str(text);
    emit(session_chunk::kView, w.bytes());
}

void SessionEncoder::texture(const std::string& path, const std::string& bytes) {
    ByteWriter w;
    w.str(path);
    w.u64(bytes.size());
    emit(session_chunk::kTexture, w.bytes(), bytes.data(), bytes.size());
}

void SessionEncoder::journal_info(std::uint32_t pid, std::uint64_t start_ticks,
                                  const std::string& program) {
    ByteWriter w;
    w.u32(pid);
    w.u64(start_ticks);
    w.str(program);
    emit(session_chunk::kJournal, w.bytes());
}

void SessionEncoder::end(std::uint32_t entries) {
    ByteWriter w;
    w.u32(entries);
    w.u32(next_blob_);
    w.u32(next_state_);
    emit(session_chunk::kEnd, w.bytes());
}

void SessionEncoder::retain_only(const History::Snapshot& live) {
    std::unordered_set<const void*> ids;
    std::unordered_set<std::uint64_t> steps;
    for (const auto& e : live.entries)
        for (const History::StepRecord& s : e->steps) {
            steps.insert(s.id);
            ids.insert(&s.correspondence->positions);
            for (const HalfedgeMesh::MemoryBlock& b : s.mesh->memory_blocks()) ids.insert(b.id);
        }
    for (auto it = blobs_.begin(); it != blobs_.end();)
        it = ids.count(it->first) ? std::next(it) : blobs_.erase(it);
    for (auto it = states_.begin(); it != states_.end();)
        it = steps.count(it->first) ? std::next(it) : states_.erase(it);
}

}  // namespace trilab
