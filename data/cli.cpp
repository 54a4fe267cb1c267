#include "app/commands.hpp"

namespace flotsam {
void register_data_commands(CLI::App&, const std::string&) {}
}  // namespace flotsam
