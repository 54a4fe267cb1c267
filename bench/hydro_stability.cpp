// Stability map of the two hydro schemes: for each case and step size, whether a run
// held, needed its depth clamped (negative depth), reversed a draining film (friction),
// or blew up, and what the scheme's guard does outside the study (`guard`: runs; refused,
// the setting is rejected; stops, the leap-frog's Courant check ends the run). One CSV
// row per run; a line per run on stderr.
// Asserts nothing and times nothing: `make -f Makefile.pipeline stability-hydro` writes
// docs/data/hydro_stability.csv and draws docs/img/hydro_stability.png from it.
//
//   hydro_stability [--csv PATH]
//
// Step sizes are the schemes' own numbers (finite volumes: cfl = dt max(a_x/dx, a_y/dy)
// for the split step, dt max(a_x/dx + a_y/dy) for Heun's, at most 1 unless studying;
// leap-frog: courant = dt sqrt(g h_max) sqrt(1/dx^2 + 1/dy^2), at most 1) and, to put them
// on one axis, the first step as dt sqrt(g h_max) / dx.
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "cases/hydro_cases.hpp"
#include "common/atomic_file.hpp"
#include "hydro/leapfrog.hpp"
#include "hydro/solver.hpp"

using namespace flotsam;
using namespace flotsam::hydro;

namespace {

struct Case {
    std::string name;
    Scene scene;
    PhysicsDef def;
    double duration = 1.0;  // [s]
    bool film = false;      // a draining film: a reversing flow counts as a failure
};

std::vector<Case> cases() {
    std::vector<Case> out;
    PhysicsDef walls = test::closed_def();
    walls.study_past_stability_limit = true;
    out.push_back({"wave in a basin", test::basin_wave(40), walls, 1.5, false});
    PhysicsDef open = walls;
    open.west.kind = open.east.kind = BoundaryKind::transmissive;
    open.dry_depth = 1e-8;
    out.push_back({"dry dam break", test::dam_break_scene(200, 1.0, 0.0), open, 0.5, false});
    PhysicsDef city = walls;
    city.default_manning_n = 0.013;
    out.push_back({"bore into buildings", test::bore_into_buildings(), city, 2.0, false});
    PhysicsDef film = walls;
    film.default_manning_n = 0.025;
    film.max_dt = 1.0;  // let the step follow the step setting
    out.push_back({"thin film on a slope", test::film_on_slope(), film, 20.0, true});
    return out;
}

double deepest(const Scene& s) {
    double h = 0.0;
    for (std::size_t k = 0; k < s.z.size(); ++k) h = std::max(h, (s.eta0.empty() ? 0.0 : s.eta0[k]) - s.z[k]);
    return h;
}

struct Row {
    std::string outcome;
    std::string guard = "runs";  // what the schemes' own guards do outside the study: runs, refused, stops
    test::Watch w;
    SolverStats stats;
    double max_courant = -1.0;  // leap-frog only
};

template <class S>
Row watch(S& solver, const Case& c) {
    Row r;
    r.w = test::run_watched(solver, c.scene, c.duration);
    r.stats = solver.stats();
    if (r.w.blew_up())
        r.outcome = "blow-up";
    else if (r.stats.negative_depth_fixes > 0 && r.stats.min_depth_seen < -1e-12)
        r.outcome = "negative depth";
    else if (c.film && r.w.reversals > 0)
        r.outcome = "reverses";
    else
        r.outcome = "stable";
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    std::string csv_path;
    for (int k = 1; k + 1 < argc; k += 2)
        if (std::string(argv[k]) == "--csv") csv_path = argv[k + 1];
    std::string csv =
        "case,scheme,friction,step_setting,first_step_s,c_dt_over_dx,steps,outcome,min_depth_before_clamp_m,negative_depth_fixes,"
        "outflow_limits,level_rise_m,max_speed_m_s,roof_depth_m,reversals,volume_error,max_courant,guard\n";
    const std::vector<double> fv_cfl = {0.1, 0.2, 0.3, 0.4, 0.45, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2};
    const std::vector<double> lf_courant = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 1.0, 1.02, 1.05, 1.1, 1.2};
    for (const Case& c : cases()) {
        const double c_over_dx = std::sqrt(c.def.gravity * deepest(c.scene)) / c.scene.grid.dx;
        auto emit = [&](const char* scheme, const char* friction, double setting, const Row& r) {
            char line[512];
            std::snprintf(line, sizeof line, "\"%s\",%s,%s,%.3g,%.6g,%.4f,%ld,%s,%.3g,%ld,%ld,%.4g,%.4g,%.4g,%ld,%.3g,%s,%s\n",
                          c.name.c_str(), scheme, friction, setting, r.w.first_step, r.w.first_step * c_over_dx, r.w.steps,
                          r.outcome.c_str(), r.stats.min_depth_seen, r.stats.negative_depth_fixes, r.stats.outflow_limits,
                          r.w.level_rise, r.w.max_speed, r.w.roof_depth, r.w.reversals, r.w.volume_error,
                          r.max_courant < 0.0 ? "" : std::to_string(r.max_courant).c_str(), r.guard.c_str());
            csv += line;
            std::fprintf(stderr, "%-22s %-8s %-8s %5.3g  dt sqrt(gh)/dx %.3f  %s\n", c.name.c_str(), scheme, friction, setting,
                         r.w.first_step * c_over_dx, r.outcome.c_str());
        };
        // The split step (the default) and Heun's; the explicit friction of the study is
        // written for Heun's only.
        for (TimeStepping stepping : {TimeStepping::split, TimeStepping::heun})
            for (Friction friction : {Friction::implicit, Friction::explicit_}) {
                if (friction == Friction::explicit_ && (!c.film || stepping == TimeStepping::split)) continue;
                for (double cfl : fv_cfl) {
                    FiniteVolumeDef fv;
                    fv.stepping = stepping;
                    fv.cfl = cfl;
                    fv.friction = friction;
                    Solver solver(c.scene, c.def, fv);
                    Row r = watch(solver, c);
                    if (cfl > 1.0) r.guard = "refused";
                    emit(stepping == TimeStepping::split ? "fv split" : "fv heun", friction == Friction::implicit ? "implicit" : "explicit",
                         cfl, r);
                }
            }
        for (double courant : lf_courant) {
            LeapfrogDef lf = default_leapfrog_def();
            lf.courant = courant;
            LeapfrogSolver solver(c.scene, c.def, lf);
            Row r = watch(solver, c);
            r.max_courant = solver.max_courant_seen();
            r.guard = courant > 1.0 ? "refused" : (r.max_courant > 1.0 ? "stops" : "runs");
            emit("leapfrog", "semi-implicit", courant, r);
        }
    }
    if (csv_path.empty()) {
        std::fputs(csv.c_str(), stdout);
        return 0;
    }
    ensure_parent_dir(csv_path);
    write_text_atomic(csv_path, csv);
    std::fprintf(stderr, "hydro_stability: wrote %s\n", csv_path.c_str());
    return 0;
}
