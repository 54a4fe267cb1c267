#include "common/timeseries.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam {

double TimeSeries::at(double t) const {
    if (time.empty()) fail(source, "", "empty time series");
    if (t < time.front() - 1e-9 || t > time.back() + 1e-9)
        fail(source, "",
             "time " + std::to_string(t) + " s is outside the series [" + std::to_string(time.front()) + ", " +
                 std::to_string(time.back()) + "] s");
    if (t <= time.front()) return value.front();
    if (t >= time.back()) return value.back();
    const auto it = std::upper_bound(time.begin(), time.end(), t);
    const std::size_t k = std::size_t(it - time.begin());
    const double w = (t - time[k - 1]) / (time[k] - time[k - 1]);
    return (1.0 - w) * value[k - 1] + w * value[k];
}

namespace {
// A header's name for the time column: "time", "time_s", "Time [s]", "t", "seconds".
bool names_time(std::string c) {
    for (char& ch : c) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    const auto a = c.find_first_not_of(" \t\""), b = c.find_last_not_of(" \t\"\r");
    if (a == std::string::npos) return false;
    c = c.substr(a, b - a + 1);
    return c.rfind("time", 0) == 0 || c == "t" || c == "t_s" || c == "t [s]" || c == "seconds" || c == "s";
}
bool parse_double(const std::string& s, double& out) {
    const char* b = s.c_str();
    while (*b == ' ' || *b == '\t') ++b;
    char* e = nullptr;
    out = std::strtod(b, &e);
    if (e == b) return false;
    while (*e == ' ' || *e == '\t' || *e == '\r') ++e;
    return *e == '\0';
}
}  // namespace

TimeSeries read_time_series_csv(const std::string& path, double max_gap) {
    check_input_file("", path);  // /dev/zero or a FIFO would be read forever
    check_input_size("", path, 1e9, "a time series");
    std::ifstream f(path);
    if (!f) fail(path, "", "cannot open");
    TimeSeries s;
    s.source = path;
    std::string line;
    int lineno = 0;
    bool header_allowed = true;
    std::vector<int> lines;  // file line of each sample
    const int time_column = 0;  // time first, the value second
    std::string header;         // for messages
    while (std::getline(f, line)) {
        ++lineno;
        if (lineno == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 byte-order mark
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const auto first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        std::vector<std::string> cols;
        std::stringstream ss(line);
        std::string c;
        while (std::getline(ss, c, ',')) cols.push_back(c);
        const std::string here = "line " + std::to_string(lineno);
        double t = 0, v = 0;
        const bool numeric = cols.size() == 2 && parse_double(cols[time_column], t) && parse_double(cols[1 - time_column], v);
        if (!numeric) {
            if (header_allowed && cols.size() == 2) {  // a header such as "time,eta"
                header_allowed = false;
                header = line;
                // A header naming time second contradicts how the file is read: say so
                // here, not as a time-order error further down.
                if (!names_time(cols[0]) && names_time(cols[1]))
                    fail(path, here + ": header '" + line + "'",
                         "names time in column 2: flotsam reads time in column 1 and the value in column 2; write the "
                         "columns (and the header) as time,value");
                continue;
            }
            if (cols.size() != 2)
                fail(path, here, "expected 2 comma-separated columns (time,value), found " + std::to_string(cols.size()));
            fail(path, here, "not a number: '" + line + "'");
        }
        header_allowed = false;
        if (!std::isfinite(t) || !std::isfinite(v)) fail(path, here, "NaN or infinite value");
        if (!s.time.empty()) {
            if (!(t > s.time.back()))
                fail(path, here,
                     "time " + std::to_string(t) + " s does not increase (previous " + std::to_string(s.time.back()) + " s; " +
                         (header.empty() ? std::string("no header: column 1 is read as time")
                                         : "column " + std::to_string(time_column + 1) + " of the header '" + header +
                                               "' is read as time") +
                         ")");
            if (max_gap > 0.0 && t - s.time.back() > max_gap)
                fail(path, here,
                     "gap of " + std::to_string(t - s.time.back()) + " s between samples (at most " + std::to_string(max_gap) +
                         " s allowed)");
        }
        s.time.push_back(t);
        s.value.push_back(v);
        lines.push_back(lineno);
    }
    if (s.time.size() < 2) fail(path, "", "needs at least 2 samples, has " + std::to_string(s.time.size()));
    if (max_gap <= 0.0) {
        std::vector<double> spacing(s.time.size() - 1);
        for (std::size_t k = 0; k + 1 < s.time.size(); ++k) spacing[k] = s.time[k + 1] - s.time[k];
        std::vector<double> sorted = spacing;
        std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
        const double allowed = std::max(10.0, 10.0 * sorted[sorted.size() / 2]);
        for (std::size_t k = 0; k < spacing.size(); ++k)
            if (spacing[k] > allowed)
                fail(path, "line " + std::to_string(lines[k + 1]),
                     "gap of " + std::to_string(spacing[k]) + " s between samples (at most " + std::to_string(allowed) +
                         " s allowed: 10 s or ten times the median spacing " + std::to_string(sorted[sorted.size() / 2]) +
                         " s; missing data?)");
    }
    return s;
}

void require_coverage(const TimeSeries& s, double t0, double t1) {
    if (s.time.front() > t0 + 1e-9 || s.time.back() < t1 - 1e-9)
        fail(s.source, "",
             "covers [" + std::to_string(s.time.front()) + ", " + std::to_string(s.time.back()) + "] s but the run needs [" +
                 std::to_string(t0) + ", " + std::to_string(t1) + "] s");
}

void write_time_series_csv(const std::string& path, const TimeSeries& s, const std::string& value_name) {
    std::string text = "time," + value_name + "\n";
    char buf[96];
    for (std::size_t k = 0; k < s.time.size(); ++k) {
        std::snprintf(buf, sizeof buf, "%.10g,%.10g\n", s.time[k], s.value[k]);
        text += buf;
    }
    write_text_atomic(path, text);
}

}  // namespace flotsam
