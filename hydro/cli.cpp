#include "app/commands.hpp"

namespace flotsam {
void register_hydro_commands(CLI::App&, const std::string&) {}
}  // namespace flotsam
