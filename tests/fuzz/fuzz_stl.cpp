// libFuzzer target: the STL reader (read_stl_bytes), then its writer and reader again. See
// tests/fuzz/README.md.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return trilab::fuzz::run_mesh_reader(data, size, "fuzz.stl", trilab::read_stl_bytes);
}
