#pragma once
// Shared by the session-file and journal tests: fixture histories, a temporary path, and the
// exact comparison of two histories (every state's arrays bit for bit, by name and type).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <string>
#include <vector>

#include "app/history/history.h"
#include "app/history/session_types.h"
#include "app/ops/operation.h"
#include "core/algorithms/generators.h"
#include "core/progress.h"
#include "test_helpers.h"

namespace trilab::test {

/// A path in the temporary folder, unique to this process.
inline std::string temp_path(const std::string& name) {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/trilab-session-test-" +
           std::to_string(getpid()) + "-" + name;
}

/// Runs `text` on the current state and pushes every step, as the viewer does.
inline void push_operation(History& history, const std::string& text) {
    const Operation op = parse_operation(text);
    NullProgress progress;
    OperationResult r = run_operation(op, history.current_mesh(), progress);
    std::vector<HalfedgeMesh> meshes;
    std::vector<MorphCorrespondence> corr;
    for (OperationStep& s : r.steps) {
        meshes.push_back(std::move(s.mesh));
        corr.push_back(std::move(s.correspondence));
    }
    history.push(r.label, r.parameters, r.ms, std::move(meshes), std::move(corr), op);
}

/// A sphere with every kind of attribute, then subdivision (new connectivity), smoothing
/// steps (positions only), noise, decimation (a coarser mesh), a viewer-made load entry, and
/// an undo: the current entry is not the last.
inline History sample_history() {
    History h(std::size_t(-1));
    HalfedgeMesh m = attributed_sphere();
    auto label = m.add_face_property<int>("f:label", -1);
    for (Face f : m.faces()) label[f] = int(f.idx() % 7);
    auto weight = m.add_edge_property<float>("e:weight", 1.0f);
    for (Edge e : m.edges()) weight[e] = 0.5f + float(e.idx() % 3);
    auto selection = m.add_vertex_property<std::uint8_t>("v:selection", 0);
    for (Vertex v : m.vertices()) selection[v] = std::uint8_t(v.idx() % 3 == 0);
    h.reset(m, "Load sphere.obj", "/data/sphere.obj", 1.5);
    push_operation(h, "smooth --iterations 3");
    push_operation(h, "subdivide --scheme loop --iterations 1");
    push_operation(h, "noise --amount 2 --seed 4");
    push_operation(h, "decimate --target-vertices 60");
    push_operation(h, "smooth --iterations 2 --step 0.25");
    h.undo();
    return h;
}

/// A tetrahedron with two operations: a small file (about 4 KB) for byte-by-byte tests.
inline History small_history() {
    History h(std::size_t(-1));
    h.reset(make_tetrahedron(), "Load tetrahedron.off");
    push_operation(h, "noise --amount 5 --seed 2");
    push_operation(h, "smooth --iterations 2");
    return h;
}

/// Every array of `a` equals `b`'s of the same name, type, default and bits; the same names
/// in the same order.
inline void require_same_arrays(const HalfedgeMesh& a, const HalfedgeMesh& b) {
    namespace st = session_types;
    for (int c = st::Vertices; c <= st::Faces; ++c) {
        REQUIRE(st::container_size(a, c) == st::container_size(b, c));
        const std::vector<std::string> names = st::array_names(a, c);
        REQUIRE(names == st::array_names(b, c));
        for (const std::string& name : names) {
            bool found = false;
            for (std::uint32_t code = st::kFirstCode; code <= st::kLastCode; ++code)
                st::visit(code, [&](auto tag) {
                    using T = typename decltype(tag)::type;
                    const PropertyArray<T>* x = st::find_array<T>(a, c, name);
                    if (!x) return;
                    found = true;
                    const PropertyArray<T>* y = st::find_array<T>(b, c, name);
                    INFO("array " << name);
                    REQUIRE(y);
                    const std::vector<T>& u = x->data();
                    const std::vector<T>& v = y->data();
                    REQUIRE(u.size() == v.size());
                    if constexpr (std::is_same_v<T, std::string>) {
                        REQUIRE(u == v);
                        REQUIRE(x->default_value() == y->default_value());
                    } else {
                        REQUIRE((u.empty() || std::memcmp(static_cast<const void*>(u.data()),
                                                          static_cast<const void*>(v.data()),
                                                          u.size() * sizeof(T)) == 0));
                        REQUIRE(std::memcmp(static_cast<const void*>(&x->default_value()),
                                            static_cast<const void*>(&y->default_value()),
                                            sizeof(T)) == 0);
                    }
                });
            INFO("array " << name);
            REQUIRE(found);
        }
    }
    REQUIRE(a.n_vertices() == b.n_vertices());
    REQUIRE(a.n_faces() == b.n_faces());
}

/// The same entries (labels, parameters, typed operations, steps, times unless `times` is
/// false: another run of the same script) and current entry, every state and correspondence
/// bit for bit.
inline void require_same_history(const History& a, const History& b, bool times = true) {
    REQUIRE(a.size() == b.size());
    REQUIRE(a.current() == b.current());
    const History::Snapshot sa = a.snapshot(), sb = b.snapshot();
    for (std::size_t i = 0; i < a.size(); ++i) {
        INFO("entry " << i);
        const History::EntryRecord& x = *sa.entries[i];
        const History::EntryRecord& y = *sb.entries[i];
        REQUIRE(x.label == y.label);
        REQUIRE(x.parameters == y.parameters);
        REQUIRE(x.operation == y.operation);
        if (times) REQUIRE(x.ms == y.ms);
        REQUIRE(x.steps.size() == y.steps.size());
        for (std::size_t k = 0; k < x.steps.size(); ++k) {
            INFO("step " << k);
            require_same_arrays(*x.steps[k].mesh, *y.steps[k].mesh);
            REQUIRE(x.steps[k].correspondence->kind == y.steps[k].correspondence->kind);
            const auto& p = x.steps[k].correspondence->positions;
            const auto& q = y.steps[k].correspondence->positions;
            REQUIRE(p.size() == q.size());
            REQUIRE((p.empty() || std::memcmp(p.data()->data(), q.data()->data(),
                                              p.size() * sizeof(Point)) == 0));
        }
    }
}

}  // namespace trilab::test
