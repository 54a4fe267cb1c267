// The wet/dry suite (cases/wetdry_exact.hpp) for each front treatment: one markdown table
// per case, each run's error against the exact solution, the observed order between
// successive grids, the volume change, the smallest step against the case's wave-speed
// bound, and how the run ended. Prints figures; asserts nothing (tests/hydro_wetdry_test.cpp
// asserts the default settings at small sizes; docs/studies/wetdry_suite.md shows the
// full tables).
//
//   wetdry_suite [--size small|full] [--case NAME] [--variant NAME] [--csv FILE]
//                [--threads N] [--max-seconds S] [--speed-factor F]
//
// small: what CI runs (8 processor s for both variants, each of the default's failures
// included); full: the grids (95 s). Each run stops early when its stable step
// collapses (below 1e-3 of its running median for more than 20 steps), after 40 times the
// steps the bound allows, after --max-seconds of processor time (default 60 small, 600
// full), or when it blows up (non-finite, or a speed --speed-factor times the case's scale,
// default 100); its row says so. One thread unless --threads.
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "cases/wetdry_exact.hpp"
#include "common/atomic_file.hpp"
#include "hydro/solver.hpp"

using namespace flotsam;
using namespace flotsam::hydro;

namespace {

// A scheme to compare: the finite-volume settings and a change to the case's physics.
// Another variant is one more line in variants().
struct Variant {
    std::string name;
    FiniteVolumeDef fv;
    std::function<void(PhysicsDef&)> tweak;
};

FiniteVolumeDef scheme(TimeStepping stepping, FrontTreatment fronts, Precision precision = Precision::float64) {
    FiniteVolumeDef fv;
    fv.stepping = stepping;
    fv.fronts = fronts;
    fv.precision = precision;
    return fv;
}

std::vector<Variant> variants() {
    const auto dry = [](double depth) { return [depth](PhysicsDef& d) { d.dry_depth = depth; }; };
    const FiniteVolumeDef other_precision = scheme(TimeStepping::split, FrontTreatment::plain,
                                                   FiniteVolumeDef{}.precision == Precision::float32 ? Precision::float64 : Precision::float32);
    return {
        {"default", FiniteVolumeDef{}, {}},  // split steps, plain fronts, dry tolerance 1e-6 m, the default precision
        {std::string("default-") + std::string(enum_name(other_precision.precision)), other_precision, {}},
        {"heun-plain", scheme(TimeStepping::heun, FrontTreatment::plain), {}},
        {"tracked", scheme(TimeStepping::heun, FrontTreatment::tracked), dry(1e-9)},
        {"default-1e-9", FiniteVolumeDef{}, dry(1e-9)},
    };
}

// A case of the suite at the grids of each size (cells along x).
struct SuiteCase {
    std::string name;
    std::string what;  // the heading's description
    std::vector<int> small, full;
    std::function<test::WetDryCase(int)> make;
    bool converges = true;  // false: a lake at rest, exact to round-off at any grid (no order)
};

std::vector<SuiteCase> suite() {
    const test::Thacker planar;
    const test::ThackerRadial radial;
    const test::Parabola parabola;
    const test::SolitaryRunup runup;
    char planar_what[200], radial_what[200], parabola_what[200], runup_what[260];
    std::snprintf(planar_what, sizeof planar_what,
                  "Thacker's planar surface: a = %g m, h0 = %g m, eta = %g m on [-2, 2]^2 m, walls, one period (%.4f s)", planar.a,
                  planar.h0, planar.eta, planar.period());
    std::snprintf(radial_what, sizeof radial_what,
                  "Thacker's radial oscillation: a = %g m, r0 = %g m, h0 = %g m on [-2, 2]^2 m, walls, one period (%.4f s)",
                  radial.a, radial.r0, radial.h0, radial.period());
    std::snprintf(parabola_what, sizeof parabola_what,
                  "Sampson's parabola, undamped: h0 = %g m, a = %g m, B = %g m/s on [-5000, 5000] m x 4 rows, walls, one "
                  "period (%.1f s)",
                  parabola.h0, parabola.a, parabola.B, parabola.period());
    std::snprintf(runup_what, sizeof runup_what,
                  "Synolakis' solitary wave: H/d = %g on 1:%g, d = %g m, [-5, 75] m x 4 rows, walls; exact maximum runup "
                  "%.5f m (linear theory's integral; asymptotic formula %.5f m)",
                  runup.H / runup.d, runup.cot_beta, runup.d, runup.peak().runup, runup.asymptotic_runup());
    return {
        {"thacker-planar", planar_what, {25, 50, 100}, {50, 100, 200, 400}, [](int n) { return test::thacker_planar_case(n); }},
        {"thacker-radial", radial_what, {25, 50, 100}, {50, 100, 200, 400}, [](int n) { return test::thacker_radial_case(n); }},
        {"parabola", parabola_what, {128, 256, 512}, {128, 256, 512, 1024}, [](int n) { return test::parabola_case(n); }},
        {"solitary-runup", runup_what, {400, 800}, {400, 800, 1600, 3200}, [](int n) { return test::solitary_runup_case(n); }},
        {"ritter-5mm",
         "Ritter's dam break: 5 mm of still water over [0, 5] m, dry [5, 10] m, 4 rows, walls, 6 s (tip at 7.658 m)",
         {400, 800, 1600},
         {400, 800, 1600, 3200},
         [](int n) { return test::dam_break_case(n, 0.005, 0.0, 6.0); }},
        {"ritter-2cm", "Ritter's dam break: 2 cm, 3 s (tip at 7.658 m)", {400, 800, 1600}, {400, 800, 1600, 3200},
         [](int n) { return test::dam_break_case(n, 0.02, 0.0, 3.0); }},
        {"stoker", "Stoker's dam break onto a thin wet bed: 5 mm west of x = 5 m, 0.05 mm east, 4 rows, walls, 6 s", {400, 800, 1600},
         {400, 800, 1600, 3200}, [](int n) { return test::dam_break_case(n, 0.005, 0.00005, 6.0); }},
        {"steps-at-rest",
         "Lakes at rest over stair steps partly out of the water, a ridge 2e-9 m above the water, a sill 3e-9 m under it: "
         "[0, 1]^2 m, 10 s",
         {50},
         {50, 100, 200},
         [](int n) { return test::steps_at_rest_case(n, 10.0); },
         false},
        {"city-at-rest", "The city basin (80 x 50 cells of 1 cm, 5 cm buildings, a dry shore) at rest at level 0, 10 s", {80},
         {80}, [](int) { return test::city_at_rest_case(3, 10.0); }, false},
    };
}

std::string fmt(const char* f, double v) {
    if (std::isnan(v)) return "—";
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

struct Row {
    int n = 0;
    test::WetDryResult r;
};

double order_of(const std::vector<Row>& rows, std::size_t k, double (*value)(const test::WetDryResult&), bool converges) {
    if (!converges || k == 0 || !rows[k].r.finished() || !rows[k - 1].r.finished()) return std::nan("");
    const double a = value(rows[k - 1].r), b = value(rows[k].r);
    if (!(a > 0.0) || !(b > 0.0)) return std::nan("");
    return test::observed_order(a, b, rows[k - 1].n, rows[k].n);
}

double l1(const test::WetDryResult& r) { return r.checks.empty() ? std::nan("") : r.last().depth_l1; }
double l1u(const test::WetDryResult& r) { return r.checks.empty() ? std::nan("") : r.last().velocity_l1; }

}  // namespace

int main(int argc, char** argv) {
    std::string size = "small", only_case, only_variant, csv_path;
    int threads = 1;
    double max_seconds = -1.0, speed_factor = test::RunLimits{}.speed_factor;
    for (int a = 1; a < argc; ++a) {
        auto value = [&]() -> std::string {
            if (a + 1 >= argc) {
                std::fprintf(stderr, "wetdry_suite: %s needs a value\n", argv[a]);
                std::exit(2);
            }
            return argv[++a];
        };
        const std::string arg = argv[a];
        if (arg == "--size")
            size = value();
        else if (arg == "--case")
            only_case = value();
        else if (arg == "--variant")
            only_variant = value();
        else if (arg == "--csv")
            csv_path = value();
        else if (arg == "--threads")
            threads = std::atoi(value().c_str());
        else if (arg == "--max-seconds")
            max_seconds = std::atof(value().c_str());
        else if (arg == "--speed-factor")
            speed_factor = std::atof(value().c_str());
        else {
            std::fprintf(stderr,
                         "usage: wetdry_suite [--size small|full] [--case NAME] [--variant NAME] [--csv FILE] [--threads N] "
                         "[--max-seconds S] [--speed-factor F]\n");
            return 2;
        }
    }
    if (size != "small" && size != "full") {
        std::fprintf(stderr, "wetdry_suite: --size is small or full, not %s\n", size.c_str());
        return 2;
    }
    const bool full = size == "full";
    omp_set_num_threads(threads);
    test::RunLimits limits;
    limits.max_seconds = max_seconds >= 0.0 ? max_seconds : (full ? 600.0 : 60.0);
    limits.speed_factor = speed_factor;
    std::string csv =
        "case,cells,variant,outcome,stop_time_s,depth_l1,depth_linf_m,velocity_l1,film_outside_cells,max_film_outside_cells,runup_m,"
        "runup_exact_m,"
        "volume_change,max_volume_change,min_dt_fraction,dt_bound_s,max_speed_m_s,min_depth_seen_m,positivity_redos,steps,"
        "processor_s,wall_s\n";
    std::printf("# Wet/dry suite, --size %s, %d thread%s\n", size.c_str(), threads, threads == 1 ? "" : "s");
    const std::clock_t cpu0 = std::clock();
    bool any = false;
    for (const SuiteCase& sc : suite()) {
        if (!only_case.empty() && sc.name != only_case) continue;
        any = true;
        const std::vector<int>& sizes = full ? sc.full : sc.small;
        const bool runup = sc.name == "solitary-runup";
        std::printf("\n## %s\n\n%s.\n\n", sc.name.c_str(), sc.what.c_str());
        if (runup)
            std::printf(
                "| N | variant | runup [m] | error | order | volume change | min dt / bound | steps | processor s | outcome |\n"
                "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
        else
            std::printf(
                "| N | variant | L1 h | order | L∞ h [m] | L1 u | order | film outside [cells] | volume change | min dt / bound | "
                "steps | processor s | outcome |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
        for (const Variant& var : variants()) {
            if (!only_variant.empty() && var.name != only_variant) continue;
            std::vector<Row> rows;
            for (int n : sizes) {
                const test::WetDryCase c = sc.make(n);
                rows.push_back({n, test::run_wetdry(c, var.fv, var.tweak, limits)});
                const std::size_t k = rows.size() - 1;
                const test::WetDryResult& r = rows[k].r;
                const double runup_m = r.max_wet_level, runup_err = runup_m / c.runup_exact - 1.0;
                const std::string volume = fmt("%.1e", r.volume_change), dtf = fmt("%.3f", r.min_dt_fraction);
                if (runup) {
                    double order = std::nan("");
                    if (k > 0 && rows[k - 1].r.finished() && r.finished()) {
                        const double prev = std::abs(rows[k - 1].r.max_wet_level / c.runup_exact - 1.0);
                        order = test::observed_order(prev, std::abs(runup_err), rows[k - 1].n, n);
                    }
                    std::printf("| %d | %s | %s | %s | %s | %s | %s | %ld | %.1f | %s |\n", n, var.name.c_str(),
                                fmt("%.5f", runup_m).c_str(), fmt("%+.2e", runup_err).c_str(), fmt("%.2f", order).c_str(),
                                volume.c_str(), dtf.c_str(), r.steps, r.processor_seconds, r.outcome_text().c_str());
                } else {
                    const bool have = !r.checks.empty() && r.finished();
                    std::printf("| %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %ld | %.1f | %s |\n", n, var.name.c_str(),
                                have ? fmt("%.3e", l1(r)).c_str() : "—", fmt("%.2f", order_of(rows, k, l1, sc.converges)).c_str(),
                                have ? fmt("%.2e", r.last().depth_linf).c_str() : "—",
                                have ? fmt("%.3e", l1u(r)).c_str() : "—", fmt("%.2f", order_of(rows, k, l1u, sc.converges)).c_str(),
                                have ? fmt("%.1f", r.last().film_outside).c_str() : "—", volume.c_str(), dtf.c_str(), r.steps, r.processor_seconds,
                                r.outcome_text().c_str());
                }
                std::fflush(stdout);
                char line[768];
                const test::CheckError e = r.checks.empty() ? test::CheckError{} : r.last();
                std::snprintf(line, sizeof line,
                              "%s,%d,%s,\"%s\",%.6g,%.6e,%.6e,%.6e,%.3f,%.3f,%.8g,%.8g,%.3e,%.3e,%.4f,%.6g,%.5g,%.3e,%ld,%ld,%.3f,%.3f\n",
                              sc.name.c_str(), n, var.name.c_str(), r.outcome_text().c_str(), r.stop_time,
                              r.checks.empty() ? std::nan("") : e.depth_l1, r.checks.empty() ? std::nan("") : e.depth_linf,
                              r.checks.empty() ? std::nan("") : e.velocity_l1, e.film_outside, r.film_outside, runup ? runup_m : std::nan(""),
                              runup ? c.runup_exact : std::nan(""), r.volume_change, r.max_volume_change, r.min_dt_fraction,
                              r.dt_bound, r.max_speed, r.min_depth_seen, r.positivity_redos, r.steps, r.processor_seconds,
                              r.wall_seconds);
                csv += line;
            }
        }
    }
    if (!any) {
        std::fprintf(stderr, "wetdry_suite: no case named %s\n", only_case.c_str());
        return 2;
    }
    std::printf("\nprocessor time in all: %.1f s\n", double(std::clock() - cpu0) / CLOCKS_PER_SEC);
    if (!csv_path.empty()) {
        ensure_parent_dir(csv_path);
        write_text_atomic(csv_path, csv);
        std::fprintf(stderr, "wetdry_suite: wrote %s\n", csv_path.c_str());
    }
    return 0;
}
