#pragma once
// One table per enum: every value with the identifier that files, the CLI and history use
// ("curvature-flow") and the label the viewer shows ("Curvature flow"). Name and parse
// functions, the CLI's option parsing and help, and the panels' combo boxes all read the
// same table, so a value is spelled in exactly one place.
//
//   inline constexpr EnumEntry<Easing> kEasings[] = {{Easing::Linear, "linear", "Linear"}, ...};
//   enum_id(kEasings, Easing::Linear) == "linear";
//   parse_enum(kEasings, "linear", "easing") == Easing::Linear;  // throws InvalidArgument
#include <cstddef>
#include <string>

#include "core/errors.h"

namespace trilab {

template <class E>
struct EnumEntry {
    E value;
    const char* id;     ///< lower-case, dash-separated: the text form
    const char* label;  ///< for people: the viewer's combo boxes
};

/// The entries of a table as a plain range (a pointer and a count), so a table of any length
/// passes through non-template code.
template <class E>
struct EnumTableView {
    const EnumEntry<E>* first = nullptr;
    std::size_t count = 0;
    template <std::size_t N>
    constexpr EnumTableView(const EnumEntry<E> (&table)[N]) : first(table), count(N) {}
    const EnumEntry<E>* begin() const { return first; }
    const EnumEntry<E>* end() const { return first + count; }
};

/// The identifier of `value` (the first entry's when the value is not in the table).
template <class E>
const char* enum_id(EnumTableView<E> table, E value) {
    for (const EnumEntry<E>& e : table)
        if (e.value == value) return e.id;
    return table.first->id;
}

/// The label of `value`.
template <class E>
const char* enum_label(EnumTableView<E> table, E value) {
    for (const EnumEntry<E>& e : table)
        if (e.value == value) return e.label;
    return table.first->label;
}

/// "a, b or c": the identifiers, for messages and help texts.
template <class E>
std::string enum_ids(EnumTableView<E> table, const char* last_separator = " or ") {
    std::string s;
    for (std::size_t i = 0; i < table.count; ++i) {
        if (i > 0) s += i + 1 == table.count ? last_separator : ", ";
        s += table.first[i].id;
    }
    return s;
}

/// The value whose identifier is `id`; throws InvalidArgument naming `what` and the choices.
template <class E>
E parse_enum(EnumTableView<E> table, const std::string& id, const char* what) {
    for (const EnumEntry<E>& e : table)
        if (id == e.id) return e.value;
    throw InvalidArgument(std::string(what) + " '" + id + "' unknown: use " + enum_ids(table));
}

}  // namespace trilab
