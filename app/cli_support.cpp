#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/toml_lite.hpp"

namespace flotsam {

std::string join_command_line(int argc, char** argv, const std::vector<DroppedOption>& drop) {
    std::string s;
    for (int k = 0; k < argc; ++k) {
        std::string a = argv[k];
        bool dropped = false;
        for (const auto& d : drop) {
            if (a == "--" + d.name) {
                dropped = true;
                if (d.takes_value) ++k;
            } else if (a.rfind("--" + d.name + "=", 0) == 0) {
                dropped = true;
            }
        }
        if (dropped) continue;
        if (!s.empty()) s += ' ';
        const bool quote = a.empty() || a.find_first_of(" \t\"'$") != std::string::npos;
        s += quote ? "'" + a + "'" : a;
    }
    return s;
}

const std::vector<DroppedOption>& hydro_run_control_options() {
    static const std::vector<DroppedOption> options = {
        {"out", true},        {"restart", false},           {"threads", true}, {"quiet", false}, {"label", true},
        {"stop-after", true}, {"checkpoint-interval", true}, {"allow-large-run", false},
        {"boundary-output", true}, {"boundary-box", true}, {"boundary-interval", true}};
    return options;
}

CLI::Validator in_range(const Range& r) {
    return CLI::Validator(
        [r](std::string& text) -> std::string {
            const char* b = text.c_str();
            char* e = nullptr;
            const double v = std::strtod(b, &e);
            if (e == b || *e != '\0') return "'" + text + "' is not a number";
            // Decimal only: strtod also reads hexadecimal ("0x10" is 16), which nobody
            // means in a setting.
            if (text.find_first_of("xXpP") != std::string::npos)
                return "'" + text + "' is not a decimal number (write 16, not 0x10)";
            return range_problem(v, r);
        },
        describe(r), "range");
}

void add_config_option(CLI::App* sub) {
    // Read by expand_config_files() before parsing: CLI11 2.1 only reads config files
    // for the top-level app, so a subcommand's file is turned into arguments instead.
    sub->add_option("--config",
                    "TOML file of settings: keys are the long option names (output-interval = 0.5), "
                    "optionally under a [section] named after the command; unknown keys are an error");
}

namespace {

// Every subcommand name under `app` ("hydro", "scene", "generate", ...).
void command_names(const CLI::App* app, std::set<std::string>& out) {
    for (const CLI::App* sub : app->get_subcommands([](const CLI::App*) { return true; })) {
        out.insert(sub->get_name());
        command_names(sub, out);
    }
}

// Runs the option's own checks (in_range and the like) on one value from a settings file.
void check_setting(CLI::Option* opt, const std::string& path, const std::string& what, const std::string& value) {
    std::vector<std::string> parts;
    const char delimiter = opt->get_delimiter();
    if (delimiter != '\0') {
        std::string part;
        for (char c : value) {
            if (c == delimiter) {
                parts.push_back(part);
                part.clear();
            } else {
                part += c;
            }
        }
        parts.push_back(part);
    } else {
        parts.push_back(value);
    }
    for (int k = 0;; ++k) {
        CLI::Validator* check = nullptr;
        try {
            check = opt->get_validator(k);
        } catch (const CLI::OptionNotFound&) {
            return;
        }
        for (std::string p : parts) {
            const std::string problem = (*check)(p);
            if (!problem.empty()) fail(path, what, problem);
        }
    }
}

bool on_command_line(const std::vector<std::string>& args, std::size_t from, const std::string& name) {
    for (std::size_t k = from; k < args.size(); ++k)
        if (args[k] == "--" + name || args[k].rfind("--" + name + "=", 0) == 0) return true;
    return false;
}

}  // namespace

std::vector<std::string> expand_config_files(CLI::App& app, int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    // The subcommand chain named at the front of the arguments.
    CLI::App* sub = &app;
    std::size_t k = 0;
    std::vector<std::string> chain;
    while (k < args.size()) {
        CLI::App* next = nullptr;
        try {
            next = sub->get_subcommand(args[k]);
        } catch (const CLI::OptionNotFound&) {
            break;
        }
        sub = next;
        chain.push_back(args[k]);
        ++k;
    }
    if (sub == &app) return args;
    const std::size_t first_option = k;
    std::string path;
    std::vector<std::string> rest;
    for (std::size_t a = first_option; a < args.size(); ++a) {
        if (args[a] == "--config" && a + 1 < args.size()) {
            path = args[++a];
        } else if (args[a].rfind("--config=", 0) == 0) {
            path = args[a].substr(9);
        } else {
            rest.push_back(args[a]);
        }
    }
    if (path.empty()) return args;
    const TomlDoc doc = read_toml_lite(path);
    std::string command, section;
    for (const auto& c : chain) {
        command += (command.empty() ? "" : " ") + c;
        section += (section.empty() ? "" : ".") + c;
    }
    std::vector<std::string> out(args.begin(), args.begin() + std::ptrdiff_t(first_option));
    std::vector<std::string> from_file;
    std::set<std::string> commands;
    command_names(&app, commands);
    for (const TomlTable& t : doc.tables) {
        // A section must name a command: [hydor] is a typo, not another command's settings.
        for (std::size_t a = 0, b; a < t.name.size(); a = b + 1) {
            b = std::min(t.name.find('.', a), t.name.size());
            const std::string part = t.name.substr(a, b - a);
            if (commands.count(part)) continue;
            std::string known;
            for (const auto& c : commands) known += (known.empty() ? "" : ", ") + c;
            fail(path, "section [" + t.name + "]", "'" + part + "' is not a flotsam command (sections: " + known + ")");
        }
        // Keys may sit at the top level or under a section named after the command
        // ([hydro], or [scene.generate] / [generate]); another command's section is fine
        // in a shared file.
        if (!t.name.empty() && t.name != section && t.name != chain.back()) continue;
        for (const auto& [key, v] : t.values) {
            CLI::Option* opt = key == "config" || key == "help" ? nullptr : sub->get_option_no_throw("--" + key);
            if (!opt && sub->get_option_no_throw("--" + kebab_case(key)))
                toml_fail(doc, t, key,
                          "is the old spelling: keys are kebab-case, as the command-line options; write '" + kebab_case(key) + "'");
            if (!opt) toml_fail(doc, t, key, "is not a setting of 'flotsam " + command + "' (see --help)");
            if (on_command_line(rest, 0, key)) continue;  // the command line wins
            if (opt->get_expected_max() == 0) {           // a flag (CLI11 gives flags a type size of 1)
                if (v.kind != TomlValue::Kind::Bool) toml_fail(doc, t, key, "a flag takes true or false, not " + v.raw);
                from_file.push_back("--" + key + "=" + v.raw);
                continue;
            }
            std::vector<std::string> values;
            if (v.kind == TomlValue::Kind::String)
                values = {v.text};
            else if (v.kind == TomlValue::Kind::NumberArray || v.kind == TomlValue::Kind::StringArray)
                values = v.items;
            else
                values = {v.raw};
            if (values.empty() || (values.size() == 1 && values[0].empty())) continue;  // "" or []: not set
            if (values.size() > 1 && opt->get_items_expected_max() == 1)
                toml_fail(doc, t, key, "takes one value, the file gives an array of " + std::to_string(values.size()));
            for (const auto& value : values) check_setting(opt, path, "key '" + key + "'", value);
            from_file.push_back("--" + key);
            from_file.insert(from_file.end(), values.begin(), values.end());
        }
    }
    out.insert(out.end(), from_file.begin(), from_file.end());
    out.insert(out.end(), rest.begin(), rest.end());
    return out;
}

}  // namespace flotsam

namespace flotsam {

std::string apply_scene_hydro_defaults(CLI::App* sub, const std::string& scene_path) {
    const nc::File f = nc::File::open_read(scene_path);
    cf::require_kind(f, {"scene"}, "--scene");
    const std::string text = f.att_text(NC_GLOBAL, "flotsam_hydro_defaults").value_or("");
    std::string applied;
    std::istringstream in(text);
    // The leap-frog runs on one grid: a scene's recommended nesting is for finite volumes.
    const CLI::Option* scheme = sub->get_option_no_throw("--scheme");
    const bool one_grid = scheme && scheme->count() > 0 && scheme->as<std::string>() == "leapfrog";
    for (std::string line; std::getline(in, line);) {
        const auto eq = line.find(" = ");
        if (eq == std::string::npos) fail(scene_path, "attribute 'flotsam_hydro_defaults'", "bad line '" + line + "'");
        const std::string key = line.substr(0, eq), value = line.substr(eq + 3);
        CLI::Option* opt = sub->get_option_no_throw("--" + key);
        if (!opt) fail(scene_path, "attribute 'flotsam_hydro_defaults'", "names an unknown hydro option '" + key + "'");
        if (opt->count() > 0) continue;  // the command line (or --config) wins
        if (one_grid && key.rfind("nest-", 0) == 0) continue;
        // The scene's value goes through the option's own checks, and a failure names the
        // scene and its attribute, not an option the user never gave.
        const std::string here = "attribute 'flotsam_hydro_defaults', line '" + line + "'";
        check_setting(opt, scene_path, here, value);
        try {
            opt->add_result(value);
            opt->run_callback();
        } catch (const CLI::Error& e) {
            fail(scene_path, here, std::string(e.what()) + " (a setting the scene recommends; give --" + key + " to override it)");
        }
        applied += (applied.empty() ? "" : ", ") + key + " = " + value;
    }
    return applied;
}

}  // namespace flotsam
