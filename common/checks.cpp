#include "common/checks.hpp"

#include <cmath>
#include <cstdio>

#include "common/error.hpp"

namespace flotsam {

namespace {
const double inf = std::numeric_limits<double>::infinity();
}  // namespace

std::string number_text(double v) {
    if (v == inf) return "inf";
    if (v == -inf) return "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

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
        s = (r.whole ? "whole numbers in " : std::string()) + (r.min_open || r.min == -inf ? "(" : "[") + number_text(r.min) +
            ", " + number_text(r.max) + (r.max_open || r.max == inf ? ")" : "]");
    if (!r.unit.empty()) s += " " + r.unit;
    return s;
}

std::string range_problem(double value, const Range& r) {
    if (!std::isfinite(value)) return number_text(value) + " is not a finite number (allowed: " + describe(r) + ")";
    const bool below = r.min_open ? !(value > r.min) : !(value >= r.min);
    const bool above = r.max_open ? !(value < r.max) : !(value <= r.max);
    if (below || above) return number_text(value) + " is outside the allowed range " + describe(r);
    if (r.whole && value != std::floor(value)) return number_text(value) + " is not a whole number (allowed: " + describe(r) + ")";
    return "";
}

void check_range(const std::string& name, double value, const Range& r, const std::string& file) {
    const std::string p = range_problem(value, r);
    if (!p.empty()) fail(file, name, p);
}

}  // namespace flotsam
