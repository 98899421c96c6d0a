#pragma once
// Shared body of the libFuzzer targets: feed the bytes to one in-memory reader; a clean
// trilab::Error is fine, anything else (a crash, a sanitizer report, another exception, a
// returned mesh that fails validate() or holds a non-finite position or attribute, or one
// that does not survive our writer and reader of its format) aborts, so libFuzzer keeps
// the input.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/errors.h"
#include "core/io/image_io.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"

namespace trilab::fuzz {

namespace detail {

[[noreturn]] inline void fail(const char* what, const std::string& detail = "") {
    std::fprintf(stderr, "%s%s%s\n", what, detail.empty() ? "" : ": ", detail.c_str());
    std::abort();
}

template <class T, class Property>
void check_finite_property(const Property& p, const char* what) {
    if (!p) return;
    for (const T& v : p.vector())
        if (!v.allFinite()) fail("reader returned a non-finite attribute", what);
}

/// Positions and every attribute of `mesh` are finite.
inline void check_finite(const HalfedgeMesh& mesh) {
    for (Vertex v : mesh.vertices())
        if (!mesh.position(v).allFinite()) fail("reader returned a non-finite position");
    check_finite_property<Vector3>(mesh.get_vertex_property<Vector3>("v:normal"), "v:normal");
    check_finite_property<Color>(mesh.get_vertex_property<Color>("v:color"), "v:color");
    check_finite_property<TexCoord>(mesh.get_vertex_property<TexCoord>("v:texcoord"), "v:texcoord");
    check_finite_property<TexCoord>(mesh.get_halfedge_property<TexCoord>("h:texcoord"),
                                    "h:texcoord");
}

}  // namespace detail

/// Feeds the bytes to `read` (an in-memory reader such as read_ply_bytes, called with the
/// label `name`, whose extension names the format). A returned mesh must be valid with
/// finite positions and attributes, and must survive a round trip: our writer for the same
/// format (every encoding) writes it, and the reader reads that back with the same faces
/// (and vertices, except STL, which merges them). Only STL may refuse to write a mesh the
/// reader returned (no faces; float32 overflow in binary).
template <class Read>
int run_mesh_reader(const std::uint8_t* data, std::size_t size, const char* name, Read read) {
    // An exact-size copy: libstdc++ allocates size + 1, so ASan sees any read past the end
    // (other than the terminating zero every std::string has).
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    LoadedMesh loaded;
    try {
        loaded = read(bytes, name);
    } catch (const Error& e) {
        if (std::string(e.what()).empty()) detail::fail("trilab::Error with an empty message");
        return 0;
    }
    const ValidationResult result = validate(loaded.mesh);
    if (!result.ok) detail::fail("reader returned an invalid mesh", result.message);
    detail::check_finite(loaded.mesh);

    const std::string ext = file_extension(name);
    const bool stl = ext == "stl";
    for (const bool ascii : {false, true}) {
        if (ascii && ext != "ply" && ext != "stl") break;  // one encoding only
        WriteOptions options;
        options.ascii = ascii;
        std::string written;
        try {
            written = write_mesh_bytes(loaded.mesh, name, options);
        } catch (const IoError& e) {
            if (!stl || e.reason().empty()) detail::fail("our writer refused it", e.what());
            continue;
        }
        LoadedMesh back;
        try {
            back = read(written, name);
        } catch (const Error& e) {
            detail::fail("our reader refused what our writer wrote", e.what());
        }
        if (!validate(back.mesh).ok) detail::fail("the round trip gave an invalid mesh");
        detail::check_finite(back.mesh);
        if (back.mesh.n_faces() != loaded.mesh.n_faces())
            detail::fail("the round trip changed the face count");
        if (!stl && back.mesh.n_vertices() != loaded.mesh.n_vertices())
            detail::fail("the round trip changed the vertex count");
    }
    return 0;
}

/// The same for the image reader (read_image_bytes, the format from `name`'s extension): an
/// image must have exactly width x height RGBA pixels.
inline int run_image_reader(const std::uint8_t* data, std::size_t size, const char* name) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        const Image image = read_image_bytes(bytes, name);
        if (image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
            std::fprintf(stderr, "image size does not match its pixels\n");
            std::abort();
        }
    } catch (const Error& e) {
        if (std::string(e.what()).empty()) std::abort();
    }
    return 0;
}

}  // namespace trilab::fuzz
