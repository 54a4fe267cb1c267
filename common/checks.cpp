#include "common/checks.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "common/error.hpp"

namespace flotsam {

namespace {
const double inf = std::numeric_limits<double>::infinity();

std::string num(double v) {
    if (v == inf) return "inf";
    if (v == -inf) return "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}
}  // namespace

std::string number_text(double v) { return num(v); }

Range Range::positive(std::string unit) { return {0.0, inf, true, false, false, std::move(unit)}; }
Range Range::non_negative(std::string unit) { return {0.0, inf, false, false, false, std::move(unit)}; }
Range Range::at_least(double a, std::string unit) { return {a, inf, false, false, false, std::move(unit)}; }
Range Range::any(std::string unit) { return {-inf, inf, false, false, false, std::move(unit)}; }
Range Range::count(double a, double b, std::string unit) { return {a, b, false, false, true, std::move(unit)}; }

std::string describe(const Range& r) {
    std::string s;
    if (r.min == -inf && r.max == inf)
        s = "any finite number";
    else
        s = (r.whole ? "whole numbers in " : std::string()) + (r.min_open || r.min == -inf ? "(" : "[") + num(r.min) + ", " +
            num(r.max) + (r.max_open || r.max == inf ? ")" : "]");
    if (!r.unit.empty()) s += " " + r.unit;
    return s;
}

std::string range_problem(double value, const Range& r) {
    if (!std::isfinite(value)) return num(value) + " is not a finite number (allowed: " + describe(r) + ")";
    const bool below = r.min_open ? !(value > r.min) : !(value >= r.min);
    const bool above = r.max_open ? !(value < r.max) : !(value <= r.max);
    if (below || above) return num(value) + " is outside the allowed range " + describe(r);
    if (r.whole && value != std::floor(value)) return num(value) + " is not a whole number (allowed: " + describe(r) + ")";
    return "";
}

void check_range(const std::string& name, double value, const Range& r, const std::string& file) {
    const std::string p = range_problem(value, r);
    if (!p.empty()) fail(file, name, p);
}

double memory_limit_bytes() {
    static const double limit = [] {
        double bytes = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
        std::ifstream cg("/sys/fs/cgroup/memory.max");
        std::string s;
        if (cg >> s && s != "max") {
            const double c = std::strtod(s.c_str(), nullptr);
            if (c > 0 && c < bytes) bytes = c;
        }
        // A lower limit on request (the fuzz targets use it so that a valid but huge input
        // gives its named error at once).
        if (const char* mb = std::getenv("FLOTSAM_MEMORY_LIMIT_MB"); mb && std::strtod(mb, nullptr) > 0)
            bytes = std::min(bytes, std::strtod(mb, nullptr) * 1024 * 1024);
        return bytes > 0 ? bytes : 1e12;
    }();
    return limit;
}

void check_allocation(const std::string& name, const std::string& value_text, double count, double bytes_each,
                      const std::string& what, const std::string& file) {
    const double bytes = count * bytes_each, limit = memory_limit_bytes();
    if (std::isfinite(bytes) && bytes >= 0 && bytes <= limit) return;
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s would make %.3g %s (%.3g GB), more than this machine's %.3g GB", value_text.c_str(), count,
                  what.c_str(), bytes / 1e9, limit / 1e9);
    fail(file, name, buf);
}

}  // namespace flotsam
