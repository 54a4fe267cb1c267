// One definition per setting, in one table per parameter family (the body's shape,
// coefficients and model in debris/body.hpp, the step and the flow replay in
// debris/world.hpp, a hydro run in hydro/run_settings.hpp, the data and sweep commands in
// app/): its key, the member of the definition struct it sets, its unit, a one-line help
// and its valid range. The default is the struct's own initialiser
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
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "common/checks.hpp"
#include "common/enum_names.hpp"
#include "common/toml_lite.hpp"

namespace flotsam {

// Where a setting lives in its definition struct: a member (&BodyDef::cd1), or a member
// of a member, reached by member_of<&RunDef::finite_volume, &FiniteVolumeDef::cfl>().
template <class Def, class T>
struct Field {
    T Def::*member = nullptr;
    T& (*reach)(Def&) = nullptr;  // a member of a member
    Field(T Def::*m) : member(m) {}
    Field(T& (*r)(Def&)) : reach(r) {}
    T& of(Def& d) const { return reach ? reach(d) : d.*member; }
    const T& of(const Def& d) const { return reach ? reach(const_cast<Def&>(d)) : d.*member; }
};

template <class T>
struct member_pointer_traits;
template <class C, class T>
struct member_pointer_traits<T C::*> {
    using owner = C;
    using type = T;
};
template <auto M, auto... Ms, class D>
auto& follow_members(D& d) {
    if constexpr (sizeof...(Ms) == 0)
        return d.*M;
    else
        return follow_members<Ms...>(d.*M);
}
// The member reached through a chain of members, as a function a Field holds.
template <auto M, auto... Ms>
auto member_of() {
    using Def = typename member_pointer_traits<decltype(M)>::owner;
    using T = std::remove_reference_t<decltype(follow_members<M, Ms...>(std::declval<Def&>()))>;
    return static_cast<T& (*)(Def&)>([](Def& d) -> T& { return follow_members<M, Ms...>(d); });
}

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

// How a setting shows as a command-line option where it differs from the usual (a value
// with its default and range check, in the command's own section of --help).
struct OptionForm {
    std::string group;           // the --help section; "": the command's options
    bool required = false;       // the command fails without it
    bool existing_file = false;  // a path that must name an existing file
    bool no_default = false;     // --help shows no default: the initial value means "not given"
    bool unchecked = false;      // a number taken as given, without a range check
    int items = 0;               // a list of exactly this many values (0: any number)
    bool names_in_type = false;  // a choice whose names show as the value's type, TEXT:{a,b}, not after the help
    bool names_in_help = false;  // a choice whose help names its values already
};

template <class Def>
struct Setting {
    using Member =
        std::variant<Field<Def, double>, Field<Def, int>, Field<Def, bool>, Choice<Def>, Factor<Def>, Field<Def, std::uint64_t>,
                     Field<Def, std::string>, Field<Def, std::vector<double>>, Field<Def, std::vector<int>>,
                     Field<Def, std::vector<std::string>>, Field<Def, std::optional<double>>>;
    std::string key;   // kebab-case: `--key` and `key = ...`
    std::string unit;  // UDUNITS; "1" a number without unit; "" a choice, a switch or a text
    std::string help;  // one line: the option's help and the long_name where files record it
    Range range;       // valid values of a number (of each number of a list)
    Member member;
    OptionForm form = {};

    template <class T>
    const Field<Def, T>* field() const {
        return std::get_if<Field<Def, T>>(&member);
    }
    bool is_switch() const { return field<bool>() != nullptr; }
    bool is_choice() const { return std::holds_alternative<Choice<Def>>(member); }
    bool is_factor() const { return std::holds_alternative<Factor<Def>>(member); }
    bool is_whole() const { return field<int>() || field<std::uint64_t>(); }
    bool is_number() const { return field<double>() || is_whole() || is_factor(); }
    bool is_optional() const { return field<std::optional<double>>() != nullptr; }  // a number, or none given
    bool is_text() const { return field<std::string>() != nullptr; }
    bool is_list() const { return field<std::vector<double>>() || field<std::vector<int>>() || field<std::vector<std::string>>(); }

    // The NetCDF variable and CSV column name: the key with '_' for '-'.
    std::string variable() const {
        std::string v = key;
        for (char& c : v)
            if (c == '-') c = '_';
        return v;
    }

    // A number's value in d (a factor, applied rather than held: 1).
    double number(const Def& d) const {
        if (const auto m = field<double>()) return m->of(d);
        if (const auto m = field<int>()) return double(m->of(d));
        if (const auto m = field<std::uint64_t>()) return double(m->of(d));
        return 1.0;
    }
    // Sets a number (a factor multiplies its members); the caller checks the range.
    void set_number(Def& d, double v) const {
        if (const auto m = field<double>()) m->of(d) = v;
        if (const auto m = field<int>()) m->of(d) = int(v);
        if (const auto m = field<std::uint64_t>()) m->of(d) = std::uint64_t(v);
        if (const auto f = std::get_if<Factor<Def>>(&member))
            for (double Def::*m : f->scales) d.*m *= v;
    }
    bool flag(const Def& d) const { return field<bool>()->of(d); }
    void set_flag(Def& d, bool v) const { field<bool>()->of(d) = v; }
    const Choice<Def>& choice() const { return std::get<Choice<Def>>(member); }

    // The value in d as a TOML value: 0.25, true, "local", [4, 1, 2]; a number as the
    // shortest text that reads back to it; a list of one value as that value, an empty
    // list or text as "" (which --config files read as not given).
    std::string text(const Def& d) const {
        if (is_switch()) return flag(d) ? "true" : "false";
        if (is_choice()) return std::string("\"") + choice().get(d) + "\"";
        if (const auto t = field<std::string>()) return "\"" + t->of(d) + "\"";
        if (const auto l = field<std::vector<std::string>>())
            return list_text(l->of(d), [](const std::string& v) { return "\"" + v + "\""; });
        if (const auto l = field<std::vector<double>>()) return list_text(l->of(d), number_text_exact);
        if (const auto l = field<std::vector<int>>()) return list_text(l->of(d), number_text_exact);
        if (const auto o = field<std::optional<double>>()) return o->of(d) ? number_text_exact(*o->of(d)) : "\"\"";
        return number_text_exact(number(d));
    }

private:
    static std::string number_text_exact(double v) {
        char buf[40];
        return std::string(buf, std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general).ptr);
    }
    template <class T, class Text>
    static std::string list_text(const std::vector<T>& values, Text text) {
        if (values.empty()) return "\"\"";
        if (values.size() == 1) return text(values[0]);
        std::string out = "[";
        for (std::size_t k = 0; k < values.size(); ++k) out += (k ? ", " : "") + text(values[k]);
        return out + "]";
    }
};

template <class Def>
using Settings = std::vector<Setting<Def>>;

// The Choice of an enum member: choice_of<&BodyDef::contact>(), or of a member of a
// member: choice_of<&PhysicsDef::west, &BoundaryDef::kind>().
template <auto M, auto... Ms>
Choice<typename member_pointer_traits<decltype(M)>::owner> choice_of() {
    using Def = typename member_pointer_traits<decltype(M)>::owner;
    using E = std::remove_cvref_t<decltype(follow_members<M, Ms...>(std::declval<Def&>()))>;
    return {
        [](const Def& d) { return enum_name(follow_members<M, Ms...>(const_cast<Def&>(d))); },
        [](Def& d, std::string_view name, const std::string& where) { follow_members<M, Ms...>(d) = parse_enum<E>(name, where); },
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

// The settings in d as TOML, one `key=value` line each (Setting::text): those of the
// command's own --help section first, then each other section's, in table order; keys in
// `leave_out` are not written. A `--config` file that sets d again.
template <class Def>
std::string settings_toml(const Settings<Def>& table, const Def& d, const std::vector<std::string>& leave_out = {}) {
    std::vector<std::string> groups{""};
    for (const auto& s : table)
        if (std::find(groups.begin(), groups.end(), s.form.group) == groups.end()) groups.push_back(s.form.group);
    std::string out;
    for (const auto& group : groups)
        for (const auto& s : table)
            if (s.form.group == group && !s.is_factor() && std::find(leave_out.begin(), leave_out.end(), s.key) == leave_out.end())
                out += s.key + "=" + s.text(d) + "\n";
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
    } else if (const auto text = s.template field<std::string>()) {
        text->of(d) = toml_string(doc, t, s.key);
    } else if (s.is_list() || s.is_optional()) {
        toml_fail(doc, t, s.key, "is not a setting this file can give");
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
