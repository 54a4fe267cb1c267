// Finite numbers in range, or a named error: the one check every numeric option,
// settings key and spec value goes through. A check is data — a name, a value
// and a Range — so a table of parameters can drive it:
//
//     check_range("--cfl", s.cfl, Range::open_closed(0, 0.5));
//     // --cfl: nan is not a finite number (allowed: (0, 0.5])
//     // --cfl: 0.7 is outside the allowed range (0, 0.5]
//
// And sizes before allocation: check_allocation() compares what an option would make a
// run allocate with the machine's memory and names the option when it cannot fit.
#pragma once
#include <cstddef>
#include <limits>
#include <string>

namespace flotsam {

struct Range {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false, max_open = false;  // (min, ... and ..., max)
    bool whole = false;                       // whole numbers only
    std::string unit;                         // for messages: "s", "m", "s m^-1/3"

    static Range closed(double a, double b, std::string unit = "") { return {a, b, false, false, false, std::move(unit)}; }
    static Range open_closed(double a, double b, std::string unit = "") { return {a, b, true, false, false, std::move(unit)}; }
    static Range positive(std::string unit = "");                   // (0, inf)
    static Range non_negative(std::string unit = "");               // [0, inf)
    static Range at_least(double a, std::string unit = "");         // [a, inf)
    static Range any(std::string unit = "");                        // any finite number
    static Range count(double a, double b, std::string unit = "");  // whole numbers in [a, b]
    Range& up_to(double b) {
        max = b;
        return *this;
    }  // then at most b
    Range& below(double b) {
        max = b;
        max_open = true;
        return *this;
    }
};

// A number for messages: "1e-09", "0.45", "1e+12" (6 significant digits).
std::string number_text(double v);

// "(0, 0.5] s", "whole numbers in [1, 16]", "any finite number".
std::string describe(const Range& r);

// Empty when `value` is finite and in `r`; else what is wrong, naming the value and the
// range.
std::string range_problem(double value, const Range& r);

// Throws flotsam::Error "<file>: <name>: <problem>" (an empty file is left out).
void check_range(const std::string& name, double value, const Range& r, const std::string& file = "");

// The memory the process may use [bytes]: the physical memory, or the cgroup's limit
// when lower, or FLOTSAM_MEMORY_LIMIT_MB when that is lower still.
double memory_limit_bytes();

// Throws naming `name` (and the file, if any) when `count` items of `bytes_each` bytes
// would exceed memory_limit_bytes() (or overflow): "--output-interval: 1e-09 s would make
// 4.2e+11 frame times (3.3e+03 GB), more than this machine's 24 GB".
void check_allocation(const std::string& name, const std::string& value_text, double count, double bytes_each,
                      const std::string& what, const std::string& file = "");

}  // namespace flotsam
