#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"

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
        {"stop-after", true}, {"checkpoint-interval", true}};
    return options;
}

void add_config_option(CLI::App* sub) {
    // Read by expand_config_files() before parsing: CLI11 2.1 only reads config files
    // for the top-level app, so a subcommand's file is turned into arguments instead.
    sub->add_option("--config",
                    "TOML file of settings: keys are the long option names (duration = 420), "
                    "optionally under a [section] named after the command; unknown keys are an error");
}

namespace {

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
    if (!std::ifstream(path)) fail(path, "", "cannot open the settings file");
    std::vector<CLI::ConfigItem> items;
    try {
        items = CLI::ConfigTOML().from_file(path);
    } catch (const CLI::Error& e) {
        fail(path, "", std::string("not a valid TOML settings file: ") + e.what());
    }
    std::vector<std::string> out(args.begin(), args.begin() + std::ptrdiff_t(first_option));
    std::vector<std::string> from_file;
    for (const auto& item : items) {
        if (item.name == "++" || item.name == "--") continue;  // section markers
        // Keys may sit at the top level or under a section named after the command
        // ([hydro], or [scene.generate] / [generate]).
        bool ours = item.parents.empty();
        if (!ours) {
            ours = item.parents == chain || (item.parents.size() == 1 && item.parents[0] == chain.back());
            if (!ours) continue;  // a section for another command: fine in a shared file
        }
        const CLI::Option* opt = sub->get_option_no_throw("--" + item.name);
        if (!opt || item.name == "config" || item.name == "help")
            fail(
                path, "key '" + item.name + "'", "is not a setting of 'flotsam " + [&] {
                    std::string c;
                    for (const auto& s : chain) c += (c.empty() ? "" : " ") + s;
                    return c;
                }() + "' (see --help)");
        if (on_command_line(rest, 0, item.name)) continue;  // the command line wins
        if (opt->get_type_size() == 0) {                    // a flag
            const std::string v = item.inputs.empty() ? "true" : item.inputs.front();
            if (v == "true" || v == "1")
                from_file.push_back("--" + item.name);
            else if (v != "false" && v != "0")
                fail(path, "key '" + item.name + "'", "a flag takes true or false, not '" + v + "'");
            continue;
        }
        from_file.push_back("--" + item.name);
        for (const auto& v : item.inputs) from_file.push_back(v);
    }
    out.insert(out.end(), from_file.begin(), from_file.end());
    out.insert(out.end(), rest.begin(), rest.end());
    return out;
}

}  // namespace flotsam

namespace flotsam {

std::string apply_scene_hydro_defaults(CLI::App* sub, const std::string& scene_path) {
    const nc::File f = nc::File::open_read(scene_path);
    const std::string text = f.att_text(NC_GLOBAL, "flotsam_hydro_defaults").value_or("");
    std::string applied;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        const auto eq = line.find(" = ");
        if (eq == std::string::npos) fail(scene_path, "attribute 'flotsam_hydro_defaults'", "bad line '" + line + "'");
        const std::string key = line.substr(0, eq), value = line.substr(eq + 3);
        CLI::Option* opt = sub->get_option_no_throw("--" + key);
        if (!opt) fail(scene_path, "attribute 'flotsam_hydro_defaults'", "names an unknown hydro option '" + key + "'");
        if (opt->count() > 0) continue;  // the command line (or --config) wins
        opt->add_result(value);
        opt->run_callback();
        applied += (applied.empty() ? "" : ", ") + key + " = " + value;
    }
    return applied;
}

}  // namespace flotsam
