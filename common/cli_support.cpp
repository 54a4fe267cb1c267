#include <string>

#include "app/commands.hpp"

namespace flotsam {

std::string join_command_line(int argc, char** argv) {
    std::string s;
    for (int k = 0; k < argc; ++k) {
        if (k) s += ' ';
        std::string a = argv[k];
        const bool quote = a.empty() || a.find_first_of(" \t\"'$") != std::string::npos;
        s += quote ? "'" + a + "'" : a;
    }
    return s;
}

void add_config_option(CLI::App* sub) {
    sub->set_config("--config", "", "TOML file of settings (keys are the long option names; unknown keys are an error)");
    sub->allow_config_extras(CLI::config_extras_mode::error);
}

}  // namespace flotsam
