// Progress on stderr: one line redrawn in place on a terminal, plain lines at most
// every `log_interval` wall seconds otherwise (a log file stays readable).
#pragma once
#include <chrono>
#include <string>

namespace flotsam {

class Progress {
public:
    // label: e.g. "hydro r03"; total: the simulated end time [s]
    Progress(std::string label, double total, double log_interval = 10.0, bool quiet = false);
    // sim_time [s], dt [s], steps done so far; prints when due
    void update(double sim_time, double dt, long steps);
    void finish(double sim_time, long steps);

private:
    std::string label_;
    double total_;
    double log_interval_;
    bool quiet_;
    bool tty_;
    std::chrono::steady_clock::time_point start_, last_;
    long steps_at_last_ = 0;
    bool printed_ = false;
};

}  // namespace flotsam
