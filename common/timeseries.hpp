// A scalar time series read from CSV (two columns: time in s, value in the series'
// unit), linear between samples. Used for boundary water levels and discharges.
#pragma once
#include <string>
#include <vector>

namespace flotsam {

struct TimeSeries {
    std::vector<double> time;   // [s], strictly increasing
    std::vector<double> value;  // unit of the series (m for a level, m^3/s for a discharge)
    std::string source;         // file it came from, for messages

    double at(double t) const;  // linear; throws outside [time.front(), time.back()]
    double start() const { return time.front(); }
    double end() const { return time.back(); }
};

// Reads "time,<name>" CSV. A header line is optional; '#' starts a comment line.
// Throws naming the file and line for: a wrong column count, a non-number, NaN or
// infinity, time not strictly increasing, a gap between samples longer than
// `max_gap` seconds, or fewer than two samples. max_gap = 0 (the default) sizes the
// check to the record: a gap is missing data when it is longer than 10 s and longer than
// ten times the record's median sample spacing (so a full-scale record sampled every
// minute passes, and a 10 Hz flume record with a hole of 11 s does not).
TimeSeries read_time_series_csv(const std::string& path, double max_gap = 0.0);

// Throws naming the file when the series does not cover [t0, t1].
void require_coverage(const TimeSeries& s, double t0, double t1);

// Writes "time,<value_name>" CSV with full double precision, atomically.
void write_time_series_csv(const std::string& path, const TimeSeries& s, const std::string& value_name);

}  // namespace flotsam
