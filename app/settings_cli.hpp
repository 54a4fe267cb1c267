// Command-line options from a settings table (common/settings.hpp): `--key VALUE` for a
// number (checked against its range, the help shows unit and range) or a choice (by
// name), `--key` / `--no-key` for a switch. The options write straight into the
// definition struct, whose initialisers are the defaults shown by --help.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <variant>

#include "app/commands.hpp"
#include "common/settings.hpp"

namespace flotsam {

template <class Def>
void add_setting_options(CLI::App* sub, const Settings<Def>& table, Def& def) {
    for (const Setting<Def>& s : table) {
        const std::string name = "--" + s.key;
        const std::string unit = s.unit.empty() || s.unit == "1" ? "" : " [" + s.unit + "]";
        if (const auto m = std::get_if<double Def::*>(&s.member)) {
            sub->add_option(name, def.**m, s.help + unit)->capture_default_str()->check(in_range(s.range));
        } else if (const auto n = std::get_if<int Def::*>(&s.member)) {
            sub->add_option(name, def.**n, s.help + unit)->capture_default_str()->check(in_range(s.range));
        } else if (const auto b = std::get_if<bool Def::*>(&s.member)) {
            sub->add_flag(name + ",!--no-" + s.key, def.**b, s.help)->capture_default_str();
        } else if (s.is_choice()) {
            const Choice<Def> c = s.choice();
            Def* d = &def;
            sub->add_option_function<std::string>(
                   name, [c, d, name](const std::string& v) { c.set(*d, v, name); }, s.help + " (" + c.names() + ")")
                ->default_str(c.get(def));
        }
        // A Factor is a design parameter of sweeps, not an option.
    }
}

}  // namespace flotsam
