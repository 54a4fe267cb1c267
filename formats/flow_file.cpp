#include "formats/flow_file.hpp"

#include <algorithm>
#include <limits>

#include "common/cf.hpp"
#include "common/error.hpp"

namespace flotsam {

FlowWriter::FlowWriter(nc::File f) : file_(std::move(f)) {}

FlowWriter::FlowWriter(const std::string& path, const FlowFileDef& def) : file_(nc::File::create(path)) {
    nc::File& f = file_;
    const Grid& g = def.window;
    nx_ = std::size_t(g.nx);
    ny_ = std::size_t(g.ny);
    ngauge_ = def.gauges.size();
    if (def.z.size() != g.size()) fail(path, "variable 'z'", "size does not match the output window");

    const int dt = f.def_dim("time", def.frame_times.size());
    const int dy = f.def_dim("y", ny_), dx = f.def_dim("x", nx_);
    const int vt = cf::def_time(f, dt, "time", "time since the start of the run");
    const cf::XYAxes axes = cf::def_xy(f, dx, dy, "cell centre");
    cf::def_crs(f, def.crs);
    const std::string grid_mapping = cf::grid_mapping_of(def.crs);
    const int vz = cf::def_var(f, {.name = "z",
                                   .type = NC_FLOAT,
                                   .dims = {dy, dx},
                                   .units = "m",
                                   .long_name = "bed elevation above still water level, buildings included",
                                   .grid_mapping = grid_mapping});
    f.put_att(vz, "positive", std::string("up"));

    const std::size_t cy = std::min<std::size_t>(ny_, std::size_t(def.chunk)),
                      cx = std::min<std::size_t>(nx_, std::size_t(def.chunk));
    auto field3 = [&](const char* name, const char* standard_name, const char* units, const char* long_name) {
        return cf::def_var(f, {.name = name,
                               .type = NC_FLOAT,
                               .dims = {dt, dy, dx},
                               .units = units,
                               .standard_name = standard_name,
                               .long_name = long_name,
                               .coordinates = "time y x",
                               .chunks = {1, cy, cx},
                               .deflate = def.deflate_level,
                               .grid_mapping = grid_mapping});
    };
    h_ = field3("h", flow_names::depth, "m", "water depth (0 where dry)");
    // The long names differ only in "x-"/"y-component of": QGIS (MDAL) pairs them as one vector.
    u_ = field3("u", flow_names::x_velocity, "m s-1", "x-component of depth-averaged velocity (0 where dry)");
    v_ = field3("v", flow_names::y_velocity, "m s-1", "y-component of depth-averaged velocity (0 where dry)");

    auto field2 = [&](const char* name, const char* units, const char* long_name) {
        return cf::def_var(f, {.name = name,
                               .type = NC_FLOAT,
                               .dims = {dy, dx},
                               .units = units,
                               .long_name = long_name,
                               .chunks = {cy, cx},
                               .deflate = def.deflate_level,
                               .grid_mapping = grid_mapping});
    };
    maxd_ = field2("max_depth", "m", "largest water depth over the run");
    maxs_ = field2("max_speed", "m s-1", "largest depth-averaged speed over the run");
    arr_ = field2("arrival_time", "s", "time when the water depth first exceeds arrival_depth");
    f.def_fill(arr_, cf::fill_value);
    f.put_att(arr_, "arrival_depth", def.arrival_depth);
    f.put_att(arr_, "comment", std::string("fill value where the depth never exceeds arrival_depth"));
    max_level_ = cf::def_var(f, {.name = "max_level",
                                 .type = NC_FLOAT,
                                 .dims = {dy, dx},
                                 .units = "m",
                                 .standard_name = "sea_surface_height_above_mean_sea_level",
                                 .long_name = "highest water level over the run (z + max_depth)",
                                 .chunks = {cy, cx},
                                 .deflate = def.deflate_level,
                                 .fill = true,
                                 .grid_mapping = grid_mapping});
    f.put_att(max_level_, "cell_methods", std::string("time: maximum"));
    f.put_att(max_level_, "comment", std::string("fill value where the cell was never wet"));
    flooded_ = cf::def_var(f, {.name = "flooded",
                               .type = NC_BYTE,
                               .dims = {dy, dx},
                               .long_name = "1 where the water depth exceeded flood_depth at some time in the run",
                               .chunks = {cy, cx},
                               .deflate = def.deflate_level,
                               .grid_mapping = grid_mapping});
    f.put_att(flooded_, "flag_values", std::vector<std::int8_t>{0, 1});
    f.put_att(flooded_, "flag_meanings", std::string("dry flooded"));
    f.put_att(flooded_, "flood_depth", def.flood_depth);
    f.put_att(flooded_, "comment",
              std::string("the inundation line is the 0.5 contour of this flag (docs/hydro.md, \"What a run writes\")"));
    auto runup_scalar = [&](const char* name, const char* long_name) {
        const int v = cf::def_var(f, {.name = name, .units = "m", .long_name = long_name, .fill = true});
        f.put_att(v, "flood_depth", def.flood_depth);
        return v;
    };
    runup_z_ = runup_scalar("runup_elevation", "highest ground elevation above still water that flooded (flooded = 1)");
    runup_x_ = runup_scalar("runup_x", "x of the cell centre where the runup elevation was reached");
    runup_y_ = runup_scalar("runup_y", "y of the cell centre where the runup elevation was reached");

    const bool gauges = ngauge_ > 0 && def.gauge_samples > 0;
    int gn = -1, gx = -1, gy = -1;
    if (gauges) {
        const int dg = f.def_dim("gauge", ngauge_), dgt = f.def_dim("gauge_time", def.gauge_samples);
        std::vector<std::string> names;
        for (const auto& gauge : def.gauges) names.push_back(gauge.name);
        gn = f.def_text_var("gauge_name", {dg}, cf::longest(names));
        f.put_att(gn, "cf_role", std::string("timeseries_id"));
        gx = cf::def_var(f, {.name = "gauge_x", .dims = {dg}, .units = "m"});
        gy = cf::def_var(f, {.name = "gauge_y", .dims = {dg}, .units = "m"});
        gt_ = cf::def_time(f, dgt, "gauge_time", "", false);
        f.put_att(gt_, "sample_interval_s", def.gauge_interval);
        auto gauge_var = [&](const char* name, const char* standard_name, const char* units, const char* long_name) {
            return cf::def_var(f, {.name = name,
                                   .type = NC_FLOAT,
                                   .dims = {dgt, dg},
                                   .units = units,
                                   .standard_name = standard_name,
                                   .long_name = long_name,
                                   .coordinates = "gauge_time gauge_x gauge_y gauge_name"});
        };
        geta_ = gauge_var("gauge_eta", "sea_surface_height_above_mean_sea_level", "m",
                          "water level above still water at the gauge (bed level where dry)");
        gh_ = gauge_var("gauge_h", "", "m", "water depth at the gauge");  // no standard_name: h alone carries it
        gu_ = gauge_var("gauge_u", "", "m s-1", "x velocity at the gauge");
        gv_ = gauge_var("gauge_v", "", "m s-1", "y velocity at the gauge");
    }
    cf::put_conventions(f);
    cf::put_kind(f, "flow");
    for (const auto& [k, val] : def.attributes) f.put_att(NC_GLOBAL, k, val);
    f.enddef();

    if (gauges) {
        std::vector<std::string> names;
        std::vector<double> xs, ys;
        for (const auto& gauge : def.gauges) {
            names.push_back(gauge.name);
            xs.push_back(gauge.x);
            ys.push_back(gauge.y);
        }
        f.put(gn, names);
        f.put(gx, xs);
        f.put(gy, ys);
    }
    f.put(vt, def.frame_times);
    f.put(axes.x, g.xs());
    f.put(axes.y, g.ys());
    f.put(vz, def.z);
}

FlowWriter FlowWriter::reopen(const std::string& path) {
    FlowWriter w(nc::File::open_write(path));
    w.find_vars();
    return w;
}

void FlowWriter::find_vars() {
    h_ = file_.var("h");
    u_ = file_.var("u");
    v_ = file_.var("v");
    time_ = file_.var("time");
    maxd_ = file_.var("max_depth");
    maxs_ = file_.var("max_speed");
    arr_ = file_.var("arrival_time");
    max_level_ = file_.var("max_level");
    flooded_ = file_.var("flooded");
    runup_z_ = file_.var("runup_elevation");
    runup_x_ = file_.var("runup_x");
    runup_y_ = file_.var("runup_y");
    nx_ = file_.dim_length("x");
    ny_ = file_.dim_length("y");
    if (file_.has_dim("gauge")) {
        ngauge_ = file_.dim_length("gauge");
        gt_ = file_.var("gauge_time");
        geta_ = file_.var("gauge_eta");
        gh_ = file_.var("gauge_h");
        gu_ = file_.var("gauge_u");
        gv_ = file_.var("gauge_v");
    }
}

void FlowWriter::write_frame(std::size_t k, const std::vector<float>& h, const std::vector<float>& u, const std::vector<float>& v) {
    const std::vector<std::size_t> start = {k, 0, 0}, count = {1, ny_, nx_};
    file_.put_slab(h_, start, count, h.data());
    file_.put_slab(u_, start, count, u.data());
    file_.put_slab(v_, start, count, v.data());
}

void FlowWriter::write_gauges(std::size_t first, std::size_t count, const std::vector<double>& time, const std::vector<float>& eta,
                              const std::vector<float>& h, const std::vector<float>& u, const std::vector<float>& v) {
    if (gt_ < 0 || count == 0) return;
    file_.put_slab(gt_, {first}, {count}, time.data());
    const std::vector<std::size_t> s = {first, 0}, c = {count, ngauge_};
    file_.put_slab(geta_, s, c, eta.data());
    file_.put_slab(gh_, s, c, h.data());
    file_.put_slab(gu_, s, c, u.data());
    file_.put_slab(gv_, s, c, v.data());
}

void FlowWriter::write_summary(const std::vector<float>& max_depth, const std::vector<float>& max_speed,
                               const std::vector<float>& arrival_time) {
    file_.put(maxd_, max_depth);
    file_.put(maxs_, max_speed);
    file_.put(arr_, arrival_time);
}

void FlowWriter::write_runup(const RunupSummary& r) {
    file_.put(max_level_, cf::filled(r.max_level));
    file_.put(flooded_, r.flooded);
    file_.put(runup_z_, cf::filled(std::vector<double>{r.elevation}));
    file_.put(runup_x_, cf::filled(std::vector<double>{r.x}));
    file_.put(runup_y_, cf::filled(std::vector<double>{r.y}));
}

RunupSummary runup_summary(const Grid& window, const std::vector<float>& z, const std::vector<float>& max_depth,
                           double flood_depth) {
    RunupSummary r;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    r.elevation = r.x = r.y = nan;
    r.max_level.resize(max_depth.size());
    r.flooded.resize(max_depth.size());
    for (int j = 0; j < window.ny; ++j)
        for (int i = 0; i < window.nx; ++i) {
            const std::size_t k = window.index(i, j);
            r.max_level[k] = max_depth[k] > 0.0f ? z[k] + max_depth[k] : float(nan);
            r.flooded[k] = max_depth[k] > flood_depth ? 1 : 0;
            if (r.flooded[k] && !(z[k] <= r.elevation)) {  // strictly higher, or the first
                r.elevation = z[k];
                r.x = window.x(i);
                r.y = window.y(j);
            }
        }
    return r;
}

}  // namespace flotsam
