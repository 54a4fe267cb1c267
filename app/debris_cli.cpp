// flotsam debris: replay one or more bodies through a stored flow and write their
// trajectories (debris/trajectory_output.hpp, schema in formats/trajectory_file.hpp).
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <numbers>
#include <sstream>

#include "app/commands.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/progress.hpp"
#include "debris/catalogue.hpp"
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
    std::string body_type;  // catalogue entry; "": the options' values (the paper's box)
    bool list_bodies = false;
};

// The body options that a catalogue entry sets when the command line leaves them out.
void apply_catalogue(DebrisOptions& o, const CLI::App* sub) {
    if (o.body_type.empty()) return;
    const debris::BodyDef c = debris::catalogue_body_def(o.body_type, "--body");
    auto take = [&](const char* option, double& field, double value) {
        if (sub->get_option(option)->count() == 0) field = value;
    };
    take("--length", o.body.length, c.length);
    take("--width", o.body.width, c.width);
    take("--height", o.body.height, c.height);
    take("--specific-gravity", o.body.specific_gravity, c.specific_gravity);
    take("--cd1", o.body.cd1, c.cd1);
    take("--cd2", o.body.cd2, c.cd2);
    take("--cm", o.body.cm, c.cm);
    take("--mu", o.body.mu, c.mu);
    take("--restitution", o.body.restitution, c.restitution);
}

void print_catalogue() {
    std::printf("%-22s %8s %7s %7s %10s %5s %5s %5s %5s %5s  %s\n", "name", "L [m]", "B [m]", "D [m]", "mass [kg]", "cd1", "cd2",
                "cm", "mu", "e", "description");
    for (const auto& b : debris::catalogue())
        std::printf("%-22s %8.3f %7.3f %7.3f %10.4g %5.2f %5.2f %5.2f %5.2f %5.2f  %s\n", b.name.c_str(), b.length, b.width,
                    b.height, b.mass, b.cd1, b.cd2, b.cm, b.mu, b.restitution, b.description.c_str());
}

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
        } catch (const std::exception&) {
            fail("--at", text, "expected x,y,heading_deg (numbers)");
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

void run_debris(const DebrisOptions& o, bool dt_max_default, const std::string& command_line) {
    debris::BodyDef base = o.body;
    base.contact = debris::parse_contact_model(o.contact);
    base.collision = debris::parse_collision_model(o.collision);
    base.added_mass = debris::parse_added_mass(o.added_mass);
    base.axis_shift = !o.no_axis_shift;
    if (!(o.output_interval > 0)) fail("--output-interval", std::to_string(o.output_interval), "must be positive");
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

    debris::WorldDef wdef = debris::default_world_def(bodies);
    if (!(o.dt_max > 0) && !dt_max_default) fail("--dt-max", std::to_string(o.dt_max), "must be positive");
    if (!(o.vertex_step_fraction > 0)) fail("--vertex-step-fraction", std::to_string(o.vertex_step_fraction), "must be positive");
    if (!dt_max_default) wdef.step.dt_max = o.dt_max;
    wdef.step.vertex_step_fraction = o.vertex_step_fraction;
    wdef.step.integrator = debris::parse_integrator(o.integrator);
    wdef.flow.time_interpolation = debris::parse_time_interpolation(o.time_interpolation);
    wdef.threads = o.threads;
    std::vector<std::uint8_t> building;
    {
        const debris::FlowReader probe(o.flow, wdef.flow);  // only for its grid
        if (scene) building = debris::buildings_on_grid(*scene, probe.grid());
    }
    debris::World world(o.flow, std::move(building), wdef);
    for (const auto& b : bodies) {
        if (!world.covers(b.x, b.y)) fail("body '" + b.name + "'", "position", "outside the flow grid");
        world.add_body(b);
    }
    const double t0 = world.time();
    const double t_end = o.end_time < 0 ? world.flow().end_time() : o.end_time;
    if (t_end < t0) fail("--end-time", std::to_string(t_end), "before the flow's first frame");

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
    // Positions are in the flow's frame: its CRS, if any, is the trajectories'.
    const cf::GridMapping crs = cf::read_crs(nc::File::open_read(o.flow), "h");
    debris::write_trajectory_file(o.out, world, series, {command_line, o.flow, start_names, crs});
}

}  // namespace

void register_debris_commands(CLI::App& app, const std::string& command_line) {
    auto opts = std::make_shared<DebrisOptions>();
    CLI::App* sub = app.add_subcommand("debris", "Replay debris bodies through a stored flow and write their trajectories");
    add_config_option(sub);
    sub->add_option("--flow", opts->flow, "flow file written by `flotsam hydro` (required)")->check(CLI::ExistingFile);
    sub->add_option("--scene", opts->scene, "scene file: building mask and named start points")->check(CLI::ExistingFile);
    sub->add_option("--start", opts->starts, "a body at this scene start point (repeatable)");
    sub->add_option("--at", opts->ats, "a body at x,y,heading_deg [m, m, degrees] (repeatable)");
    sub->add_option("--out", opts->out, "trajectory file to write (CF trajectory NetCDF)")->capture_default_str();
    sub->add_option("--cd1", opts->body.cd1, "drag coefficient, flow toward a face")->capture_default_str();
    sub->add_option("--cd2", opts->body.cd2, "drag coefficient, flow leaving a face")->capture_default_str();
    sub->add_option("--cm", opts->body.cm, "inertia coefficient Cm = 1 + Ca")->capture_default_str();
    sub->add_option("--mu", opts->body.mu, "friction coefficient with the ground")->capture_default_str();
    sub->add_option("--restitution", opts->body.restitution, "coefficient of restitution against obstacles")->capture_default_str();
    sub->add_option("--contact", opts->contact, "friction model: center (CC) or local (LC)")->capture_default_str();
    sub->add_option("--collision", opts->collision, "collision model: single (SC) or multi (MC)")->capture_default_str();
    sub->add_option("--added-mass", opts->added_mass, "implicit (stable) or explicit (for the stability study only)")
        ->capture_default_str();
    sub->add_flag("--no-axis-shift", opts->no_axis_shift, "local contact without the rotation about the contact centroid");
    sub->add_option("--length", opts->body.length, "body length [m]")->capture_default_str();
    sub->add_option("--width", opts->body.width, "body width [m]")->capture_default_str();
    sub->add_option("--height", opts->body.height, "body height [m]")->capture_default_str();
    sub->add_option("--specific-gravity", opts->body.specific_gravity, "body specific gravity")->capture_default_str();
    sub->add_option("--samples-per-face", opts->body.samples_per_face, "drag sample points per side face")->capture_default_str();
    sub->add_option("--step-tolerance", opts->body.step_tolerance, "ground above the bottom by more than this x draft blocks")
        ->capture_default_str();
    sub->add_option("--output-interval", opts->output_interval, "time between trajectory samples [s]")->capture_default_str();
    sub->add_option("--end-time", opts->end_time, "stop here [s] (default: the flow's last frame; later holds it steady)");
    sub->add_option("--dt-max", opts->dt_max,
                    "largest time step [s] (default: 0.01 s for the paper's 0.25 m box, scaled as sqrt(length / 0.25 m) for "
                    "the shortest body: the same step in Froude-scaled time at any scale)");
    sub->add_option("--vertex-step-fraction", opts->vertex_step_fraction,
                    "largest corner displacement per step, in grid cells (no tunnelling at the default)")
        ->capture_default_str();
    sub->add_option("--integrator", opts->integrator, "fluid-force stage: euler (semi-implicit) or heun (predictor-corrector)")
        ->capture_default_str();
    sub->add_option("--time-interpolation", opts->time_interpolation,
                    "between stored frames: linear or cubic (Catmull-Rom, guarded)")
        ->capture_default_str();
    sub->add_option("--threads", opts->threads, "OpenMP threads over bodies (0: default)")->capture_default_str();
    sub->add_flag("--quiet", opts->quiet, "no progress lines");
    sub->add_option("--body", opts->body_type,
                    "a body from the catalogue (docs/debris.md): its dimensions, mass and coefficients, unless given as "
                    "options; one of " +
                        debris::catalogue_names());
    sub->add_flag("--list-bodies", opts->list_bodies, "print the debris catalogue and exit");
    sub->callback([opts, sub, command_line] {
        if (opts->list_bodies) {
            print_catalogue();
            return;
        }
        if (opts->flow.empty()) fail("debris", "--flow", "required");
        apply_catalogue(*opts, sub);
        run_debris(*opts, sub->get_option("--dt-max")->count() == 0, command_line);
    });
}

}  // namespace flotsam
