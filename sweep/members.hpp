// The members of a sweep: every (flow, run of bodies, start, variant, parameter set) of a
// spec, in one order, and their shards. The perturbed starts are pure functions of the
// spec (seeded, platform-independent random numbers), so every shard of a sweep builds
// the same member list.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "debris/body.hpp"
#include "sweep/spec_file.hpp"

namespace flotsam::sweep {

// Where a member sits in the sweep (shared by Member and the file's MemberRecord).
struct MemberIndex {
    int id = 0;            // position in the full member list
    int flow = 0;          // index into spec.flows
    int body = 0;          // index into spec.bodies
    int perturbation = 0;  // 0: the exact start; k > 0: the k-th perturbed start
    int variant = 0;       // index into spec.variants
    int param_set = 0;     // index into spec.params
    int run = 0;           // the run it is part of: the members of one run share a world and meet each other
};
// One trajectory of the sweep.
struct Member : MemberIndex {
    debris::BodyDef def;  // the body as run (name = the body's name)
};

// The bodies that share a run, in the order of their first body: a source's bodies (every
// body of one GIS feature), all of them with one_world, any other body alone.
std::vector<std::vector<int>> body_runs(const SweepSpec& spec);

// The sweep's members, counted without building them: flows x bodies x starts x variants
// x parameter sets, flow outermost.
double member_count(const SweepSpec& spec);
// Throws naming the spec when the members would pass 2e9 or the machine's memory.
void check_member_count(const SweepSpec& spec);

// All members, flow outermost, then the bodies' runs (body_runs), perturbation, variant,
// parameter set and the run's bodies: a run's members are consecutive (for a spec of
// bodies that each run alone: flow, body, perturbation, variant, parameter set).
std::vector<Member> enumerate_members(const SweepSpec& spec);

// The k-th perturbed start (k = 0: unperturbed) of the bodies `bodies` (one run): x, y
// [m], heading [rad] each. Perturbed, a run moves as a whole: one offset of its bodies'
// centroid and one turn about it, drawn from its first body's stream.
std::vector<std::array<double, 3>> perturbed_starts(const SweepSpec& spec, const std::vector<int>& bodies, int k);
// The same for one body alone.
std::array<double, 3> perturbed_start(const SweepSpec& spec, int body, int k);

// Shard i of n: the contiguous member ids [first, last).
struct Shard {
    int index = 0, count = 1;
};
Shard parse_shard(const std::string& text);  // "i/n", 0 <= i < n
std::array<int, 2> shard_range(int members, const Shard& shard);
// The same over whole runs (a run's members are never split between shards).
std::array<int, 2> shard_range(const std::vector<Member>& members, const Shard& shard);

}  // namespace flotsam::sweep
