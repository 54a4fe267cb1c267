// What a hydro run writes besides the stepping (run_driver.hpp): the flow file's
// definition, a fresh start, a restart and the checkpoints.
#include <cstdio>
#include <filesystem>

#include "common/error.hpp"
#include "common/sha256.hpp"
#include "common/version.hpp"
#include "hydro/restart_key.hpp"
#include "hydro/run_driver.hpp"

namespace flotsam::hydro {

namespace {

std::string boundary_files(const PhysicsDef& d) {
    std::string s;
    const BoundaryDef* sides[4] = {&d.west, &d.east, &d.south, &d.north};
    const char* names[4] = {"west", "east", "south", "north"};
    for (int k = 0; k < 4; ++k)
        for (const std::string& f : {sides[k]->series_file, sides[k]->forcing_file})
            if (!f.empty()) s += std::string(s.empty() ? "" : "; ") + names[k] + ": " + f;
    return s;
}

std::string boundary_checksums(const PhysicsDef& d) {
    std::string s;
    for (const BoundaryDef* b : {&d.west, &d.east, &d.south, &d.north})
        for (const std::string& f : {b->series_file, b->forcing_file})
            if (!f.empty()) s += std::string(s.empty() ? "" : "; ") + "sha256:" + sha256_file(f);
    return s;
}

std::vector<FlowGauge> gauge_points_of(const Scene& scene, const RunDef& run) {
    std::vector<FlowGauge> points;
    for (const auto& p : scene.points)
        if (p.kind == "gauge") points.push_back({p.name, p.x, p.y});
    for (const auto& g : run.gauges) points.push_back(g);
    return points;
}

// The flow file's definition: the window's bed, the axes, the gauges and the global
// attributes that say how the flow was made.
FlowFileDef flow_file_def(const Scene& scene, const RunDef& run, const PhysicsDef& def, const RunOutput& o,
                          const std::string& scheme) {
    FlowFileDef fd;
    fd.window = o.win.grid;
    fd.z = window_bed(scene, o.win);
    fd.frame_times = o.times;
    fd.gauges = o.gauge_points;
    fd.gauge_samples = o.gauges.samples();
    fd.gauge_interval = run.gauge_interval;
    fd.arrival_depth = run.arrival_depth;
    fd.flood_depth = run.flood_depth;
    fd.deflate_level = run.deflate_level;
    fd.crs = scene.crs;
    fd.attributes["title"] = "flotsam shallow-water flow" + std::string(scene.synthetic ? " (synthetic scene)" : "");
    fd.attributes["source"] = version_string() + "; " + scheme;
    fd.attributes["history"] = run.command_line;
    fd.attributes["flotsam_config"] = run.config_text;
    fd.attributes["scene_file"] = run.scene_file;
    fd.attributes["scene_sha256"] = sha256_file(run.scene_file);  // debris replays check it (debris/scene_match.hpp)
    fd.attributes["scene_buildings_sha256"] = scene_buildings_sha256(scene);  // debris checks the building mask
    fd.attributes["scene_title"] = scene.title;
    fd.attributes["realisation"] = std::to_string(run.realisation);
    fd.attributes["boundary_file"] = boundary_files(def);
    fd.attributes["boundary_checksum"] = boundary_checksums(def);
    char dry[32];
    std::snprintf(dry, sizeof dry, "%g", def.dry_depth);  // std::to_string's "%f" would write 1e-9 as 0.000000
    fd.attributes["dry_depth_m"] = dry;
    return fd;
}

}  // namespace

RunOutput::RunOutput(const Scene& scene, const RunDef& run, const PhysicsDef& def)
    : win(make_window(scene.grid, run.window)),
      times(frame_times(run.duration, run.output_interval)),
      gauge_points(gauge_points_of(scene, run)),
      gauges(gauge_points, scene.grid, run.gauge_interval, run.duration),
      key(restart_key(run, def)),
      file(run.out_file),
      checkpoint(checkpoint_path(run.out_file)) {
    sum.max_depth.assign(win.grid.size(), 0.0f);
    sum.max_speed.assign(win.grid.size(), 0.0f);
    sum.arrival.assign(win.grid.size(), float(kFill));
}

std::vector<float> window_bed(const Scene& scene, const Window& win) {
    std::vector<float> z(win.grid.size());
    for (int j = win.j0; j <= win.j1; ++j)
        for (int i = win.i0; i <= win.i1; ++i) z[win.grid.index(i - win.i0, j - win.j0)] = float(scene.z[scene.grid.index(i, j)]);
    return z;
}

void start_run(RunSolver& solver, const Scene& scene, const RunDef& run, const PhysicsDef& def, RunOutput& o) {
    const FlowFileDef fd = flow_file_def(scene, run, def, o, solver.description());
    o.writer.emplace(o.file.temp_path(), fd);
    if (!run.boundary_output.file.empty()) {
        o.outline.emplace(run.boundary_output, scene.grid, scene.crs, fd.attributes);
        o.outline->record(0.0, o.outline->read(solver), 0.0, o.outline->read(solver));
    }
    o.state.volume_start = solver.volume();
    write_frame(*o.writer, 0, solver, o.win);
    o.state.next_frame = 1;
    accumulate(o.sum, solver, o.win, 0.0, run.arrival_depth);
    o.gauges.record(0.0, o.gauges.read(solver), 0.0, o.gauges.read(solver));
}

void resume_run(RunSolver& solver, RunOutput& o) {
    o.file.keep_partial();  // the interrupted run's work: never removed, whatever happens next
    if (!std::filesystem::exists(o.checkpoint)) fail(o.checkpoint, "", "no checkpoint to restart from");
    if (!std::filesystem::exists(o.file.temp_path()))
        fail(o.file.temp_path(), "", "the partial output of the interrupted run is missing");
    const std::string afresh = "remove " + o.checkpoint + " and " + o.file.temp_path() + " to start afresh";
    // The settings first (attributes only), so that a refusal touches no state.
    const std::string written_with = read_checkpoint_key(o.checkpoint);
    if (written_with != o.key)
        fail(o.checkpoint, "",
             "was written with other settings, scene or boundary files (" + differing_settings(written_with, o.key) +
                 "): restart with the checkpoint's settings, or " + afresh);
    try {
        o.state = read_checkpoint(o.checkpoint, solver.state_arrays(), o.sum);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + "; it cannot be continued: " + afresh);
    }
    solver.set_time(o.state.time);
    if (o.state.pump_stopped) solver.set_pump_level_at_stop(o.state.pump_level);
    o.writer.emplace(FlowWriter::reopen(o.file.temp_path()));
    o.gauges.resume_at(o.state.next_gauge);
}

void save_checkpoint(RunSolver& solver, const PhysicsDef& def, RunOutput& o, double t, long steps) {
    o.gauges.flush(*o.writer);
    o.writer->sync();
    o.state.time = t;
    o.state.steps = steps;
    o.state.next_gauge = o.gauges.next();
    o.state.pump_stopped = def.west.kind == BoundaryKind::pump && t >= def.pump.stop;
    o.state.pump_level = solver.pump_level_at_stop();
    o.state.key = o.key;
    write_checkpoint(o.checkpoint, solver.state_arrays(), o.sum, o.state);
    o.file.keep_partial();  // the checkpoint continues from it
}

}  // namespace flotsam::hydro
