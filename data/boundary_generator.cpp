#include "data/boundary_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam {

namespace {

class Rng {  // mt19937_64 with our own [0,1) mapping: identical on every standard library
public:
    explicit Rng(std::uint64_t seed) : engine_(seed) {}
    double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }

private:
    std::mt19937_64 engine_;
};

// Rise during pumping, as a fraction of the peak: an initial front (share f, time scale
// tau) then a nearly linear fill. q(u) = 1 - (1+u)e^-u starts with zero value and slope,
// so the level leaves rest C1-smoothly.
double rise(const BoundaryGenDef& d, double t) {
    const double u = t / d.front_time;
    const double q = 1.0 - (1.0 + u) * std::exp(-u);
    return q * (d.front_fraction + (1.0 - d.front_fraction) * t / d.pump_end);
}

double rise_slope(const BoundaryGenDef& d, double t) {
    const double u = t / d.front_time;
    const double q = 1.0 - (1.0 + u) * std::exp(-u), dq = u * std::exp(-u) / d.front_time;
    return dq * (d.front_fraction + (1.0 - d.front_fraction) * t / d.pump_end) + q * (1.0 - d.front_fraction) / d.pump_end;
}

void check(const BoundaryGenDef& d) {
    if (d.count < 1) fail("--count", "", "needs at least one record");
    if (!(d.dt > 0.0)) fail("--dt", number_text(d.dt) + " s", "must be positive");
    if (!(d.duration > d.dt))
        fail("--duration", number_text(d.duration) + " s",
             "is not longer than --dt (" + number_text(d.dt) + " s): a record needs at least two samples");
    if (!(d.spread >= 0.0) || !(d.peak > 0.0)) fail("--peak/--spread", "", "need peak > 0 and spread >= 0");
    if (!(d.period_min > 0.0 && d.period_max >= d.period_min) || d.modes < 1)
        fail("boundary generate", "periods", "need 0 < period_min <= period_max and modes >= 1");
}

// One realisation's raw departure: random-phase sinusoids, periods log-uniform in
// [period_min, period_max], unit variance in expectation.
std::vector<double> raw_departure(const BoundaryGenDef& d, Rng& rng, const std::vector<double>& t) {
    std::vector<double> period(d.modes), phase(d.modes);
    for (int m = 0; m < d.modes; ++m) {
        period[m] = d.period_min * std::pow(d.period_max / d.period_min, rng.uniform());
        phase[m] = 2.0 * std::numbers::pi * rng.uniform();
    }
    const double amp = std::sqrt(2.0 / d.modes);
    std::vector<double> v(t.size());
    for (std::size_t k = 0; k < t.size(); ++k)
        for (int m = 0; m < d.modes; ++m) v[k] += amp * std::sin(2.0 * std::numbers::pi * t[k] / period[m] + phase[m]);
    return v;
}

}  // namespace

double leading_wave(const BoundaryGenDef& d, double t) {
    if (t <= 0.0) return 0.0;
    if (t <= d.pump_end) return d.peak * rise(d, t);
    // Return flow: relaxation toward still water with time scale return_time, starting
    // with the pumping-end slope k so the level stays C1: r(s) = e^(-s/T) (1 + (k + 1/T) s).
    const double s = t - d.pump_end, T = d.return_time;
    const double k = rise_slope(d, d.pump_end) / rise(d, d.pump_end);
    return d.peak * rise(d, d.pump_end) * std::exp(-s / T) * (1.0 + (k + 1.0 / T) * s);
}

std::vector<TimeSeries> generate_boundary_records(const BoundaryGenDef& d) {
    check(d);
    const std::size_t n = std::size_t(std::llround(d.duration / d.dt)) + 1;
    std::vector<double> t(n);
    for (std::size_t k = 0; k < n; ++k) t[k] = double(k) * d.dt;
    Rng rng(d.seed);
    std::vector<std::vector<double>> dep;
    for (int r = 0; r < d.count; ++r) dep.push_back(raw_departure(d, rng, t));
    // With three or more records, remove the ensemble mean and rescale at every time so
    // the ensemble (sample) std is exactly `spread`: the departures stay smooth because
    // the sample std of ten smooth series is itself smooth and far from zero.
    if (d.count >= 3)
        for (std::size_t k = 0; k < n; ++k) {
            double mean = 0.0, var = 0.0;
            for (const auto& v : dep) mean += v[k];
            mean /= d.count;
            for (const auto& v : dep) var += (v[k] - mean) * (v[k] - mean);
            const double sd = std::sqrt(var / (d.count - 1));
            for (auto& v : dep) v[k] = sd > 0.0 ? (v[k] - mean) / sd : 0.0;
        }
    std::vector<TimeSeries> out(d.count);
    for (int r = 0; r < d.count; ++r) {
        out[r].time = t;
        out[r].value.resize(n);
        out[r].source = "synthetic WG1 record " + std::to_string(r);
        for (std::size_t k = 0; k < n; ++k) {
            // The flume starts at rest: the departure grows in as 1 - exp(-(t/onset)^2).
            const double onset = 1.0 - std::exp(-(t[k] / d.departure_onset) * (t[k] / d.departure_onset));
            out[r].value[k] = leading_wave(d, t[k]) + d.spread * onset * dep[r][k];
        }
    }
    return out;
}

BoundarySummary summarise_boundary(const std::vector<TimeSeries>& recs, double std_from) {
    BoundarySummary s;
    s.std_from = std_from;
    s.std_min = 1e30;
    s.max_mean = -1e30;
    const std::size_t n = recs.front().time.size(), c = recs.size();
    double std_sum = 0.0;
    int std_count = 0;
    for (std::size_t k = 0; k < n; ++k) {
        double mean = 0.0, var = 0.0;
        for (const auto& r : recs) mean += r.value[k];
        mean /= double(c);
        for (const auto& r : recs) var += (r.value[k] - mean) * (r.value[k] - mean);
        if (mean > s.max_mean) {
            s.max_mean = mean;
            s.time_of_max = recs.front().time[k];
        }
        if (c < 2 || recs.front().time[k] < std_from) continue;
        const double sd = std::sqrt(var / double(c - 1));
        s.std_min = std::min(s.std_min, sd);
        s.std_max = std::max(s.std_max, sd);
        std_sum += sd;
        ++std_count;
    }
    if (std_count == 0)
        s.std_min = 0.0;
    else
        s.std_mean = std_sum / std_count;
    return s;
}

std::vector<std::string> boundary_record_paths(const std::string& dir, int count) {
    std::vector<std::string> paths;
    for (int r = 0; r < count; ++r) {
        char name[32];
        std::snprintf(name, sizeof name, "wg1_r%02d.csv", r);
        paths.push_back((std::filesystem::path(dir) / name).string());
    }
    return paths;
}

std::vector<std::string> write_boundary_records(const std::string& dir, const std::vector<TimeSeries>& records) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) fail(dir, "", "cannot create directory: " + ec.message());
    const std::vector<std::string> paths = boundary_record_paths(dir, int(records.size()));
    for (std::size_t r = 0; r < records.size(); ++r) write_time_series_csv(paths[r], records[r], "eta");
    return paths;
}

void froude_scale(std::vector<TimeSeries>& records, double lambda) {
    if (!(lambda > 0.0)) fail("--froude-scale", std::to_string(lambda), "must be positive");
    const double time_scale = std::sqrt(lambda);
    for (auto& r : records) {
        for (double& t : r.time) t *= time_scale;
        for (double& v : r.value) v *= lambda;
    }
}

TimeSeries load_boundary_record(const std::string& path, double duration) {
    TimeSeries s = read_time_series_csv(path);
    require_coverage(s, 0.0, duration);
    return s;
}

}  // namespace flotsam
