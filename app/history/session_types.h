#pragma once
// The element types a session file stores property arrays of (docs/file-formats.md#session-
// files): a code per type, and the one dispatch from a code to the C++ type. Values are stored
// as their bytes in memory (little-endian), strings as u32 length + bytes.
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>

#include "core/halfedge_mesh.h"
#include "core/types.h"

namespace trilab::session_types {

template <class T>
struct Tag {
    using type = T;
};

/// Calls f(Tag<T>{}) for the type of `code`; false for an unknown code.
template <class F>
bool visit(std::uint32_t code, F&& f) {
    switch (code) {
        case 1:
            f(Tag<Eigen::Vector3d>{});
            return true;
        case 2:
            f(Tag<Eigen::Vector2d>{});
            return true;
        case 3:
            f(Tag<Eigen::Vector3f>{});
            return true;
        case 4:
            f(Tag<double>{});
            return true;
        case 5:
            f(Tag<float>{});
            return true;
        case 6:
            f(Tag<std::int32_t>{});
            return true;
        case 7:
            f(Tag<std::uint32_t>{});
            return true;
        case 8:
            f(Tag<std::uint8_t>{});
            return true;
        case 9:
            f(Tag<std::int64_t>{});
            return true;
        case 10:
            f(Tag<std::uint64_t>{});
            return true;
        case 11:
            f(Tag<std::int8_t>{});
            return true;
        case 12:
            f(Tag<std::int16_t>{});
            return true;
        case 13:
            f(Tag<std::uint16_t>{});
            return true;
        case 14:
            f(Tag<Vertex>{});
            return true;
        case 15:
            f(Tag<Halfedge>{});
            return true;
        case 16:
            f(Tag<Edge>{});
            return true;
        case 17:
            f(Tag<Face>{});
            return true;
        case 18:
            f(Tag<std::string>{});
            return true;
        case 19:  // three vertex indices (a subdivision vertex's parents)
            f(Tag<Eigen::Matrix<std::uint32_t, 3, 1>>{});
            return true;
        default:
            return false;
    }
}
inline constexpr std::uint32_t kFirstCode = 1, kLastCode = 19;

/// Bytes per element of type `code`: the size of a fixed-size type, 0 for strings (stored with
/// their length) and for an unknown code.
inline std::size_t element_size(std::uint32_t code) {
    std::size_t size = 0;
    visit(code, [&](auto tag) {
        using T = typename decltype(tag)::type;
        if constexpr (!std::is_same_v<T, std::string>) size = sizeof(T);
    });
    return size;
}
inline constexpr std::uint32_t kPointCode = 1;

/// The containers of a mesh: vertices, halfedges, edges, faces.
enum Container : std::uint8_t { Vertices = 0, Halfedges = 1, Edges = 2, Faces = 3 };

/// The array `name` of type T in container `c`, or nullptr.
template <class T>
const PropertyArray<T>* find_array(const HalfedgeMesh& m, int c, const std::string& name) {
    switch (c) {
        case Vertices:
            return m.get_vertex_property<T>(name).array();
        case Halfedges:
            return m.get_halfedge_property<T>(name).array();
        case Edges:
            return m.get_edge_property<T>(name).array();
        default:
            return m.get_face_property<T>(name).array();
    }
}
template <class T>
PropertyArray<T>* find_array(HalfedgeMesh& m, int c, const std::string& name) {
    switch (c) {
        case Vertices:
            return m.get_vertex_property<T>(name).array();
        case Halfedges:
            return m.get_halfedge_property<T>(name).array();
        case Edges:
            return m.get_edge_property<T>(name).array();
        default:
            return m.get_face_property<T>(name).array();
    }
}
/// Adds array `name` of type T with default `d` to container `c`.
template <class T>
PropertyArray<T>* add_array(HalfedgeMesh& m, int c, const std::string& name, T d) {
    switch (c) {
        case Vertices:
            return m.add_vertex_property<T>(name, std::move(d)).array();
        case Halfedges:
            return m.add_halfedge_property<T>(name, std::move(d)).array();
        case Edges:
            return m.add_edge_property<T>(name, std::move(d)).array();
        default:
            return m.add_face_property<T>(name, std::move(d)).array();
    }
}
inline std::vector<std::string> array_names(const HalfedgeMesh& m, int c) {
    switch (c) {
        case Vertices:
            return m.vertex_property_names();
        case Halfedges:
            return m.halfedge_property_names();
        case Edges:
            return m.edge_property_names();
        default:
            return m.face_property_names();
    }
}
/// Storage size of container `c`.
inline std::size_t container_size(const HalfedgeMesh& m, int c) {
    switch (c) {
        case Vertices:
            return m.vertices_size();
        case Halfedges:
            return m.halfedges_size();
        case Edges:
            return m.edges_size();
        default:
            return m.faces_size();
    }
}

}  // namespace trilab::session_types
