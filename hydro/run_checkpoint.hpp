// Checkpoints of a hydro run (run.cpp): the solver's exact state, the maxima so far and
// where the output stands, so that --restart continues an interrupted run to the bytes
// of an uninterrupted one. Written atomically; the restart key (restart_key.hpp) says
// which settings, scene and boundary files wrote it.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "hydro/run_frames.hpp"

namespace flotsam::hydro {

struct Checkpoint {
    double time = 0.0;
    long steps = 0;
    std::size_t next_frame = 0, next_gauge = 0;
    double volume_start = 0.0;
    double pump_level = 0.0;
    bool pump_stopped = false;
    std::string key;  // restart_key() of the run that wrote it
};

template <class S>
void write_checkpoint(const std::string& path, S& s, const Summary& sum, const Checkpoint& c) {
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        const auto arrays = s.state_arrays();
        std::vector<int> vs;
        for (std::size_t k = 0; k < arrays.size(); ++k) {
            const int d = f.def_dim("state_" + std::to_string(k) + "_cell", arrays[k]->size());
            vs.push_back(f.def_var("state_" + std::to_string(k), NC_DOUBLE, {d}));
        }
        const int dw = f.def_dim("window_cell", sum.max_depth.size());
        const int vmd = f.def_var("max_depth", NC_FLOAT, {dw}), vms = f.def_var("max_speed", NC_FLOAT, {dw}),
                  va = f.def_var("arrival_time", NC_FLOAT, {dw});
        f.put_att(NC_GLOBAL, "time", c.time);
        f.put_att(NC_GLOBAL, "steps", double(c.steps));
        f.put_att(NC_GLOBAL, "next_frame", double(c.next_frame));
        f.put_att(NC_GLOBAL, "next_gauge", double(c.next_gauge));
        f.put_att(NC_GLOBAL, "volume_start", c.volume_start);
        f.put_att(NC_GLOBAL, "pump_level", c.pump_level);
        f.put_att(NC_GLOBAL, "pump_stopped", c.pump_stopped ? 1 : 0);
        f.put_att(NC_GLOBAL, "restart_key", c.key);
        f.enddef();
        for (std::size_t k = 0; k < arrays.size(); ++k) f.put(vs[k], *arrays[k]);
        f.put(vmd, sum.max_depth);
        f.put(vms, sum.max_speed);
        f.put(va, sum.arrival);
        f.close();
    }
    out.commit();
}

// The simulated time a checkpoint was written at [s]; < 0 when it has none.
double read_checkpoint_time(const std::string& path);

// The restart key a checkpoint holds; throws for one written before they held keys.
std::string read_checkpoint_key(const std::string& path);

template <class S>
Checkpoint read_checkpoint(const std::string& path, S& s, Summary& sum) {
    const nc::File f = nc::File::open_read(path);
    auto need = [&](const char* name) {
        auto v = f.att_double(NC_GLOBAL, name);
        if (!v) fail(path, std::string("attribute '") + name + "'", "missing: not a flotsam checkpoint");
        return *v;
    };
    Checkpoint c;
    c.time = need("time");
    c.steps = long(need("steps"));
    c.next_frame = std::size_t(need("next_frame"));
    c.next_gauge = std::size_t(need("next_gauge"));
    c.volume_start = need("volume_start");
    c.pump_level = need("pump_level");
    c.pump_stopped = need("pump_stopped") != 0.0;
    c.key = read_checkpoint_key(path);
    const auto arrays = s.state_arrays();
    for (std::size_t k = 0; k < arrays.size(); ++k) {
        const std::string name = "state_" + std::to_string(k);
        auto v = f.get_double(f.var(name));
        if (v.size() != arrays[k]->size())
            fail(path, "variable '" + name + "'", "size does not match this scene's grid and solver");
        *arrays[k] = std::move(v);
    }
    sum.max_depth = f.get_float(f.var("max_depth"));
    sum.max_speed = f.get_float(f.var("max_speed"));
    sum.arrival = f.get_float(f.var("arrival_time"));
    return c;
}

}  // namespace flotsam::hydro
