// flotsam sweep, flotsam sweep merge, flotsam stats: many debris runs over stored flows,
// and the statistics over them (docs/sweep.md); each command's options from a settings
// table (common/settings.hpp).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>

#include "app/commands.hpp"
#include "app/sourced_bodies.hpp"
#include "app/settings_cli.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/output_lock.hpp"
#include "formats/scene.hpp"
#include "formats/stats_file.hpp"
#include "sweep/sweep.hpp"
#include "sweep/sweep_stats.hpp"

namespace flotsam {

namespace {

struct SweepOptions {
    std::string spec, out = "sweep.nc", summary, shard = "0/1", scene, ground;
    std::vector<std::string> flows;
    int threads = 0;
    bool no_read_ahead = false;
    bool quiet = false;
    bool allow_large_run = false;
};

const Settings<SweepOptions>& sweep_settings() {
    using O = SweepOptions;
    const OptionForm input{.existing_file = true, .no_default = true};
    static const Settings<O> table = {
        {"spec", "", "sweep spec (TOML, see docs/sweep.md)", Range(), &O::spec, input},
        {"out", "", "trajectory file to write (CF trajectory NetCDF)", Range(), &O::out},
        {"summary", "", "one-row-per-trajectory CSV (default: --out with .csv)", Range(), &O::summary, {.no_default = true}},
        {"shard", "", "run block i of n of the member list (i/n); join with `sweep merge`", Range(), &O::shard},
        {"threads", "1", "OpenMP threads over members (0: default)", Range::count(0, 4096), &O::threads},
        {"no-read-ahead",
         "",
         "read each frame on the stepping thread (default: one more thread reads the next frame meanwhile)",
         Range(),
         &O::no_read_ahead,
         {.no_default = true}},
        {"scene", "", "scene file (overrides the spec's [sweep] scene)", Range(), &O::scene, input},
        {"ground", "",
         "a finer scene of the same place for the bodies' ground, steps and buildings (overrides [sweep] ground; "
         "docs/debris.md, \"Ground finer than the flow\")",
         Range(), &O::ground, input},
        {"flow", "", "flow file (repeatable; replaces the spec's [flows])", Range(), &O::flows, input},
        {"quiet", "", "no progress lines", Range(), &O::quiet, {.no_default = true}},
        {"allow-large-run",
         "",
         "run even when the estimated work (steps x members) passes the bound flotsam stops at (docs/reliability.md)",
         Range(),
         &O::allow_large_run,
         {.no_default = true}},
    };
    return table;
}

struct MergeOptions {
    std::vector<std::string> parts;
    std::string out = "sweep.nc", summary;
};

const Settings<MergeOptions>& merge_settings() {
    using O = MergeOptions;
    static const Settings<O> table = {
        {"out", "", "merged trajectory file", Range(), &O::out},
        {"summary", "", "one-row-per-trajectory CSV (default: --out with .csv)", Range(), &O::summary, {.no_default = true}},
    };
    return table;
}

struct StatsOptions {
    std::string sweep, scene, out = "stats.nc", csv;
    sweep::StatsDef def = sweep::default_stats_def();
};

const Settings<StatsOptions>& stats_settings() {
    using O = StatsOptions;
    using sweep::StatsDef;
    static const Settings<O> table = {
        {"sweep",
         "",
         "sweep file (flotsam sweep, or merged)",
         Range(),
         &O::sweep,
         {.required = true, .existing_file = true, .no_default = true}},
        {"scene",
         "",
         "scene with the sections and regions (default: the sweep's scene)",
         Range(),
         &O::scene,
         {.existing_file = true, .no_default = true}},
        {"out", "", "statistics file to write (NetCDF)", Range(), &O::out},
        {"csv", "", "also write CSV tables into this folder", Range(), &O::csv, {.no_default = true}},
        {"arrival-time", "s", "region counts at this time", Range::non_negative("s"),
         member_of<&O::def, &StatsDef::arrival_time>()},
        {"yaw-window", "s", "yaw statistics over this long after the run's start (paper Fig. 16) and after motion start",
         Range::positive("s"), member_of<&O::def, &StatsDef::yaw_window>()},
        {"yaw-min-speed", "m/s", "yaw against the motion only when faster than this", Range::non_negative("m/s"),
         member_of<&O::def, &StatsDef::yaw_min_speed>()},
        {"yaw-bin", "degree", "yaw histogram bin width", Range::closed(0.01, 360.0, "degree"),
         member_of<&O::def, &StatsDef::yaw_bin_width>()},
        {"r-min-distance", "m", "R(t) undefined where the control's mean distance is below this", Range::non_negative("m"),
         member_of<&O::def, &StatsDef::r_min_distance>()},
        {"kde-points", "1", "points on the speed axis of the densities", Range::count(2, 1e6),
         member_of<&O::def, &StatsDef::kde_points>()},
        {"map-coarsen", "1", "map cell = this many scene cells per side", Range::count(1, 1e4),
         member_of<&O::def, &StatsDef::map_coarsen>()},
    };
    return table;
}

// The impacts on buildings beside the summary (summary name with _impacts.csv), where there are any.
void write_impacts_beside(const std::string& summary, const sweep::SweepResult& r) {
    for (const auto& m : r.members)
        if (!m.impacts.empty()) return sweep::write_impacts_summary_csv(sweep::impacts_path_for(summary), r);
}

void run_sweep_command(const SweepOptions& o) {
    if (o.spec.empty()) fail("sweep", "--spec", "required (or use `flotsam sweep merge`)");
    std::shared_ptr<const Scene> scene;
    sweep::SweepSpec spec = sweep::read_sweep_spec(o.spec, {o.scene, o.ground, o.flows}, &scene);
    std::vector<NamedPath> inputs = {{"--spec", o.spec}, {"--scene", spec.scene}, {"--ground", spec.ground}};
    for (const auto& f : spec.flows) inputs.push_back({"--flow", f});
    for (const auto& s : spec.sources) inputs.push_back({"[[sources]] file", s.file, true});
    expand_sources(spec, scene.get(), o.allow_large_run);
    const std::string summary = o.summary.empty() ? sweep::summary_path_for(o.out) : o.summary;
    const OutputGuard guard({{"--out", o.out}, {o.summary.empty() ? "--summary (from --out)" : "--summary", summary}}, inputs);
    sweep::SweepRunDef def;
    def.shard = sweep::parse_shard(o.shard);
    def.threads = capped_threads(o.threads, "--threads", o.quiet);  // more than processors only slows a run down
    def.allow_large_run = o.allow_large_run;
    def.read_ahead = !o.no_read_ahead;
    def.quiet = o.quiet;
    sweep::SweepRunStats st;
    sweep::SweepInputs in = sweep::open_sweep(std::move(spec), std::move(scene), def);
    const sweep::SweepResult r = sweep::run_sweep(in, def, &st);
    sweep::write_sweep_file(o.out, r);
    sweep::write_summary_csv(summary, r);
    write_impacts_beside(summary, r);
    if (!o.quiet) {
        std::fprintf(stderr,
                     "sweep: %d of %d members (shard %s) over %zu flows, %zu frames read (%.1f s), %.1f s wall; wrote %s and %s\n",
                     st.members, r.member_count, o.shard.c_str(), st.flows_opened, st.frames_loaded, st.io_seconds, st.wall_seconds,
                     o.out.c_str(), summary.c_str());
        const sweep::CollisionReport c = sweep::collision_report(r);
        // Said also when none: a study's log shows the collisions were all resolved (docs/debris.md, "Collisions").
        std::fprintf(stderr, "sweep: %ld jammed and %ld unresolved collision steps in %ld members (columns jammed_steps, "
                     "unresolved_collisions of %s)\n",
                     c.jammed, c.unresolved, c.members, summary.c_str());
    }
}

void run_merge_command(const MergeOptions& o) {
    const std::string summary = o.summary.empty() ? sweep::summary_path_for(o.out) : o.summary;
    std::vector<NamedPath> inputs;
    for (const auto& p : o.parts) inputs.push_back({"part", p});
    const OutputGuard guard({{"--out", o.out}, {o.summary.empty() ? "--summary (from --out)" : "--summary", summary}}, inputs);
    std::vector<sweep::SweepResult> parts;
    for (const auto& p : o.parts) parts.push_back(sweep::read_sweep_file(p));
    const sweep::SweepResult r = sweep::merge_sweeps(parts, o.parts);
    sweep::write_sweep_file(o.out, r);
    sweep::write_summary_csv(summary, r);
    write_impacts_beside(summary, r);
}

void run_stats_command(const StatsOptions& o, const std::string& command_line) {
    // --csv names a folder the tables go into (each table written whole, then renamed):
    // an existing folder is reused, a file there is refused; one writer at a time.
    if (!o.csv.empty() && std::filesystem::exists(o.csv) && !std::filesystem::is_directory(o.csv))
        fail("--csv", o.csv, "is a file: --csv names the folder the CSV tables are written into");
    std::vector<NamedPath> outputs = {{"--out", o.out}};
    if (!o.csv.empty())  // the tables written into the folder are outputs too
        for (const auto& p : stats_file::csv_paths(o.csv)) outputs.push_back({"--csv", p});
    const OutputGuard guard(outputs, {{"--sweep", o.sweep}, {"--scene", o.scene}});
    std::optional<OutputLock> csv_lock;
    if (!o.csv.empty()) csv_lock.emplace(o.csv);
    const sweep::SweepResult r = sweep::read_sweep_file(o.sweep);
    const std::string scene_path = o.scene.empty() ? r.scene_file : o.scene;
    if (scene_path.empty())
        fail(o.sweep, "scene_file", "the sweep names no scene: give --scene (its sections and regions are needed)");
    const Scene scene = read_scene(scene_path);
    // The sweep's trajectories are positions on its flows' scene: the same grid, bed and
    // buildings (when the sweep recorded them) and the same CRS.
    if (!r.scene_buildings_sha256.empty() && r.scene_buildings_sha256 != scene_buildings_sha256(scene))
        fail(o.sweep, "",
             "was run on another scene than " + scene_path + " (the grid or the building mask differ: scene_buildings_sha256 " +
                 r.scene_buildings_sha256 + " in the sweep, " + scene_buildings_sha256(scene) + " for the scene); give the sweep's scene (" +
                 r.scene_file + ")");
    cf::check_same_crs(o.sweep, r.crs, scene_path, scene.crs);
    sweep::check_tracks_on(r, scene.grid, "the grid of the scene " + scene_path);
    const sweep::SweepStats s = sweep::compute_stats(r, scene, o.def);
    sweep::write_stats_file(o.out, s, o.def, o.sweep, scene_path, command_line);
    if (!o.csv.empty()) sweep::write_stats_csv(o.csv, s, r);
}

}  // namespace

void register_pipeline_commands(CLI::App& app, const std::string& command_line) {
    auto so = std::make_shared<SweepOptions>();
    CLI::App* sweep_cmd = app.add_subcommand(
        "sweep", "Run a sweep (flows x bodies x variants x parameter sets x start perturbations) from a TOML spec");
    add_config_option(sweep_cmd);
    add_setting_options(sweep_cmd, sweep_settings(), *so);
    sweep_cmd->require_subcommand(0, 1);

    auto mo = std::make_shared<MergeOptions>();
    CLI::App* merge =
        sweep_cmd->add_subcommand("merge", "Join the shards of one sweep into one file (same bytes as an unsharded run)");
    merge->add_option("parts", mo->parts, "sweep files written with --shard")->required()->check(CLI::ExistingFile);
    add_setting_options(merge, merge_settings(), *mo);
    merge->callback([mo] { run_merge_command(*mo); });
    sweep_cmd->callback([so, merge] {
        if (merge->parsed()) return;
        run_sweep_command(*so);
    });

    auto to = std::make_shared<StatsOptions>();
    CLI::App* stats =
        app.add_subcommand("stats", "The paper's statistics over a sweep, and per-cell pass probability and largest speed");
    add_config_option(stats);
    add_setting_options(stats, stats_settings(), *to);
    stats->callback([to, command_line] { run_stats_command(*to, command_line); });
}

}  // namespace flotsam
