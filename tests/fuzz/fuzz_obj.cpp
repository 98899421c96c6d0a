// libFuzzer target: the OBJ reader (read_obj_bytes), then its writer and reader again. See
// tests/fuzz/README.md.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return trilab::fuzz::run_mesh_reader(data, size, "fuzz.obj", trilab::read_obj_bytes);
}
