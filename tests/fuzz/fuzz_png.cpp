// libFuzzer target: the PNG image reader (read_image_bytes). See tests/fuzz/README.md.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return trilab::fuzz::run_image_reader(data, size, "fuzz.png");
}
