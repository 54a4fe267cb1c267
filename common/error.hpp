// Errors that reach the user. Every message names the file (or option), the variable
// or line, and what is wrong, so a user can fix the input without reading code.
#pragma once
#include <stdexcept>
#include <string>

namespace flotsam {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// "file: what: problem" with empty parts left out.
std::string where(const std::string& file, const std::string& what);

[[noreturn]] void fail(const std::string& file, const std::string& what, const std::string& problem);

}  // namespace flotsam
