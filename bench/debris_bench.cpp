// Debris benchmark: FD-like and LD-like bodies (local contact, multi collision) through
// a 420 s synthetic flow at 2 cm on a port-sized window with building blocks. Prints
// steps per second and the compute time of one 420 s body-run, with frame reading
// (I/O and decompression) reported apart. Not a test: timings belong here.
//
//   build/debris_bench [scratch_dir]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "debris/world.hpp"
#include "formats/flow_file.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

const Grid window{200, 125, 0.51, -2.99, 0.02, 0.02};  // x 0.5..4.5, y −3..−0.5

bool building(double x, double y) {
    const bool land = !(x > 0.9 && x < 3.75 && y > -2.65 && y < -2.05);
    // 12 cm blocks on a 20 cm pitch (8 cm roads), east of the LD start and along the basin.
    const double fx = std::fmod(x + 10.0, 0.2), fy = std::fmod(y + 10.0, 0.2);
    return land && x > 3.05 && fx < 0.12 && fy < 0.12;
}
double bed(double x, double y) {
    if (building(x, y)) return 0.045;
    if (x > 0.9 && x < 3.75 && y > -2.65 && y < -2.05)
        return -0.03 + 0.01 * std::fabs(y + 2.35) / 0.3;  // basin, shallower at the quays
    return 0.01 + 0.005 * std::max(0.0, y + 2.0);         // land
}
// Level: a smooth rise to 6 cm at 300 s, then the return flow back to still water.
double level(double t) { return t < 300 ? 0.06 * std::sin(0.5 * M_PI * t / 300) : 0.06 * std::cos(0.5 * M_PI * (t - 300) / 120); }

std::string make_flow(const std::string& path) {
    FlowFileDef def;
    def.window = window;
    for (int k = 0; k <= 420; ++k) def.frame_times.push_back(k);
    def.z.resize(window.size());
    for (int j = 0; j < window.ny; ++j)
        for (int i = 0; i < window.nx; ++i) def.z[window.index(i, j)] = float(bed(window.x(i), window.y(j)));
    FlowWriter w(path, def);
    std::vector<float> h(window.size()), u(window.size()), v(window.size());
    for (int k = 0; k <= 420; ++k) {
        const double t = k, eta = level(t), sign = t < 300 ? 1.0 : -0.3;  // return flow weaker than the leading wave
        for (int j = 0; j < window.ny; ++j)
            for (int i = 0; i < window.nx; ++i) {
                const double x = window.x(i), y = window.y(j), depth = std::max(0.0, eta - bed(x, y));
                const std::size_t c = window.index(i, j);
                h[c] = float(depth);
                const double speed = depth > 0 ? sign * (0.05 + 2.0 * depth) : 0.0;
                u[c] = float(speed * (1.0 + 0.2 * std::sin(3 * y + 0.05 * t)));
                v[c] = float(depth > 0 ? 0.04 * std::sin(2 * x - 0.03 * t) + 0.03 * std::cos(5 * y) : 0.0);
            }
        w.write_frame(std::size_t(k), h, u, v);
    }
    std::vector<float> zero(window.size(), 0.0f);
    w.write_summary(zero, zero, zero);
    w.close();
    return path;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : (std::filesystem::temp_directory_path() / "flotsam-debris-bench").string();
    std::filesystem::create_directories(dir);
    const std::string path = dir + "/port-2cm.nc";
    if (!std::filesystem::exists(path)) {
        const auto t0 = std::chrono::steady_clock::now();
        make_flow(path);
        std::printf("wrote %s (%d x %d cells, 421 frames) in %.1f s\n", path.c_str(), window.nx, window.ny,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::vector<std::uint8_t> mask(window.size());
    for (int j = 0; j < window.ny; ++j)
        for (int i = 0; i < window.nx; ++i) mask[window.index(i, j)] = building(window.x(i), window.y(j)) ? 1 : 0;

    struct Case {
        const char* name;
        double x, y, heading_deg;
    };
    for (const Case c : {Case{"FD", 1.37, -2.15, 0.0}, Case{"LD", 2.94, -1.26, 90.0}}) {
        for (int repeat = 0; repeat < 2; ++repeat) {
            WorldDef def = default_world_def();
            def.threads = 1;
            World w(path, mask, def);
            BodyDef b = default_body_def();
            b.name = c.name;
            b.x = c.x;
            b.y = c.y;
            b.heading = c.heading_deg * M_PI / 180.0;
            w.add_body(b);
            const auto t0 = std::chrono::steady_clock::now();
            w.advance_to(420.0);
            const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            const double io = w.flow().load_seconds(), compute = wall - io;
            const BodyState& s = w.states()[0];
            const BodyStats& st = w.stats()[0];
            std::printf(
                "%s run %d: %ld steps, compute %.3f s (%.0f steps/s), frame I/O %.3f s for %zu frames, "
                "end (%.2f, %.2f) yaw %.0f deg, collisions %ld, unresolved %ld, axis shifts %ld\n",
                c.name, repeat, st.steps, compute, double(st.steps) / compute, io, w.flow().frames_loaded(), s.x, s.y,
                s.theta * 180 / M_PI, st.collisions, st.unresolved, st.axis_shifts);
        }
    }
    return 0;
}
