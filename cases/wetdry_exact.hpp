// Wet/dry cases with exact answers (tests/hydro_wetdry_test.cpp at small sizes,
// bench/wetdry_suite.cpp at the issue's; docs/studies/wetdry_suite.md): the exact
// solutions as pure functions (SI units throughout: m, s, m/s), scenes built from them,
// and a runner that steps a solver with its own stable step and measures it against them.
//
//   Thacker planar  the plane of water circling a paraboloid (Thacker 1981; SWASHES):
//                   `Thacker` and `thacker_planar` in hydro_cases.hpp
//   Thacker radial  the axisymmetric curved surface breathing in the same bowl
//   parabola        Sampson et al. (2006) without friction, Basilisk's parabola.c, tau = 0
//   solitary runup  Synolakis (1987): a solitary wave up a 1:19.85 beach, maximum runup
//   dam breaks      Ritter (dry bed) and Stoker (wet bed) in a closed box
//   lakes at rest   ridges and stair steps that stand out of the water; the city basin
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <ctime>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <vector>

#include "cases/hydro_cases.hpp"
#include "hydro/solver.hpp"

namespace flotsam::test {

inline constexpr double kPi = 3.14159265358979323846;

// The exact state at a point: depth [m] and velocity [m/s] (0 where dry).
struct ExactFlow {
    double depth = 0.0, u = 0.0, v = 0.0;
};

// ---- Exact solutions -------------------------------------------------------------------

// Thacker's axisymmetric oscillation in a paraboloid (Thacker 1981, J. Fluid Mech.
// 107:499, the curved-surface solution; SWASHES 1.03, "2D radially symmetrical
// paraboloid": a = 1 m, r0 = 0.8 m, h0 = 0.1 m on [0, 4]^2, here centred). Bed
// z = -h0 (1 - r^2 / a^2). With D(t) = 1 - A cos(omega t), A = (a^4 - r0^4) / (a^4 + r0^4),
// omega = sqrt(8 g h0) / a:
//   level  = h0 (sqrt(1 - A^2) / D - 1 - r^2 / a^2 ((1 - A^2) / D^2 - 1))
//   depth  = level - z = h0 sqrt(1 - A^2) / D (1 - r^2 / r_s^2), r_s^2 = a^2 D / sqrt(1 - A^2)
//   (u, v) = omega A sin(omega t) / (2 D) (x, y)
// A paraboloid of water breathing between the shoreline radii r0 = 0.8 m (t = 0, at rest,
// deepest: h0 a^2 / r0^2 = 0.156 m) and a^2 / r0 = 1.25 m (half a period, 1.12 s).
struct ThackerRadial {
    double a = 1.0, r0 = 0.8, h0 = 0.1, g = 9.81;  // [m], [m], [m], [m s^-2]
    double omega() const { return std::sqrt(8.0 * g * h0) / a; }  // [1/s]
    double period() const { return 2.0 * kPi / omega(); }         // [s]
    double A() const { return (std::pow(a, 4) - std::pow(r0, 4)) / (std::pow(a, 4) + std::pow(r0, 4)); }
    double D(double t) const { return 1.0 - A() * std::cos(omega() * t); }
    double bed(double x, double y) const { return -h0 * (1.0 - (x * x + y * y) / (a * a)); }
    double level(double x, double y, double t) const {
        const double A2 = A() * A(), d = D(t), r2 = (x * x + y * y) / (a * a);
        return h0 * (std::sqrt(1.0 - A2) / d - 1.0 - r2 * ((1.0 - A2) / (d * d) - 1.0));
    }
    double shoreline_radius(double t) const { return a * std::sqrt(D(t) / std::sqrt(1.0 - A() * A())); }  // [m]
    ExactFlow flow(double x, double y, double t) const {
        const double d = D(t), rs = shoreline_radius(t);
        const double h = h0 * std::sqrt(1.0 - A() * A()) / d * (1.0 - (x * x + y * y) / (rs * rs));
        if (h <= 0.0) return {};
        const double k = omega() * A() * std::sin(omega() * t) / (2.0 * d);  // [1/s]
        return {h, k * x, k * y};
    }
    // Largest speed of any wet point over a period (at the shoreline) [m/s].
    double max_speed() const {
        double s = 0.0;
        for (int k = 0; k < 2000; ++k) {
            const double t = period() * k / 2000.0;
            s = std::max(s, std::abs(omega() * A() * std::sin(omega() * t) / (2.0 * D(t))) * shoreline_radius(t));
        }
        return s;
    }
    double max_depth() const { return h0 * a * a / (r0 * r0); }  // at t = 0 [m]
};

// Sampson, Easton and Singh (2006, Adv. Water Resour. 29:1415), without friction (tau = 0),
// as Basilisk's parabola.c: bed z = h0 (x / a)^2, h0 = 10 m, a = 3000 m, B = 5 m/s on
// [-5000, 5000] m. With s = sqrt(8 g h0) / (2 a) the level is
//   level = h0 - B^2 / (4 g) (1 + cos 2 s t) - (B s / g) x cos s t,     u = B sin s t.
// Completing the square (a^2 s^2 = 2 g h0) it is a rigid parabola of water sliding to and
// fro: depth = h0 (1 - (x - x_c)^2 / a^2) where positive, x_c = -(B / s) cos s t, so the
// shorelines are x_c -+ a (a 1071 m swing, period 2 pi / s = 1346 s).
struct Parabola {
    double h0 = 10.0, a = 3000.0, B = 5.0, g = 9.81;  // [m], [m], [m/s], [m s^-2]
    double s() const { return std::sqrt(8.0 * g * h0) / (2.0 * a); }  // [1/s]
    double period() const { return 2.0 * kPi / s(); }                 // [s]
    double bed(double x) const { return h0 * (x / a) * (x / a); }
    double level(double x, double t) const {
        return h0 - B * B / (4.0 * g) * (1.0 + std::cos(2.0 * s() * t)) - B * s() / g * x * std::cos(s() * t);
    }
    double centre(double t) const { return -B / s() * std::cos(s() * t); }  // x_c [m]
    ExactFlow flow(double x, double t) const {
        const double h = level(x, t) - bed(x);
        if (h <= 0.0) return {};
        return {h, B * std::sin(s() * t), 0.0};
    }
};

// A dam break on a flat bed: hl [m] of still water at x < x0, hr [m] at x > x0 (0: dry,
// Ritter 1892; > 0: Stoker 1957), at time t after the release. Left rarefaction from
// -c_l to u_m - c_m, where h = (2 c_l - xi)^2 / (9 g), u = 2 (xi + c_l) / 3 (xi = (x -
// x0) / t); over a dry bed it reaches the tip at 2 c_l. Over a wet bed a middle state
// (h_m, u_m = 2 (c_l - c_m)) up to the shock at S, where the Rankine-Hugoniot relations
// give u_m = S (1 - hr / h_m) and S = sqrt(g h_m (h_m + hr) / (2 hr)).
struct DamBreak {
    double hl = 0.005, hr = 0.0, x0 = 5.0, g = 9.81;
    double cl() const { return std::sqrt(g * hl); }
    // h_m by bisection on the mismatch of the rarefaction's and the shock's u_m.
    double middle_depth() const {
        if (hr <= 0.0) return 0.0;
        auto mismatch = [&](double hm) { return 2.0 * (cl() - std::sqrt(g * hm)) - shock_speed(hm) * (1.0 - hr / hm); };
        double lo = hr, hi = hl;
        for (int it = 0; it < 200; ++it) {
            const double mid = 0.5 * (lo + hi);
            (mismatch(mid) > 0.0 ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    }
    double shock_speed(double hm) const { return std::sqrt(g * hm * (hm + hr) / (2.0 * hr)); }
    double tip(double t) const { return x0 + 2.0 * cl() * t; }  // the dry-bed tip [m]
    ExactFlow flow(double x, double t, double hm) const {
        const double xi = (x - x0) / t, c0 = cl();
        if (xi <= -c0) return {hl, 0.0, 0.0};
        const double fan_h = (2.0 * c0 - xi) * (2.0 * c0 - xi) / (9.0 * g), fan_u = 2.0 * (xi + c0) / 3.0;
        if (hr <= 0.0) return xi < 2.0 * c0 ? ExactFlow{fan_h, fan_u, 0.0} : ExactFlow{};
        const double cm = std::sqrt(g * hm), um = 2.0 * (c0 - cm);
        if (xi < um - cm) return {fan_h, fan_u, 0.0};
        if (xi < shock_speed(hm)) return {hm, um, 0.0};
        return {hr, 0.0, 0.0};
    }
};

// Synolakis (1987, J. Fluid Mech. 185:523): a solitary wave of height H on water of depth d
// runs up a plane beach of slope 1 : cot_beta that meets the flat bottom at X0 = d cot_beta
// from the still shoreline. Its maximum runup under the nonlinear shallow-water equations
// equals that of linear theory, for waves that do not break (here H/d = 0.0185,
// non-breaking up to about 0.044 on this beach). The wave starts centred at X1 = X0 + L,
// L = arccosh(sqrt(20)) / gamma, gamma = sqrt(3 H / (4 d^3)) (its height 5 % of H at the
// toe), moving shoreward with u = -sqrt(g / d) eta.
//
// Linear theory (d = g = 1, x from the shoreline, offshore positive): an incident wave
// eta_i = int Phi(w) exp(-i w (x + t)) dw is matched at x = X0 to the beach's
// J0(2 w sqrt(x X0)), whose value at the shoreline is the runup:
//   R(t) = int 2 Phi(w) exp(-i w (X0 + t)) / (J0(2 w X0) - i J1(2 w X0)) dw,
// and for the solitary wave Phi(w) = H w exp(i w X1) / (2 gamma^2 sinh(pi w / (2 gamma))).
// For large X0 the maximum tends to R / d = 2.831 sqrt(cot_beta) (H / d)^(5/4) (Synolakis'
// asymptotic law; 0.08606 d here); `peak` evaluates the integral instead: 0.08828 d at
// t = 17.61 s (a finite-difference solution of the linear equations on the same beach,
// dx = 0.005 d, gives 0.08829 d at 17.61 s).
struct SolitaryRunup {
    double d = 1.0, H = 0.0185, cot_beta = 19.85, g = 9.81;  // [m], [m], -, [m s^-2]
    double gamma() const { return std::sqrt(3.0 * H / (4.0 * d * d * d)); }  // [1/m]
    double toe() const { return d * cot_beta; }                                // X0 [m]
    double half_length() const { return std::acosh(std::sqrt(20.0)) / gamma(); }  // L [m]
    double start_centre() const { return toe() + half_length(); }              // X1 [m]
    double bed(double x) const { return x < toe() ? -x / cot_beta : -d; }      // [m]
    double surface(double x) const {                                           // eta at t = 0 [m]
        const double c = std::cosh(gamma() * (x - start_centre()));
        return H / (c * c);
    }
    double asymptotic_runup() const { return d * 2.831 * std::sqrt(cot_beta) * std::pow(H / d, 1.25); }  // [m]
    // The runup R [m] of linear theory at times t [s] after the start.
    // Linear theory's shoreline: R(t) [m] at any t [s] after the start, from the integral's
    // weights (Simpson over w, computed once).
    class Shoreline {
    public:
        explicit Shoreline(const SolitaryRunup& sr) : d_(sr.d), ts_(std::sqrt(sr.d / sr.g)) {
            const double Hn = sr.H / sr.d, gm = sr.gamma() * sr.d, X0 = sr.toe() / sr.d;
            offset_ = (sr.start_centre() - sr.toe()) / sr.d;  // X1 - X0
            const double w_max = 2.0 * gm * 36.0 / kPi;         // sinh(pi w / (2 gamma)) > e^36 / 2 beyond
            dw_ = w_max / kIntervals;
            weight_.resize(kIntervals + 1);  // Simpson weight x 2 Phi(w) exp(-i w X0) / (J0 - i J1), less exp(i w X1)
            for (int k = 0; k <= kIntervals; ++k) {
                const double w = k * dw_;
                const double shape = w == 0.0 ? 2.0 * gm / kPi : w / std::sinh(kPi * w / (2.0 * gm));  // -> 2 gamma / pi
                const std::complex<double> bessel(std::cyl_bessel_j(0.0, 2.0 * w * X0), -std::cyl_bessel_j(1.0, 2.0 * w * X0));
                const double simpson = (k == 0 || k == kIntervals) ? 1.0 : (k % 2 ? 4.0 : 2.0);
                weight_[k] = simpson * dw_ / 3.0 * Hn * shape / (gm * gm) / bessel;
            }
        }
        double operator()(double t) const {
            const double tau = offset_ - t / ts_;
            std::complex<double> sum = 0.0, phase = 1.0;  // exp(i w tau), w = k dw, by rotation
            const std::complex<double> turn = std::polar(1.0, dw_ * tau);
            for (int k = 0; k <= kIntervals; ++k, phase *= turn) sum += weight_[k] * phase;
            return d_ * 2.0 * sum.real();  // the integrand at -w is the conjugate of that at w
        }

    private:
        static constexpr int kIntervals = 8000;  // even
        double d_, ts_, offset_ = 0.0, dw_ = 0.0;
        std::vector<std::complex<double>> weight_;
    };
    // Linear theory's maximum runup [m], its time [s] and the largest shoreline speed
    // cot_beta |dR/dt| [m/s] (a scale for the step): R every 0.02 sqrt(d / g) over 20
    // sqrt(d / g) either side of the linear arrival time (X1 + X0) / sqrt(g d), the peak
    // refined by golden sections.
    struct Peak {
        double runup = 0.0, time = 0.0, shoreline_speed = 0.0;
    };
    Peak peak() const {
        const Shoreline R(*this);
        const double ts = std::sqrt(d / g), t_arrive = (start_centre() + toe()) / d * ts, dt = 0.02 * ts;
        Peak p;
        double best_t = 0.0, best = -1.0, previous = 0.0;
        for (int k = 0; k <= 2000; ++k) {
            const double t = t_arrive - 20.0 * ts + k * dt, r = R(t);
            if (r > best) best = r, best_t = t;
            if (k > 0) p.shoreline_speed = std::max(p.shoreline_speed, std::abs(r - previous) / dt * cot_beta);
            previous = r;
        }
        double lo = best_t - dt, hi = best_t + dt;
        const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
        for (int it = 0; it < 40; ++it) {
            const double a = hi - phi * (hi - lo), b = lo + phi * (hi - lo);
            if (R(a) > R(b))
                hi = b;
            else
                lo = a;
        }
        p.time = 0.5 * (lo + hi);
        p.runup = R(p.time);
        return p;
    }
};

// ---- The case a run is measured against ----------------------------------------------

struct WetDryCase {
    std::string name;
    Scene scene;
    hydro::PhysicsDef def;  // what the case sets: walls, no friction, the step's upper bound
    double t_start = 0.0;   // [s] the scene is the exact state at t_start
    double t_end = 0.0;     // [s]
    std::vector<double> check_times;  // [s] errors measured there (ascending, the last t_end)
    // The exact state at a point; empty: none (then no errors, only what the case records).
    std::function<ExactFlow(double x, double y, double t)> exact;
    // Signed distance from the exact shoreline [m], positive on the dry side; empty: none.
    std::function<double(double x, double y, double t)> shoreline_distance;
    bool strip = false;            // uniform along y (a 1D case on nx x 4 cells): errors per unit width
    double speed_scale = 0.0;      // max |u| + sqrt(g max h) of the exact solution [m/s]
    double velocity_depth = 0.0;   // velocity errors where both depths exceed it [m]
    double film_depth = 5e-9;      // the thinnest water `film_outside` follows [m]
    double runup_depth = 0.0;      // > 0: record the highest level of water deeper than it [m]
    double runup_exact = 0.0;      // the exact maximum runup [m] (level above still water)
};

// Thacker's planar case (hydro_cases.hpp) on n x n cells over [-2, 2]^2, `periods` periods,
// errors every quarter period.
inline WetDryCase thacker_planar_case(int n, double periods = 1.0, const Thacker& th = Thacker{}) {
    WetDryCase c;
    c.name = "thacker-planar";
    c.scene = thacker_planar(n, th);
    c.def = closed_def();
    c.t_end = periods * th.period();
    for (int q = 1; q <= int(std::lround(4.0 * periods)); ++q) c.check_times.push_back(0.25 * q * th.period());
    c.check_times.back() = c.t_end;
    c.exact = [th](double x, double y, double t) {
        const double h = th.depth(x, y, t);
        return h > 0.0 ? ExactFlow{h, th.x_velocity(t), th.y_velocity(t)} : ExactFlow{};
    };
    c.shoreline_distance = [th](double x, double y, double t) {
        const double w = th.omega() * t;
        return std::hypot(x - th.eta * std::cos(w), y - th.eta * std::sin(w)) - th.a;
    };
    c.speed_scale = th.eta * th.omega() + std::sqrt(th.g * th.h0);
    c.velocity_depth = 0.01 * th.h0;
    return c;
}

// Thacker's radial case on n x n cells over [-2, 2]^2, starting at rest (t = 0).
inline WetDryCase thacker_radial_case(int n, double periods = 1.0, const ThackerRadial& th = ThackerRadial{}) {
    WetDryCase c;
    c.name = "thacker-radial";
    Scene& s = c.scene;
    s = flat_scene(n, n, 4.0 / n, -2.0, 0.0);
    s.grid.y0 = -2.0 + 0.5 * s.grid.dy;
    s.eta0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::size_t k = s.grid.index(i, j);
            const double x = s.grid.x(i), y = s.grid.y(j);
            s.z[k] = th.bed(x, y);
            s.eta0[k] = s.z[k] + th.flow(x, y, 0.0).depth;
        }
    c.def = closed_def();
    c.t_end = periods * th.period();
    for (int q = 1; q <= int(std::lround(4.0 * periods)); ++q) c.check_times.push_back(0.25 * q * th.period());
    c.check_times.back() = c.t_end;
    c.exact = [th](double x, double y, double t) { return th.flow(x, y, t); };
    c.shoreline_distance = [th](double x, double y, double t) { return std::hypot(x, y) - th.shoreline_radius(t); };
    c.speed_scale = th.max_speed() + std::sqrt(th.g * th.max_depth());
    c.velocity_depth = 0.01 * th.h0;
    return c;
}

// A strip of n x 4 square cells over [x_min, x_min + length], bed z(x), level eta(x) and
// velocity u(x) at cell centres.
template <class Bed, class Level, class Velocity>
Scene strip_scene(int n, double x_min, double length, Bed&& bed, Level&& level, Velocity&& velocity) {
    Scene s = flat_scene(n, 4, length / n, x_min, 0.0);
    s.eta0.assign(s.grid.size(), 0.0);
    s.u0.assign(s.grid.size(), 0.0);
    s.v0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < n; ++i) {
            const std::size_t k = s.grid.index(i, j);
            const double x = s.grid.x(i);
            s.z[k] = bed(x);
            s.eta0[k] = std::max(level(x), s.z[k]);
            s.u0[k] = s.eta0[k] > s.z[k] ? velocity(x) : 0.0;
        }
    return s;
}

// The parabola on n x 4 cells over [-5000, 5000] m, `periods` periods, errors every
// quarter period. The step's upper bound is lifted (the flume's 0.05 s would need 27 000
// steps a period; the CFL step is 2.7 s at 128 cells, 0.34 s at 1024).
inline WetDryCase parabola_case(int n, double periods = 1.0, const Parabola& p = Parabola{}) {
    WetDryCase c;
    c.name = "parabola";
    c.scene = strip_scene(
        n, -5000.0, 10000.0, [&](double x) { return p.bed(x); }, [&](double x) { return p.level(x, 0.0); },
        [&](double x) { return p.flow(x, 0.0).u; });
    c.def = closed_def();
    c.def.max_dt = 1e6;
    c.t_end = periods * p.period();
    for (int q = 1; q <= int(std::lround(4.0 * periods)); ++q) c.check_times.push_back(0.25 * q * p.period());
    c.check_times.back() = c.t_end;
    c.exact = [p](double x, double, double t) { return p.flow(x, t); };
    c.shoreline_distance = [p](double x, double, double t) { return std::abs(x - p.centre(t)) - p.a; };
    c.strip = true;
    c.speed_scale = p.B + std::sqrt(p.g * p.h0);
    c.velocity_depth = 0.01 * p.h0;
    return c;
}

// A dam break in a closed box (ritter_box's: [0, 10] m, dam at 5 m, nx x 4 cells, walls),
// hl | hr [m], run to t_end [s] (before any wave reaches a wall).
inline WetDryCase dam_break_case(int nx, double hl, double hr, double t_end) {
    const DamBreak db{hl, hr};
    const double hm = db.middle_depth();
    WetDryCase c;
    c.name = hr > 0.0 ? "stoker" : "ritter";
    c.scene = strip_scene(
        nx, 0.0, 10.0, [](double) { return 0.0; }, [&](double x) { return x < db.x0 ? hl : hr; }, [](double) { return 0.0; });
    c.def = closed_def();
    c.t_end = t_end;
    c.check_times = {t_end};
    c.exact = [db, hm](double x, double, double t) { return db.flow(x, t, hm); };
    if (hr <= 0.0) c.shoreline_distance = [db](double x, double, double t) { return x - db.tip(t); };
    c.strip = true;
    // |u| <= 2 c_l (the dry-bed tip; behind a shock u_m < 2 c_l), depth <= hl.
    c.speed_scale = 3.0 * db.cl();
    c.velocity_depth = std::max(0.01 * hl, 2.0 * hr);
    return c;
}

// Synolakis' runup on n x 4 cells over [-5 d, 75 d] (the shoreline at 0, the toe at 19.85 d,
// the wave's centre at 38.3 d, a wall at 75 d where it is 7e-4 H high), run 8 sqrt(d / g)
// past linear theory's maximum. The runup is the highest level of any cell holding more
// than 1e-4 d of water.
inline WetDryCase solitary_runup_case(int n, const SolitaryRunup& sr = SolitaryRunup{}) {
    WetDryCase c;
    c.name = "solitary-runup";
    const double x_min = -5.0 * sr.d, length = 80.0 * sr.d;
    c.scene = strip_scene(
        n, x_min, length, [&](double x) { return sr.bed(x); }, [&](double x) { return sr.surface(x); },
        [&](double x) { return -std::sqrt(sr.g / sr.d) * sr.surface(x); });
    c.def = closed_def();
    const SolitaryRunup::Peak peak = sr.peak();
    c.t_end = peak.time + 8.0 * std::sqrt(sr.d / sr.g);
    c.check_times = {c.t_end};
    c.strip = true;
    c.speed_scale = std::max(peak.shoreline_speed, std::sqrt(sr.g / sr.d) * sr.H) + std::sqrt(sr.g * (sr.d + sr.H));
    c.runup_depth = 1e-4 * sr.d;
    c.runup_exact = peak.runup;
    return c;
}

// Still water at level 0 on n x n cells over [0, 1]^2 m, stepped ground standing out of it:
//  - west third: stairs rising to the north-east in 1 cm steps (z from -4 cm to +2 cm,
//    their edges across the cells at an angle to the grid), the one at z = 0 exactly at the
//    water's level, the two above it dry;
//  - a ridge along y (x in [0.45, 0.55) m) whose crest stands twice the dry tolerance
//    above the water, holding back ...
//  - ... an east lake whose level is 1 mm lower (bed -2 cm), with a sill in it (x in
//    [0.75, 0.80) m) covered by three times the dry tolerance of water.
// The exact answer: the state stays as it is (each lake at rest, the ridge dry).
inline Scene steps_at_rest(int n, double dry_depth = hydro::PhysicsDef{}.dry_depth) {
    Scene s = flat_scene(n, n, 1.0 / n, 0.0, 0.0);
    s.grid.y0 = 0.5 * s.grid.dy;
    s.eta0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::size_t k = s.grid.index(i, j);
            const double x = s.grid.x(i), y = s.grid.y(j);
            double z = -0.02, level = 0.0;
            if (x < 1.0 / 3.0) z = -0.04 + 0.01 * std::floor(7.0 * (1.5 * x + y) / 1.5);  // steps 0..6
            if (x >= 0.45 && x < 0.55) z = 2.0 * dry_depth;
            if (x >= 0.55) level = -0.001;
            if (x >= 0.75 && x < 0.80) z = -0.001 - 3.0 * dry_depth;
            s.z[k] = z;
            s.eta0[k] = std::max(level, z);
        }
    return s;
}

// A lake at rest: the scene held for `duration` seconds; exact depth max(0, level0 - z).
inline WetDryCase at_rest_case(const std::string& name, const Scene& scene, double duration) {
    WetDryCase c;
    c.name = name;
    c.scene = scene;
    c.def = closed_def();
    c.t_end = duration;
    c.check_times = {duration};
    const Scene s = scene;
    c.exact = [s](double x, double y, double) {
        const std::size_t k = s.grid.index(s.grid.cell_i(x), s.grid.cell_j(y));
        return ExactFlow{std::max(0.0, s.eta0[k] - s.z[k]), 0.0, 0.0};
    };
    double h_max = 0.0;
    for (std::size_t k = 0; k < s.z.size(); ++k) h_max = std::max(h_max, s.eta0[k] - s.z[k]);
    c.speed_scale = std::sqrt(c.def.gravity * h_max);
    c.velocity_depth = 0.0;
    return c;
}

inline WetDryCase steps_at_rest_case(int n, double duration) { return at_rest_case("steps-at-rest", steps_at_rest(n), duration); }

// The city basin (hydro_cases.hpp: 80 x 50 cells of 1 cm, 5 cm buildings, a dry shore)
// with still water at level 0.
inline WetDryCase city_at_rest_case(unsigned seed, double duration) {
    Scene s = city_basin(80, 50, seed);
    s.eta0.assign(s.grid.size(), 0.0);
    for (std::size_t k = 0; k < s.z.size(); ++k) s.eta0[k] = std::max(0.0, s.z[k]);
    return at_rest_case("city-at-rest", s, duration);
}

// ---- The runner ------------------------------------------------------------------------

// Errors at one check time. Integrals over the whole domain [m^3, m^3/s] (per unit width
// for a strip [m^2, m^2/s]).
struct CheckError {
    double t = 0.0;            // [s]
    double depth_l1 = 0.0;     // int |h - h_exact|, dry cells included
    double depth_linf = 0.0;   // max |h - h_exact| [m]
    double velocity_l1 = 0.0;  // int |(u, v) - (u, v)_exact| where both depths exceed velocity_depth
    double film_outside = std::numeric_limits<double>::quiet_NaN();  // [cells] (WetDryResult)
};

enum class Outcome { finished, stalled, blew_up };

struct WetDryResult {
    Outcome outcome = Outcome::finished;
    double stop_time = 0.0;  // [s] where the run ended
    std::string reason;      // why it stopped early
    std::vector<CheckError> checks;  // at each check time reached
    double volume_change = 0.0;      // V_end / V_0 - 1
    double max_volume_change = 0.0;  // largest |V / V_0 - 1| after any step
    // Smallest stable step relative to the case's bound cfl / (speed_scale (1/dx + 1/dy))
    // (no more than max_dt), over all steps.
    double min_dt_fraction = std::numeric_limits<double>::infinity();
    double dt_bound = 0.0;   // [s]
    double max_speed = 0.0;  // largest speed of any cell after any step [m/s]
    // The farthest that water deeper than film_depth stood outside the exact wet region, in
    // cells (centre distance / dx + 1/2: the cell's outer edge in 1D; negative: every such
    // cell inside it), largest over all steps; NaN without a shoreline. At a dry-bed front
    // it is a precursor running ahead; on a receding shore, a film left behind.
    double film_outside = std::numeric_limits<double>::quiet_NaN();
    double max_wet_level = -std::numeric_limits<double>::infinity();  // runup [m] (runup_depth > 0)
    double min_depth_seen = 0.0;  // the solver's most negative depth before its clamp [m]
    long steps = 0, positivity_redos = 0;
    double processor_seconds = 0.0, wall_seconds = 0.0;
    bool finished() const { return outcome == Outcome::finished; }
    const CheckError& last() const { return checks.back(); }
    std::string outcome_text() const;
};

inline std::string WetDryResult::outcome_text() const {
    char buf[160];
    if (outcome == Outcome::finished) return "finished";
    std::snprintf(buf, sizeof buf, "%s at t = %.4g s (%s)", outcome == Outcome::stalled ? "stalled" : "blew up", stop_time,
                  reason.c_str());
    return buf;
}

// Limits that stop a run early.
struct RunLimits {
    double step_factor = 40.0;      // steps cap: this many times duration / dt_bound
    double max_seconds = 0.0;       // processor-time cap [s]; 0: none
    double collapse_ratio = 1e-3;   // a stable step below this fraction of the running median ...
    int collapse_steps = 20;        // ... for more than this many steps in a row: stalled
    double speed_factor = 100.0;    // a speed above this many times speed_scale: blown up
};

// The median of all values pushed so far (two heaps).
class RunningMedian {
public:
    void push(double v) {
        if (low_.empty() || v <= low_.top())
            low_.push(v);
        else
            high_.push(v);
        if (low_.size() > high_.size() + 1) high_.push(low_.top()), low_.pop();
        if (high_.size() > low_.size()) low_.push(high_.top()), high_.pop();
    }
    double median() const { return low_.size() > high_.size() ? low_.top() : 0.5 * (low_.top() + high_.top()); }
    bool empty() const { return low_.empty(); }

private:
    std::priority_queue<double> low_;
    std::priority_queue<double, std::vector<double>, std::greater<double>> high_;
};

// Errors of `solver` against the case's exact state at time t.
template <class S>
CheckError measure(const S& solver, const WetDryCase& c, double t) {
    CheckError e;
    e.t = t;
    const Grid& g = solver.grid();
    const double area = g.dx * g.dy / (c.strip ? g.ny * g.dy : 1.0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const ExactFlow x = c.exact(g.x(i), g.y(j), t);
            const double h = solver.depth(i, j), dh = std::abs(h - x.depth);
            e.depth_l1 += dh * area;
            e.depth_linf = std::max(e.depth_linf, dh);
            if (h > c.velocity_depth && x.depth > c.velocity_depth)
                e.velocity_l1 += std::hypot(solver.x_velocity(i, j) - x.u, solver.y_velocity(i, j) - x.v) * area;
        }
    return e;
}

// The farthest water deeper than film_depth stands outside the exact wet region at time t
// [cells] (WetDryResult::film_outside).
template <class S>
double film_outside(const S& solver, const WetDryCase& c, double t) {
    const Grid& g = solver.grid();
    double outside = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            if (solver.depth(i, j) > c.film_depth)
                outside = std::max(outside, c.shoreline_distance(g.x(i), g.y(j), t) / g.dx + 0.5);
    return outside;
}

// Steps `solver` (built from c.scene and c.def, its time set to c.t_start) to c.t_end with
// its own stable step, cut only to land on the check times; after each step scans every
// cell (finite, speed, runup), the volume, and the film's position; stops early when the
// run stalls (the stable step collapses, or the step or time cap is reached) or blows up.
// `cfl` is the solver's step setting (its stable step is cfl / max(a_x/dx + a_y/dy)).
template <class S>
WetDryResult run_wetdry(S& solver, const WetDryCase& c, double cfl, const RunLimits& limits = {}) {
    WetDryResult r;
    const Grid& g = solver.grid();
    r.dt_bound = std::min(cfl / (c.speed_scale * (1.0 / g.dx + 1.0 / g.dy)), solver.def().max_dt);
    const long max_steps = long(limits.step_factor * (c.t_end - c.t_start) / r.dt_bound) + 100;
    const double speed_limit = limits.speed_factor * c.speed_scale;
    const double v0 = solver.volume();
    const std::clock_t cpu0 = std::clock();
    const auto wall0 = std::chrono::steady_clock::now();
    auto cpu_seconds = [&] { return double(std::clock() - cpu0) / CLOCKS_PER_SEC; };
    RunningMedian median;
    int collapsed = 0;
    std::size_t next = 0;
    const double t_tol = 1e-12 * std::max(1.0, c.t_end);
    auto stop = [&](Outcome o, std::string why) {
        r.outcome = o;
        r.reason = std::move(why);
    };
    char buf[200];
    while (solver.time() < c.t_end - t_tol) {
        const double dt_stable = solver.stable_dt();
        if (!std::isfinite(dt_stable) || dt_stable <= 0.0) {
            stop(Outcome::blew_up, "stable step " + std::to_string(dt_stable));
            break;
        }
        r.min_dt_fraction = std::min(r.min_dt_fraction, dt_stable / r.dt_bound);
        if (!median.empty() && dt_stable < limits.collapse_ratio * median.median()) {
            if (++collapsed > limits.collapse_steps) {
                std::snprintf(buf, sizeof buf, "step %.2g s, median %.2g s", dt_stable, median.median());
                stop(Outcome::stalled, buf);
                break;
            }
        } else {
            collapsed = 0;
        }
        median.push(dt_stable);
        const double t_next = next < c.check_times.size() ? c.check_times[next] : c.t_end;
        solver.step(std::min(dt_stable, t_next - solver.time()));
        ++r.steps;
        // The scan: finite, speed, runup.
        bool finite = true;
        double speed = 0.0;
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) {
                const double h = solver.depth(i, j), u = solver.x_velocity(i, j), v = solver.y_velocity(i, j);
                finite &= std::isfinite(h) & std::isfinite(u) & std::isfinite(v);
                speed = std::max(speed, std::hypot(u, v));
                if (c.runup_depth > 0.0 && h > c.runup_depth) r.max_wet_level = std::max(r.max_wet_level, solver.level(i, j));
            }
        r.max_speed = std::max(r.max_speed, speed);
        const double dv = solver.volume() / v0 - 1.0;
        r.max_volume_change = std::max(r.max_volume_change, std::abs(dv));
        if (!finite || !std::isfinite(dv)) {
            stop(Outcome::blew_up, "not finite");
            break;
        }
        if (speed > speed_limit) {
            std::snprintf(buf, sizeof buf, "speed %.3g m/s", speed);
            stop(Outcome::blew_up, buf);
            break;
        }
        if (c.shoreline_distance) {
            const double a = film_outside(solver, c, solver.time());
            r.film_outside = std::isnan(r.film_outside) ? a : std::max(r.film_outside, a);
        }
        if (next < c.check_times.size() && solver.time() >= c.check_times[next] - t_tol) {
            if (c.exact) {
                CheckError e = measure(solver, c, solver.time());
                if (c.shoreline_distance) e.film_outside = film_outside(solver, c, solver.time());
                r.checks.push_back(e);
            }
            ++next;
        }
        if (r.steps >= max_steps) {
            std::snprintf(buf, sizeof buf, "step cap %ld", max_steps);
            stop(Outcome::stalled, buf);
            break;
        }
        if (limits.max_seconds > 0.0 && cpu_seconds() > limits.max_seconds) {
            std::snprintf(buf, sizeof buf, "time cap %.0f s", limits.max_seconds);
            stop(Outcome::stalled, buf);
            break;
        }
    }
    r.stop_time = solver.time();
    r.volume_change = solver.volume() / v0 - 1.0;
    r.min_depth_seen = solver.stats().min_depth_seen;
    r.positivity_redos = solver.stats().positivity_redos;
    r.processor_seconds = cpu_seconds();
    r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    return r;
}

// The case run by the finite-volume solver with the settings fv (in its precision), the
// case's physics changed by `tweak` (a variant's: e.g. the dry tolerance).
inline WetDryResult run_wetdry(const WetDryCase& c, const hydro::FiniteVolumeDef& fv,
                               const std::function<void(hydro::PhysicsDef&)>& tweak = {}, const RunLimits& limits = {}) {
    hydro::PhysicsDef def = c.def;
    if (tweak) tweak(def);
    auto run = [&]<class Real>() {
        hydro::BasicSolver<Real> solver(c.scene, def, fv);
        solver.set_time(c.t_start);
        return run_wetdry(solver, c, fv.cfl, limits);
    };
    return fv.precision == hydro::Precision::float32 ? run.template operator()<float>() : run.template operator()<double>();
}

// Observed order of an error between grids of n_coarse and n_fine cells along x.
inline double observed_order(double e_coarse, double e_fine, int n_coarse, int n_fine) {
    return std::log(e_coarse / e_fine) / std::log(double(n_fine) / double(n_coarse));
}

}  // namespace flotsam::test
