#include "app/commands.hpp"

namespace flotsam {
void register_pipeline_commands(CLI::App&, const std::string&) {}
}  // namespace flotsam
