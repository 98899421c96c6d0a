// An operation's parameters as widgets, from its declaration: combo boxes, sliders, typed
// fields, check boxes; a typed value outside its range clamped at once; see panels.h.

#include <imgui.h>
#include <imgui_internal.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/key_bindings.h"
#include "app/viewer/panel_helpers.h"
#include "app/viewer/panels.h"
#include "app/viewer/plots.h"
#include "app/viewer/widgets.h"
#include "core/algorithms/fairing.h"
#include "core/number_text.h"

namespace trilab::viewer {

using namespace ui;

namespace {
/// A typed value outside the declared range was replaced by `kept`: the text field lets go
/// (so it shows `kept` at once, like the slider), and the reason goes to `notes`.
void keep_typed_value(const ParamSpec& p, double typed, double kept,
                      std::vector<std::string>* notes) {
    ImGui::ClearActiveID();
    if (!notes) return;
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s: %g is outside %g .. %g; using %g", p.label.c_str(), typed,
                  p.min, p.max, kept);
    notes->push_back(buf);
}

}  // namespace

std::string panel_words(const std::string& cli_text) {
    // Declarations and their messages speak of the command line ("--min-faces N"); the panel
    // names the same parameters by their labels ("min faces N").
    std::string text;
    for (std::size_t i = 0; i < cli_text.size(); ++i) {
        const bool option =
            cli_text.compare(i, 2, "--") == 0 && i + 2 < cli_text.size() &&
            std::isalpha(static_cast<unsigned char>(cli_text[i + 2])) &&
            (i == 0 || cli_text[i - 1] == ' ' || cli_text[i - 1] == '(' || cli_text[i - 1] == '/');
        if (option) {
            ++i;
            // The option's dashes become spaces, as in its label.
            for (std::size_t j = i + 1; j < cli_text.size() && cli_text[j] != ' ' &&
                                        cli_text[j] != ')' && cli_text[j] != ',';
                 ++j) {
                text += cli_text[j] == '-' ? ' ' : cli_text[j];
                i = j;
            }
            continue;
        }
        text += cli_text[i];
    }
    return text;
}

std::string default_note_text(const ParamSpec& p) {
    return p.default_note.empty() ? "default" : panel_words(p.default_note);
}

double clamp_to_declared(const ParamSpec& p, double x) {
    double kept = std::clamp(x, p.min, p.max);
    if (p.min_exclusive && kept <= p.min) {  // the smallest value above min the panel offers
        const double ui_low = p.ui_min != 0 || p.ui_max != 0 ? p.ui_min : p.min;
        kept = ui_low > p.min ? ui_low : std::nextafter(p.min, p.max);
    }
    return kept;
}

namespace {

/// One parameter's widgets: what they edit and how.
struct ParamWidget {
    const ParamSpec& p;
    ParamValue& v;
    double lo, hi;  ///< the slider's span
    float w;        ///< the widget width
    ImGuiSliderFlags flags;
    std::vector<std::string>* notes;
};

/// A combo box, as wide as its longest choice where it can be.
void choice_widget(const ParamWidget& pw) {
    const ParamSpec& p = pw.p;
    ParamValue& v = pw.v;
    const float w = pw.w;
    int current = 0;
    float widest = 0;  // the combo shows its longest choice whole where it can
    for (std::size_t c = 0; c < p.choices.size(); ++c) {
        if (p.choices[c].value == int(v.x)) current = int(c);
        widest = std::max(widest, ImGui::CalcTextSize(p.choices[c].label.c_str()).x);
    }
    const float fit = widest + ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().FramePadding.x;
    ImGui::SetNextItemWidth(
        std::max(w, std::min(fit, widget_width(fit / ImGui::GetFontSize(), 0.3f))));
    if (ImGui::BeginCombo(p.label.c_str(), p.choices[current].label.c_str())) {
        for (std::size_t c = 0; c < p.choices.size(); ++c)
            if (ImGui::Selectable(p.choices[c].label.c_str(), int(c) == current))
                v.x = p.choices[c].value;
        ImGui::EndCombo();
    }
}

/// A slider (or, over wide ranges, a typed field); an optional one with its check box.
void integer_widget(const ParamWidget& pw) {
    const ParamSpec& p = pw.p;
    ParamValue& v = pw.v;
    const double lo = pw.lo, hi = pw.hi;
    std::vector<std::string>* notes = pw.notes;
    // An optional number's check box carries its label: set, or the default.
    const std::string label = p.optional ? "##" + p.name : p.label;
    if (p.optional) {
        if (checkbox(p.label.c_str(), &v.on, (p.name + ":on").c_str()) && v.on)
            v.x = std::clamp(v.x, p.min, p.max);  // from "unset" to a value
        ImGui::SameLine();
    }
    if (!v.on) {  // unset: the run's default, said in words
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", default_note_text(p).c_str());
        ImGui::PopTextWrapPos();
        return;
    }
    ImGui::SetNextItemWidth(pw.w);
    if (hi - lo <= 1000) {
        int x = int(std::clamp(v.x, lo, hi));
        if (ImGui::SliderInt(label.c_str(), &x, int(lo), int(hi), "%d",
                             ImGuiSliderFlags_AlwaysClamp))
            v.x = x;
    } else {  // wide ranges (vertex counts): type the number
        long long x = std::llround(v.x);
        if (ImGui::InputScalar(label.c_str(), ImGuiDataType_S64, &x)) {
            v.x = std::clamp(double(x), p.min, p.max);
            if (v.x != double(x)) keep_typed_value(p, double(x), v.x, notes);
        }
    }
}

/// A typed field and a slider; a switchable one with its check box.
void number_widget(const ParamWidget& pw) {
    const ParamSpec& p = pw.p;
    ParamValue& v = pw.v;
    const double lo = pw.lo, hi = pw.hi;
    const float w = pw.w;
    std::vector<std::string>* notes = pw.notes;
    // A switchable or optional number: the check box carries the label, and sets it.
    const bool switchable = p.kind == ParamKind::Switchable || p.optional;
    if (switchable) {
        if (checkbox(p.label.c_str(), &v.on, (p.name + ":on").c_str()) && v.on)
            v.x = clamp_to_declared(p, v.x);  // from "unset" to a value
        ImGui::SameLine();
        if (!v.on) ImGui::BeginDisabled();
    }
    // Type any value ("2e-2" works) or drag the slider. A typed value outside the
    // declared range is clamped at once: the field lets go of it and shows the
    // value used, as do the slider and every message (keep_typed_value()).
    ImGui::SetNextItemWidth(w * 0.45f);
    double x = v.x;
    const bool typed = ImGui::InputDouble("##value", &x, 0.0, 0.0, "%g");
    note_widget(p.name + ":value");
    if (typed && std::isfinite(x)) {
        v.x = clamp_to_declared(p, x);
        // "0" on the way to "0.05" above an exclusive 0 is not a typing mistake.
        const bool on_the_way = p.min_exclusive && x == p.min;
        if (v.x != x && !on_the_way) keep_typed_value(p, x, v.x, notes);
    }
    // A slider where its span fits a float's (max-error has none: scale-dependent).
    if (std::abs(lo) < 1e30 && std::abs(hi) < 1e30) {
        ImGui::SameLine();
        float f = float(std::clamp(v.x, lo, hi));
        // Beyond the slider's span the slider shows the value itself, not its end.
        char beyond[64];
        std::snprintf(beyond, sizeof beyond, "%.4g", v.x);
        const bool outside = v.x < lo || v.x > hi;
        ImGui::SetNextItemWidth(w * 0.55f);
        const std::string label = switchable ? "##" + p.name : p.label;
        if (ImGui::SliderFloat(label.c_str(), &f, float(lo), float(hi), outside ? beyond : "%.4g",
                               pw.flags))
            v.x = f;
    } else if (!switchable) {
        ImGui::SameLine();
        ImGui::TextUnformatted(p.label.c_str());
    }
    v.x = clamp_to_declared(p, v.x);
    if (switchable && !v.on) ImGui::EndDisabled();
}

/// Two typed integers, the second not below the first.
void range_widget(const ParamWidget& pw) {
    const ParamSpec& p = pw.p;
    ParamValue& v = pw.v;
    int range[2] = {int(v.x), int(v.y)};
    ImGui::SetNextItemWidth(pw.w);
    if (ImGui::InputInt2(p.label.c_str(), range)) {
        v.x = std::clamp(double(range[0]), p.min, p.max);
        v.y = std::clamp(double(range[1]), v.x, p.max);
    }
}

}  // namespace

bool operation_widgets(Operation& op, std::vector<std::string>* notes) {
    bool changed = false;
    const OperationDef& def = *op.def;
    const float w = widget_width();
    for (std::size_t i = 0; i < def.params.size(); ++i) {
        if (def.why_not(op.values, i)) continue;  // hidden: it does not apply
        const ParamSpec& p = def.params[i];
        if (p.cli_only) continue;  // a knob of the command line, or the panel's own widgets
        ParamValue& v = op.values[i];
        const ParamValue before = v;
        ImGui::PushID(p.name.c_str());
        const double lo = p.ui_min != 0 || p.ui_max != 0 ? p.ui_min : p.min;
        const double hi = p.ui_min != 0 || p.ui_max != 0 ? p.ui_max : p.max;
        const ImGuiSliderFlags flags =
            p.logarithmic ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None;
        const ParamWidget pw{p, v, lo, hi, w, flags, notes};
        switch (p.kind) {
            case ParamKind::Choice:
                choice_widget(pw);
                break;
            case ParamKind::Flag: {
                bool on = v.x != 0;
                if (checkbox(p.label.c_str(), &on)) v.x = on ? 1 : 0;
                break;
            }
            case ParamKind::Integer:
                integer_widget(pw);
                break;
            case ParamKind::Switchable:
            case ParamKind::Number:
                number_widget(pw);
                break;
            case ParamKind::Range:
                range_widget(pw);
                break;
        }
        note_widget(p.name);
        if (ImGui::IsItemHovered() && !p.help.empty()) ImGui::SetTooltip("%s", p.help.c_str());
        ImGui::PopID();
        if (v != before) {
            v.given = true;
            changed = true;
        }
    }
    return changed;
}

}  // namespace trilab::viewer
