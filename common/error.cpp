#include "common/error.hpp"

namespace flotsam {

std::string where(const std::string& file, const std::string& what) {
    if (file.empty()) return what;
    if (what.empty()) return file;
    return file + ": " + what;
}

void fail(const std::string& file, const std::string& what, const std::string& problem) {
    const std::string w = where(file, what);
    throw Error(w.empty() ? problem : w + ": " + problem);
}

}  // namespace flotsam
