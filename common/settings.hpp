// One definition per setting, in one table per parameter family (the body's shape,
// coefficients and model in debris/body.hpp, the step and the flow replay in
// debris/world.hpp): its key, the member of the definition struct it sets, its unit, a
// one-line help and its valid range. The default is the struct's own initialiser
// (Box2D's b2BodyDef style), read from a default-constructed struct. The command line
// (app/settings_cli.hpp), the TOML readers (`--config` files and sweep specs) and the
// writers that record settings in files all take them from the table, so a setting is
// named, documented, checked and recorded in one place.
//
// Keys are kebab-case, spelled as the command-line option without `--`: `--dt-max 0.01`
// on the command line is `dt-max = 0.01` in every TOML file (docs/sweep.md says why).
// NetCDF variables and CSV columns use the same name with '_' (`dt_max`), as NetCDF
// names do.
#pragma once
#include <cstdio>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "common/checks.hpp"
#include "common/enum_names.hpp"
#include "common/toml_lite.hpp"

namespace flotsam {

// A member that holds one of an enum's values (common/enum_names.hpp).
template <class Def>
struct Choice {
    const char* (*get)(const Def&);                                      // the value's name
    void (*set)(Def&, std::string_view name, const std::string& where);  // throws naming `where` on an unknown name
    std::string (*names)();                                              // "a, b, c"
};

// A number that is held by no member but multiplies some (1 leaves them as they are):
// the drag factor Cd of a sweep design scales cd1 and cd2 together.
template <class Def>
struct Factor {
    std::vector<double Def::*> scales;
};

template <class Def>
struct Setting {
    std::string key;   // kebab-case: `--key` and `key = ...`
    std::string unit;  // UDUNITS; "1" a number without unit; "" a choice or a switch
    std::string help;  // one line: the option's help and the long_name where files record it
    Range range;       // valid values of a number
    std::variant<double Def::*, int Def::*, bool Def::*, Choice<Def>, Factor<Def>> member;

    bool is_number() const { return !is_switch() && !is_choice(); }
    bool is_switch() const { return std::holds_alternative<bool Def::*>(member); }
    bool is_choice() const { return std::holds_alternative<Choice<Def>>(member); }
    bool is_factor() const { return std::holds_alternative<Factor<Def>>(member); }
    bool is_whole() const { return std::holds_alternative<int Def::*>(member); }

    // The NetCDF variable and CSV column name: the key with '_' for '-'.
    std::string variable() const {
        std::string v = key;
        for (char& c : v)
            if (c == '-') c = '_';
        return v;
    }

    // A number's value in d (a factor, applied rather than held: 1).
    double number(const Def& d) const {
        if (const auto m = std::get_if<double Def::*>(&member)) return d.**m;
        if (const auto m = std::get_if<int Def::*>(&member)) return double(d.**m);
        return 1.0;
    }
    // Sets a number (a factor multiplies its members); the caller checks the range.
    void set_number(Def& d, double v) const {
        if (const auto m = std::get_if<double Def::*>(&member)) d.** m = v;
        if (const auto m = std::get_if<int Def::*>(&member)) d.** m = int(v);
        if (const auto f = std::get_if<Factor<Def>>(&member))
            for (double Def::*m : f->scales) d.*m *= v;
    }
    bool flag(const Def& d) const { return d.*std::get<bool Def::*>(member); }
    void set_flag(Def& d, bool v) const { d.*std::get<bool Def::*>(member) = v; }
    const Choice<Def>& choice() const { return std::get<Choice<Def>>(member); }

    // The value in d as a TOML value would be written: 0.25, true, "local".
    std::string text(const Def& d) const {
        if (is_switch()) return flag(d) ? "true" : "false";
        if (is_choice()) return std::string("\"") + choice().get(d) + "\"";
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.10g", number(d));
        return buf;
    }
};

template <class Def>
using Settings = std::vector<Setting<Def>>;

// The Choice of an enum member: choice_of<&BodyDef::contact>().
template <class T>
struct member_pointer_traits;
template <class C, class T>
struct member_pointer_traits<T C::*> {
    using owner = C;
    using type = T;
};
template <auto M>
Choice<typename member_pointer_traits<decltype(M)>::owner> choice_of() {
    using Def = typename member_pointer_traits<decltype(M)>::owner;
    using E = typename member_pointer_traits<decltype(M)>::type;
    return {[](const Def& d) { return enum_name(d.*M); },
            [](Def& d, std::string_view name, const std::string& where) { d.*M = parse_enum<E>(name, where); },
            [] { return enum_list<E>(); }};
}

// The setting with this key; nullptr when none.
template <class Def>
const Setting<Def>* find_setting(const Settings<Def>& table, std::string_view key) {
    for (const auto& s : table)
        if (s.key == key) return &s;
    return nullptr;
}

template <class Def>
std::vector<std::string> setting_keys(const Settings<Def>& table) {
    std::vector<std::string> out;
    for (const auto& s : table) out.push_back(s.key);
    return out;
}

// An enum value by name from a TOML string (common/enum_names.hpp); an unknown name is
// an error naming the file, line, key and the known names.
template <class E>
E toml_enum(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    const std::string name = toml_string(doc, t, key);
    try {
        return parse_enum<E>(name, key);
    } catch (const Error&) {
        toml_fail(doc, t, key, "unknown value '" + name + "' (" + enum_list<E>() + ")");
    }
}

// Sets d from the TOML value of one setting: a number checked against its range, a
// switch from true/false, a choice by name; errors name the file, line and key.
template <class Def>
void read_setting(const TomlDoc& doc, const TomlTable& t, const Setting<Def>& s, Def& d) {
    if (s.is_switch()) {
        s.set_flag(d, toml_bool(doc, t, s.key));
    } else if (s.is_choice()) {
        const std::string name = toml_string(doc, t, s.key);
        try {
            s.choice().set(d, name, "");
        } catch (const Error&) {
            toml_fail(doc, t, s.key, "unknown value '" + name + "' (" + s.choice().names() + ")");
        }
    } else {
        const double v = toml_number(doc, t, s.key);
        const std::string problem = range_problem(v, s.range);
        if (!problem.empty()) toml_fail(doc, t, s.key, problem);
        s.set_number(d, v);
    }
}

// Every setting of `table` that the TOML table holds, read into d. Keys that are no
// setting are the caller's (toml_allow_only).
template <class Def>
void read_settings(const TomlDoc& doc, const TomlTable& t, const Settings<Def>& table, Def& d) {
    for (const auto& s : table)
        if (t.values.count(s.key)) read_setting(doc, t, s, d);
}

}  // namespace flotsam
