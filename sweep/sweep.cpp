#include "sweep/sweep.hpp"

#include <chrono>
#include <functional>
#include <cmath>
#include <memory>
#include <numbers>

#include "common/cf.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/progress.hpp"
#include "debris/scene_match.hpp"
#include "debris/trajectory_output.hpp"
#include "debris/world.hpp"
#include "formats/scene.hpp"

namespace flotsam::sweep {

namespace {

// The output time axis: t0 + k Δ up to the end time (the spec's, or the earliest last
// frame), sized before it is built (the trajectories hold 7 series of this length per member).
std::vector<double> output_times(const SweepInputs& in, const SettingNames& names) {
    const SweepSpec& spec = in.spec;
    double t0 = 0.0, last = 0.0;
    for (std::size_t f = 0; f < in.flows.size(); ++f) {
        const debris::FlowDescription& flow = in.flows[f]->description();
        if (f == 0) {
            t0 = flow.start_time();
            last = flow.end_time();
        } else if (flow.start_time() != t0) {
            fail(spec.flows[f], "time",
                 "starts at " + std::to_string(flow.start_time()) + " s, the sweep's first flow at " + std::to_string(t0) +
                     " s (all flows of a sweep share one time axis)");
        }
        last = std::min(last, flow.end_time());
    }
    const double t_end = spec.end_time >= 0 ? spec.end_time : last;
    if (t_end < t0)
        fail(spec.path.empty() ? names.end_time : spec.path, spec.path.empty() ? number_text(t_end) : names.end_time,
             "before the flows' first frame");
    check_allocation(names.output_interval, number_text(spec.output_interval) + " s", (t_end - t0) / spec.output_interval + 2,
                     7.0 * sizeof(double) * std::max(1.0, member_count(spec)), "output times (for every member)", spec.path);
    // t0 + k Δ from k (no accumulated round-off), the last one at t_end.
    std::vector<double> times{t0};
    for (long k = 1; times.back() < t_end; ++k) times.push_back(std::min(t0 + double(k) * spec.output_interval, t_end));
    return times;
}

// The sweep's description, as every shard records it (the members come later).
SweepResult describe_sweep(const SweepInputs& in, const SweepRunDef& def) {
    const SweepSpec& spec = in.spec;
    SweepResult r;
    r.spec_file = spec.path;
    r.spec_sha256 = spec.sha256;
    r.scene_file = spec.scene;
    r.ground_file = spec.ground;
    r.design = spec.design;
    r.flows = spec.flows;
    for (const auto& b : spec.bodies) {
        r.bodies.push_back(b.name);
        r.body_types.push_back(b.type);
        r.body_sources.push_back(b.source);
    }
    for (const auto& v : spec.variants) r.variants.push_back(v.name);
    r.params = spec.params;
    r.perturbation = spec.perturbation;
    r.member_count = int(in.members.size());
    r.output_interval = spec.output_interval;
    r.world = in.world;
    r.time = in.times;
    r.shard = def.shard;
    // Every flow of a sweep comes from one scene; the first one's CRS is the sweep's.
    r.crs = in.flows.front()->description().crs;
    // The scene every shard records, whichever flows its members are on (merging shards
    // compares it).
    r.scene_buildings_sha256 = in.scene ? scene_buildings_sha256(*in.scene) : in.flows.front()->description().scene_buildings_sha256;
    return r;
}

// The work of this shard, flow by flow, before any body steps: refused past the bounds
// (common/checks.hpp) unless allowed.
// The work of `members` members on the flows, `on_flow(f)` of them on flow f, refused past
// the bounds (common/checks.hpp) unless allowed.
void check_work_on_flows(const SweepInputs& in, const SweepRunDef& def, double members, const std::function<double(int)>& on_flow) {
    double body_steps = 0.0;
    for (int f = 0; f < int(in.flows.size()); ++f) {
        const double n = on_flow(f);
        if (n == 0) continue;
        const debris::FlowReader& flow = *in.flows[std::size_t(f)];
        const Grid cells = in.ground && in.ground->grid.dx < flow.grid().dx ? in.ground->grid : flow.grid();
        body_steps += n * debris::check_replay_work(flow, cells, in.world.step, in.times.front(), in.times.back(), n,
                                                    def.allow_large_run, def.names.dt_max, def.names.vertex_step_fraction,
                                                    in.spec.path);
    }
    check_work("sweep size", number_text(members) + " members over " + number_text(double(in.flows.size())) + " flows", body_steps,
               max_body_steps, "body steps", def.allow_large_run, in.spec.path);
}

// Before the members are built: the shard's work from the member count alone (each flow
// an equal share, a shard an equal share of that), so that a sweep far past the bounds is
// refused before it allocates (a factorial of a million sets was refused only after building
// its members: on the test's flume spec 2.3 s and 750 MB; now 0.8 s and 170 MB).
void check_counted_work(const SweepInputs& in, const SweepRunDef& def) {
    const double per_flow = member_count(in.spec) / double(std::max<std::size_t>(1, in.flows.size())) / double(def.shard.count);
    check_work_on_flows(in, def, per_flow * double(in.flows.size()), [&](int) { return per_flow; });
}

// The shard's work from its members, once they are built.
void check_shard_work(const SweepInputs& in, const SweepRunDef& def) {
    const std::array<int, 2> range = shard_range(in.members, def.shard);
    check_work_on_flows(in, def, double(range[1] - range[0]), [&](int f) {
        double n = 0;
        for (int id = range[0]; id < range[1]; ++id) n += in.members[std::size_t(id)].flow == f ? 1 : 0;
        return n;
    });
}

}  // namespace

SweepInputs open_sweep(SweepSpec spec, std::shared_ptr<const Scene> scene, const SweepRunDef& def) {
    SweepInputs in;
    if (!scene && !spec.scene.empty()) scene = std::make_shared<const Scene>(read_scene(spec.scene));
    in.scene = std::move(scene);
    if (!spec.ground.empty()) in.ground = std::make_shared<const Scene>(read_scene(spec.ground));
    std::vector<debris::BodyDef> shapes;
    for (const auto& b : spec.bodies) shapes.push_back(b.def);
    in.world = debris::scaled_to_bodies(spec.world, shapes, spec.dt_max_given);  // scale-dependent settings follow the bodies
    in.world.threads = def.threads;
    in.world.read_ahead = def.read_ahead;
    for (const std::string& path : spec.flows) in.flows.push_back(debris::open_flow(path, in.world));
    in.spec = std::move(spec);
    check_member_count(in.spec);
    in.times = output_times(in, def.names);
    check_counted_work(in, def);  // before the members are built
    in.members = enumerate_members(in.spec);
    check_shard_work(in, def);
    return in;
}

namespace {

// Replays the members on flow f through one World, appending their records to r.
void run_flow(SweepInputs& in, const SweepRunDef& def, int f, const std::vector<const Member*>& on_flow, SweepResult& r,
              SweepRunStats& st) {
    const SweepSpec& spec = in.spec;
    std::vector<debris::BodyDef> bodies;
    std::vector<int> runs;
    for (const Member* m : on_flow) {
        bodies.push_back(m->def);
        runs.push_back(m->run);
    }
    debris::World world =
        debris::make_world(std::move(in.flows[std::size_t(f)]), in.scene.get(), bodies, in.world, in.ground.get(), runs);
    debris::TrajectorySeries series;
    debris::record(world, series);
    const std::string label = !def.progress_label.empty()
                                  ? def.progress_label
                                  : "sweep flow " + std::to_string(f + 1) + "/" + std::to_string(spec.flows.size()) + " (" +
                                        std::to_string(on_flow.size()) + " members)";
    Progress progress(label, r.time.back(), 10.0, def.quiet);
    long steps = 0;
    for (std::size_t k = 1; k < r.time.size(); ++k) {
        world.advance_to(r.time[k]);
        debris::record(world, series);
        steps = 0;
        for (const auto& s : world.stats()) steps += s.steps;
        progress.update(r.time[k], spec.output_interval, steps);
    }
    progress.finish(r.time.back(), steps);
    const std::vector<Impact> impacts = world.impacts();  // by body, then time
    for (std::size_t b = 0; b < on_flow.size(); ++b) {
        const Member& m = *on_flow[b];
        MemberRecord rec;
        static_cast<MemberIndex&>(rec) = m;
        rec.body_name = m.def.name;
        rec.start_name = spec.bodies[std::size_t(m.body)].start;
        rec.variant_name = spec.variants[std::size_t(m.variant)].name;
        rec.def = m.def;
        rec.heading0_deg = m.def.heading * 180.0 / std::numbers::pi;
        const debris::BodyStats& bs = world.stats()[b];
        rec.counts = bs;
        rec.track = std::move(series.tracks[b]);
        for (const Impact& i : impacts)
            if (std::size_t(i.trajectory) == b) rec.impacts.push_back(i);
        r.members.push_back(std::move(rec));
        st.steps += bs.steps;
    }
    st.flows_opened += 1;
    const debris::FlowReadStats read = world.flow().read_stats();
    st.frames_loaded += read.frames_loaded;
    st.cells_read += read.cells_read;
    st.frames_refit += read.frames_refit;
    st.window_cells += read.window_cells;
    st.io_seconds += read.load_seconds;
    st.read_cpu_seconds += read.load_cpu_seconds;
}

}  // namespace

SweepResult run_sweep(SweepInputs& in, const SweepRunDef& def, SweepRunStats* stats) {
    const auto wall0 = std::chrono::steady_clock::now();
    const auto range = shard_range(in.members, def.shard);
    SweepResult r = describe_sweep(in, def);
    SweepRunStats st;
    for (int f = 0; f < int(in.spec.flows.size()); ++f) {
        std::vector<const Member*> on_flow;
        for (int id = range[0]; id < range[1]; ++id)
            if (in.members[std::size_t(id)].flow == f) on_flow.push_back(&in.members[std::size_t(id)]);
        if (!on_flow.empty()) run_flow(in, def, f, on_flow, r, st);
    }
    st.members = int(r.members.size());
    st.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (stats) *stats = st;
    return r;
}

SweepResult run_sweep(const SweepSpec& spec, const SweepRunDef& def, SweepRunStats* stats) {
    SweepInputs in = open_sweep(spec, nullptr, def);
    return run_sweep(in, def, stats);
}

CollisionReport collision_report(const SweepResult& r) {
    CollisionReport c;
    for (const auto& m : r.members) {
        c.jammed += m.counts.jams;
        c.unresolved += m.counts.unresolved;
        c.members += (m.counts.jams + m.counts.unresolved) > 0 ? 1 : 0;
    }
    return c;
}

}  // namespace flotsam::sweep
