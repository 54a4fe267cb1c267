#include "sweep/sweep.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/progress.hpp"
#include "debris/trajectory_output.hpp"
#include "debris/world.hpp"
#include "formats/scene.hpp"

namespace flotsam::sweep {

std::vector<double> sweep_output_times(const SweepSpec& spec) {
    double t0 = 0.0, last = 0.0;
    for (std::size_t f = 0; f < spec.flows.size(); ++f) {
        const debris::FlowReader probe(spec.flows[f]);
        if (f == 0) {
            t0 = probe.start_time();
            last = probe.end_time();
        } else if (probe.start_time() != t0) {
            fail(spec.flows[f], "time",
                 "starts at " + std::to_string(probe.start_time()) + " s, the sweep's first flow at " + std::to_string(t0) +
                     " s (all flows of a sweep share one time axis)");
        }
        last = std::min(last, probe.end_time());
    }
    const double t_end = spec.end_time > 0 ? spec.end_time : last;
    if (t_end < t0) fail(spec.path, "end_time", "before the flows' first frame");
    // t0 + k Δ from k (no accumulated round-off), the last one at t_end.
    std::vector<double> times{t0};
    for (long k = 1; times.back() < t_end; ++k) times.push_back(std::min(t0 + double(k) * spec.output_interval, t_end));
    return times;
}

SweepResult run_sweep(const SweepSpec& spec, const SweepRunDef& def, SweepRunStats* stats) {
    const auto wall0 = std::chrono::steady_clock::now();
    const std::vector<Member> all = enumerate_members(spec);
    const auto range = shard_range(int(all.size()), def.shard);

    SweepResult r;
    r.spec_file = spec.path;
    r.spec_sha256 = spec.sha256;
    r.scene_file = spec.scene;
    r.design = spec.design;
    r.flows = spec.flows;
    for (const auto& b : spec.bodies) r.bodies.push_back(b.name);
    for (const auto& v : spec.variants) r.variants.push_back(v.name);
    r.params = spec.params;
    r.perturbation = spec.perturbation;
    r.member_count = int(all.size());
    r.output_interval = spec.output_interval;
    std::vector<debris::BodyDef> shapes;
    for (const auto& b : spec.bodies) shapes.push_back(b.shape);
    debris::WorldDef wdef = debris::default_world_def(shapes);  // scale-dependent settings follow the bodies
    if (spec.dt_max > 0) wdef.step.dt_max = spec.dt_max;
    wdef.threads = def.threads;
    r.dt_max = wdef.step.dt_max;
    r.time = sweep_output_times(spec);
    r.shard = def.shard;
    // Every flow of a sweep comes from one scene; the first one's CRS is the sweep's.
    r.crs = cf::read_crs(nc::File::open_read(spec.flows.front()), "h");

    std::unique_ptr<Scene> scene;
    if (!spec.scene.empty()) scene = std::make_unique<Scene>(read_scene(spec.scene));
    SweepRunStats st;
    for (int f = 0; f < int(spec.flows.size()); ++f) {
        std::vector<const Member*> on_flow;
        for (int id = range[0]; id < range[1]; ++id)
            if (all[std::size_t(id)].flow == f) on_flow.push_back(&all[std::size_t(id)]);
        if (on_flow.empty()) continue;
        const std::string& path = spec.flows[std::size_t(f)];
        std::vector<std::uint8_t> building;
        if (scene) {
            const debris::FlowReader probe(path, wdef.flow);  // only for its grid
            building = debris::buildings_on_grid(*scene, probe.grid());
        }
        debris::World world(path, std::move(building), wdef);
        for (const Member* m : on_flow) {
            if (!world.covers(m->def.x, m->def.y))
                fail(spec.path, "body '" + m->def.name + "'", "start outside the grid of flow " + path);
            world.add_body(m->def);
        }
        debris::TrajectorySeries series;
        debris::record(world, series);
        Progress progress("sweep flow " + std::to_string(f + 1) + "/" + std::to_string(spec.flows.size()) + " (" +
                              std::to_string(on_flow.size()) + " members)",
                          r.time.back(), 10.0, def.quiet);
        long steps = 0;
        for (std::size_t k = 1; k < r.time.size(); ++k) {
            world.advance_to(r.time[k]);
            debris::record(world, series);
            steps = 0;
            for (const auto& s : world.stats()) steps += s.steps;
            progress.update(r.time[k], spec.output_interval, steps);
        }
        progress.finish(r.time.back(), steps);
        for (std::size_t b = 0; b < on_flow.size(); ++b) {
            const Member& m = *on_flow[b];
            MemberRecord rec;
            rec.id = m.id;
            rec.flow = m.flow;
            rec.body = m.body;
            rec.perturbation = m.perturbation;
            rec.variant = m.variant;
            rec.param_set = m.param_set;
            rec.body_name = m.def.name;
            rec.start_name = spec.bodies[std::size_t(m.body)].start;
            rec.variant_name = spec.variants[std::size_t(m.variant)].name;
            rec.contact = debris::to_string(m.def.contact);
            rec.collision = debris::to_string(m.def.collision);
            rec.params = {m.def.cd1, m.def.cd2, m.def.cm, m.def.mu, m.def.restitution};
            rec.length = m.def.length;
            rec.width = m.def.width;
            rec.height = m.def.height;
            rec.specific_gravity = m.def.specific_gravity;
            rec.x0 = m.def.x;
            rec.y0 = m.def.y;
            rec.heading0_deg = m.def.heading * 180.0 / std::numbers::pi;
            const debris::BodyStats& bs = world.stats()[b];
            rec.collision_steps = int(bs.collisions);
            rec.unresolved_collisions = int(bs.unresolved);
            rec.axis_shift_steps = int(bs.axis_shifts);
            rec.track = std::move(series.tracks[b]);
            r.members.push_back(std::move(rec));
            st.steps += bs.steps;
        }
        st.flows_opened += 1;
        st.frames_loaded += world.flow().frames_loaded();
        st.io_seconds += world.flow().load_seconds();
    }
    st.members = int(r.members.size());
    st.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (stats) *stats = st;
    return r;
}

}  // namespace flotsam::sweep
