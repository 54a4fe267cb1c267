// flotsam debris: replay one or more bodies through a stored flow and write their
// trajectories (debris/trajectory_output.hpp, schema in formats/trajectory_file.hpp).
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <numbers>
#include <sstream>

#include "app/commands.hpp"
#include "app/debris_sources.hpp"
#include "app/settings_cli.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/output_lock.hpp"
#include "common/progress.hpp"
#include "debris/catalogue.hpp"
#include "debris/scene_match.hpp"
#include "debris/trajectory_output.hpp"
#include "debris/world.hpp"
#include "formats/impact_file.hpp"
#include "formats/scene.hpp"

namespace flotsam {

namespace {

struct DebrisOptions {
    std::string flow, scene, ground, out = "trajectories.nc";
    std::string impacts_csv;  // "": no CSV of the impacts
    std::vector<std::string> starts, ats;
    std::string sources;                     // GIS layer file of debris sources; "": none
    std::vector<std::string> source_layers;  // its layers to read; empty: all
    debris::BodyDef body = debris::default_body_def();     // every body's settings
    debris::WorldDef world = debris::default_world_def();  // step, flow replay, threads
    double output_interval = 0.5;                          // [s]
    double end_time = -1.0;                                // [s]; < 0: the flow's last frame
    bool quiet = false;
    std::string body_type;  // catalogue entry; "": the options' values (the paper's box)
    bool list_bodies = false;
    bool allow_large_run = false;  // run even past the bounds of check_replay_work
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
    o.body.impact_stiffness = c.impact_stiffness;
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

void run_debris(const DebrisOptions& o, bool dt_max_default, const std::string& command_line) {
    const debris::BodyDef& base = o.body;
    std::vector<NamedPath> outputs = {{"--out", o.out}};
    if (!o.impacts_csv.empty()) outputs.push_back({"--impacts", o.impacts_csv});
    const OutputGuard guard(outputs, {{"--flow", o.flow}, {"--scene", o.scene}, {"--ground", o.ground}});
    if (o.starts.empty() && o.ats.empty() && o.sources.empty())
        fail("debris", "bodies", "give at least one --start NAME, --at x,y,heading_deg or --sources FILE");
    if (!o.source_layers.empty() && o.sources.empty()) fail("--source-layer", o.source_layers.front(), "needs --sources FILE");

    std::unique_ptr<Scene> scene;
    if (!o.scene.empty()) scene = std::make_unique<Scene>(read_scene(o.scene));
    std::unique_ptr<Scene> ground;
    if (!o.ground.empty()) ground = std::make_unique<Scene>(read_scene(o.ground));
    std::vector<debris::BodyDef> bodies;
    std::vector<std::string> start_names, sources, types;
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
    types.assign(bodies.size(), o.body_type);
    sources.assign(bodies.size(), "");
    if (!o.sources.empty()) {
        if (!scene) fail("--sources", o.sources, "needs --scene (its CRS places the layers, its buildings check the starts)");
        for (const SourcedBody& s : bodies_from_sources(o.sources, o.source_layers, *scene, base)) {
            bodies.push_back(s.def);
            start_names.emplace_back();
            sources.push_back(s.source);
            types.push_back(s.type);
        }
        if (!o.quiet) std::fprintf(stderr, "debris: %zu bodies from %s\n", bodies.size() - o.starts.size() - o.ats.size(), o.sources.c_str());
    }

    debris::WorldDef wdef = debris::scaled_to_bodies(o.world, bodies, !dt_max_default);
    // More threads than processors only slow a run down, and thousands cannot be started.
    wdef.threads = capped_threads(wdef.threads, "--threads", o.quiet);
    debris::World world = debris::make_world(o.flow, scene.get(), bodies, wdef, ground.get());
    const double t0 = world.time();
    const double t_end = o.end_time < 0 ? world.flow().end_time() : o.end_time;
    if (t_end < t0) fail("--end-time", std::to_string(t_end), "before the flow's first frame");
    debris::check_replay_work(world.flow(), world.obstacles().grid(), wdef.step, t0, t_end, double(bodies.size()),
                              o.allow_large_run, "--dt-max", "--vertex-step-fraction");
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
                     "debris cost: %zu bodies, %ld steps, %.3f s CPU stepping, %.3f s CPU reading %zu frames (%.3f s wall waiting "
                     "for them)\n",
                     world.size(), steps, cpu - reading, reading, world.flow().frames_loaded(), world.flow().load_seconds());
    }
    // Positions are in the flow's frame: its CRS, if any, is the trajectories'.
    debris::write_trajectory_file(o.out, world, series,
                                  {command_line, o.flow, start_names, sources, types, world.flow().crs(),
                                   world.flow().scene_buildings_sha256()});
    if (!o.impacts_csv.empty()) {
        std::vector<std::string> names;
        for (const auto& p : world.params()) names.push_back(p.def.name);
        write_impacts_csv(o.impacts_csv, world.impacts(), names);
    }
    if (!o.quiet) {
        const auto impacts = world.impacts();
        double largest = 0.0;
        for (const auto& i : impacts) largest = std::max(largest, i.force);
        if (!impacts.empty()) std::fprintf(stderr, "impacts on buildings: %zu (largest force %.4g N)\n", impacts.size(), largest);
        long jammed = 0, unresolved = 0, bodies = 0;
        for (const auto& s : world.stats()) {
            jammed += s.jams;
            unresolved += s.unresolved;
            bodies += (s.jams + s.unresolved) > 0 ? 1 : 0;
        }
        if (bodies > 0)  // docs/debris.md, "Collisions"
            std::fprintf(stderr, "collisions: %ld jammed and %ld unresolved steps in %ld of %zu bodies (jammed_steps, unresolved_collisions)\n",
                         jammed, unresolved, bodies, world.size());
    }
}

}  // namespace

void register_debris_commands(CLI::App& app, const std::string& command_line) {
    auto opts = std::make_shared<DebrisOptions>();
    CLI::App* sub = app.add_subcommand("debris", "Replay debris bodies through a stored flow and write their trajectories");
    add_config_option(sub);
    sub->add_option("--flow", opts->flow, "flow file written by `flotsam hydro` (required)")->check(CLI::ExistingFile);
    sub->add_option("--scene", opts->scene, "scene file: building mask and named start points")->check(CLI::ExistingFile);
    sub->add_option("--ground", opts->ground,
                    "a finer scene of the same place: the bodies' ground, steps and buildings (docs/debris.md, \"Ground "
                    "finer than the flow\")")
        ->check(CLI::ExistingFile);
    sub->add_option("--start", opts->starts, "a body at this scene start point (repeatable)");
    sub->add_option("--at", opts->ats, "a body at x,y,heading_deg [m, m, degrees] (repeatable)");
    sub->add_option("--sources", opts->sources,
                    "debris sources from a GIS vector file: points (a body each) and yard polygons (filled with bodies); "
                    "attributes in docs/gis.md, \"Debris sources\"; needs --scene")
        ->check(CLI::ExistingFile);
    sub->add_option("--source-layer", opts->source_layers, "a layer of the --sources file to read (repeatable; default: all)");
    sub->add_option("--out", opts->out, "trajectory file to write (CF trajectory NetCDF)")->capture_default_str();
    sub->add_option("--impacts", opts->impacts_csv,
                    "also write the impacts on buildings as CSV, one row each (docs/debris.md, \"Impacts on buildings\")");
    add_setting_options(sub, debris::body_variant_settings(), opts->body);
    add_setting_options(sub, debris::body_coefficient_settings(), opts->body);
    add_setting_options(sub, debris::body_model_settings(), opts->body);
    add_setting_options(sub, debris::body_shape_settings(), opts->body);
    sub->add_option("--output-interval", opts->output_interval, "time between trajectory samples [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    sub->add_option("--end-time", opts->end_time, "stop here [s] (default: the flow's last frame; later holds it steady)")
        ->check(in_range(Range::non_negative("s")));
    add_setting_options(sub, debris::step_settings(), opts->world.step);
    add_setting_options(sub, debris::flow_replay_settings(), opts->world.flow);
    sub->add_option("--threads", opts->world.threads, "OpenMP threads over bodies (0: default)")
        ->capture_default_str()
        ->check(in_range(Range::count(0, 4096)));
    sub->add_flag("!--no-read-ahead", opts->world.read_ahead,
                  "read each frame on the stepping thread (default: one more thread reads the next frame meanwhile)");
    sub->add_flag("--quiet", opts->quiet, "no progress lines");
    sub->add_flag("--allow-large-run", opts->allow_large_run,
                  "run even when the estimated work (steps x bodies) passes the bound flotsam stops at (docs/reliability.md)");
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
