// Command-line options from a settings table (common/settings.hpp): `--key VALUE` for a
// number (checked against its range, the help shows unit and range), a text or a choice
// (by name), `--key a,b,c` for a list of numbers, `--key VALUE` repeated for a list of
// texts, `--key` / `--no-key` for a switch. The options write straight into the
// definition struct, whose initialisers are the defaults shown by --help; the setting's
// OptionForm says where an option differs from that (its --help section, required, a
// path that must exist, no default shown, a fixed number of values).
#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "app/commands.hpp"
#include "common/settings.hpp"

namespace flotsam {

namespace detail {

// The help line: the setting's help and its unit, unless the help already shows it
// ("[m]", "[m, in the scene's CRS]", "[m above still water]").
template <class Def>
std::string option_help(const Setting<Def>& s) {
    if (s.unit.empty() || s.unit == "1") return s.help;
    for (const char* end : {"]", ",", " "})
        if (s.help.find("[" + s.unit + end) != std::string::npos) return s.help;
    return s.help + " [" + s.unit + "]";
}

// The option of a member that holds a value (a number, a text or a list of them).
template <class Def, class T>
CLI::Option* add_value_option(CLI::App* sub, const Setting<Def>& s, const Field<Def, T>& field, Def& def) {
    CLI::Option* opt = sub->add_option("--" + s.key, field.of(def), option_help(s));
    const OptionForm& f = s.form;
    constexpr bool list = !std::is_same_v<T, std::string> && !std::is_arithmetic_v<T> && !std::is_same_v<T, std::optional<double>>;
    constexpr bool numbers = !std::is_same_v<T, std::string> && !std::is_same_v<T, std::vector<std::string>>;
    if (f.items > 0) opt->expected(f.items);
    if constexpr (list && numbers) opt->delimiter(',');
    if (!f.no_default) opt->capture_default_str();
    if (f.required) opt->required();
    if (f.existing_file) opt->check(CLI::ExistingFile);
    if constexpr (numbers)
        if (!f.unchecked) opt->check(in_range(s.range));
    return opt;
}

}  // namespace detail

template <class Def>
void add_setting_options(CLI::App* sub, const Settings<Def>& table, Def& def) {
    for (const Setting<Def>& s : table) {
        const std::string name = "--" + s.key;
        CLI::Option* opt = nullptr;
        if (const auto b = s.template field<bool>()) {
            if (s.form.no_default)  // a plain flag: given or not
                opt = sub->add_flag(name, b->of(def), s.help);
            else
                opt = sub->add_flag(name + ",!--no-" + s.key, b->of(def), s.help)->capture_default_str();
        } else if (s.is_choice()) {
            const Choice<Def> c = s.choice();
            Def* d = &def;
            const bool listed = s.form.names_in_type || s.form.names_in_help;
            opt = sub->add_option_function<std::string>(
                         name, [c, d, name](const std::string& v) { c.set(*d, v, name); },
                         listed ? s.help : s.help + " (" + c.names() + ")")
                      ->run_callback_for_default();  // as an option bound to a variable: `key=""` in settings dumps
            if (s.form.names_in_type) {
                std::vector<std::string> names;
                const std::string all = c.names();
                for (std::size_t a = 0, e; a < all.size(); a = e + 2) {
                    e = std::min(all.find(", ", a), all.size());
                    names.push_back(all.substr(a, e - a));
                }
                opt->check(CLI::IsMember(names));
            }
            if (!s.form.no_default) opt->default_str(c.get(def));
        } else if (s.is_factor()) {
            continue;  // a design parameter of sweeps, not an option
        } else {
            std::visit(
                [&](const auto& m) {
                    using M = std::decay_t<decltype(m)>;
                    if constexpr (!std::is_same_v<M, Choice<Def>> && !std::is_same_v<M, Factor<Def>> &&
                                  !std::is_same_v<M, Field<Def, bool>>)
                        opt = detail::add_value_option(sub, s, m, def);
                },
                s.member);
        }
        if (!s.form.group.empty()) opt->group(s.form.group);
    }
}

}  // namespace flotsam
