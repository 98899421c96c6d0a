// libFuzzer target: the OFF reader (read_off_bytes), then its writer and reader again. See
// tests/fuzz/README.md.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return trilab::fuzz::run_mesh_reader(data, size, "fuzz.off", trilab::read_off_bytes);
}
