// A side driven by another run's output (hydro/forced_side.hpp): the record read in time
// and along the side, and the waves it lets in.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <memory>
#include <sstream>

#include "common/error.hpp"
#include "hydro/solver.hpp"
#include "test_support.hpp"

using namespace flotsam;
using namespace flotsam::hydro;

namespace {

// A record at points `along` and times `time` whose values are f(t, a).
template <class F>
std::shared_ptr<SideRecord> record_of(const std::vector<double>& time, const std::vector<double>& along, F&& f) {
    auto r = std::make_shared<SideRecord>();
    r->source = "test record";
    r->time = time;
    r->along = along;
    for (double t : time)
        for (double a : along) r->level.push_back(f(t, a));
    return r;
}

}  // namespace

// Uneven sample times, as another model's output may have. A level linear in time is read
// exactly by both interpolants, a quadratic one by the cubic between samples that have
// neighbours on both sides (its slopes are the parabola's through three samples; the end
// samples take a secant); the linear one misses the quadratic by the chord's sag, here
// (t - 0.7)(2 - t) at t = 1.3: 0.42 m.
TEST(ForcedSide, TimeInterpolationIsExactForALinearLevelAndTheCubicForAQuadraticOne) {
    const std::vector<double> time{0.0, 0.7, 2.0, 2.1, 5.0};
    const std::vector<double> along{0.0, 1.0};
    auto linear = record_of(time, along, [](double t, double a) { return 0.3 + 0.2 * t - 0.1 * a; });
    auto quadratic = record_of(time, along, [](double t, double) { return t * t; });
    const std::vector<double> cells{0.25, 0.75};
    std::vector<double> level, u, v, depth;
    for (ForcingTime kind : {ForcingTime::linear, ForcingTime::cubic}) {
        const ForcedSide side(linear, cells, 0.5, kind, "west");
        for (double t : {0.0, 0.35, 1.3, 2.05, 4.9, 5.0}) {
            side.sample(t, level, u, v, depth);
            EXPECT_NEAR(level[0], 0.3 + 0.2 * t - 0.025, 1e-14) << t;
            EXPECT_NEAR(level[1], 0.3 + 0.2 * t - 0.075, 1e-14) << t;
        }
        EXPECT_TRUE(u.empty());
    }
    const ForcedSide cubic(quadratic, cells, 0.5, ForcingTime::cubic, "west");
    const ForcedSide chord(quadratic, cells, 0.5, ForcingTime::linear, "west");
    for (double t : {0.7, 1.3, 2.0, 2.05, 2.1}) {
        cubic.sample(t, level, u, v, depth);
        EXPECT_NEAR(level[0], t * t, 1e-13) << t;
    }
    chord.sample(1.3, level, u, v, depth);
    EXPECT_NEAR(level[0], 1.69 + 0.42, 1e-12);
}

// Along the side: linear between points; half a cell beyond the last point is covered,
// more is an error that names the record and the span.
TEST(ForcedSide, AlongTheSideLinearAndAnUncoveredSideIsNamed) {
    auto r = record_of({0.0, 1.0}, {0.0, 2.0}, [](double, double a) { return a; });
    std::vector<double> level, u, v, depth;
    const ForcedSide side(r, {0.5, 1.5, 2.1}, 0.5, ForcingTime::linear, "south");
    side.sample(0.5, level, u, v, depth);
    EXPECT_DOUBLE_EQ(level[0], 0.5);
    EXPECT_DOUBLE_EQ(level[1], 1.5);
    EXPECT_DOUBLE_EQ(level[2], 2.0);
    try {
        ForcedSide(r, {0.5, 2.4}, 0.5, ForcingTime::linear, "south");
        FAIL() << "an uncovered side was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("test record"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("does not cover the side"), std::string::npos) << e.what();
    }
}

namespace {

// The 10 m channel of 0.1 m water of the level-boundary tests, driven on the west by a
// 1 cm hump over 0-3 s, east wall; the state after 12 s.
std::vector<double> channel_after_hump(const PhysicsDef& d) {
    Scene scene;
    scene.grid = Grid{200, 3, 0.025, 0.025, 0.05, 0.05};
    scene.z.assign(scene.grid.size(), -0.1);
    Solver solver(scene, d);
    while (solver.time() < 12.0 - 1e-9) solver.step(std::min(solver.stable_dt(), 12.0 - solver.time()));
    std::vector<double> out;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 200; ++i) out.push_back(solver.level(i, j));
    return out;
}

double hump(double t) {
    const double s = std::sin(std::acos(-1.0) * std::min(t, 3.0) / 3.0);
    return 0.01 * s * s;
}

}  // namespace

// A record that is the same along the side is the level series: the same wave enters,
// to round-off (the two read the same samples in time, one as a record, one as a CSV).
TEST(ForcedBoundary, AUniformRecordDrivesTheChannelAsTheLevelSeriesDoes) {
    const std::string dir = test::scratch_dir("ForcedUniform");
    std::vector<double> time;
    std::ostringstream csv;
    csv.precision(17);
    csv << "time,eta\n";
    for (int k = 0; k <= 130; ++k) {
        time.push_back(0.1 * k);
        csv << 0.1 * k << "," << hump(0.1 * k) << "\n";
    }
    PhysicsDef series = default_physics_def();
    series.default_manning_n = 0.0;
    series.east.kind = BoundaryKind::wall;
    series.west.kind = BoundaryKind::level;
    series.west.series_file = test::write_file(dir, "hump.csv", csv.str());
    PhysicsDef forced = series;
    forced.west.kind = BoundaryKind::forced;
    forced.west.record = record_of(time, {0.0, 0.15}, [](double t, double) { return hump(t); });
    const auto a = channel_after_hump(series), b = channel_after_hump(forced);
    double worst = 0.0, peak = 0.0;
    for (std::size_t c = 0; c < a.size(); ++c) {
        worst = std::max(worst, std::abs(a[c] - b[c]));
        peak = std::max(peak, std::abs(a[c]));
    }
    std::printf("level series against uniform record at 12 s: largest difference %.3e m (peak %.4f m)\n", worst, peak);
    EXPECT_GT(peak, 0.005);
    EXPECT_LT(worst, 1e-14);
}

namespace {

// A linear long wave of amplitude A on water h0 deep, entering a square basin at angle
// theta from +x: eta = A f(c t - (x cos theta + y sin theta)) with f a sine of wavelength
// L grown over its first wavelength (zero ahead of the front, so the basin starts at
// rest), velocity (g / c) eta along the wave's direction.
struct ObliqueWave {
    double A = 0.001, h0 = 0.1, L = 2.0, theta = 30.0 * std::acos(-1.0) / 180.0, g = 9.81;
    double c() const { return std::sqrt(g * h0); }
    double eta(double x, double y, double t) const {
        const double xi = c() * t - (x * std::cos(theta) + y * std::sin(theta));
        if (xi <= 0.0) return 0.0;
        const double s = std::min(1.0, xi / L), grow = s * s * (3.0 - 2.0 * s);
        return A * grow * std::sin(2.0 * std::acos(-1.0) * xi / L);
    }
};

std::shared_ptr<SideRecord> wave_record(const ObliqueWave& w, const Grid& g, Side side, double t_end) {
    auto r = std::make_shared<SideRecord>();
    r->source = "oblique wave";
    const bool xs = side == Side::west || side == Side::east;
    r->along = xs ? g.ys() : g.xs();
    const double edge = side == Side::west ? g.x_min_edge() : side == Side::east ? g.x_max_edge()
                        : side == Side::south ? g.y_min_edge() : g.y_max_edge();
    for (double t = 0.0; t <= t_end + 1e-9; t += 0.02) {
        r->time.push_back(t);
        for (double a : r->along) {
            const double x = xs ? edge : a, y = xs ? a : edge, e = w.eta(x, y, t), speed = w.g / w.c() * e;
            r->level.push_back(e);
            r->u.push_back(speed * std::cos(w.theta));
            r->v.push_back(speed * std::sin(w.theta));
        }
    }
    return r;
}

}  // namespace

// The wave enters through all four sides, each forced with level and velocity; inside,
// behind the grown front, the basin holds the wave at its angle. The angle is that of the
// plane wave, of the record's wavelength, that best matches the level (a search in 0.05°
// steps); the tolerance, 0.5°, is a tenth of the angle by which a wave would have to
// turn for its crests to move by a cell across the 4 m basin (atan(0.04 / 4) = 0.57° at
// the far side): a side that bent the wave would fail it.
TEST(ForcedBoundary, AnObliqueWaveEntersAtItsAngle) {
    const ObliqueWave w;
    Scene scene;
    scene.grid = Grid{100, 100, 0.02, 0.02, 0.04, 0.04};
    scene.z.assign(scene.grid.size(), -w.h0);
    PhysicsDef d = default_physics_def();
    d.default_manning_n = 0.0;
    const double t_end = 9.0;
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) {
        BoundaryDef& b = s == Side::west ? d.west : s == Side::east ? d.east : s == Side::south ? d.south : d.north;
        b.kind = BoundaryKind::forced;
        b.record = wave_record(w, scene.grid, s, t_end);
    }
    Solver solver(scene, d);
    while (solver.time() < t_end - 1e-9) solver.step(std::min(solver.stable_dt(), t_end - solver.time()));
    const Grid& g = scene.grid;
    const double k = 2.0 * std::acos(-1.0) / w.L;
    double best = 0.0, best_angle = 0.0, error2 = 0.0, count = 0.0;
    for (double deg = 20.0; deg <= 40.0 + 1e-9; deg += 0.05) {
        const double th = deg * std::acos(-1.0) / 180.0;
        std::complex<double> sum = 0.0;
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i)
                if (w.c() * t_end - (g.x(i) * std::cos(w.theta) + g.y(j) * std::sin(w.theta)) > w.L)
                    sum += solver.level(i, j) * std::exp(std::complex<double>(0.0, -k * (g.x(i) * std::cos(th) + g.y(j) * std::sin(th))));
        if (std::abs(sum) > best) {
            best = std::abs(sum);
            best_angle = deg;
        }
    }
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            if (w.c() * t_end - (g.x(i) * std::cos(w.theta) + g.y(j) * std::sin(w.theta)) > w.L) {
                error2 += std::pow(solver.level(i, j) - w.eta(g.x(i), g.y(j), t_end), 2);
                count += 1.0;
            }
    const double rms = std::sqrt(error2 / count);
    std::printf("oblique wave at 30 deg: enters at %.2f deg; RMS level error %.3e m behind the front (%g cells; amplitude %g m)\n",
                best_angle, rms, count, w.A);
    EXPECT_GT(count, 2000.0);
    EXPECT_NEAR(best_angle, 30.0, 0.5);
    EXPECT_LT(rms, 0.05 * w.A);
}

// A point the record has dry (its depth 0, its level only its own ground, here 3 cm above
// the edge cell's) sends no water over the lower edge: the dry land stays dry. The same
// record without its depth column reads as 3 cm of still water there and floods it.
TEST(ForcedBoundary, APointTheRecordHasDrySendsNoWater) {
    Scene scene;
    scene.grid = Grid{20, 3, 0.025, 0.025, 0.05, 0.05};
    scene.z.assign(scene.grid.size(), 0.05);
    PhysicsDef d = default_physics_def();
    d.default_manning_n = 0.0;
    d.east.kind = BoundaryKind::wall;
    d.west.kind = BoundaryKind::forced;
    auto dry = record_of({0.0, 10.0}, {0.0, 0.15}, [](double, double) { return 0.08; });
    dry->u.assign(dry->level.size(), 0.0);
    dry->v.assign(dry->level.size(), 0.0);
    auto wet = std::make_shared<SideRecord>(*dry);
    dry->depth.assign(dry->level.size(), 0.0);
    auto volume_after = [&](std::shared_ptr<SideRecord> r) {
        d.west.record = r;
        Solver solver(scene, d);
        while (solver.time() < 5.0 - 1e-9) solver.step(std::min(solver.stable_dt(), 5.0 - solver.time()));
        return solver.volume();
    };
    const double v_dry = volume_after(dry), v_wet = volume_after(wet);
    std::printf("volume after 5 s: record dry %.3e m^3, without its depth %.3e m^3\n", v_dry, v_wet);
    EXPECT_EQ(v_dry, 0.0);
    EXPECT_GT(v_wet, 1e-4);
}
