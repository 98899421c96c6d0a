#pragma once
// Shared body of the libFuzzer targets: feed the bytes to one in-memory reader; a clean
// trilab::Error is fine, anything else (a crash, a sanitizer report, another exception, or a
// returned mesh that fails validate()) aborts, so libFuzzer keeps the input.
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

template <class Read>
int run_mesh_reader(const std::uint8_t* data, std::size_t size, Read read) {
    // An exact-size copy: libstdc++ allocates size + 1, so ASan sees any read past the end
    // (other than the terminating zero every std::string has).
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        const LoadedMesh loaded = read(bytes);
        const ValidationResult result = validate(loaded.mesh);
        if (!result.ok) {
            std::fprintf(stderr, "reader returned an invalid mesh: %s\n", result.message.c_str());
            std::abort();
        }
        for (Vertex v : loaded.mesh.vertices()) {
            const Point& p = loaded.mesh.position(v);
            if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
                std::fprintf(stderr, "reader returned a non-finite position\n");
                std::abort();
            }
        }
    } catch (const Error& e) {
        if (std::string(e.what()).empty()) {
            std::fprintf(stderr, "trilab::Error with an empty message\n");
            std::abort();
        }
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
