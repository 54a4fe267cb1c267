// Text for CSV tables that flotsam writes.
#pragma once
#include <string>

namespace flotsam {

// A CSV field: quoted when it holds a comma, a quote or a line break (quotes doubled).
inline std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace flotsam
