#pragma once
// Declaring an operation: its typed parameters, each bound to a field of the core's options
// struct, once. Everything else is derived from this declaration: the CLI's parsing, --help
// and error messages, the JSON echo, the history's text and the panel's widgets. Defaults are
// the options struct's own (`Options{}`), so the core, the CLI and the viewer cannot disagree.
//
//   OperationDecl<NoiseOptions> d("noise", "Add noise", "Moves every vertex ...");
//   d.number("amount", &NoiseOptions::amount_percent, 0, 1000, "percent of the mean edge length")
//    .integer("seed", &NoiseOptions::seed, 0, 4294967295, "random seed");
//   d.run(run_noise);       // OperationResult (const NoiseOptions&, const HalfedgeMesh&,
//                           //                  Progress&, const RunSettings&)
//   return d.build();       // the OperationDef the registry holds
//
// The bindings run both ways: OperationDef::options gives the struct of a set of values,
// OperationDef::from_options the values of a struct (options_of / set_options in
// app/ops/operation.h). Each operation has an options type of its own (a wrapper struct where
// the core's is shared or needs optional fields), so the type names the operation.
//
// A field of a nested struct binds through a lambda: [](SpectrumOptions& o) -> auto& { return
// o.spectral.k; }. `only_if` attaches to the last parameter the condition under which it
// applies (it is hidden in the panel and refused on the command line otherwise); `check`
// adds a test over the whole options struct.
#include <any>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "app/ops/operation.h"
#include "core/enum_table.h"
#include "core/errors.h"

namespace trilab {

namespace detail {

/// ParamValue <-> a field of type T.
template <class T>
struct ParamField {
    static void load(const T& field, ParamValue& v) {
        if constexpr (std::is_enum_v<T>)
            v.x = double(static_cast<int>(field));
        else
            v.x = double(field);
    }
    static void store(const ParamValue& v, T& field) {
        if constexpr (std::is_enum_v<T>)
            field = static_cast<T>(static_cast<int>(v.x));
        else if constexpr (std::is_same_v<T, bool>)
            field = v.x != 0;
        else if constexpr (std::is_integral_v<T>)
            field = static_cast<T>(std::llround(v.x));
        else
            field = static_cast<T>(v.x);
    }
};
/// An optional field: `on` says whether it is set.
template <class T>
struct ParamField<std::optional<T>> {
    static void load(const std::optional<T>& field, ParamValue& v) {
        v.on = field.has_value();
        if (field) ParamField<T>::load(*field, v);
    }
    static void store(const ParamValue& v, std::optional<T>& field) {
        if (!v.on) {
            field.reset();
            return;
        }
        T value{};
        ParamField<T>::store(v, value);
        field = value;
    }
};
/// A range LO:HI.
template <class T>
struct ParamField<std::optional<std::pair<T, T>>> {
    static void load(const std::optional<std::pair<T, T>>& field, ParamValue& v) {
        v.on = field.has_value();
        if (field) {
            v.x = double(field->first);
            v.y = double(field->second);
        }
    }
    static void store(const ParamValue& v, std::optional<std::pair<T, T>>& field) {
        if (v.on)
            field = std::pair<T, T>(static_cast<T>(std::llround(v.x)),
                                    static_cast<T>(std::llround(v.y)));
        else
            field.reset();
    }
};

template <class E>
std::vector<ChoiceItem> choice_items(EnumTableView<E> table) {
    std::vector<ChoiceItem> items;
    for (const EnumEntry<E>& e : table) items.push_back({static_cast<int>(e.value), e.id, e.label});
    return items;
}

}  // namespace detail

/// Builds the OperationDef of an operation whose options struct is `Options`.
template <class Options>
class OperationDecl {
public:
    using Runner = std::function<OperationResult(const Options&, const HalfedgeMesh&, Progress&,
                                                 const RunSettings&)>;
    /// Says why the parameter does not apply to `o` (nullptr: it applies).
    using Condition = std::function<const char*(const Options& o)>;

    OperationDecl(std::string name, std::string label, std::string summary) {
        def_.name = std::move(name);
        def_.label = std::move(label);
        def_.summary = std::move(summary);
    }

    /// A real number in [min, max]; `unit` is appended to the range in messages.
    template <class Field>
    OperationDecl& number(std::string name, Field field, double min, double max, std::string help,
                          std::string unit = "") {
        ParamSpec s = spec(std::move(name), ParamKind::Number, std::move(help));
        s.min = min;
        s.max = max;
        s.unit = std::move(unit);
        return add(std::move(s), field);
    }
    /// A whole number in [min, max].
    template <class Field>
    OperationDecl& integer(std::string name, Field field, double min, double max,
                           std::string help) {
        ParamSpec s = spec(std::move(name), ParamKind::Integer, std::move(help));
        s.min = min;
        s.max = max;
        return add(std::move(s), field);
    }
    /// A flag (a bool field): given means true.
    template <class Field>
    OperationDecl& flag(std::string name, Field field, std::string help) {
        return add(spec(std::move(name), ParamKind::Flag, std::move(help)), field);
    }
    /// One value of an enum, by the enum's table (core/enum_table.h).
    template <class E, class Field>
    OperationDecl& choice(std::string name, Field field, EnumTableView<E> table, std::string help) {
        ParamSpec s = spec(std::move(name), ParamKind::Choice, std::move(help));
        s.choices = detail::choice_items(table);
        return add(std::move(s), field);
    }
    /// A number that can be switched off with `off_word`: binds a bool and a number.
    template <class OnField, class ValueField>
    OperationDecl& switchable(std::string name, OnField on_field, ValueField value_field,
                              double min, double max, std::string off_word, std::string help,
                              std::string unit = "") {
        ParamSpec s = spec(std::move(name), ParamKind::Switchable, std::move(help));
        s.min = min;
        s.max = max;
        s.off_word = std::move(off_word);
        s.unit = std::move(unit);
        auto on = accessor(on_field);
        auto value = accessor(value_field);
        Binding b;
        b.load = [on, value](const Options& o, ParamValue& v) {
            v.on = on(const_cast<Options&>(o));
            v.x = double(value(const_cast<Options&>(o)));
        };
        b.store = [on, value](const ParamValue& v, Options& o) {
            on(o) = v.on;
            if (v.on) value(o) = v.x;
        };
        return push(std::move(s), std::move(b));
    }
    /// A range "LO:HI" of whole numbers in [min, max] (an optional pair field).
    template <class Field>
    OperationDecl& range(std::string name, Field field, double min, double max, std::string help) {
        ParamSpec s = spec(std::move(name), ParamKind::Range, std::move(help));
        s.min = min;
        s.max = max;
        s.optional = true;
        return add(std::move(s), field);
    }

    // Modifiers of the last parameter declared.
    /// The panel's label (default: the name with spaces for dashes).
    OperationDecl& label(std::string text) {
        last().label = std::move(text);
        return *this;
    }
    /// The panel's slider span, and whether it is logarithmic.
    OperationDecl& slider(double ui_min, double ui_max, bool logarithmic = false) {
        last().ui_min = ui_min;
        last().ui_max = ui_max;
        last().logarithmic = logarithmic;
        return *this;
    }
    /// The minimum itself is refused.
    OperationDecl& above_min() {
        last().min_exclusive = true;
        return *this;
    }
    /// Left out of the canonical text while at its default (an "off" value such as 0).
    OperationDecl& hide_default() {
        last().hide_default = true;
        return *this;
    }
    /// Its value is the number of steps a run gives, one per iteration (the viewer shows a
    /// computed preview's earlier steps when only this value changes).
    OperationDecl& counts_steps() {
        last().counts_steps = true;
        return *this;
    }
    /// --help's default where it is not one value.
    /// Keeps the last parameter out of the generic panel widgets (ParamSpec::cli_only).
    OperationDecl& cli_only() {
        last().cli_only = true;
        return *this;
    }
    OperationDecl& default_note(std::string text) {
        last().default_note = std::move(text);
        return *this;
    }
    /// The parameter applies only where `condition` returns nullptr.
    OperationDecl& only_if(Condition condition) {
        conditions_.back() = std::move(condition);
        return *this;
    }
    /// A test over the whole options struct, run after parsing (throw InvalidArgument naming
    /// the option). `given(name)` says whether an option was named explicitly.
    OperationDecl& check(
        std::function<void(const Options&, const std::function<bool(const char*)>& given)> f) {
        check_ = std::move(f);
        return *this;
    }
    OperationDecl& run(Runner runner) {
        runner_ = std::move(runner);
        return *this;
    }
    /// The run honours RunSettings::region; `help` says how (one line for --help).
    OperationDecl& acts_on_region(std::string help) {
        def_.takes_region = true;
        def_.region_help = std::move(help);
        return *this;
    }
    /// The run may stop before its last iteration (OperationResult::stopped_early): the CLI
    /// offers --keep-partial for it.
    OperationDecl& may_stop_early() {
        def_.may_stop_early = true;
        return *this;
    }

    /// The declaration as the registry holds it.
    std::unique_ptr<OperationDef> build() const {
        auto def = std::make_unique<OperationDef>(def_);
        def->options_type = &typeid(Options);
        auto bindings = bindings_;
        const auto from_options = [bindings](const Options& o) {
            ParamValues values(bindings.size());
            for (std::size_t i = 0; i < bindings.size(); ++i) bindings[i].load(o, values[i]);
            return values;
        };
        def->defaults = from_options(Options{});
        def->from_options = [from_options](const std::any& options) {
            return from_options(std::any_cast<const Options&>(options));
        };
        auto to_options = [bindings](const ParamValues& values) {
            Options o{};
            for (std::size_t i = 0; i < bindings.size() && i < values.size(); ++i)
                bindings[i].store(values[i], o);
            return o;
        };
        def->options = [to_options](const ParamValues& values) {
            return std::any(to_options(values));
        };
        auto conditions = conditions_;
        def->why_not = [conditions, to_options](const ParamValues& values,
                                                std::size_t i) -> const char* {
            if (i >= conditions.size() || !conditions[i]) return nullptr;
            return conditions[i](to_options(values));
        };
        const OperationDef* self = def.get();
        auto check = check_;
        def->check = [check, to_options, self](const ParamValues& values) {
            if (!check) return;
            check(to_options(values),
                  [&](const char* name) { return values[self->index(name)].given; });
        };
        auto runner = runner_;
        def->run = [runner, to_options](const ParamValues& values, const HalfedgeMesh& mesh,
                                        Progress& progress, const RunSettings& settings) {
            return runner(to_options(values), mesh, progress, settings);
        };
        return def;
    }

private:
    struct Binding {
        std::function<void(const Options&, ParamValue&)> load;
        std::function<void(const ParamValue&, Options&)> store;
    };

    static ParamSpec spec(std::string name, ParamKind kind, std::string help) {
        ParamSpec s;
        s.label = name;
        for (char& c : s.label)
            if (c == '-') c = ' ';
        s.name = std::move(name);
        s.kind = kind;
        s.help = std::move(help);
        return s;
    }
    /// A member pointer or a lambda returning a reference, as a lambda.
    template <class Field>
    static auto accessor(Field field) {
        if constexpr (std::is_member_object_pointer_v<Field>) return [field](Options & o) -> auto& {
                return o.*field;
            };
        else
            return field;
    }
    template <class Field>
    OperationDecl& add(ParamSpec s, Field field) {
        auto get = accessor(field);
        using T = std::decay_t<decltype(get(std::declval<Options&>()))>;
        if constexpr (std::is_same_v<T, bool>) {
            if (s.kind != ParamKind::Flag && s.kind != ParamKind::Choice) s.kind = ParamKind::Flag;
        }
        Binding b;
        b.load = [get](const Options& o, ParamValue& v) {
            detail::ParamField<T>::load(get(const_cast<Options&>(o)), v);
        };
        b.store = [get](const ParamValue& v, Options& o) {
            detail::ParamField<T>::store(v, get(o));
        };
        if constexpr (!std::is_same_v<T, bool> && !std::is_enum_v<T> && !std::is_arithmetic_v<T>)
            s.optional = true;
        return push(std::move(s), std::move(b));
    }
    OperationDecl& push(ParamSpec s, Binding b) {
        def_.params.push_back(std::move(s));
        bindings_.push_back(std::move(b));
        conditions_.emplace_back();
        return *this;
    }
    ParamSpec& last() { return def_.params.back(); }

    OperationDef def_;
    std::vector<Binding> bindings_;
    std::vector<Condition> conditions_;
    std::function<void(const Options&, const std::function<bool(const char*)>&)> check_;
    Runner runner_;
};

/// Milliseconds since `t0`.
double ms_since(std::chrono::steady_clock::time_point t0);

}  // namespace trilab
