// libFuzzer target: the PNM image reader (read_image_bytes). See tests/fuzz/README.md.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/errors.h"
#include "core/io/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        const trilab::Image image = trilab::read_image_bytes(bytes, "fuzz.pnm");
        if (image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
            std::fprintf(stderr, "image size does not match its pixels\n");
            std::abort();
        }
    } catch (const trilab::Error& e) {
        if (std::string(e.what()).empty()) std::abort();
    }
    return 0;
}
