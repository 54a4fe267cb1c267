#include "debris/world.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "debris/scene_match.hpp"

namespace flotsam::debris {

WorldDef default_world_def() { return WorldDef{}; }

const Settings<StepDef>& step_settings() {  // dt-max, vertex-step-fraction, integrator, body-contact
    static const Settings<StepDef> table = {
        {"dt-max", "s",
         "largest time step (flotsam debris: 0.01 s for the paper's 0.25 m box, x sqrt(L / 0.25 m) for the shortest body L)",
         Range::positive("s").up_to(60.0), &StepDef::dt_max},
        {"vertex-step-fraction", "1", "largest corner displacement per step, in grid cells (no tunnelling at the default)",
         Range::positive().up_to(10.0), &StepDef::vertex_step_fraction},
        {"integrator", "", "fluid-force stage: semi-implicit Euler or Heun", {}, choice_of<&StepDef::integrator>()},
        {"body-contact",
         "",
         "the bodies of one run meet each other (a yard's, a car park's, those of one `flotsam debris`; docs/debris.md, "
         "\"Bodies that meet\"); off: each goes as if alone",
         {},
         &StepDef::body_contact},
    };
    return table;
}

const Settings<FlowReaderDef>& flow_replay_settings() {
    static const Settings<FlowReaderDef> table = {
        {"time-interpolation",
         "",
         "between stored frames: linear, or cubic (Catmull-Rom, guarded)",
         {},
         choice_of<&FlowReaderDef::time_interpolation>()},
    };
    return table;
}

WorldDef scaled_to_bodies(WorldDef def, const std::vector<BodyDef>& bodies, bool dt_max_given) {
    if (bodies.empty()) return def;
    double shortest = bodies.front().length;
    for (const auto& b : bodies) shortest = std::min(shortest, b.length);
    const double s = shortest / 0.25;  // [-]; 1 for the paper's box
    const WorldDef d = default_world_def();
    if (!dt_max_given) def.step.dt_max = d.step.dt_max * std::sqrt(s);
    def.flow.accel_depth = d.flow.accel_depth * s;  // the dry tolerance is the flow file's, set by the hydro run
    return def;
}

double check_replay_work(const FlowReader& flow, const Grid& cells, const StepDef& step, double t0, double t_end, double bodies,
                         bool allowed, const std::string& dt_name, const std::string& fraction_name, const std::string& file) {
    const double speed = flow.description().largest_speed;
    const double reach = step.vertex_step_fraction * std::min(cells.dx, cells.dy);
    const double dt_vertex = speed > 0.0 ? reach / speed : std::numeric_limits<double>::infinity();
    const bool vertex_binds = dt_vertex < step.dt_max;
    const double dt = std::min(step.dt_max, dt_vertex);
    const double per_body = (t_end - t0) / dt;
    char text[400];
    if (vertex_binds)
        std::snprintf(text, sizeof text, "%s (steps of %.3g s at the largest speed of %s, %.3g m/s) over %s to %s s",
                      number_text(step.vertex_step_fraction).c_str(), dt, flow.description().path.c_str(), speed, number_text(t0).c_str(),
                      number_text(t_end).c_str());
    else
        std::snprintf(text, sizeof text, "%s s over %s to %s s of %s", number_text(step.dt_max).c_str(), number_text(t0).c_str(),
                      number_text(t_end).c_str(), flow.description().path.c_str());
    const std::string name = vertex_binds ? fraction_name : dt_name;
    check_work(name, text, per_body, max_body_steps_per_body, "steps of each body", allowed, file);
    check_work(name, std::string(text) + " for " + number_text(bodies) + " bodies", per_body * bodies, max_body_steps, "body steps",
               allowed, file);
    return per_body;
}

std::vector<std::uint8_t> buildings_on_grid(const Scene& scene, const Grid& grid) {
    if (scene.building.empty()) return {};
    std::vector<std::uint8_t> out(grid.size(), 0);
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const double x = grid.x(i), y = grid.y(j);
            if (!scene.grid.contains(x, y)) continue;
            out[grid.index(i, j)] = scene.building[scene.grid.index(scene.grid.cell_i(x), scene.grid.cell_j(y))] ? 1 : 0;
        }
    return out;
}

std::vector<std::int32_t> building_ids_on_grid(const Scene& scene, const Grid& grid, const std::vector<std::uint8_t>& mask) {
    if (mask.empty() || scene.building.empty()) return {};
    const std::vector<std::int32_t> ids = scene_building_ids(scene);
    const Grid& s = scene.grid;
    std::vector<std::int32_t> out(grid.size(), 0);
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            if (!mask[grid.index(i, j)]) continue;
            const double x = grid.x(i), y = grid.y(j);
            const int si = s.cell_i(x), sj = s.cell_j(y);
            std::int32_t id = s.contains(x, y) ? ids[s.index(si, sj)] : 0;
            double best = 1e300;
            for (int dj = -1; id == 0 && dj <= 1; ++dj)  // nearest building cell of the neighbours
                for (int di = -1; di <= 1; ++di) {
                    const int ni = si + di, nj = sj + dj;
                    if (ni < 0 || nj < 0 || ni >= s.nx || nj >= s.ny || ids[s.index(ni, nj)] == 0) continue;
                    const double d = std::hypot(s.x(ni) - x, s.y(nj) - y);
                    if (d < best) best = d, out[grid.index(i, j)] = ids[s.index(ni, nj)];
                }
            if (id != 0) out[grid.index(i, j)] = id;
        }
    return out;
}

Ground ground_from_scene(const Scene& scene, const FlowReader& flow) {
    const Grid& f = flow.grid();
    const Grid& s = scene.grid;
    const double tol = 1e-6 * std::min(s.dx, s.dy);
    if (s.dx > f.dx * (1.0 + 1e-6) || s.dy > f.dy * (1.0 + 1e-6))
        fail(scene.path, "ground",
             "its cells (" + std::to_string(s.dx) + " x " + std::to_string(s.dy) + " m) are coarser than those of flow " +
                 flow.description().path + " (" + std::to_string(f.dx) + " x " + std::to_string(f.dy) +
                 " m): a ground finer than the flow's is wanted");
    // Covering the flow's grid but for less than one of its cells at each side (a scene
    // rasterised at 4 cm may reach past the flume wall that the 1 cm one ends at); beyond
    // the ground's edge is a wall, as beyond the flow's.
    const double mx = f.dx - tol, my = f.dy - tol;
    if (s.x_min_edge() > f.x_min_edge() + mx || s.x_max_edge() < f.x_max_edge() - mx || s.y_min_edge() > f.y_min_edge() + my ||
        s.y_max_edge() < f.y_max_edge() - my)
        fail(scene.path, "ground", "does not cover the grid of flow " + flow.description().path);
    // The scene's cells whose centres lie on the flow's grid.
    const int i0 = int(std::ceil((f.x_min_edge() - s.x0) / s.dx - 1e-9)),
              i1 = int(std::floor((f.x_max_edge() - s.x0) / s.dx + 1e-9));
    const int j0 = int(std::ceil((f.y_min_edge() - s.y0) / s.dy - 1e-9)),
              j1 = int(std::floor((f.y_max_edge() - s.y0) / s.dy + 1e-9));
    Ground g;
    g.grid = Grid{std::min(i1, s.nx - 1) - std::max(i0, 0) + 1,
                  std::min(j1, s.ny - 1) - std::max(j0, 0) + 1,
                  s.x(std::max(i0, 0)),
                  s.y(std::max(j0, 0)),
                  s.dx,
                  s.dy};
    const int di = std::max(i0, 0), dj = std::max(j0, 0);
    g.z.reserve(g.grid.size());
    for (int j = 0; j < g.grid.ny; ++j)
        for (int i = 0; i < g.grid.nx; ++i) g.z.push_back(float(scene.z[s.index(di + i, dj + j)]));
    if (!scene.building.empty()) {
        g.building.reserve(g.grid.size());
        for (int j = 0; j < g.grid.ny; ++j)
            for (int i = 0; i < g.grid.nx; ++i) g.building.push_back(scene.building[s.index(di + i, dj + j)] ? 1 : 0);
    }
    return g;
}

namespace {

// The replay as the world runs it: unless set, a frame's tiles are decoded by as many
// threads as step the bodies (they wait for that frame meanwhile).
FlowReaderDef replay_def(const WorldDef& def) {
    FlowReaderDef flow = def.flow;
    if (flow.decode_threads <= 0) flow.decode_threads = def.threads > 0 ? def.threads : omp_get_max_threads();
    return flow;
}

}  // namespace

std::unique_ptr<FlowReader> open_flow(const std::string& path, const WorldDef& def) {
    return std::make_unique<FlowReader>(path, replay_def(def));
}

World::World(std::unique_ptr<FlowReader> flow, std::vector<std::uint8_t> building, const WorldDef& def, const Ground* ground)
    : def_(def), flow_(std::move(flow)) {
    if (!ground && !building.empty() && building.size() != flow_->grid().size())
        fail(flow_->description().path, "building mask", "does not match the flow grid");
    // Map coordinates (beyond 10 km from the origin): work relative to a round kilometre.
    const auto origin = [](double edge) { return std::abs(edge) > 1e4 ? 1000.0 * std::floor(edge / 1000.0) : 0.0; };
    origin_x_ = origin(flow_->grid().x_min_edge());
    origin_y_ = origin(flow_->grid().y_min_edge());
    if (origin_x_ != 0.0 || origin_y_ != 0.0) flow_->set_origin(origin_x_, origin_y_);
    if (ground) {
        Grid g = ground->grid;  // into the world's frame, as the flow's grid
        g.x0 -= origin_x_;
        g.y0 -= origin_y_;
        flow_->set_ground(g, ground->z);
        obstacles_ = ObstacleMap(g, ground->z, ground->building);
    } else {
        obstacles_ = ObstacleMap(flow_->grid(), flow_->description().bed, std::move(building));
    }
    time_ = flow_->description().start_time();
}

World::World(const std::string& flow_path, std::vector<std::uint8_t> building, const WorldDef& def, const Ground* ground)
    : World(open_flow(flow_path, def), std::move(building), def, ground) {}

World make_world(std::unique_ptr<FlowReader> flow, const Scene* scene, const std::vector<BodyDef>& bodies, const WorldDef& def,
                 const Scene* ground, const std::vector<int>& groups) {
    std::vector<std::uint8_t> building;
    std::optional<Ground> fine;
    std::vector<std::int32_t> ids;
    const FlowReader& f = *flow;
    if (scene) {
        check_flow_matches_scene(f, *scene);
        building = buildings_on_grid(*scene, f.grid());
    }
    if (ground) {
        cf::check_same_crs(ground->path, ground->crs, f.description().path, f.description().crs);
        fine = ground_from_scene(*ground, f);
    }
    for (const BodyDef& b : bodies) {
        check_body_start(b, f, scene);
        if (ground) check_body_start(b, f, ground);
    }
    // The buildings are numbered as the scene numbers them (a finer ground's cells take
    // the id of the scene's building there), so that impacts name the scene's buildings.
    const Scene* numbering = scene ? scene : ground;
    if (numbering)
        ids = fine ? building_ids_on_grid(*numbering, fine->grid, fine->building)
                   : building_ids_on_grid(*numbering, f.grid(), building);
    World world(std::move(flow), std::move(building), def, fine ? &*fine : nullptr);
    if (!ids.empty()) world.set_building_ids(std::move(ids));
    for (std::size_t k = 0; k < bodies.size(); ++k) world.add_body(bodies[k], groups.empty() ? -1 : groups[k]);
    return world;
}

World make_world(const std::string& flow_path, const Scene* scene, const std::vector<BodyDef>& bodies, const WorldDef& def,
                 const Scene* ground, const std::vector<int>& groups) {
    return make_world(open_flow(flow_path, def), scene, bodies, def, ground, groups);
}

std::size_t World::add_body(const BodyDef& def, int group) {
    BodyDef local = def;
    local.x -= origin_x_;
    local.y -= origin_y_;
    params_.push_back(make_body_params(local, def_.step.water_density));
    states_.push_back(initial_state(local, time_));
    window_fitted_ = false;
    stats_.push_back({});
    impacts_.push_back({});
    group_of_.push_back(group >= 0 ? group : -1 - int(states_.size()));  // a group of its own: an id no caller gives
    units_.clear();
    return states_.size() - 1;
}

std::vector<Impact> World::impacts() const {
    std::vector<Impact> out;
    for (std::size_t b = 0; b < impacts_.size(); ++b)
        for (Impact i : impacts_[b].events) {
            i.trajectory = int(b);
            i.x += origin_x_;
            i.y += origin_y_;
            out.push_back(i);
        }
    return out;
}

void World::clear_event_flags() {
    for (auto& s : states_) s.flags &= std::uint8_t(~flag_colliding);
}

void World::fit_window() {
    std::vector<CellWindow> regions;
    const StepContext ctx{*flow_, obstacles_, def_.step};
    for (std::size_t b = 0; b < states_.size(); ++b) {
        // Beyond what one step needs (else a body could never be served), plus the margin.
        const double r = window_pad(ctx, params_[b]) + def_.window_margin_lengths * params_[b].def.length;
        regions.push_back(flow_->cells_for(states_[b].x - r, states_[b].x + r, states_[b].y - r, states_[b].y + r));
    }
    if (regions.empty()) return;
    flow_->set_regions(regions);
    window_fitted_ = true;
}

void World::advance_to(double t) {
    if (units_.empty()) {                           // bodies of one group step together (where they meet), others alone
        std::vector<std::pair<int, int>> by_group;  // (group, body)
        for (std::size_t b = 0; b < states_.size(); ++b) by_group.push_back({group_of_[b], int(b)});
        std::stable_sort(by_group.begin(), by_group.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        for (std::size_t k = 0; k < by_group.size(); ++k) {
            if (k == 0 || by_group[k].first != by_group[k - 1].first || !def_.step.body_contact) units_.emplace_back();
            units_.back().push_back(by_group[k].second);
        }
        std::sort(units_.begin(), units_.end(), [](const auto& x, const auto& y) { return x.front() < y.front(); });
    }
    const long n = long(units_.size());
    std::vector<char> active(units_.size(), 1);
    // No more threads than units: an idle thread only adds a barrier per frame interval.
    const int threads = std::max(1, std::min<int>(int(n), def_.threads > 0 ? def_.threads : omp_get_max_threads()));
    std::vector<BodyImpacts>* impacts = obstacles_.has_buildings() ? &impacts_ : nullptr;
    while (time_ < t) {
        const double next = flow_->next_frame_time(time_);
        const double t_next = next > time_ ? std::min(t, next) : t;  // past the last frame the flow is held
        if (!window_fitted_) fit_window();
        flow_->prepare(time_);
        if (def_.read_ahead) flow_->read_ahead(t_next);  // what prepare(t_next) will read
        const StepContext ctx{*flow_, obstacles_, def_.step};
        std::fill(active.begin(), active.end(), 1);
        for (;;) {
#pragma omp parallel num_threads(threads)
            {
                StepScratch scratch;
                GroupScratch group_scratch;
#pragma omp for schedule(dynamic, 1)
                for (long u = 0; u < n; ++u) {
                    if (!active[u]) continue;
                    const std::vector<int>& unit = units_[std::size_t(u)];
                    bool done;
                    if (unit.size() == 1) {
                        const std::size_t b = std::size_t(unit.front());
                        done =
                            advance_body(ctx, params_[b], states_[b], stats_[b], t_next, scratch, impacts ? &impacts_[b] : nullptr);
                    } else {
                        BodyGroup group{unit, params_, states_, stats_, impacts};
                        done = advance_group(ctx, group, t_next, group_scratch);
                    }
                    if (done) active[u] = 0;
                }
            }
            if (std::none_of(active.begin(), active.end(), [](char a) { return a != 0; })) break;
            fit_window();  // some body left the loaded window: move it (reloads the same two frames)
            if (def_.read_ahead) flow_->read_ahead(t_next);
        }
        time_ = t_next;
    }
    flow_->finish_read_ahead();  // no netCDF call of ours outlives this one
}

}  // namespace flotsam::debris
