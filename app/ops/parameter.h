#pragma once
// The typed parameters of an operation, declared once (app/ops/operation_decl.h) and read by
// everything that shows, parses, checks or stores them: the CLI's options, --help and error
// messages, the JSON echo, the History's text, and the viewer's widgets.
//
// A parameter's value is a ParamValue: numbers, whole numbers, choices (the enum's value)
// and flags are held in `x`; a range LO:HI in `x` and `y`; `on` says whether a switchable
// number ("--normal-flip 90" or "off") is on, or whether an optional one is set at all.
#include <cstddef>
#include <string>
#include <vector>

namespace trilab {

enum class ParamKind {
    Number,      ///< a finite real in [min, max]
    Integer,     ///< a whole number in [min, max]
    Flag,        ///< present or not ("--preserve-volume"); no value
    Choice,      ///< one identifier of `choices`
    Switchable,  ///< a number in [min, max], or `off_word` to turn the feature off
    Range,       ///< "LO:HI", whole numbers with min <= LO <= HI <= max
};

/// One value of a Choice parameter: the enum's value, its identifier and its label.
struct ChoiceItem {
    int value = 0;
    std::string id;     ///< what the CLI and the history write: "curvature-flow"
    std::string label;  ///< what the panel shows: "Curvature flow (cotangent)"
};

struct ParamSpec {
    std::string name;   ///< "step": the option --step, the JSON key, the widget's id
    std::string label;  ///< the panel's label: "step"
    ParamKind kind = ParamKind::Number;
    double min = 0, max = 0;        ///< the accepted range (Number, Integer, Switchable, Range)
    bool min_exclusive = false;     ///< min itself is refused ("above 0")
    double ui_min = 0, ui_max = 0;  ///< the panel's slider span (both 0: min to max)
    bool logarithmic = false;       ///< the panel's slider is logarithmic
    bool optional = false;          ///< may be left unset (`on` false): the run picks a default
    bool hide_default = false;      ///< left out of the canonical text at its default
    bool counts_steps = false;      ///< its value is the number of steps a run gives
    std::string unit;               ///< appended to the range in messages: " (degrees)"
    std::string help;               ///< one line for --help and the panel's tooltip
    /// Not a panel widget: a command-line knob (threads, size limits) or a value a panel
    /// sets with widgets of its own (the Frequency panel's band sliders).
    bool cli_only = false;
    std::string default_note;  ///< --help's default where it is not a single value
    std::vector<ChoiceItem> choices;
    std::string off_word;  ///< Switchable: the word that turns it off ("off")
};

struct ParamValue {
    double x = 0;        ///< the number, whole number, choice value, flag (0/1) or LO
    double y = 0;        ///< HI of a range
    bool on = true;      ///< Switchable: on; optional: set
    bool given = false;  ///< named explicitly (on the command line, or changed in a panel)
    /// The same meaning: `given` aside, and `x`, `y` aside while off (a switchable number
    /// switched off, an optional one unset), where the run does not read them.
    bool operator==(const ParamValue& o) const {
        return on == o.on && (!on || (x == o.x && y == o.y));
    }
    bool operator!=(const ParamValue& o) const { return !(*this == o); }
};

/// One value per ParamSpec of the operation, in declaration order.
using ParamValues = std::vector<ParamValue>;

/// The text of `v` as the CLI takes it ("0.5", "loop", "off", "3:9"; "" for a flag).
std::string format_param_value(const ParamSpec& spec, const ParamValue& v);
/// Parses the CLI text of a value; throws InvalidArgument "--name: expected ..., got 'text'".
ParamValue parse_param_value(const ParamSpec& spec, const std::string& text);
/// Checks a value set programmatically (a panel, a sweep) the way parsing would; throws the
/// same messages.
void check_param_value(const ParamSpec& spec, const ParamValue& v);
/// The option's one-line description for --help: "--step T  lambda*dt (0 to 1e6, default 0.5)".
std::string param_usage(const ParamSpec& spec, const ParamValue& default_value);
/// Shortest text that reads back as exactly `v`.
std::string format_number(double v);

}  // namespace trilab
