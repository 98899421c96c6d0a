#pragma once
// The X11 colour names (XPM colours such as "snow", "DarkSlateGray", "gray50"), generated at
// build time from Debian's x11-common table /usr/share/X11/rgb.txt
// (third_party/cmake/embed_x11_colors.cmake): every name X11 knows, none retyped.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace trilab {

struct X11Color {
    const char* key;  ///< the name in lower case without spaces
    std::uint8_t r, g, b;
};

/// The table, sorted by key (generated source).
extern const X11Color kX11Colors[];
extern const std::size_t kX11ColorCount;

/// The colour of an X11 name, ignoring case and spaces as X11 does ("Dark Slate Gray" and
/// "darkslategray" are the same); nullptr when X11 does not know the name.
const X11Color* find_x11_color(std::string_view name);

}  // namespace trilab
