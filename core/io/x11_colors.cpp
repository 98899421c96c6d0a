#include "core/io/x11_colors.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <string>

namespace trilab {

const X11Color* find_x11_color(std::string_view name) {
    std::string key;
    key.reserve(name.size());
    for (char c : name)
        if (c != ' ' && c != '\t') key += char(std::tolower(static_cast<unsigned char>(c)));
    const X11Color* end = kX11Colors + kX11ColorCount;
    const X11Color* it = std::lower_bound(
        kX11Colors, end, key, [](const X11Color& c, const std::string& k) { return k > c.key; });
    return it != end && key == it->key ? it : nullptr;
}

}  // namespace trilab
