// Names of enum values, written once per enum: one table gives how a value is written
// (in files, help texts, recorded settings) and which spellings are read back (options,
// settings files, sweep specs). Each enum declares its table next to itself and a
// one-line `enum_names(E)` that returns it; everything else is generic:
//
//     enum class Scheme { finite_volume, leapfrog };
//     inline constexpr EnumNames<Scheme, 2> scheme_names{
//         "scheme", {{{Scheme::finite_volume, "fv"}, {Scheme::leapfrog, "leapfrog"}}}};
//     constexpr const auto& enum_names(Scheme) { return scheme_names; }
//
//     enum_name(Scheme::leapfrog)              // "leapfrog"
//     parse_enum<Scheme>("fv", "--scheme")     // Scheme::finite_volume
//     parse_enum<Scheme>("fw", "--scheme")     // Error "--scheme: unknown scheme 'fw' (fv, leapfrog)"
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "common/error.hpp"

namespace flotsam {

template <class E>
struct EnumName {
    E value;
    const char* name;
};

// The first name listed for a value is how it is written; later ones for the same value
// are other accepted spellings ("centre", "CC").
template <class E, std::size_t N>
struct EnumNames {
    const char* what;  // what the values are, for messages: "boundary", "contact model"
    std::array<EnumName<E>, N> names;

    constexpr const char* name_of(E v) const {
        for (const auto& n : names)
            if (n.value == v) return n.name;
        return "?";
    }
    // "a, b, c": each value's written name, in table order.
    std::string list() const {
        std::string out;
        for (std::size_t k = 0; k < N; ++k)
            if (name_of(names[k].value) == names[k].name) out += (out.empty() ? "" : ", ") + std::string(names[k].name);
        return out;
    }
    // Throws "<option>: unknown <what> '<text>' (a, b, c)".
    E parse(std::string_view text, const std::string& option) const {
        for (const auto& n : names)
            if (text == n.name) return n.value;
        fail("", option, "unknown " + std::string(what) + " '" + std::string(text) + "' (" + list() + ")");
    }
};

// Generic access through the enum's `enum_names(E)` (found by argument-dependent lookup).
template <class E>
const char* enum_name(E v) {
    return enum_names(v).name_of(v);
}
template <class E>
E parse_enum(std::string_view text, const std::string& option) {
    return enum_names(E{}).parse(text, option);
}
template <class E>
std::string enum_list() {
    return enum_names(E{}).list();
}

}  // namespace flotsam
