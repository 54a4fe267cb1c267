#pragma once
#include <string>

namespace flotsam {
// "flotsam <version> (<git commit>)", fixed at configure time.
std::string version_string();
}  // namespace flotsam
