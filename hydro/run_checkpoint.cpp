// Writing and reading hydro checkpoints (run_checkpoint.hpp).
#include "hydro/run_checkpoint.hpp"

#include <cstring>
#include <type_traits>
#include <variant>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/sha256.hpp"

namespace flotsam::hydro {

namespace {

// The attributes of the bookkeeping, in the order they are hashed.
struct Field {
    const char* name;
    double value;
};
std::vector<Field> fields_of(const Checkpoint& c) {
    return {{"time", c.time},
            {"steps", double(c.steps)},
            {"next_frame", double(c.next_frame)},
            {"next_gauge", double(c.next_gauge)},
            {"volume_start", c.volume_start},
            {"pump_level", c.pump_level},
            {"pump_stopped", c.pump_stopped ? 1.0 : 0.0}};
}

template <class T>
void hash_array(Sha256& h, const std::string& name, const std::vector<T>& a) {
    const std::uint64_t n = a.size(), bytes = sizeof(T);
    h.update(name.data(), name.size());
    h.update(&n, sizeof n);
    h.update(&bytes, sizeof bytes);
    h.update(a.data(), a.size() * sizeof(T));
}

}  // namespace

std::string checkpoint_checksum(const Checkpoint& c, const std::vector<StateArray>& state, const Summary& sum) {
    Sha256 h;
    for (const Field& f : fields_of(c)) {
        h.update(f.name, std::strlen(f.name));
        h.update(&f.value, sizeof f.value);
    }
    h.update(c.key.data(), c.key.size());
    for (std::size_t k = 0; k < state.size(); ++k)
        std::visit([&](const auto* a) { hash_array(h, "state_" + std::to_string(k), *a); }, state[k]);
    hash_array(h, "max_depth", sum.max_depth);
    hash_array(h, "max_speed", sum.max_speed);
    hash_array(h, "arrival_time", sum.arrival);
    return h.hex();
}

void write_checkpoint(const std::string& path, const std::vector<StateArray>& state, const Summary& sum, const Checkpoint& c) {
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        std::vector<int> vs;
        for (std::size_t k = 0; k < state.size(); ++k)
            std::visit(
                [&](const auto* a) {
                    using T = typename std::remove_cvref_t<decltype(*a)>::value_type;
                    const int d = f.def_dim("state_" + std::to_string(k) + "_cell", a->size());
                    vs.push_back(f.def_var("state_" + std::to_string(k), std::is_same_v<T, float> ? NC_FLOAT : NC_DOUBLE, {d}));
                },
                state[k]);
        const int dw = f.def_dim("window_cell", sum.max_depth.size());
        const int vmd = f.def_var("max_depth", NC_FLOAT, {dw}), vms = f.def_var("max_speed", NC_FLOAT, {dw}),
                  va = f.def_var("arrival_time", NC_FLOAT, {dw});
        for (const Field& field : fields_of(c))
            if (std::string(field.name) == "pump_stopped")
                f.put_att(NC_GLOBAL, field.name, c.pump_stopped ? 1 : 0);
            else
                f.put_att(NC_GLOBAL, field.name, field.value);
        f.put_att(NC_GLOBAL, "restart_key", c.key);
        f.put_att(NC_GLOBAL, "state_sha256", checkpoint_checksum(c, state, sum));
        f.enddef();
        for (std::size_t k = 0; k < state.size(); ++k) std::visit([&](const auto* a) { f.put(vs[k], *a); }, state[k]);
        f.put(vmd, sum.max_depth);
        f.put(vms, sum.max_speed);
        f.put(va, sum.arrival);
        f.close();
    }
    out.commit();
}

Checkpoint read_checkpoint(const std::string& path, const std::vector<StateArray>& state, Summary& sum) {
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
    const auto checksum = f.att_text(NC_GLOBAL, "state_sha256");
    if (!checksum)
        fail(path, "attribute 'state_sha256'", "missing: written by an older flotsam, whose checkpoints cannot be continued");
    for (std::size_t k = 0; k < state.size(); ++k) {
        const std::string name = "state_" + std::to_string(k);
        std::visit(
            [&](auto* a) {
                using T = typename std::remove_cvref_t<decltype(*a)>::value_type;
                std::vector<T> v;
                if constexpr (std::is_same_v<T, float>)
                    v = f.get_float(f.var(name));
                else
                    v = f.get_double(f.var(name));
                if (v.size() != a->size())
                    fail(path, "variable '" + name + "'", "size does not match this scene's grid and solver");
                *a = std::move(v);
            },
            state[k]);
    }
    sum.max_depth = f.get_float(f.var("max_depth"));
    sum.max_speed = f.get_float(f.var("max_speed"));
    sum.arrival = f.get_float(f.var("arrival_time"));
    if (checkpoint_checksum(c, state, sum) != *checksum)
        fail(path, "attribute 'state_sha256'",
             "does not match what the checkpoint holds: the file is damaged (changed after it was written)");
    return c;
}

double read_checkpoint_time(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    return f.att_double(NC_GLOBAL, "time").value_or(-1.0);
}

std::string read_checkpoint_key(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    const auto key = f.att_text(NC_GLOBAL, "restart_key");
    if (!key) fail(path, "attribute 'restart_key'", "missing: written by an older flotsam, whose checkpoints cannot be continued");
    return *key;
}

}  // namespace flotsam::hydro
