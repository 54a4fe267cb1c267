// Synthetic WG1 water-level records (SCENE.md, "The ten boundary records"): one smooth
// leading-wave shape plus, per realisation, a smooth time-correlated departure whose
// ensemble standard deviation is `spread` at every time after the first few seconds.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "common/timeseries.hpp"

namespace flotsam {

// The record model and its parameters.
struct BoundaryGenDef {
    int count = 10;           // realisations [-]
    double duration = 420.0;  // record length [s]
    double dt = 0.1;          // sample interval [s]
    std::uint64_t seed = 1;
    double peak = 0.06;            // level at the end of pumping [m]
    double spread = 0.001;         // ensemble standard deviation of the departures [m]
    double pump_end = 300.0;       // end of pumping [s]
    double front_fraction = 0.2;   // share of the peak arriving with the initial front [-]
    double front_time = 15.0;      // time scale of the initial front [s]
    double return_time = 50.0;     // relaxation time of the return flow [s]
    double departure_onset = 8.0;  // departures grow in over this time from t = 0 [s]
    double period_min = 20.0;      // shortest period of the departures [s]
    double period_max = 200.0;     // longest period of the departures [s]
    int modes = 6;                 // sinusoids per realisation [-]
};

// The ensemble-mean level at time t [m] (s, m).
double leading_wave(const BoundaryGenDef& def, double t);

// `count` records of (time [s], eta [m]).
std::vector<TimeSeries> generate_boundary_records(const BoundaryGenDef& def);

// Numbers for a quick look at an ensemble: all in m, times in s.
struct BoundarySummary {
    double max_mean = 0.0;     // largest ensemble-mean level [m]
    double time_of_max = 0.0;  // [s]
    double std_min = 0.0;      // ensemble std over t >= std_from [m]
    double std_mean = 0.0;     // [m]
    double std_max = 0.0;      // [m]
    double std_from = 30.0;    // start of the window for the std numbers [s]
};
// Records must share their sample times.
BoundarySummary summarise_boundary(const std::vector<TimeSeries>& records, double std_from = 30.0);

// The paths of `count` records in `dir`: wg1_r00.csv, wg1_r01.csv, ...
std::vector<std::string> boundary_record_paths(const std::string& dir, int count);

// The records at `lambda` times the flume's scale by Froude's law: times x sqrt(lambda),
// levels x lambda (lambda = 250: the flume's records at the prototype scale of Kainan).
void froude_scale(std::vector<TimeSeries>& records, double lambda);

// File names wg1_r00.csv, wg1_r01.csv, ... in `dir` (created when missing).
std::vector<std::string> write_boundary_records(const std::string& dir, const std::vector<TimeSeries>& records);

// Reads a user's or a generated record (CSV "time,eta") for a run of `duration` seconds:
// the checks of read_time_series_csv (file and line named) and coverage of [0, duration].
TimeSeries load_boundary_record(const std::string& path, double duration);

}  // namespace flotsam
