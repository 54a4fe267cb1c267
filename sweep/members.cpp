#include "sweep/members.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam::sweep {

std::vector<std::vector<int>> body_runs(const SweepSpec& spec) {
    std::vector<std::vector<int>> runs;
    std::vector<std::pair<std::string, std::size_t>> by_source;  // source, its run
    for (int b = 0; b < int(spec.bodies.size()); ++b) {
        const std::string& source = spec.bodies[std::size_t(b)].source;
        if (spec.one_world && !runs.empty()) {
            runs.front().push_back(b);
            continue;
        }
        const auto it = std::find_if(by_source.begin(), by_source.end(), [&](const auto& s) { return s.first == source; });
        if (!source.empty() && it != by_source.end()) {
            runs[it->second].push_back(b);
            continue;
        }
        if (!source.empty()) by_source.push_back({source, runs.size()});
        runs.push_back({b});
    }
    return runs;
}

std::vector<std::array<double, 3>> perturbed_starts(const SweepSpec& spec, const std::vector<int>& bodies, int k) {
    std::vector<std::array<double, 3>> out;
    for (const int b : bodies) {
        const BodySpec& s = spec.bodies[std::size_t(b)];
        out.push_back({s.x, s.y, s.heading});
    }
    if (k == 0) return out;
    const double deg = std::numbers::pi / 180.0;
    // Its own stream per (first body, k): the same offsets whatever the flows, variants or sets.
    Rng rng(spec.perturbation.seed * 0x100000001b3ULL + std::uint64_t(bodies.front()) * 0x10001ULL + std::uint64_t(k));
    const double dx = spec.perturbation.position_std * rng.normal();
    const double dy = spec.perturbation.position_std * rng.normal();
    const double dh = spec.perturbation.heading_std * rng.normal();
    if (bodies.size() == 1) {
        const BodySpec& b = spec.bodies[std::size_t(bodies.front())];
        return {{b.x + dx, b.y + dy, (b.heading_deg + dh) * deg}};
    }
    double cx = 0.0, cy = 0.0;
    for (const auto& p : out) cx += p[0], cy += p[1];
    cx /= double(out.size());
    cy /= double(out.size());
    const double c = std::cos(dh * deg), s = std::sin(dh * deg);
    for (auto& p : out) {
        const double rx = p[0] - cx, ry = p[1] - cy;
        p = {cx + c * rx - s * ry + dx, cy + s * rx + c * ry + dy, p[2] + dh * deg};
    }
    return out;
}

std::array<double, 3> perturbed_start(const SweepSpec& spec, int body, int k) { return perturbed_starts(spec, {body}, k).front(); }

double member_count(const SweepSpec& spec) {
    return double(spec.flows.size()) * double(spec.bodies.size()) * double(spec.perturbation.count + 1) *
           double(spec.variants.size()) * double(spec.params.size());
}

void check_member_count(const SweepSpec& spec) {
    const double members = member_count(spec);
    if (members > 2e9)
        fail(spec.path, "sweep size",
             number_text(members) + " members (flows x bodies x starts x variants x parameter sets), more than 2e9");
    check_allocation("sweep size", number_text(members) + " members", members, double(sizeof(Member)), "members", spec.path);
}

std::vector<Member> enumerate_members(const SweepSpec& spec) {
    std::vector<Member> out;
    const int np = spec.perturbation.count + 1;
    check_member_count(spec);  // sized before anything is allocated
    const std::vector<std::vector<int>> runs = body_runs(spec);
    int run = 0;
    for (int f = 0; f < int(spec.flows.size()); ++f)
        for (const std::vector<int>& bodies : runs)
            for (int k = 0; k < np; ++k) {
                const std::vector<std::array<double, 3>> starts = perturbed_starts(spec, bodies, k);
                for (int v = 0; v < int(spec.variants.size()); ++v)
                    for (int p = 0; p < int(spec.params.size()); ++p, ++run)
                        for (std::size_t i = 0; i < bodies.size(); ++i) {
                            const int b = bodies[i];
                            Member m;
                            static_cast<MemberIndex&>(m) = {int(out.size()), f, b, k, v, p, run};
                            debris::BodyDef& d = m.def;
                            const BodySpec& body = spec.bodies[std::size_t(b)];
                            d = body.def;
                            d.name = body.name;
                            d.x = starts[i][0];
                            d.y = starts[i][1];
                            d.heading = starts[i][2];
                            d.contact = spec.variants[std::size_t(v)].contact;
                            d.collision = spec.variants[std::size_t(v)].collision;
                            if (!spec.bodies_as_given)
                                apply_parameters(body.type.empty() ? spec.params[std::size_t(p)].values
                                                                   : catalogue_values(spec, body, spec.params[std::size_t(p)].values),
                                                 d);
                            out.push_back(m);
                        }
            }
    return out;
}

Shard parse_shard(const std::string& text) {
    const auto slash = text.find('/');
    Shard s;
    try {
        std::size_t a = 0, b = 0;
        if (slash == std::string::npos) throw std::invalid_argument(text);
        s.index = std::stoi(text.substr(0, slash), &a);
        s.count = std::stoi(text.substr(slash + 1), &b);
        if (a != slash || b != text.size() - slash - 1) throw std::invalid_argument(text);
    } catch (const std::exception&) {
        fail("--shard", text, "expected i/n (e.g. 0/4)");
    }
    if (s.count < 1 || s.index < 0 || s.index >= s.count) fail("--shard", text, "needs 0 <= i < n");
    return s;
}

std::array<int, 2> shard_range(int members, const Shard& shard) {
    const auto bound = [&](int i) { return int((long long)members * i / shard.count); };
    return {bound(shard.index), bound(shard.index + 1)};
}

std::array<int, 2> shard_range(const std::vector<Member>& members, const Shard& shard) {
    std::vector<int> first;  // the first member of each run
    for (std::size_t k = 0; k < members.size(); ++k)
        if (k == 0 || members[k].run != members[k - 1].run) first.push_back(int(k));
    const std::array<int, 2> runs = shard_range(int(first.size()), shard);
    const auto member_of = [&](int r) { return r < int(first.size()) ? first[std::size_t(r)] : int(members.size()); };
    return {member_of(runs[0]), member_of(runs[1])};
}

}  // namespace flotsam::sweep
