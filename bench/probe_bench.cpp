// The cost of reading a flow file in a child process before flotsam reads it
// (nc::probe_structure, docs/reliability.md "libhdf5 and corrupted files"), on a flow of
// the size of a whole 1 cm flow: the real layout's city window at 1 cm (910 x 400 cells,
// the window `scene import` recommends), 421 frames 1 s apart (a 420 s run), h, u and v
// in (1, 64, 64) chunks with shuffle and deflate, as `flotsam hydro` writes them. The
// values are smooth fields plus noise kept to 17 bits of mantissa, which compresses
// to about the size of a real one (1.0-1.1 GB). Prints the size, the probe's wall time (the first
// probe of the file, then a second process's, both with the file in the page cache), the
// time to open it as a replay does (FlowReader) and to read every frame of h, u and v (what
// a replay of the whole flow reads).
// Not a test: timings belong here.
//
//   build/probe_bench [FLOW]   (default runs/probe_bench/flow_1gb.nc; written when missing)
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "common/netcdf.hpp"
#include "common/netcdf_probe.hpp"
#include "debris/flow_reader.hpp"
#include "formats/flow_file.hpp"

using namespace flotsam;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A deterministic field: waves plus noise with the low 6 mantissa bits cleared.
float value(std::size_t k, std::size_t frame, int field, std::uint64_t& state) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double noise = double(state >> 40) / double(1ULL << 24) - 0.5;
    const double x = double(k % 910) * 0.01, y = double(k / 910) * 0.01, t = double(frame);
    const double base = field == 0 ? 0.05 + 0.03 * std::sin(0.7 * x - 0.05 * t) * std::cos(1.3 * y)
                                   : 0.4 * std::sin(0.5 * x + (field == 1 ? 0.02 : 0.03) * t + y);
    float f = float(base + 0.002 * noise);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits &= ~0x3Fu;
    std::memcpy(&f, &bits, sizeof f);
    return field == 0 ? std::fabs(f) : f;
}

void write_flow(const std::string& path) {
    FlowFileDef d;
    d.window = Grid{910, 400, -0.995, -4.095, 0.01, 0.01};
    d.z.assign(d.window.size(), -0.05f);
    for (int k = 0; k <= 420; ++k) d.frame_times.push_back(double(k));
    d.attributes["title"] = "probe_bench: a flow of a whole 1 cm flow's size";
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    FlowWriter w(path + ".part", d);
    std::vector<float> h(d.window.size()), u(h.size()), v(h.size());
    std::uint64_t state = 1;
    for (std::size_t frame = 0; frame < d.frame_times.size(); ++frame) {
        for (std::size_t k = 0; k < h.size(); ++k) {
            h[k] = value(k, frame, 0, state);
            u[k] = value(k, frame, 1, state);
            v[k] = value(k, frame, 2, state);
        }
        w.write_frame(frame, h, u, v);
    }
    w.write_summary(h, u, std::vector<float>(h.size(), 0.0f));
    w.write_runup(runup_summary(d.window, d.z, h, 0.001));
    w.close();
    std::filesystem::rename(path + ".part", path);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string path = argc > 1 ? argv[1] : "runs/probe_bench/flow_1gb.nc";
    if (!std::filesystem::exists(path)) {
        const auto t0 = std::chrono::steady_clock::now();
        write_flow(path);
        std::printf("wrote %s in %.1f s\n", path.c_str(), seconds_since(t0));
    }
    std::printf("flow: %s, %.3f GB\n", path.c_str(), double(std::filesystem::file_size(path)) / 1e9);
    // The probe, twice: in this process (the first probe of the file), and in a fresh
    // process (a second command on the same file); the page cache is warm for both after
    // the reads below have run once.
    for (int pass = 0; pass < 2; ++pass) {
        std::fflush(stdout);
        auto t0 = std::chrono::steady_clock::now();
        const pid_t child = ::fork();
        if (child == 0) {
            nc::probe_structure(path);
            ::_exit(0);
        }
        int status = 0;
        ::waitpid(child, &status, 0);
        const double probe = seconds_since(t0);
        t0 = std::chrono::steady_clock::now();
        nc::set_probe_enabled(false);
        std::size_t frames = 0;
        double open_s = 0;
        {
            debris::FlowReaderDef def;
            def.decode_tiles = false;
            const debris::FlowReader reader(path, def);
            open_s = seconds_since(t0);
            frames = reader.description().frame_times.size();
        }
        t0 = std::chrono::steady_clock::now();
        {
            const nc::File f = nc::File::open_read(path);
            std::vector<float> slab(910 * 400);
            for (const char* name : {"h", "u", "v"}) {
                const int var = f.var(name);
                for (std::size_t k = 0; k < frames; ++k) f.get_slab(var, {k, 0, 0}, {1, 400, 910}, slab.data());
            }
        }
        const double read_all = seconds_since(t0);
        nc::set_probe_enabled(true);
        std::printf("pass %d: probe %.3f s (exit %d); FlowReader open %.3f s; every frame of h, u, v read %.1f s; probe / read = %.2f %%\n",
                    pass + 1, probe, WIFEXITED(status) ? WEXITSTATUS(status) : -1, open_s, read_all, 100.0 * probe / read_all);
    }
    return 0;
}
