#pragma once
// The CLI's timings: "ms" in --json is the operation itself, file reading and writing
// excluded, measured with this.
#include <chrono>

namespace trilab::cli {

/// Milliseconds since `t0`.
inline double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace trilab::cli
