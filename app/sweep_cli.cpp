// flotsam sweep, flotsam sweep merge, flotsam stats: many debris runs over stored flows,
// and the statistics over them (docs/sweep.md).
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/output_lock.hpp"
#include "formats/scene.hpp"
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

struct MergeOptions {
    std::vector<std::string> parts;
    std::string out = "sweep.nc", summary;
};

struct StatsOptions {
    std::string sweep, scene, out = "stats.nc", csv;
    sweep::StatsDef def = sweep::default_stats_def();
};

// The impacts on buildings beside the summary (summary name with _impacts.csv), where there are any.
void write_impacts_beside(const std::string& summary, const sweep::SweepResult& r) {
    for (const auto& m : r.members)
        if (!m.impacts.empty()) return sweep::write_impacts_summary_csv(sweep::impacts_path_for(summary), r);
}

void run_sweep_command(const SweepOptions& o) {
    if (o.spec.empty()) fail("sweep", "--spec", "required (or use `flotsam sweep merge`)");
    sweep::SweepSpec spec = sweep::read_sweep_spec(o.spec, o.scene, o.flows);
    if (!o.ground.empty()) spec.ground = o.ground;
    const std::string summary = o.summary.empty() ? sweep::summary_path_for(o.out) : o.summary;
    std::vector<NamedPath> inputs = {{"--spec", o.spec}, {"--scene", spec.scene}, {"--ground", spec.ground}};
    for (const auto& f : spec.flows) inputs.push_back({"--flow", f});
    const OutputGuard guard({{"--out", o.out}, {o.summary.empty() ? "--summary (from --out)" : "--summary", summary}}, inputs);
    sweep::SweepRunDef def;
    def.shard = sweep::parse_shard(o.shard);
    def.threads = capped_threads(o.threads, "--threads", o.quiet);  // more than processors only slows a run down
    def.allow_large_run = o.allow_large_run;
    def.read_ahead = !o.no_read_ahead;
    def.quiet = o.quiet;
    sweep::SweepRunStats st;
    const sweep::SweepResult r = sweep::run_sweep(spec, def, &st);
    sweep::write_sweep_file(o.out, r);
    sweep::write_summary_csv(summary, r);
    write_impacts_beside(summary, r);
    if (!o.quiet)
        std::fprintf(stderr,
                     "sweep: %d of %d members (shard %s) over %zu flows, %zu frames read (%.1f s), %.1f s wall; wrote %s and %s\n",
                     st.members, r.member_count, o.shard.c_str(), st.flows_opened, st.frames_loaded, st.io_seconds, st.wall_seconds,
                     o.out.c_str(), summary.c_str());
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
    const OutputGuard guard({{"--out", o.out}, {"--csv", o.csv}}, {{"--sweep", o.sweep}, {"--scene", o.scene}});
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
    sweep_cmd->add_option("--spec", so->spec, "sweep spec (TOML, see docs/sweep.md)")->check(CLI::ExistingFile);
    sweep_cmd->add_option("--out", so->out, "trajectory file to write (CF trajectory NetCDF)")->capture_default_str();
    sweep_cmd->add_option("--summary", so->summary, "one-row-per-trajectory CSV (default: --out with .csv)");
    sweep_cmd->add_option("--shard", so->shard, "run block i of n of the member list (i/n); join with `sweep merge`")
        ->capture_default_str();
    sweep_cmd->add_option("--threads", so->threads, "OpenMP threads over members (0: default)")
        ->capture_default_str()
        ->check(in_range(Range::count(0, 4096)));
    sweep_cmd->add_flag("--no-read-ahead", so->no_read_ahead,
                        "read each frame on the stepping thread (default: one more thread reads the next frame meanwhile)");
    sweep_cmd->add_option("--scene", so->scene, "scene file (overrides the spec's [sweep] scene)")->check(CLI::ExistingFile);
    sweep_cmd
        ->add_option("--ground", so->ground,
                     "a finer scene of the same place for the bodies' ground, steps and buildings (overrides [sweep] "
                     "ground; docs/debris.md, \"Ground finer than the flow\")")
        ->check(CLI::ExistingFile);
    sweep_cmd->add_option("--flow", so->flows, "flow file (repeatable; replaces the spec's [flows])")->check(CLI::ExistingFile);
    sweep_cmd->add_flag("--quiet", so->quiet, "no progress lines");
    sweep_cmd->add_flag("--allow-large-run", so->allow_large_run,
                        "run even when the estimated work (steps x members) passes the bound flotsam stops at "
                        "(docs/reliability.md)");
    sweep_cmd->require_subcommand(0, 1);

    auto mo = std::make_shared<MergeOptions>();
    CLI::App* merge =
        sweep_cmd->add_subcommand("merge", "Join the shards of one sweep into one file (same bytes as an unsharded run)");
    merge->add_option("parts", mo->parts, "sweep files written with --shard")->required()->check(CLI::ExistingFile);
    merge->add_option("--out", mo->out, "merged trajectory file")->capture_default_str();
    merge->add_option("--summary", mo->summary, "one-row-per-trajectory CSV (default: --out with .csv)");
    merge->callback([mo] { run_merge_command(*mo); });
    sweep_cmd->callback([so, merge] {
        if (merge->parsed()) return;
        run_sweep_command(*so);
    });

    auto to = std::make_shared<StatsOptions>();
    CLI::App* stats =
        app.add_subcommand("stats", "The paper's statistics over a sweep, and per-cell pass probability and largest speed");
    add_config_option(stats);
    stats->add_option("--sweep", to->sweep, "sweep file (flotsam sweep, or merged)")->required()->check(CLI::ExistingFile);
    stats->add_option("--scene", to->scene, "scene with the sections and regions (default: the sweep's scene)")
        ->check(CLI::ExistingFile);
    stats->add_option("--out", to->out, "statistics file to write (NetCDF)")->capture_default_str();
    stats->add_option("--csv", to->csv, "also write CSV tables into this folder");
    stats->add_option("--arrival-time", to->def.arrival_time, "region counts at this time [s]")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("s")));
    stats
        ->add_option("--yaw-window", to->def.yaw_window,
                     "yaw statistics over this long after the run's start (paper Fig. 16) and after motion start [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    stats->add_option("--yaw-min-speed", to->def.yaw_min_speed, "yaw against the motion only when faster than this [m/s]")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("m/s")));
    stats->add_option("--yaw-bin", to->def.yaw_bin_width, "yaw histogram bin width [degree]")
        ->capture_default_str()
        ->check(in_range(Range::closed(0.01, 360.0, "degree")));
    stats
        ->add_option("--r-min-distance", to->def.r_min_distance,
                     "R(t) undefined where the control's mean distance is below this [m]")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("m")));
    stats->add_option("--kde-points", to->def.kde_points, "points on the speed axis of the densities")
        ->capture_default_str()
        ->check(in_range(Range::count(2, 1e6)));
    stats->add_option("--map-coarsen", to->def.map_coarsen, "map cell = this many scene cells per side")
        ->capture_default_str()
        ->check(in_range(Range::count(1, 1e4)));
    stats->callback([to, command_line] { run_stats_command(*to, command_line); });
}

}  // namespace flotsam
