#pragma once
// Numbers and counts in messages, written as people write them: "tolerance 1e+09", not
// "1000000000.000000"; "1 vertex", "2 vertices", not "1 vertices". Used by the core's
// messages, the operations' reports (app/ops), trilab-cli and the viewer; no GL, no ImGui.
#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>

namespace trilab {

/// The shortest text that reads back as exactly `v` ("0.5", "1e+09", "-3"; "inf", "nan").
inline std::string number_text(double v) {
    char buf[64];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v);
    return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

/// "1 vertex", "0 vertices", "12 vertices": `n` with the singular `one` when n is 1 and the
/// plural `many` otherwise. `one` and `many` may be whole phrases ("coincident vertex left
/// apart", "coincident vertices left apart").
inline std::string count_text(std::size_t n, std::string_view one, std::string_view many) {
    std::string s = std::to_string(n);
    s += ' ';
    s += n == 1 ? one : many;
    return s;
}

}  // namespace trilab
