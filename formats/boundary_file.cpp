#include "formats/boundary_file.hpp"

#include "common/error.hpp"

namespace flotsam {

BoundaryWriter::BoundaryWriter(const std::string& path, const BoundaryFileDef& def)
    : file_(nc::File::create(path)), stations_(def.x.size()) {
    nc::File& f = file_;
    if (def.y.size() != stations_ || def.names.size() != stations_ || stations_ == 0)
        fail(path, "stations", "positions and names must be given, one of each per station");
    const int dt = f.def_dim("time", NC_UNLIMITED), ds = f.def_dim("station", stations_);
    time_ = cf::def_time(f, dt, "time", "time since the start of the run");
    const std::string grid_mapping = cf::grid_mapping_of(def.crs);
    const bool mapped = !def.crs.empty();
    const int vn = f.def_text_var("station_name", {ds}, cf::longest(def.names));
    f.put_att(vn, "cf_role", std::string("timeseries_id"));
    f.put_att(vn, "long_name", std::string("box side and index along it"));
    auto coordinate = [&](const char* name, const char* standard_name, const char* long_name) {
        return cf::def_var(f, {.name = name,
                               .dims = {ds},
                               .units = "m",
                               .standard_name = mapped ? standard_name : "",
                               .long_name = long_name,
                               .grid_mapping = grid_mapping});
    };
    const int vx = coordinate("x", "projection_x_coordinate", "station x");
    const int vy = coordinate("y", "projection_y_coordinate", "station y");
    cf::def_crs(f, def.crs);
    auto series = [&](const char* name, const char* standard_name, const char* units, const char* long_name, bool fill) {
        return cf::def_var(f, {.name = name,
                               .dims = {dt, ds},
                               .units = units,
                               .standard_name = standard_name,
                               .long_name = long_name,
                               .coordinates = "time y x station_name",
                               .fill = fill,
                               .grid_mapping = grid_mapping});
    };
    eta_ = series("eta", boundary_names::level, "m", "water level above still water (the bed's where dry)", false);
    u_ = series("u", boundary_names::x_velocity, "m s-1", "depth-averaged velocity toward +x (0 where dry)", false);
    v_ = series("v", boundary_names::y_velocity, "m s-1", "depth-averaged velocity toward +y (0 where dry)", false);
    depth_ = series("depth", boundary_names::depth, "m", "water depth", false);
    cf::put_conventions(f, "timeSeries");
    cf::put_kind(f, boundary_names::file_kind);
    for (const auto& [k, val] : def.attributes) f.put_att(NC_GLOBAL, k, val);
    f.enddef();
    f.put(vn, def.names);
    f.put(vx, def.x);
    f.put(vy, def.y);
}

void BoundaryWriter::write(std::size_t first, std::size_t count, const std::vector<double>& time,
                           const std::vector<double>& eta, const std::vector<double>& depth, const std::vector<double>& u,
                           const std::vector<double>& v) {
    if (count == 0) return;
    const std::size_t n = count * stations_;
    if (time.size() < count || eta.size() < n || depth.size() < n || u.size() < n || v.size() < n)
        fail(file_.path(), "boundary samples", "arrays shorter than the samples to write");
    file_.put_slab(time_, {first}, {count}, time.data());
    for (const auto& [var, values] : {std::pair{eta_, &eta}, {depth_, &depth}, {u_, &u}, {v_, &v}})
        file_.put_slab(var, {first, 0}, {count, stations_}, values->data());
    file_.sync();
}

}  // namespace flotsam
