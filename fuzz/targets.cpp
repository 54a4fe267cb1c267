#include "fuzz/targets.hpp"

#include <netcdf.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/netcdf_probe.hpp"
#include "common/timeseries.hpp"
#include "fuzz/nc_model.hpp"
#include "data/dem_import.hpp"
#include "data/resample.hpp"
#include "debris/flow_reader.hpp"
#include "debris/world.hpp"
#include "formats/flow_file.hpp"
#include "formats/scene.hpp"
#include "sweep/members.hpp"
#include "sweep/spec_file.hpp"
#include "sweep/sweep_file.hpp"
#include "sweep/sweep_stats.hpp"

namespace flotsam::fuzz {

namespace {

// ---- reading the fuzz input ----

struct Bytes {
    const std::uint8_t* p;
    std::size_t n;
    bool empty() const { return n == 0; }
    std::uint8_t byte() {
        if (!n) return 0;
        --n;
        return *p++;
    }
    std::uint32_t u32() {
        std::uint32_t v = 0;
        for (int k = 0; k < 4; ++k) v = (v << 8) | byte();
        return v;
    }
    double raw_double() {
        std::uint64_t v = 0;
        for (int k = 0; k < 8; ++k) v = (v << 8) | byte();
        double d;
        std::memcpy(&d, &v, sizeof d);
        return d;
    }
    // A value that readers must catch: non-finite, fill values, absurd sizes, signs.
    double value() {
        static const double table[] = {std::nan(""),
                                       std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(),
                                       0.0,
                                       -1.0,
                                       1.0,
                                       0.5,
                                       1e30,
                                       9.969209968386869e36,
                                       -9.969209968386869e36,
                                       1e300,
                                       -1e300,
                                       1e-300,
                                       2147483648.0,
                                       -2147483649.0,
                                       3e9,
                                       1e6,
                                       -0.05,
                                       100.0};
        const std::uint8_t k = byte();
        if (k < sizeof table / sizeof table[0]) return table[k];
        if (k < 200) return double(int(k) - 128) * 0.1;
        return raw_double();
    }
    std::string text() {
        static const char* table[] = {"", "gauge", "start", "FD", "LD", "LC+MC", "CC+SC", "x", "0/1", "1/0", "a/b", "-1/2"};
        const std::uint8_t k = byte();
        if (k < sizeof table / sizeof table[0]) return table[k];
        if (k == 200) return std::string(300, 'a');
        std::string s;
        const int len = byte() % 12;
        for (int q = 0; q < len; ++q) s += char(byte());
        return s;
    }
};

std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
    const std::string path = work_dir() + "/" + name;
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return path;
}

// Applies the edits the input describes.
void edit(Model& m, Bytes& in) {
    int edits = 0;
    while (!in.empty() && edits++ < 16) {
        const std::uint8_t op = in.byte() % 10;
        if (m.vars.empty() || m.dims.empty()) return;
        Var& v = m.vars[in.byte() % m.vars.size()];
        switch (op) {
            case 0: {  // resize a dimension (every variable on it follows)
                auto& d = m.dims[in.byte() % m.dims.size()];
                const std::size_t sizes[] = {0, 1, 2, 3, d.second ? d.second - 1 : 0, d.second + 1, d.second * 2};
                d.second = sizes[in.byte() % 7];
                for (Var& w : m.vars) m.fit(w);
                break;
            }
            case 1: {  // move one variable onto a new dimension of another length: tables disagree
                if (v.dims.empty()) break;
                const std::size_t len = in.byte() % 6;
                m.dims.emplace_back("fuzz_dim_" + std::to_string(m.dims.size()), len);
                v.dims[in.byte() % v.dims.size()] = int(m.dims.size() - 1);
                m.fit(v);
                break;
            }
            case 2:
            case 3: {  // one value
                if (v.is_text()) {
                    if (!v.texts.empty()) v.texts[in.u32() % v.texts.size()] = in.text();
                } else if (!v.numbers.empty()) {
                    v.numbers[in.u32() % v.numbers.size()] = in.value();
                }
                break;
            }
            case 4: {  // every value
                if (v.is_text()) {
                    const std::string s = in.text();
                    std::fill(v.texts.begin(), v.texts.end(), s);
                } else {
                    std::fill(v.numbers.begin(), v.numbers.end(), in.value());
                }
                break;
            }
            case 5:  // transpose a 2-D variable (z(x, y) for z(y, x))
                if (v.dims.size() == 2) std::swap(v.dims[0], v.dims[1]);
                m.fit(v);
                break;
            case 6:  // drop the variable
                m.vars.erase(m.vars.begin() + (&v - m.vars.data()));
                break;
            case 7: {  // an attribute: a special number, a text, or gone
                std::vector<Att>& atts = in.byte() % 2 ? m.atts : v.atts;
                if (atts.empty()) break;
                Att& a = atts[in.byte() % atts.size()];
                const std::uint8_t how = in.byte() % 3;
                if (how == 0) {
                    atts.erase(atts.begin() + (&a - atts.data()));
                } else if (a.type == NC_CHAR || a.type == NC_STRING) {
                    a.text = in.text();
                } else {
                    a.type = NC_DOUBLE;
                    a.numbers.assign(1, in.value());
                }
                break;
            }
            case 8: {  // a fill value that some data equal
                if (v.is_text() || v.numbers.empty()) break;
                v.atts.push_back({"_FillValue", v.type, "", {v.numbers[in.u32() % v.numbers.size()]}});
                break;
            }
            case 9: {  // a variable's type: float, int or byte
                const nc_type types[] = {NC_FLOAT, NC_INT, NC_BYTE, NC_DOUBLE};
                if (!v.is_text()) v.type = types[in.byte() % 4];
                break;
            }
        }
    }
}

// ---- the small valid files the NetCDF targets start from ----

Scene base_scene() {
    Scene s;
    s.grid = Grid{12, 10, 0.05, 0.05, 0.1, 0.1};
    s.z.resize(s.grid.size());
    s.building.assign(s.grid.size(), 0);
    s.manning_n.assign(s.grid.size(), 0.013);
    for (int j = 0; j < s.grid.ny; ++j)
        for (int i = 0; i < s.grid.nx; ++i) {
            const bool b = i >= 8 && i < 10 && j >= 6 && j < 8;
            s.z[s.grid.index(i, j)] = -0.05 + 0.01 * i + (b ? 0.1 : 0.0);
            s.building[s.grid.index(i, j)] = b ? 1 : 0;
        }
    s.points = {{"G1", "gauge", 0.3, 0.5, 0.0}, {"FD", "start", 0.4, 0.5, 30.0}};
    s.sections = {{"S1", 0.6, 0.0, 1.0}, {"S2", 1.0, 0.2, 0.8}};
    s.regions = {{"R1", {{0.8, 0.0}, {1.2, 0.0}, {1.2, 1.0}, {0.8, 1.0}}}};
    s.title = "fuzz base scene";
    return s;
}

struct Base {
    std::string scene, flow, sweep;
    Scene scene_data;
};

const Base& base() {
    static const Base b = [] {
        Base out;
        out.scene_data = base_scene();
        out.scene = work_dir() + "/scene.nc";
        write_scene(out.scene, out.scene_data, "fuzz");
        // A flow on the scene's grid: three frames of a uniform current toward +x.
        const Scene& s = out.scene_data;
        FlowFileDef fd;
        fd.window = s.grid;
        fd.z.assign(s.z.begin(), s.z.end());
        fd.frame_times = {0.0, 1.0, 2.0};
        fd.gauges = {{"G1", 0.3, 0.5}};
        fd.gauge_samples = 3;
        fd.gauge_interval = 1.0;
        out.flow = work_dir() + "/flow.nc";
        {
            FlowWriter w(out.flow, fd);
            const std::size_t n = s.grid.size();
            for (std::size_t k = 0; k < 3; ++k)
                w.write_frame(k, std::vector<float>(n, 0.08f), std::vector<float>(n, 0.2f), std::vector<float>(n, 0.0f));
            w.write_gauges(0, 3, {0.0, 1.0, 2.0}, {0.f, 0.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 0.f});
            w.write_summary(std::vector<float>(n, 0.08f), std::vector<float>(n, 0.2f), std::vector<float>(n, 0.0f));
            w.close();
        }
        // A sweep: two bodies, two parameter sets, one flow, straight tracks across S1.
        sweep::SweepResult r;
        r.spec_file = "spec.toml";
        r.spec_sha256 = "0";
        r.scene_file = out.scene;
        r.design = "one_at_a_time";
        r.flows = {out.flow};
        r.bodies = {"FD", "LD"};
        r.variants = {"LC+MC"};
        r.params = {{"control", sweep::paper_control(), true}, {"cd1x2", sweep::paper_control(), false}};
        r.params[1].values[0] *= 2;
        r.member_count = 4;
        r.output_interval = 1.0;
        r.world.step.dt_max = 0.01;
        r.time = {0.0, 1.0, 2.0, 3.0};
        for (int m = 0; m < 4; ++m) {
            sweep::MemberRecord rec;
            rec.id = m;
            rec.body = m / 2;
            rec.param_set = m % 2;
            rec.body_name = r.bodies[std::size_t(rec.body)];
            rec.start_name = rec.body_name;
            rec.variant_name = "LC+MC";
            rec.def = debris::default_body_def();  // LC+MC
            if (rec.param_set == 1) rec.def.cd1 *= 2;
            rec.def.length = 0.25;
            rec.def.width = rec.def.height = 0.1;
            rec.def.specific_gravity = 0.25;
            rec.def.x = 0.3;
            rec.def.y = 0.4 + 0.1 * m;
            for (int k = 0; k < 4; ++k) {
                rec.track.x.push_back(0.3 + 0.2 * k * (1 + m % 2));
                rec.track.y.push_back(rec.def.y);
                rec.track.yaw_deg.push_back(10.0 * k);
                rec.track.u.push_back(0.2);
                rec.track.v.push_back(0.0);
                rec.track.omega.push_back(0.0);
                rec.track.status.push_back(std::int8_t(k ? 3 : 1));
            }
            r.members.push_back(rec);
        }
        out.sweep = work_dir() + "/sweep.nc";
        sweep::write_sweep_file(out.sweep, r);
        return out;
    }();
    return b;
}

// The base file `from` edited by the input, written to `name`; empty when NetCDF refused
// the edits.
std::string edited(const std::string& from, const std::string& name, const std::uint8_t* data, std::size_t size) {
    static std::map<std::string, Model> models;
    auto it = models.find(from);
    if (it == models.end()) it = models.emplace(from, load_model(from)).first;
    Model m = it->second;
    Bytes in{data, size};
    edit(m, in);
    const std::string path = work_dir() + "/" + name;
    return save_model(m, path) ? path : std::string();
}

void expect_named_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error&) {}
}

// The base file `from` with bytes changed, written to `name`: the input (after its first
// byte, which chose this mode) is a list of (offset: 2 bytes, value: 1 byte), offsets
// taken modulo the file's size (the small base files fit in 64 kB: their structure, heaps
// and chunk index all within reach). Corrupted structure is what makes libhdf5 itself
// crash or hang; the readers must then give a named error (nc::probe_structure).
std::string mutated(const std::string& from, const std::string& name, const std::uint8_t* data, std::size_t size) {
    static std::map<std::string, std::string> bytes_of;
    auto it = bytes_of.find(from);
    if (it == bytes_of.end()) {
        std::ifstream in(from, std::ios::binary);
        it = bytes_of.emplace(from, std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>())).first;
    }
    std::string b = it->second;
    for (std::size_t k = 0; k + 3 <= size && !b.empty(); k += 3) {
        const std::size_t offset = (std::size_t(data[k]) << 8 | data[k + 1]) % b.size();
        b[offset] = char(data[k + 2]);
    }
    const std::string path = work_dir() + "/" + name;
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(b.data(), std::streamsize(b.size()));
    return path;
}

// A NetCDF target's file: structure edits of the base file (first byte below 0xF0), or
// byte mutations of it (0xF0 and above). Edited files are structurally valid (written by
// NetCDF), so the libhdf5 probe, a fork per file, is left to FLOTSAM_NO_PROBE; a mutated
// file is read with the probe on, as a user's would be.
struct TargetFile {
    std::string path;
    bool probe;
};
TargetFile target_file(const std::string& from, const std::string& name, const std::uint8_t* data, std::size_t size) {
    if (size > 0 && data[0] >= 0xF0) return {mutated(from, name, data + 1, size - 1), true};
    return {edited(from, name, data, size), false};
}

// Runs f with the probe on or as the environment says, and restores it.
void with_probe(bool on, const std::function<void()>& f) {
    const bool before = nc::probe_enabled();
    if (on) nc::set_probe_enabled(true);
    try {
        f();
    } catch (...) {
        nc::set_probe_enabled(before);
        throw;
    }
    nc::set_probe_enabled(before);
}

}  // namespace

const std::string& work_dir() {
    static const std::string dir = [] {
        // Valid but huge inputs (a 1e5 x 1e5 DEM header) get their named error at once.
        ::setenv("FLOTSAM_MEMORY_LIMIT_MB", "512", 0);
        const auto d = std::filesystem::temp_directory_path() / ("flotsam-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        static const std::string* const to_remove = new std::string(d.string());  // outlives static destruction
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(*to_remove, ec);
        });
        return d.string();
    }();
    return dir;
}

void csv(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return;
    const bool dem = data[0] & 1;
    const std::string path = write_input(dem ? "dem.asc" : "series.csv", data + 1, size - 1);
    expect_named_error([&] {
        if (dem) {
            const Dem d = read_ascii_grid(path);
            const Grid to =
                grid_covering(d.grid.x_min_edge(), d.grid.x_max_edge(), d.grid.y_min_edge(), d.grid.y_max_edge(), 2.0 * d.grid.dx);
            (void)resample(d.grid, d.z, to);
        } else {
            const TimeSeries s = read_time_series_csv(path);
            for (double t : {s.start(), 0.5 * (s.start() + s.end()), s.end()}) (void)s.at(t);
            require_coverage(s, 0.0, 10.0);
        }
    });
}

void toml(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return;
    (void)base();  // scene.nc and flow.nc for specs that name them
    const bool features = data[0] & 1;
    const std::string path = write_input(features ? "features.toml" : "spec.toml", data + 1, size - 1);
    std::filesystem::current_path(work_dir());
    expect_named_error([&] {
        if (features) {
            (void)read_import_features(path, kainan_import_features());
        } else {
            const sweep::SweepSpec spec = sweep::read_sweep_spec(path);
            (void)sweep::enumerate_members(spec);
        }
    });
}

void settings(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return;
    static const std::vector<std::vector<std::string>> commands = {{"hydro"},           {"debris"},
                                                                   {"sweep"},           {"sweep", "merge"},
                                                                   {"stats"},           {"scene", "generate"},
                                                                   {"scene", "import"}, {"boundary", "generate"}};
    const auto& command = commands[data[0] % commands.size()];
    const std::string path = write_input("settings.toml", data + 1, size - 1);
    CLI::App app{"flotsam"};
    register_hydro_commands(app, "");
    register_data_commands(app, "");
    register_debris_commands(app, "");
    register_pipeline_commands(app, "");
    std::vector<std::string> args = {"flotsam"};
    args.insert(args.end(), command.begin(), command.end());
    args.push_back("--config");
    args.push_back(path);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    expect_named_error([&] { (void)expand_config_files(app, int(argv.size()), argv.data()); });
}

void scene(const std::uint8_t* data, std::size_t size) {
    const TargetFile file = target_file(base().scene, "edited_scene.nc", data, size);
    const std::string& path = file.path;
    if (path.empty()) return;
    with_probe(file.probe, [&] {
        expect_named_error([&] {
            const Scene s = read_scene(path);
            for (const auto& r : s.regions) (void)r.contains(0.5, 0.5);
            (void)s.find_point("FD");
            (void)debris::buildings_on_grid(s, base().scene_data.grid);
        });
    });
}

void flow(const std::uint8_t* data, std::size_t size) {
    const TargetFile file = target_file(base().flow, "edited_flow.nc", data, size);
    const std::string& path = file.path;
    if (path.empty()) return;
    with_probe(file.probe, [&] { flow_replay(path); });
}

void flow_replay(const std::string& path) {
    expect_named_error([&] {
        debris::World world(path, {});
        debris::BodyDef b = debris::default_body_def();
        b.name = "fuzz";
        const Grid& g = world.flow().grid();
        b.x = g.x(g.nx / 2);
        b.y = g.y(g.ny / 2);
        b.length = 0.1;
        b.width = b.height = 0.05;
        world.add_body(b);
        world.advance_to(std::min(world.flow().description().end_time(), world.time() + 1.5));
    });
}

void sweep(const std::uint8_t* data, std::size_t size) {
    const TargetFile file = target_file(base().sweep, "edited_sweep.nc", data, size);
    const std::string& path = file.path;
    if (path.empty()) return;
    with_probe(file.probe, [&] {
        expect_named_error([&] {
            const sweep::SweepResult r = sweep::read_sweep_file(path);
            (void)sweep::compute_stats(r, base().scene_data);
            sweep::write_summary_csv(work_dir() + "/summary.csv", r);
        });
    });
}

const std::string& base_file(const std::string& which) {
    static const std::string none;
    if (which == "scene") return base().scene;
    if (which == "flow") return base().flow;
    if (which == "sweep") return base().sweep;
    return none;
}

const std::vector<Target>& targets() {
    static const std::vector<Target> t = {{"csv", csv},     {"toml", toml}, {"settings", settings},
                                          {"scene", scene}, {"flow", flow}, {"sweep", sweep}};
    return t;
}

}  // namespace flotsam::fuzz
