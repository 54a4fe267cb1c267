#include "formats/flow_file.hpp"

#include <algorithm>

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
    const int vt = f.def_var("time", NC_DOUBLE, {dt});
    f.put_att(vt, "standard_name", std::string("time"));
    f.put_att(vt, "units", std::string(flow_names::time_units));
    f.put_att(vt, "calendar", std::string("standard"));
    f.put_att(vt, "axis", std::string("T"));
    f.put_att(vt, "long_name", std::string("time since the start of the run"));
    const int vx = f.def_var("x", NC_DOUBLE, {dx});
    f.put_att(vx, "standard_name", std::string("projection_x_coordinate"));
    f.put_att(vx, "units", std::string("m"));
    f.put_att(vx, "axis", std::string("X"));
    f.put_att(vx, "long_name", std::string("x of cell centre (east)"));
    const int vy = f.def_var("y", NC_DOUBLE, {dy});
    f.put_att(vy, "standard_name", std::string("projection_y_coordinate"));
    f.put_att(vy, "units", std::string("m"));
    f.put_att(vy, "axis", std::string("Y"));
    f.put_att(vy, "long_name", std::string("y of cell centre (north)"));
    const int vz = f.def_var("z", NC_FLOAT, {dy, dx});
    f.put_att(vz, "units", std::string("m"));
    f.put_att(vz, "positive", std::string("up"));
    f.put_att(vz, "long_name", std::string("bed elevation above still water level, buildings included"));

    const std::size_t cy = std::min<std::size_t>(ny_, std::size_t(def.chunk)),
                      cx = std::min<std::size_t>(nx_, std::size_t(def.chunk));
    auto field3 = [&](const char* name, const char* sn, const char* units, const char* ln) {
        const int v = f.def_var(name, NC_FLOAT, {dt, dy, dx});
        f.def_chunking(v, {1, cy, cx});
        if (def.deflate_level > 0) f.def_deflate(v, def.deflate_level, true);
        f.put_att(v, "standard_name", std::string(sn));
        f.put_att(v, "units", std::string(units));
        f.put_att(v, "long_name", std::string(ln));
        f.put_att(v, "coordinates", std::string("time y x"));
        return v;
    };
    h_ = field3("h", flow_names::depth, "m", "water depth (0 where dry)");
    u_ = field3("u", flow_names::x_velocity, "m s-1", "depth-averaged velocity toward +x (0 where dry)");
    v_ = field3("v", flow_names::y_velocity, "m s-1", "depth-averaged velocity toward +y (0 where dry)");

    auto field2 = [&](const char* name, const char* units, const char* ln) {
        const int v = f.def_var(name, NC_FLOAT, {dy, dx});
        f.def_chunking(v, {cy, cx});
        if (def.deflate_level > 0) f.def_deflate(v, def.deflate_level, true);
        f.put_att(v, "units", std::string(units));
        f.put_att(v, "long_name", std::string(ln));
        return v;
    };
    maxd_ = field2("max_depth", "m", "largest water depth over the run");
    maxs_ = field2("max_speed", "m s-1", "largest depth-averaged speed over the run");
    arr_ = field2("arrival_time", "s", "time when the water depth first exceeds arrival_depth");
    f.def_fill(arr_, 9.969209968386869e36);
    f.put_att(arr_, "arrival_depth", def.arrival_depth);
    f.put_att(arr_, "comment", std::string("fill value where the depth never exceeds arrival_depth"));

    if (ngauge_ > 0 && def.gauge_samples > 0) {
        const int dg = f.def_dim("gauge", ngauge_), dgt = f.def_dim("gauge_time", def.gauge_samples);
        const int gn = f.def_var("gauge_name", NC_STRING, {dg});
        f.put_att(gn, "cf_role", std::string("timeseries_id"));
        const int gx = f.def_var("gauge_x", NC_DOUBLE, {dg});
        f.put_att(gx, "units", std::string("m"));
        const int gy = f.def_var("gauge_y", NC_DOUBLE, {dg});
        f.put_att(gy, "units", std::string("m"));
        gt_ = f.def_var("gauge_time", NC_DOUBLE, {dgt});
        f.put_att(gt_, "standard_name", std::string("time"));
        f.put_att(gt_, "units", std::string(flow_names::time_units));
        f.put_att(gt_, "calendar", std::string("standard"));
        f.put_att(gt_, "sample_interval_s", def.gauge_interval);
        auto gauge_var = [&](const char* name, const char* sn, const char* units, const char* ln) {
            const int v = f.def_var(name, NC_FLOAT, {dgt, dg});
            if (sn[0]) f.put_att(v, "standard_name", std::string(sn));
            f.put_att(v, "units", std::string(units));
            f.put_att(v, "long_name", std::string(ln));
            f.put_att(v, "coordinates", std::string("gauge_time gauge_x gauge_y gauge_name"));
            return v;
        };
        geta_ = gauge_var("gauge_eta", "sea_surface_height_above_mean_sea_level", "m",
                          "water level above still water at the gauge (bed level where dry)");
        gh_ = gauge_var("gauge_h", "", "m", "water depth at the gauge");  // no standard_name: h alone carries it
        gu_ = gauge_var("gauge_u", "", "m s-1", "x velocity at the gauge");
        gv_ = gauge_var("gauge_v", "", "m s-1", "y velocity at the gauge");

        f.put_att(NC_GLOBAL, "Conventions", std::string("CF-1.11"));
        for (const auto& [k, val] : def.attributes) f.put_att(NC_GLOBAL, k, val);
        f.enddef();
        std::vector<std::string> names;
        std::vector<double> xs, ys;
        for (const auto& g2 : def.gauges) {
            names.push_back(g2.name);
            xs.push_back(g2.x);
            ys.push_back(g2.y);
        }
        f.put(gn, names);
        f.put(gx, xs);
        f.put(gy, ys);
    } else {
        f.put_att(NC_GLOBAL, "Conventions", std::string("CF-1.11"));
        for (const auto& [k, val] : def.attributes) f.put_att(NC_GLOBAL, k, val);
        f.enddef();
    }
    f.put(vt, def.frame_times);
    f.put(vx, g.xs());
    f.put(vy, g.ys());
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

}  // namespace flotsam
