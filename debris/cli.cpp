#include "app/commands.hpp"

namespace flotsam {
void register_debris_commands(CLI::App&, const std::string&) {}
}  // namespace flotsam
