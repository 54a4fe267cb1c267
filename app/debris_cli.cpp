// flotsam debris: replay one or more bodies through a stored flow and write their
// trajectories (debris/trajectory_output.hpp, schema in formats/trajectory_file.hpp).
#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <numbers>
#include <sstream>

#include "app/commands.hpp"
#include "app/sourced_bodies.hpp"
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
#include "sweep/sweep.hpp"

namespace flotsam {

namespace {

struct DebrisOptions {
    std::string flow, scene, ground, out = "trajectories.nc";
    std::string impacts_csv;  // "": no CSV of the impacts
    std::vector<std::string> starts, ats;
    std::string sources;                                   // GIS layer file of debris sources; "": none
    std::vector<std::string> source_layers;                // its layers to read; empty: all
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

// "x,y,heading_deg" → its three numbers.
std::array<double, 3> parse_at(const std::string& text) {
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
    return {v[0], v[1], v[2]};
}

// The run as a sweep of one flow: one control run of every body (as given), no
// perturbation; the bodies placed as a spec's are.
sweep::SweepSpec debris_spec(const DebrisOptions& o, bool dt_max_default, const Scene* scene) {
    const debris::BodyDef& base = o.body;
    sweep::SweepSpec spec;
    spec.scene = o.scene;
    spec.ground = o.ground;
    spec.flows = {o.flow};
    spec.output_interval = o.output_interval;
    spec.end_time = o.end_time;
    spec.world = o.world;
    spec.dt_max_given = !dt_max_default;
    spec.bodies_as_given = true;
    spec.one_world = true;  // every body of the run meets the others
    spec.design = "control";
    spec.params = {{"control", sweep::paper_control(), true}};
    spec.variants = {{"", base.contact, base.collision}};
    for (const auto& name : o.starts) {
        if (!scene) fail("--start", name, "needs --scene (the start points are named there)");
        const ScenePoint* p = sweep::scene_start(*scene, name);
        if (!p) fail(o.scene, "point '" + name + "'", "no start point of that name in the scene");
        spec.bodies.push_back(sweep::body_at(name, p->x, p->y, p->heading_deg, base));
        spec.bodies.back().start = name;
    }
    for (const auto& text : o.ats) {
        const auto at = parse_at(text);
        spec.bodies.push_back(sweep::body_at("body" + std::to_string(spec.bodies.size()), at[0], at[1], at[2], base));
    }
    for (auto& b : spec.bodies) b.type = o.body_type;
    if (!o.sources.empty()) {
        if (!scene) fail("--sources", o.sources, "needs --scene (its CRS places the layers, its buildings check the starts)");
        const std::vector<SourcedBody> sourced = bodies_from_sources(o.sources, o.source_layers, *scene, base, o.allow_large_run);
        for (const SourcedBody& s : sourced) spec.bodies.push_back(body_spec_of(s));
        if (!o.quiet) std::fprintf(stderr, "debris: %zu bodies from %s\n", sourced.size(), o.sources.c_str());
    }
    return spec;
}

// The trajectory file (and the impacts CSV) of the run, and the end-of-run lines.
void write_debris_outputs(const DebrisOptions& o, const sweep::SweepInputs& in, const sweep::SweepResult& r,
                          debris::TrajectoryFileDef file) {
    std::vector<debris::TrajectoryRecord> records;
    std::vector<Impact> impacts;  // by body, then time
    std::vector<std::string> names;
    for (std::size_t k = 0; k < r.members.size(); ++k) {
        const sweep::MemberRecord& m = r.members[k];
        const sweep::BodySpec& b = in.spec.bodies[std::size_t(m.body)];
        file.start_names.push_back(b.start);
        file.sources.push_back(b.source);
        file.body_types.push_back(b.type);
        for (Impact i : m.impacts) {
            i.trajectory = int(k);
            impacts.push_back(i);
        }
        names.push_back(m.def.name);
        records.push_back({m.def, m.counts, m.track});
    }
    debris::write_trajectory_file(o.out, records, r.time, impacts, r.world, file);
    if (!o.impacts_csv.empty()) write_impacts_csv(o.impacts_csv, impacts, names);
    if (o.quiet) return;
    double largest = 0.0;
    for (const auto& i : impacts) largest = std::max(largest, i.force);
    if (!impacts.empty()) std::fprintf(stderr, "impacts on buildings: %zu (largest force %.4g N)\n", impacts.size(), largest);
    const sweep::CollisionReport c = sweep::collision_report(r);
    // Said also when none (docs/debris.md, "Collisions").
    std::fprintf(stderr, "collisions: %ld jammed and %ld unresolved steps in %ld of %zu bodies (jammed_steps, unresolved_collisions)\n",
                 c.jammed, c.unresolved, c.members, records.size());
}

void run_debris(const DebrisOptions& o, bool dt_max_default, const std::string& command_line) {
    std::vector<NamedPath> outputs = {{"--out", o.out}};
    if (!o.impacts_csv.empty()) outputs.push_back({"--impacts", o.impacts_csv});
    const OutputGuard guard(outputs, {{"--flow", o.flow}, {"--scene", o.scene}, {"--ground", o.ground}, {"--sources", o.sources, true}});
    if (o.starts.empty() && o.ats.empty() && o.sources.empty())
        fail("debris", "bodies", "give at least one --start NAME, --at x,y,heading_deg or --sources FILE");
    if (!o.source_layers.empty() && o.sources.empty()) fail("--source-layer", o.source_layers.front(), "needs --sources FILE");
    std::shared_ptr<const Scene> scene;
    if (!o.scene.empty()) scene = std::make_shared<const Scene>(read_scene(o.scene));
    sweep::SweepRunDef def;
    def.threads = capped_threads(o.world.threads, "--threads", o.quiet);  // more than processors only slows a run down
    def.read_ahead = o.world.read_ahead;
    def.quiet = o.quiet;
    def.allow_large_run = o.allow_large_run;
    def.progress_label = "debris";
    def.names = {"--dt-max", "--vertex-step-fraction", "--output-interval", "--end-time"};
    sweep::SweepInputs in = sweep::open_sweep(debris_spec(o, dt_max_default, scene.get()), scene, def);
    // Positions are in the flow's frame: its CRS, if any, is the trajectories'.
    const debris::FlowDescription& flow = in.flows.front()->description();
    const debris::TrajectoryFileDef file{command_line, o.flow, {}, {}, {}, flow.crs, flow.scene_buildings_sha256};
    const std::clock_t cpu_start = std::clock();
    sweep::SweepRunStats st;
    const sweep::SweepResult r = sweep::run_sweep(in, def, &st);
    if (!o.quiet)  // for cost charts (pipelines/accuracy_debris.py); CPU time of all threads
        std::fprintf(stderr,
                     "debris cost: %d bodies, %ld steps, %.3f s CPU stepping, %.3f s CPU reading %zu frames (%.3f s wall waiting "
                     "for them)\n",
                     st.members, st.steps, double(std::clock() - cpu_start) / CLOCKS_PER_SEC - st.read_cpu_seconds,
                     st.read_cpu_seconds, st.frames_loaded, st.io_seconds);
    write_debris_outputs(o, in, r, file);
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
