// libFuzzer target: the OM reader (read_om_bytes), then its writer and reader again. See
// tests/fuzz/README.md.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return trilab::fuzz::run_mesh_reader(data, size, "fuzz.om", trilab::read_om_bytes);
}
