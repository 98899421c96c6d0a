// libFuzzer target: the STL reader (read_stl_bytes). See tests/fuzz/README.md.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return trilab::fuzz::run_mesh_reader(data, size, [](const std::string& bytes) {
        return trilab::read_stl_bytes(bytes, "fuzz.stl");
    });
}
