// flotsam debris: replay one or more bodies through a stored flow and write their
// trajectories (debris/trajectory_output.hpp, schema in formats/trajectory_file.hpp).
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <numbers>
#include <sstream>

#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/output_lock.hpp"
#include "common/progress.hpp"
#include "debris/scene_match.hpp"
#include "debris/trajectory_output.hpp"
#include "debris/world.hpp"
#include "formats/scene.hpp"

namespace flotsam {

namespace {

struct DebrisOptions {
    std::string flow, scene, out = "trajectories.nc";
    std::vector<std::string> starts, ats;
    std::string contact = "local", collision = "multi", added_mass = "implicit";
    debris::BodyDef body = debris::default_body_def();
    bool no_axis_shift = false;
    double output_interval = 0.5;  // [s]
    double end_time = -1.0;        // [s]; < 0: the flow's last frame
    double dt_max = debris::default_step_def().dt_max;
    double vertex_step_fraction = debris::default_step_def().vertex_step_fraction;
    std::string integrator = debris::to_string(debris::default_step_def().integrator);
    std::string time_interpolation = debris::to_string(debris::default_flow_reader_def().time_interpolation);
    int threads = 0;
    bool quiet = false;
};

// "x,y,heading_deg" → a body at that place.
debris::BodyDef parse_at(const std::string& text, const debris::BodyDef& base, int index) {
    std::stringstream ss(text);
    std::string part;
    std::vector<double> v;
    while (std::getline(ss, part, ',')) {
        try {
            std::size_t used = 0;
            v.push_back(std::stod(part, &used));
            if (used != part.size()) throw std::invalid_argument(part);
            if (!std::isfinite(v.back())) throw std::invalid_argument(part);
        } catch (const std::exception&) {
            fail("--at", text, "expected x,y,heading_deg (finite numbers)");
        }
    }
    if (v.size() != 3) fail("--at", text, "expected x,y,heading_deg (three numbers)");
    debris::BodyDef b = base;
    b.name = "body" + std::to_string(index);
    b.x = v[0];
    b.y = v[1];
    b.heading = v[2] * std::numbers::pi / 180.0;
    return b;
}

void run_debris(const DebrisOptions& o, const std::string& command_line) {
    debris::BodyDef base = o.body;
    base.contact = debris::parse_contact_model(o.contact);
    base.collision = debris::parse_collision_model(o.collision);
    base.added_mass = debris::parse_added_mass(o.added_mass);
    base.axis_shift = !o.no_axis_shift;
    const OutputGuard guard({{"--out", o.out}}, {{"--flow", o.flow}, {"--scene", o.scene}});
    if (o.starts.empty() && o.ats.empty()) fail("debris", "bodies", "give at least one --start NAME or --at x,y,heading_deg");

    std::unique_ptr<Scene> scene;
    if (!o.scene.empty()) scene = std::make_unique<Scene>(read_scene(o.scene));
    std::vector<debris::BodyDef> bodies;
    std::vector<std::string> start_names;
    for (const auto& name : o.starts) {
        if (!scene) fail("--start", name, "needs --scene (the start points are named there)");
        const ScenePoint* p = scene->find_point(name);
        if (!p || p->kind != "start") fail(o.scene, "point '" + name + "'", "no start point of that name in the scene");
        debris::BodyDef b = base;
        b.name = name;
        b.x = p->x;
        b.y = p->y;
        b.heading = p->heading_deg * std::numbers::pi / 180.0;
        bodies.push_back(b);
        start_names.push_back(name);
    }
    for (const auto& at : o.ats) {
        bodies.push_back(parse_at(at, base, int(bodies.size())));
        start_names.emplace_back();
    }

    debris::WorldDef wdef = debris::default_world_def();
    if (!(o.dt_max > 0)) fail("--dt-max", std::to_string(o.dt_max), "must be positive");
    if (!(o.vertex_step_fraction > 0)) fail("--vertex-step-fraction", std::to_string(o.vertex_step_fraction), "must be positive");
    wdef.step.dt_max = o.dt_max;
    wdef.step.vertex_step_fraction = o.vertex_step_fraction;
    wdef.step.integrator = debris::parse_integrator(o.integrator);
    wdef.flow.time_interpolation = debris::parse_time_interpolation(o.time_interpolation);
    wdef.threads = o.threads;
    std::vector<std::uint8_t> building;
    {
        const debris::FlowReader probe(o.flow, wdef.flow);  // only for its grid
        if (scene) {
            debris::check_flow_matches_scene(probe, *scene);
            building = debris::buildings_on_grid(*scene, probe.grid());
        }
        for (const auto& b : bodies) debris::check_body_start(b, probe, scene.get());
    }
    debris::World world(o.flow, std::move(building), wdef);
    for (const auto& b : bodies) {
        world.add_body(b);
    }
    const double t0 = world.time();
    const double t_end = o.end_time < 0 ? world.flow().end_time() : o.end_time;
    if (t_end < t0) fail("--end-time", std::to_string(t_end), "before the flow's first frame");
    check_allocation("--output-interval", number_text(o.output_interval) + " s", (t_end - t0) / o.output_interval + 2,
                     7.0 * sizeof(double) * double(bodies.size()), "trajectory samples");

    debris::TrajectorySeries series;
    debris::record(world, series);
    Progress progress("debris", t_end, 10.0, o.quiet);
    const std::clock_t cpu_start = std::clock();
    // Output times t0 + k Δ, computed from k (no accumulated round-off), ending at t_end.
    for (long k = 1;; ++k) {
        const double t = std::min(t0 + double(k) * o.output_interval, t_end);
        world.advance_to(t);
        debris::record(world, series);
        long steps = 0;
        for (const auto& s : world.stats()) steps += s.steps;
        progress.update(t, o.output_interval, steps);
        if (t >= t_end) break;
    }
    long steps = 0;
    for (const auto& s : world.stats()) steps += s.steps;
    progress.finish(t_end, steps);
    if (!o.quiet) {  // for cost charts (pipelines/accuracy_debris.py); CPU time of all threads
        const double cpu = double(std::clock() - cpu_start) / CLOCKS_PER_SEC, reading = world.flow().load_cpu_seconds();
        std::fprintf(stderr,
                     "debris cost: %zu bodies, %ld steps, %.3f s CPU stepping, %.3f s CPU reading %zu frames (%.3f s wall)\n",
                     world.size(), steps, cpu - reading, reading, world.flow().frames_loaded(), world.flow().load_seconds());
    }
    debris::write_trajectory_file(o.out, world, series, {command_line, o.flow, start_names});
}

}  // namespace

void register_debris_commands(CLI::App& app, const std::string& command_line) {
    auto opts = std::make_shared<DebrisOptions>();
    CLI::App* sub = app.add_subcommand("debris", "Replay debris bodies through a stored flow and write their trajectories");
    add_config_option(sub);
    sub->add_option("--flow", opts->flow, "flow file written by `flotsam hydro`")->required()->check(CLI::ExistingFile);
    sub->add_option("--scene", opts->scene, "scene file: building mask and named start points")->check(CLI::ExistingFile);
    sub->add_option("--start", opts->starts, "a body at this scene start point (repeatable)");
    sub->add_option("--at", opts->ats, "a body at x,y,heading_deg [m, m, degrees] (repeatable)");
    sub->add_option("--out", opts->out, "trajectory file to write (CF trajectory NetCDF)")->capture_default_str();
    sub->add_option("--cd1", opts->body.cd1, "drag coefficient, flow toward a face")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("cd1")));
    sub->add_option("--cd2", opts->body.cd2, "drag coefficient, flow leaving a face")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("cd2")));
    sub->add_option("--cm", opts->body.cm, "inertia coefficient Cm = 1 + Ca")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("cm")));
    sub->add_option("--mu", opts->body.mu, "friction coefficient with the ground")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("mu")));
    sub->add_option("--restitution", opts->body.restitution, "coefficient of restitution against obstacles")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("restitution")));
    sub->add_option("--contact", opts->contact, "friction model: center (CC) or local (LC)")->capture_default_str();
    sub->add_option("--collision", opts->collision, "collision model: single (SC) or multi (MC)")->capture_default_str();
    sub->add_option("--added-mass", opts->added_mass, "implicit (stable) or explicit (for the stability study only)")
        ->capture_default_str();
    sub->add_flag("--no-axis-shift", opts->no_axis_shift, "local contact without the rotation about the contact centroid");
    sub->add_option("--length", opts->body.length, "body length [m]")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("length")));
    sub->add_option("--width", opts->body.width, "body width [m]")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("width")));
    sub->add_option("--height", opts->body.height, "body height [m]")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("height")));
    sub->add_option("--specific-gravity", opts->body.specific_gravity, "body specific gravity")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("specific_gravity")));
    sub->add_option("--samples-per-face", opts->body.samples_per_face, "drag sample points per side face")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("samples_per_face")));
    sub->add_option("--step-tolerance", opts->body.step_tolerance, "ground above the bottom by more than this x draft blocks")
        ->capture_default_str()
        ->check(in_range(debris::body_parameter_range("step_tolerance")));
    sub->add_option("--output-interval", opts->output_interval, "time between trajectory samples [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    sub->add_option("--end-time", opts->end_time, "stop here [s] (default: the flow's last frame; later holds it steady)")
        ->check(in_range(Range::non_negative("s")));
    sub->add_option("--dt-max", opts->dt_max, "largest time step [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    sub->add_option("--vertex-step-fraction", opts->vertex_step_fraction,
                    "largest corner displacement per step, in grid cells (no tunnelling at the default)")
        ->capture_default_str()
        ->check(in_range(Range::positive().up_to(10.0)));
    sub->add_option("--integrator", opts->integrator, "fluid-force stage: euler (semi-implicit) or heun (predictor-corrector)")
        ->capture_default_str();
    sub->add_option("--time-interpolation", opts->time_interpolation,
                    "between stored frames: linear or cubic (Catmull-Rom, guarded)")
        ->capture_default_str();
    sub->add_option("--threads", opts->threads, "OpenMP threads over bodies (0: default)")
        ->capture_default_str()
        ->check(in_range(Range::count(0, 4096)));
    sub->add_flag("--quiet", opts->quiet, "no progress lines");
    sub->callback([opts, command_line] { run_debris(*opts, command_line); });
}

}  // namespace flotsam
