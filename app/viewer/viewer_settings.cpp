// The viewer's settings as key=value text; see viewer_settings.h.
#include "app/viewer/viewer_settings.h"

#include "app/viewer/tool.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/algorithms/coloring.h"
#include "core/algorithms/morph.h"
#include "core/up_axis.h"

namespace trilab::viewer {
namespace {

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '\\')
            out += "\\\\";
        else if (c == '\n')
            out += "\\n";
        else
            out += c;
    }
    return out;
}

std::string unescape(const std::string& s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 1 < s.size()) {
            ++i;
            out += s[i] == 'n' ? '\n' : s[i];
        } else {
            out += s[i];
        }
    }
    return out;
}

std::string format(double v) {
    char buf[40];
    std::snprintf(buf, sizeof(buf), "%.17g", v);
    return buf;
}
std::string format(float v) {
    char buf[40];
    std::snprintf(buf, sizeof(buf), "%.9g", double(v));
    return buf;
}

/// Reads `count` finite numbers separated by spaces; throws std::invalid_argument.
std::vector<double> numbers(const std::string& text, std::size_t count) {
    std::istringstream in(text);
    std::vector<double> out;
    std::string word;
    while (in >> word) {
        char* end = nullptr;
        const double v = std::strtod(word.c_str(), &end);
        if (end == word.c_str() || *end != '\0' || !std::isfinite(v))
            throw std::invalid_argument("'" + word + "' is not a finite number");
        out.push_back(v);
    }
    if (out.size() != count)
        throw std::invalid_argument("expected " + std::to_string(count) + " number" +
                                    (count == 1 ? "" : "s") + ", got " +
                                    std::to_string(out.size()));
    return out;
}

/// Writes every setting (the writer) or applies those present (the reader): one list of keys
/// for both directions.
struct Writer {
    std::string text;
    void put(const std::string& key, const std::string& value) {
        text += key + "=" + escape(value) + "\n";
    }
    void number(const std::string& key, float& v) { put(key, format(v)); }
    void number(const std::string& key, double& v) { put(key, format(v)); }
    void number(const std::string& key, int& v) { put(key, std::to_string(v)); }
    void flag(const std::string& key, bool& v) { put(key, v ? "1" : "0"); }
    void vec3(const std::string& key, glm::vec3& v) {
        put(key, format(v.x) + " " + format(v.y) + " " + format(v.z));
    }
    void text_value(const std::string& key, std::string& v) { put(key, v); }
    template <class E, class Name, class Parse>
    void choice(const std::string& key, E& v, Name name, Parse) {
        put(key, name(v));
    }
    template <class E>
    void index(const std::string& key, E& v, int) {
        put(key, std::to_string(int(v)));
    }
    void operation(const std::string& key, Operation& op) { put(key, op.text()); }
};

struct Reader {
    std::map<std::string, std::pair<std::size_t, std::string>> values;  ///< key: line, value
    std::vector<std::string> notes;

    /// Runs `apply` on the value of `key` when present; a thrown reason becomes a note.
    template <class F>
    void with(const std::string& key, F apply) {
        auto it = values.find(key);
        if (it == values.end()) return;
        const auto [line, value] = it->second;
        values.erase(it);
        try {
            apply(value);
        } catch (const std::exception& e) {
            notes.push_back("viewer settings line " + std::to_string(line) + ": " + key + ": " +
                            e.what() + " (kept as it was)");
        }
    }
    void number(const std::string& key, float& v) {
        with(key, [&](const std::string& s) { v = float(numbers(s, 1)[0]); });
    }
    void number(const std::string& key, double& v) {
        with(key, [&](const std::string& s) { v = numbers(s, 1)[0]; });
    }
    void number(const std::string& key, int& v) {
        with(key, [&](const std::string& s) {
            const double d = numbers(s, 1)[0];
            if (d != std::floor(d) || std::fabs(d) > 1e9)
                throw std::invalid_argument("expected a whole number, got '" + s + "'");
            v = int(d);
        });
    }
    void flag(const std::string& key, bool& v) {
        with(key, [&](const std::string& s) {
            if (s != "0" && s != "1")
                throw std::invalid_argument("expected 0 or 1, got '" + s + "'");
            v = s == "1";
        });
    }
    void vec3(const std::string& key, glm::vec3& v) {
        with(key, [&](const std::string& s) {
            const std::vector<double> d = numbers(s, 3);
            v = glm::vec3(float(d[0]), float(d[1]), float(d[2]));
        });
    }
    void text_value(const std::string& key, std::string& v) {
        with(key, [&](const std::string& s) { v = s; });
    }
    template <class E, class Name, class Parse>
    void choice(const std::string& key, E& v, Name, Parse parse) {
        with(key, [&](const std::string& s) { v = parse(s); });
    }
    template <class E>
    void index(const std::string& key, E& v, int count) {
        with(key, [&](const std::string& s) {
            const double d = numbers(s, 1)[0];
            if (d != std::floor(d) || d < 0 || d >= count)
                throw std::invalid_argument("expected 0 to " + std::to_string(count - 1) +
                                            ", got '" + s + "'");
            v = E(int(d));
        });
    }
    void operation(const std::string& key, Operation& op) {
        with(key, [&](const std::string& s) {
            // The defaults as they are (some operations' defaults are no valid run, e.g.
            // remove-components before a limit is chosen); anything else parses and checks.
            Operation defaults = make_operation(op.def->name);
            Operation parsed = s == defaults.text() ? std::move(defaults) : parse_operation(s);
            if (parsed.def != op.def)
                throw std::invalid_argument("'" + s + "' is not a " + op.def->name + " operation");
            op = std::move(parsed);
        });
    }
};

/// A tool's settings through the writer or the reader (Tool::settings()).
template <class V>
class ToolSettings : public SettingsVisitor {
public:
    explicit ToolSettings(V& v) : v_(v) {}
    void number(const std::string& key, int& x) override { v_.number(key, x); }
    void number(const std::string& key, float& x) override { v_.number(key, x); }
    void flag(const std::string& key, bool& x) override { v_.flag(key, x); }
    void text(const std::string& key, std::string& x) override { v_.text_value(key, x); }
    void operation(const std::string& key, Operation& op) override { v_.operation(key, op); }

private:
    V& v_;
};

template <class V>
void visit(V& v, const ViewerSettingsRefs& r) {
    RenderStyle& s = r.style;
    v.choice("style.mode", s.mode, render_mode_name, parse_render_mode);
    v.flag("style.wireframe", s.wireframe);
    v.number("style.wire_width", s.wire_width);
    v.vec3("style.wire_color", s.wire_color);
    v.vec3("style.line_color", s.line_color);
    v.flag("style.back_face_color", s.back_face_color);
    v.flag("style.cull_hidden_back_faces", s.cull_hidden_back_faces);
    v.vec3("style.front_color", s.front_color);
    v.vec3("style.back_color", s.back_color);
    v.flag("style.vertex_colors", s.vertex_colors);
    v.choice("style.scalar_display", s.scalar_display, scalar_display_name, parse_scalar_display);
    v.number("style.scalar_steps", s.scalar_steps);
    v.number("style.isoline_width", s.isoline_width);
    v.number("style.point_size", s.point_size);
    v.flag("style.occlude_points", s.occlude_points);
    v.number("style.ambient", s.ambient);
    v.flag("style.specular", s.specular);
    v.number("style.specular_strength", s.specular_strength);
    v.number("style.shininess", s.shininess);
    v.flag("style.fog", s.fog);
    v.number("style.fog_amount", s.fog_amount);
    v.vec3("style.background", s.background);
    v.index("style.texture_mode", s.texture_mode, 3);
    v.flag("style.face_normals", s.face_normals);
    v.flag("style.vertex_normals", s.vertex_normals);
    v.number("style.vector_length", s.vector_length);
    v.vec3("style.face_normal_color", s.face_normal_color);
    v.vec3("style.vertex_normal_color", s.vertex_normal_color);

    ViewSettings& vs = r.settings;
    v.index("view.wireframe", vs.wireframe, 3);
    v.choice("view.coloring", vs.coloring, coloring_name, parse_coloring);
    v.number("view.legend_low_percentile", vs.coloring_options.low_percentile);
    v.number("view.legend_high_percentile", vs.coloring_options.high_percentile);
    v.index("view.projection", vs.projection, 2);
    v.choice("view.up", vs.up, up_axis_name,
             [](const std::string& name) { return parse_up_axis(name, "view.up"); });
    v.flag("view.use_checkerboard", vs.use_checkerboard);

    // Every tool's panel (its operation's values, its own settings), then the window's.
    ToolSettings<V> tools(v);
    for (Tool* tool : r.tools) tool->settings(tools);
    PanelState& p = r.panels;
    v.text_value("screenshot.path", p.screenshot.path);
    v.number("screenshot.width", p.screenshot.width);
    v.number("screenshot.height", p.screenshot.height);
    v.flag("screenshot.transparent", p.screenshot.transparent);
    v.number("morph.duration", r.morph.duration);
    v.choice("morph.easing", r.morph.easing, easing_name, parse_easing);
    v.choice("morph.playback", r.morph.playback, playback_name, parse_playback);
}

}  // namespace

std::string viewer_settings_text(const ViewerSettingsRefs& refs) {
    Writer w;
    const Camera& c = refs.camera;
    const glm::quat q = c.rotation();
    const glm::vec3 t = c.target();
    w.put("camera.rotation",
          format(q.w) + " " + format(q.x) + " " + format(q.y) + " " + format(q.z));
    w.put("camera.target", format(t.x) + " " + format(t.y) + " " + format(t.z));
    w.put("camera.distance", format(c.distance()));
    w.put("camera.radius", format(c.radius()));
    w.put("camera.fov_y", format(c.fov_y()));
    visit(w, refs);
    return w.text;
}

std::vector<std::string> apply_viewer_settings(const std::string& text,
                                               const ViewerSettingsRefs& refs) {
    Reader r;
    std::istringstream in(text);
    std::string line;
    std::size_t number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (line.empty()) continue;
        const std::size_t eq = line.find('=');
        if (eq == std::string::npos || eq == 0) {
            r.notes.push_back("viewer settings line " + std::to_string(number) +
                              ": expected key=value (ignored)");
            continue;
        }
        r.values[line.substr(0, eq)] = {number, unescape(line.substr(eq + 1))};
    }
    // The camera: all five values or none.
    std::vector<double> q, t;
    double distance = 0, radius = 0, fov = 0;
    bool camera = r.values.count("camera.rotation") > 0;
    r.with("camera.rotation", [&](const std::string& s) { q = numbers(s, 4); });
    r.with("camera.target", [&](const std::string& s) { t = numbers(s, 3); });
    r.with("camera.distance", [&](const std::string& s) { distance = numbers(s, 1)[0]; });
    r.with("camera.radius", [&](const std::string& s) { radius = numbers(s, 1)[0]; });
    r.with("camera.fov_y", [&](const std::string& s) { fov = numbers(s, 1)[0]; });
    if (camera) {
        if (q.size() != 4 || t.size() != 3 ||
            !refs.camera.set_state(glm::quat(float(q[0]), float(q[1]), float(q[2]), float(q[3])),
                                   glm::vec3(float(t[0]), float(t[1]), float(t[2])),
                                   float(distance), float(radius), float(fov)))
            r.notes.push_back(
                "viewer settings: the camera is incomplete or out of range (kept "
                "as it was)");
    }
    visit(r, refs);
    for (const auto& [key, value] : r.values)
        r.notes.push_back("viewer settings line " + std::to_string(value.first) +
                          ": unknown setting '" + key + "' (ignored)");
    return r.notes;
}

}  // namespace trilab::viewer
