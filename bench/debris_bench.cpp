// Debris benchmark: FD-like and LD-like bodies (local contact, multi collision) through
// a 420 s synthetic flow at 2 cm on a port-sized window with building blocks. Prints
// steps per second and the compute time of one 420 s body-run, with frame reading
// (I/O and decompression) reported apart. Then many bodies in one run (a yard's worth):
// body steps per second of wall and of processor time at each count of --bodies, over
// the first --seconds of the flow. Then bodies that meet (--yards): empty 40 ft containers
// packed 0.5 m apart in yards of 50, afloat and carried by a current onto a wall where they
// pile up, with body-body contact on and off, over --yard-seconds. Not a test: timings
// belong here.
//
//   build/debris_bench [scratch_dir] [--bodies 100,1000,5000] [--yards 100,1000,5000] [--threads 2]
//                      [--seconds 180] [--yard-seconds 150]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <string>

#include "debris/catalogue.hpp"
#include "debris/world.hpp"
#include "formats/flow_file.hpp"
#include "formats/trajectory_file.hpp"

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

// N paper boxes at seeded places on the open ground and water of the window (headings
// spread), in one world, each alone (each its own group): the cost of a sweep's worth of
// single bodies.
void many_bodies(const std::string& path, const std::vector<std::uint8_t>& mask, int count, int threads, double seconds) {
    WorldDef def = default_world_def();
    def.threads = threads;
    World w(path, mask, def);
    std::uint64_t state = 12345;
    auto uniform = [&] {  // SplitMix64
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    };
    for (int n = 0; n < count;) {
        BodyDef b = default_body_def();
        b.x = window.x(0) + 0.2 + uniform() * (window.nx * window.dx - 0.4);
        b.y = window.y(0) + 0.2 + uniform() * (window.ny * window.dy - 0.4);
        b.heading = uniform() * M_PI;
        bool clear = true;  // the centre and a margin off the buildings
        for (double dx : {-0.15, 0.0, 0.15})
            for (double dy : {-0.15, 0.0, 0.15}) clear = clear && !building(b.x + dx, b.y + dy);
        if (!clear) continue;
        b.name = "b" + std::to_string(n++);
        w.add_body(b);
    }
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    w.advance_to(seconds);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    long steps = 0, released = 0;
    for (std::size_t k = 0; k < w.size(); ++k) {
        steps += w.stats()[k].steps;
        released += (w.states()[k].flags & flag_released) ? 1 : 0;
    }
    std::printf(
        "%5d bodies, %d threads, 0-%.0f s: %ld body steps (%ld released) in %.2f s wall, %.2f s processor: "
        "%.3g body steps per wall s, %.3g per processor s\n",
        count, threads, seconds, steps, released, wall, cpu, double(steps) / wall, double(steps) / cpu);
}

// A basin of 2.4 x 1.2 km on 10 m cells, 3 m of water over a flat bed, walls of buildings
// across it every 90 m from its north edge (one cell thick), and a current of 1 m/s north
// (0.9 to 1.1 m/s across it), frames every 10 s for 300 s.
const Grid basin{240, 120, 5.0, 5.0, 10.0, 10.0};
constexpr double wall_pitch = 90.0;  // [m]
bool basin_wall(double, double y) { return y > 1150.0 || std::fmod(1150.0 - y, wall_pitch) > wall_pitch - 10.0; }

std::string make_basin_flow(const std::string& path) {
    FlowFileDef def;
    def.window = basin;
    for (int k = 0; k <= 30; ++k) def.frame_times.push_back(10.0 * k);
    def.z.assign(basin.size(), -3.0f);
    for (int j = 0; j < basin.ny; ++j)
        for (int i = 0; i < basin.nx; ++i)
            if (basin_wall(basin.x(i), basin.y(j))) def.z[basin.index(i, j)] = 5.0f;
    FlowWriter w(path, def);
    std::vector<float> h(basin.size()), u(basin.size(), 0.0f), v(basin.size());
    for (int j = 0; j < basin.ny; ++j)
        for (int i = 0; i < basin.nx; ++i) {
            const std::size_t c = basin.index(i, j);
            const bool wall = basin_wall(basin.x(i), basin.y(j));
            h[c] = wall ? 0.0f : 3.0f;
            v[c] = wall ? 0.0f : float(1.0 + 0.1 * std::sin(basin.x(i) / 200.0));
        }
    for (std::size_t k = 0; k < def.frame_times.size(); ++k) w.write_frame(k, h, u, v);
    std::vector<float> zero(basin.size(), 0.0f);
    w.write_summary(zero, zero, v);
    w.close();
    return path;
}

// `count` containers in yards of 50 (5 along by 10 across, 0.2 m apart), each yard 3 m
// south of a wall, in rows under the basin's walls, each yard one group (its bodies meet):
// the current carries them onto the walls at once, where they pile up and stay pressed
// against each other. Through the first `seconds`; with body contact on and off.
void yards(const std::string& path, const std::vector<std::uint8_t>& mask, int count, int threads, double seconds) {
    const BodyDef c = catalogue_body_def("container_40ft", "bench");
    const int per_yard = 50, along = 5;
    const double gap = 0.2, pitch_x = 5 * (c.length + gap) + 20.0;
    const int yards_across = int((basin.nx * basin.dx - 40.0) / pitch_x);
    for (const bool contact : {true, false}) {
        std::vector<BodyDef> bodies;
        std::vector<int> group;
        for (int n = 0; n < count; ++n) {
            const int yard = n / per_yard, k = n % per_yard;
            BodyDef b = c;
            b.name = "c" + std::to_string(n);
            const double top = 1150.0 - (yard / yards_across) * wall_pitch - 3.0;  // the yard's north edge
            b.x = 20.0 + c.length / 2 + (yard % yards_across) * pitch_x + (k % along) * (c.length + gap);
            b.y = top - c.width / 2 - (k / along) * (c.width + gap);
            bodies.push_back(b);
            group.push_back(yard);
        }
        WorldDef def = scaled_to_bodies(default_world_def(), bodies, false);
        def.threads = threads;
        def.step.body_contact = contact;
        World w(path, mask, def);
        for (std::size_t k = 0; k < bodies.size(); ++k) w.add_body(bodies[k], group[k]);
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        w.advance_to(seconds);
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
        long steps = 0, contacts = 0, unresolved = 0;
        double deepest = 0.0;
        for (std::size_t k = 0; k < w.size(); ++k) {
            steps += w.stats()[k].steps;
            contacts += w.stats()[k].body_contacts;
            unresolved += w.stats()[k].unresolved;
            deepest = std::max(deepest, w.stats()[k].max_body_overlap);
        }
        std::printf(
            "%5d containers in %d yards, body contact %-3s, %d threads, 0-%.0f s: %ld body steps, %ld of them in contact, "
            "%ld unresolved, deepest overlap left %.2g m; %.2f s wall, %.2f s processor: %.3g body steps per wall s, %.3g "
            "per processor s\n",
            count, (count + per_yard - 1) / per_yard, contact ? "on" : "off", threads, seconds, steps, contacts, unresolved,
            deepest, wall, cpu, double(steps) / wall, double(steps) / cpu);
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::string dir = (std::filesystem::temp_directory_path() / "flotsam-debris-bench").string();
    std::vector<int> counts, yard_counts;
    int threads = 2;
    double seconds = 180.0, yard_seconds = 150.0;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        if (a == "--bodies" && k + 1 < argc) {
            std::stringstream ss(argv[++k]);
            for (std::string n; std::getline(ss, n, ',');) counts.push_back(std::stoi(n));
        } else if (a == "--yards" && k + 1 < argc) {
            std::stringstream ss(argv[++k]);
            for (std::string n; std::getline(ss, n, ',');) yard_counts.push_back(std::stoi(n));
        } else if (a == "--yard-seconds" && k + 1 < argc) {
            yard_seconds = std::stod(argv[++k]);
        } else if (a == "--threads" && k + 1 < argc) {
            threads = std::stoi(argv[++k]);
        } else if (a == "--seconds" && k + 1 < argc) {
            seconds = std::stod(argv[++k]);
        } else {
            dir = a;
        }
    }
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
            const double io = w.flow().read_stats().load_seconds, compute = wall - io;
            const BodyState& s = w.states()[0];
            const BodyStats& st = w.stats()[0];
            std::printf(
                "%s run %d: %ld steps, compute %.3f s (%.0f steps/s), frame I/O %.3f s for %zu frames, "
                "end (%.2f, %.2f) yaw %.0f deg, collisions %ld, unresolved %ld, axis shifts %ld\n",
                c.name, repeat, st.steps, compute, double(st.steps) / compute, io, w.flow().read_stats().frames_loaded, s.x, s.y,
                s.theta * 180 / M_PI, st.collisions, st.unresolved, st.axis_shifts);
        }
    }
    for (const int n : counts) many_bodies(path, mask, n, threads, seconds);
    if (!yard_counts.empty()) {
        const std::string basin_path = dir + "/basin-10m.nc";
        if (!std::filesystem::exists(basin_path)) make_basin_flow(basin_path);
        std::vector<std::uint8_t> walls(basin.size());
        for (int j = 0; j < basin.ny; ++j)
            for (int i = 0; i < basin.nx; ++i) walls[basin.index(i, j)] = basin_wall(basin.x(i), basin.y(j)) ? 1 : 0;
        for (const int n : yard_counts) yards(basin_path, walls, n, threads, yard_seconds);
    }
    return 0;
}
