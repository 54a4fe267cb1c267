// The parameter-set designs of a sweep (spec_file.hpp): one factor at a time, full
// factorial, random and Latin hypercube samples, with their labels.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>

#include "common/checks.hpp"
#include "sweep/spec_file.hpp"

namespace flotsam::sweep {

namespace {

std::string numbered(const char* prefix, int k, int count) {
    const std::size_t digits = std::max<std::size_t>(2, std::to_string(std::max(count - 1, 0)).size());
    std::string n = std::to_string(k);
    return prefix + std::string(digits > n.size() ? digits - n.size() : 0, '0') + n;
}

}  // namespace

std::uint64_t Rng::next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

double Rng::uniform() { return double(next() >> 11) * 0x1.0p-53; }

double Rng::normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();  // u1 in (0, 1]
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::vector<ParameterSet> one_at_a_time(const ParamValues& control, const std::vector<int>& varied, double factor) {
    std::vector<ParameterSet> out{{"control", control, true}};
    for (int p : varied) {
        const std::string& key = design_parameters()[std::size_t(p)].key;
        ParameterSet up{key + "x" + number_text(factor), control, false};
        up.values[p] = control[p] * factor;
        ParameterSet down{key + "/" + number_text(factor), control, false};
        down.values[p] = control[p] / factor;
        out.push_back(up);
        out.push_back(down);
    }
    return out;
}

std::vector<ParameterSet> factorial(const ParamValues& control, const std::vector<std::vector<double>>& levels) {
    const std::size_t np = control.size();
    std::vector<std::vector<double>> lv(np);
    std::size_t total = 1;
    for (std::size_t p = 0; p < np; ++p) {
        lv[p] = p >= levels.size() || levels[p].empty() ? std::vector<double>{control[p]} : levels[p];
        total *= lv[p].size();
    }
    std::vector<ParameterSet> out;
    for (std::size_t k = 0; k < total; ++k) {
        ParameterSet s{numbered("grid", int(k), int(total)), ParamValues(np), false};
        std::size_t rest = k;
        for (int p = int(np) - 1; p >= 0; --p) {  // last parameter fastest
            s.values[p] = lv[p][rest % lv[p].size()];
            rest /= lv[p].size();
        }
        s.is_control = s.values == control;
        out.push_back(s);
    }
    return out;
}

std::vector<ParameterSet> random_samples(const ParamRanges& ranges, int count, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<ParameterSet> out;
    for (int k = 0; k < count; ++k) {
        ParameterSet s{numbered("random", k, count), ParamValues(ranges.size()), false};
        for (std::size_t p = 0; p < ranges.size(); ++p) s.values[p] = ranges[p][0] + (ranges[p][1] - ranges[p][0]) * rng.uniform();
        out.push_back(s);
    }
    return out;
}

std::vector<ParameterSet> latin_hypercube(const ParamRanges& ranges, int count, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<ParameterSet> out(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) out[std::size_t(k)] = {numbered("lhs", k, count), ParamValues(ranges.size()), false};
    for (std::size_t p = 0; p < ranges.size(); ++p) {
        std::vector<int> strata(static_cast<std::size_t>(count));
        for (int k = 0; k < count; ++k) strata[std::size_t(k)] = k;
        for (int k = count - 1; k > 0; --k)
            std::swap(strata[std::size_t(k)], strata[std::size_t(rng.next() % std::uint64_t(k + 1))]);  // Fisher–Yates
        for (int k = 0; k < count; ++k) {
            const double u = (strata[std::size_t(k)] + rng.uniform()) / count;
            out[std::size_t(k)].values[p] = ranges[p][0] + (ranges[p][1] - ranges[p][0]) * u;
        }
    }
    return out;
}

}  // namespace flotsam::sweep
