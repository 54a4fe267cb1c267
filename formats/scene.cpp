#include "formats/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/checks.hpp"
#include "common/sha256.hpp"
#include "common/units.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/version.hpp"

namespace flotsam {

bool Region::contains(double x, double y) const {
    // Even-odd ray casting toward +x.
    bool inside = false;
    const std::size_t n = polygon.size();
    for (std::size_t a = 0, b = n - 1; a < n; b = a++) {
        const double xa = polygon[a][0], ya = polygon[a][1], xb = polygon[b][0], yb = polygon[b][1];
        if ((ya > y) != (yb > y) && x < xa + (y - ya) * (xb - xa) / (yb - ya)) inside = !inside;
    }
    return inside;
}

template <class Cell>
std::vector<std::int32_t> building_components(int nx, int ny, const std::vector<Cell>& mask) {
    std::vector<std::int32_t> id(mask.size(), 0);
    if (mask.size() != std::size_t(nx) * std::size_t(ny)) return id;
    std::vector<std::size_t> stack;
    std::int32_t next = 0;
    for (std::size_t start = 0; start < mask.size(); ++start) {
        if (!mask[start] || id[start]) continue;
        id[start] = ++next;  // a new component, numbered by its first cell in the row-major scan
        stack.push_back(start);
        while (!stack.empty()) {
            const std::size_t k = stack.back();
            stack.pop_back();
            const int i = int(k % std::size_t(nx)), j = int(k / std::size_t(nx));
            const auto visit = [&](int ii, int jj) {
                if (ii < 0 || jj < 0 || ii >= nx || jj >= ny) return;
                const std::size_t n = std::size_t(jj) * std::size_t(nx) + std::size_t(ii);
                if (mask[n] && !id[n]) {
                    id[n] = next;
                    stack.push_back(n);
                }
            };
            visit(i - 1, j);
            visit(i + 1, j);
            visit(i, j - 1);
            visit(i, j + 1);
        }
    }
    return id;
}
template std::vector<std::int32_t> building_components(int, int, const std::vector<std::int8_t>&);
template std::vector<std::int32_t> building_components(int, int, const std::vector<std::uint8_t>&);

std::vector<std::int32_t> scene_building_ids(const Scene& s) {
    if (s.building.empty()) return {};
    bool matches = s.building_id.size() == s.building.size();
    for (std::size_t k = 0; matches && k < s.building.size(); ++k) matches = (s.building[k] != 0) == (s.building_id[k] > 0);
    return matches ? s.building_id : building_components(s.grid.nx, s.grid.ny, s.building);
}

const ScenePoint* Scene::find_point(const std::string& name) const {
    for (const auto& p : points)
        if (p.name == name) return &p;
    return nullptr;
}

namespace {

std::vector<double> read_field(const nc::File& f, const std::string& name, const Grid& g, double factor = 1.0) {
    const int v = f.var(name);
    const auto shape = f.shape(v);
    if (shape.size() != 2 || shape[0] != std::size_t(g.ny) || shape[1] != std::size_t(g.nx))
        fail(
            f.path(), "variable '" + name + "'",
            "shape must be (y, x) = (" + std::to_string(g.ny) + ", " + std::to_string(g.nx) + "), found " + [&] {
                std::string s = "(";
                for (std::size_t k = 0; k < shape.size(); ++k) s += (k ? ", " : "") + std::to_string(shape[k]);
                return s + ")";
            }());
    const auto dims = f.dim_names(v);
    if (dims[0] != f.dim_names(f.var("y"))[0] || dims[1] != f.dim_names(f.var("x"))[0])
        fail(f.path(), "variable '" + name + "'", "dimensions must be (y, x), found (" + dims[0] + ", " + dims[1] + ")");
    std::vector<double> values = nc::read_finite(f, name);
    if (factor != 1.0)
        for (double& a : values) a *= factor;
    return values;
}

// Every value of a field within [lo, hi] (physical bounds), or a named error with the cell.
void check_bounds(const std::string& path, const std::string& name, const std::vector<double>& v, const Grid& g, double lo,
                  double hi, const std::string& unit, const std::string& why) {
    for (std::size_t k = 0; k < v.size(); ++k)
        if (!(v[k] >= lo && v[k] <= hi)) {
            const int i = int(k % std::size_t(g.nx)), j = int(k / std::size_t(g.nx));
            fail(path, "variable '" + name + "'",
                 number_text(v[k]) + " " + unit + " at cell (i " + std::to_string(i) + ", j " + std::to_string(j) +
                     ") is outside [" + number_text(lo) + ", " + number_text(hi) + "] " + unit + " (" + why + ")");
        }
}

// A feature table column: one-dimensional, on dimension `dim` of length n. Checked before
// it is read, so a short column is a named error, never a read past its end.
void check_column(const nc::File& f, const std::string& var, const std::string& dim, std::size_t n) {
    const int v = f.var(var);
    const auto dims = f.value_dims(v);  // a string column's: without its string length
    const auto shape = f.value_shape(v);
    if (dims.size() == 1 && dims[0] == dim && shape[0] == n) return;
    // (Appended piecewise: GCC 12 warns -Wrestrict on one long a + b + c chain.)
    std::string found;
    for (std::size_t k = 0; k < dims.size(); ++k) {
        found += k ? ", " : "(";
        found += dims[k];
        found += " = ";
        found += std::to_string(shape[k]);
    }
    found += dims.empty() ? "a scalar" : ")";
    std::string problem = "must be one-dimensional on dimension '";
    problem += dim;
    problem += "' of length ";
    problem += std::to_string(n);
    problem += " (the length of the table's names), found ";
    problem += found;
    fail(f.path(), "variable '" + var + "'", problem);
}

std::vector<std::string> read_names(const nc::File& f, const std::string& var) {
    const int v = f.var(var);
    if (f.value_shape(v).size() != 1) fail(f.path(), "variable '" + var + "'", "must be one-dimensional");
    return f.get_strings(v);
}

// The names of a table: none empty, none twice (runs and statistics refer to them by name).
void check_names(const std::string& path, const std::string& var, const std::vector<std::string>& names) {
    for (std::size_t k = 0; k < names.size(); ++k) {
        if (names[k].empty()) fail(path, "variable '" + var + "'", "entry " + std::to_string(k) + " is an empty name");
        for (std::size_t q = 0; q < k; ++q)
            if (names[q] == names[k])
                fail(path, "variable '" + var + "'",
                     "'" + names[k] + "' is the name of entries " + std::to_string(q) + " and " + std::to_string(k) +
                         " (names must differ)");
    }
}

// The columns of table `table` ("point", "section", "region"), all checked against the
// length of its name column.
std::vector<std::string> read_table_names(const nc::File& f, const std::string& table, const std::vector<std::string>& columns) {
    const std::string name_var = table + "_name";
    const int v = f.var(name_var);
    const auto dims = f.value_dims(v);
    if (dims.size() != 1) fail(f.path(), "variable '" + name_var + "'", "must be one-dimensional");
    const std::vector<std::string> names = f.get_strings(v);
    for (const auto& c : columns) check_column(f, c, dims[0], names.size());
    return names;
}

}  // namespace

Scene read_scene(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    cf::require_kind(f, {"scene"});
    Scene s;
    s.path = path;
    if (f.shape(f.var("x")).size() != 1) fail(path, "variable 'x'", "must be one-dimensional");
    if (f.shape(f.var("y")).size() != 1) fail(path, "variable 'y'", "must be one-dimensional");
    // Coordinates in any length unit (km, ft) become metres.
    std::vector<double> x = nc::read_finite(f, "x");
    std::vector<double> y = nc::read_finite(f, "y");
    const double fx = units::length_factor(f, f.var("x")), fy = units::length_factor(f, f.var("y"));
    for (double& a : x) a *= fx;
    for (double& a : y) a *= fy;
    for (const auto* c : {&x, &y})
        for (double a : *c)
            if (!(std::fabs(a) <= 1e8))
                fail(path, c == &x ? "variable 'x'" : "variable 'y'",
                     number_text(a) + " m is no coordinate of a map (beyond 1e8 m; a fill value?)");
    s.grid = grid_from_coordinates(x, y, path);
    // The bed in metres, positive up, on Earth: from the deepest trench to the highest peak.
    const int vz = f.var("z");
    s.z = read_field(f, "z", s.grid, units::length_factor(f, vz) * units::vertical_sign(f, vz));
    check_bounds(path, "z", s.z, s.grid, -11000.0, 9000.0, "m", "no bed on Earth is deeper or higher: a fill value?");
    if (f.has_var("manning_n")) {
        s.manning_n = read_field(f, "manning_n", s.grid);
        for (std::size_t k = 0; k < s.manning_n.size(); ++k)
            if (!(s.manning_n[k] >= 0.0 && s.manning_n[k] < 1.0))
                fail(path, "variable 'manning_n'",
                     "value " + std::to_string(s.manning_n[k]) + " at flat index " + std::to_string(k) +
                         " is outside [0, 1) s m^-1/3");
    }
    if (f.has_var("building")) {
        const auto b = read_field(f, "building", s.grid);
        s.building.resize(b.size());
        for (std::size_t k = 0; k < b.size(); ++k) {
            if (b[k] != 0.0 && b[k] != 1.0)
                fail(path, "variable 'building'",
                     "must be 0 or 1, found " + std::to_string(b[k]) + " at flat index " + std::to_string(k));
            s.building[k] = std::int8_t(b[k]);
        }
    }
    if (f.has_var("building_id")) {
        if (s.building.empty()) fail(path, "variable 'building_id'", "given without the variable 'building' (the mask)");
        const auto ids = read_field(f, "building_id", s.grid);
        s.building_id.resize(ids.size());
        for (std::size_t k = 0; k < ids.size(); ++k) {
            if (!(ids[k] >= 0.0 && ids[k] < 2e9 && ids[k] == std::floor(ids[k])))
                fail(path, "variable 'building_id'",
                     "must be a whole number >= 0, found " + number_text(ids[k]) + " at flat index " + std::to_string(k));
            s.building_id[k] = std::int32_t(ids[k]);
        }
        // A mask edited without its ids (another tool): the ids no longer say which cells
        // are buildings, so the mask's components replace them.
        s.building_id = scene_building_ids(s);
    } else if (!s.building.empty()) {
        s.building_id = building_components(s.grid.nx, s.grid.ny, s.building);  // a scene written before the ids
    }
    const bool has_eta0 = f.has_var("eta0"), has_u0 = f.has_var("u0"), has_v0 = f.has_var("v0");
    if (has_eta0) {
        const int v = f.var("eta0");
        s.eta0 = read_field(f, "eta0", s.grid, units::length_factor(f, v) * units::vertical_sign(f, v));
        check_bounds(path, "eta0", s.eta0, s.grid, -11000.0, 9000.0, "m", "a water level on Earth: a fill value?");
    }
    if (has_u0 != has_v0) fail(path, has_u0 ? "variable 'u0'" : "variable 'v0'", "u0 and v0 must be given together");
    if (has_u0) {
        s.u0 = read_field(f, "u0", s.grid, units::speed_factor(f, f.var("u0")));
        s.v0 = read_field(f, "v0", s.grid, units::speed_factor(f, f.var("v0")));
        check_bounds(path, "u0", s.u0, s.grid, -1000.0, 1000.0, "m/s", "no water flows faster: a fill value?");
        check_bounds(path, "v0", s.v0, s.grid, -1000.0, 1000.0, "m/s", "no water flows faster: a fill value?");
    }
    if (!s.building.empty() && std::find(s.building.begin(), s.building.end(), 0) == s.building.end())
        fail(path, "variable 'building'", "every cell is a building: a scene needs open ground or water");

    if (f.has_var("point_name")) {
        const auto names = read_table_names(f, "point", {"point_kind", "point_x", "point_y", "point_heading"});
        const auto kinds = read_names(f, "point_kind");
        const auto px = nc::read_finite(f, "point_x"), py = nc::read_finite(f, "point_y"), ph = nc::read_finite(f, "point_heading");
        for (std::size_t k = 0; k < names.size(); ++k) {
            const std::string here = "point " + std::to_string(k) + " ('" + names[k] + "')";
            if (kinds[k] != "gauge" && kinds[k] != "start")
                fail(path, "variable 'point_kind'", here + ": kind '" + kinds[k] + "' is neither 'gauge' nor 'start'");
            s.points.push_back({names[k], kinds[k], px[k] * fx, py[k] * fy, ph[k]});
        }
        check_names(path, "point_name", names);
    }
    if (f.has_var("section_name")) {
        const auto names = read_table_names(f, "section", {"section_x", "section_y_min", "section_y_max"});
        const auto sx = nc::read_finite(f, "section_x"), s0 = nc::read_finite(f, "section_y_min"),
                   s1 = nc::read_finite(f, "section_y_max");
        for (std::size_t k = 0; k < names.size(); ++k) {
            if (!(s0[k] < s1[k]))
                fail(path, "section '" + names[k] + "'",
                     "section_y_min " + number_text(s0[k]) + " m is not below section_y_max " + number_text(s1[k]) + " m");
            s.sections.push_back({names[k], sx[k] * fx, s0[k] * fy, s1[k] * fy});
        }
        check_names(path, "section_name", names);
    }
    if (f.has_var("region_name")) {
        const auto names = read_table_names(f, "region", {"region_vertex_start", "region_vertex_count"});
        const auto start = f.get_int(f.var("region_vertex_start")), count = f.get_int(f.var("region_vertex_count"));
        const auto vx = nc::read_finite(f, "region_vertex_x"), vy = nc::read_finite(f, "region_vertex_y");
        if (vy.size() != vx.size())
            fail(path, "variable 'region_vertex_y'",
                 "has " + std::to_string(vy.size()) + " values, region_vertex_x " + std::to_string(vx.size()));
        for (std::size_t k = 0; k < names.size(); ++k) {
            Region r{names[k], {}};
            if (start[k] < 0 || count[k] < 3 || std::size_t(start[k]) + std::size_t(count[k]) > vx.size())
                fail(path, "variable 'region_vertex_start'", "region '" + names[k] + "' has an invalid vertex range");
            for (int v = start[k]; v < start[k] + count[k]; ++v) r.polygon.push_back({vx[v] * fx, vy[v] * fy});
            s.regions.push_back(std::move(r));
        }
        check_names(path, "region_name", names);
    }
    s.title = f.att_text(NC_GLOBAL, "title").value_or("");
    s.source = f.att_text(NC_GLOBAL, "source").value_or("");
    s.comment = f.att_text(NC_GLOBAL, "comment").value_or("");
    s.synthetic = f.att_text(NC_GLOBAL, "flotsam_synthetic").value_or("") == "true";
    s.crs = cf::read_crs(f, "z");
    s.hydro_defaults = f.att_text(NC_GLOBAL, "flotsam_hydro_defaults").value_or("");
    return s;
}

std::string scene_buildings_sha256(const Scene& s) {
    std::string bytes = "grid " + std::to_string(s.grid.nx) + " x " + std::to_string(s.grid.ny) + "\nbuilding ";
    // Whole numbers only: the same scene in other units (x in km, z in ft) gives the same.
    if (s.building.empty())
        bytes += "none";
    else
        for (std::int8_t b : s.building) bytes += b ? '1' : '0';
    return sha256_hex(bytes);
}

namespace {

// What write_scene writes, one part each: its variables are defined while the file is in
// define mode, then their values are put, in the same order as defined.

// The gridded fields (y, x): z, and Manning's n, the building mask and the initial state
// where the scene has them.
class SceneFields {
public:
    SceneFields(nc::File& f, const Scene& s, int dx, int dy) : f_(f), s_(s) {
        const Grid& g = s.grid;
        const std::vector<std::size_t> chunk = {std::size_t(std::min(g.ny, 128)), std::size_t(std::min(g.nx, 128))};
        auto field = [&](const char* name, nc_type t, const char* units, const char* standard_name, const char* long_name) {
            return cf::def_var(f, {.name = name,
                                   .type = t,
                                   .dims = {dy, dx},
                                   .units = units,
                                   .standard_name = standard_name,
                                   .long_name = long_name,
                                   .chunks = chunk,
                                   .deflate = 4,
                                   .grid_mapping = cf::grid_mapping_of(s.crs)});
        };
        vz_ = field("z", NC_FLOAT, "m", "", "bed and building elevation above still water level");
        f.put_att(vz_, "positive", std::string("up"));
        if (!s.manning_n.empty()) vn_ = field("manning_n", NC_FLOAT, "s m-1/3", "", "Manning roughness coefficient");
        if (!s.building.empty()) {
            vb_ = field("building", NC_BYTE, "", "", "building mask (1 = building)");
            f.put_att(vb_, "flag_values", std::vector<std::int8_t>{0, 1});
            f.put_att(vb_, "flag_meanings", std::string("open building"));
            vid_ = field("building_id", NC_INT, "", "", "building each cell belongs to (0 = none)");
            f.put_att(vid_, "comment",
                      std::string("a footprint's number when imported with footprints, else the 4-connected components of "
                                  "the mask numbered by their first cell, row by row from the south-west"));
        }
        if (!s.eta0.empty()) ve_ = field("eta0", NC_FLOAT, "m", "sea_surface_height_above_mean_sea_level", "initial water level");
        if (!s.u0.empty()) {
            vu_ = field("u0", NC_FLOAT, "m s-1", "", "initial x velocity");
            vv_ = field("v0", NC_FLOAT, "m s-1", "", "initial y velocity");
        }
    }
    void put() const {
        auto as_float = [](const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); };
        f_.put(vz_, as_float(s_.z));
        if (vn_ >= 0) f_.put(vn_, as_float(s_.manning_n));
        if (vb_ >= 0) f_.put(vb_, s_.building);
        if (vid_ >= 0) f_.put(vid_, scene_building_ids(s_));
        if (ve_ >= 0) f_.put(ve_, as_float(s_.eta0));
        if (vu_ >= 0) {
            f_.put(vu_, as_float(s_.u0));
            f_.put(vv_, as_float(s_.v0));
        }
    }

private:
    nc::File& f_;
    const Scene& s_;
    int vz_ = -1, vn_ = -1, vb_ = -1, vid_ = -1, ve_ = -1, vu_ = -1, vv_ = -1;
};

// The named points: gauges and debris starts.
class PointTable {
public:
    PointTable(nc::File& f, const std::vector<ScenePoint>& points) : f_(f) {
        if (points.empty()) return;
        for (const auto& p : points) {
            names_.push_back(p.name);
            kinds_.push_back(p.kind);
            x_.push_back(p.x);
            y_.push_back(p.y);
            heading_.push_back(p.heading_deg);
        }
        const int d = f.def_dim("point", points.size());
        vname_ = f.def_text_var("point_name", {d}, cf::longest(names_));
        vkind_ = cf::def_var(f, {.name = "point_kind",
                                 .type = NC_CHAR,
                                 .dims = {d},
                                 .long_name = "gauge: record a time series; start: a debris start",
                                 .text_length = cf::longest(kinds_)});
        vx_ = cf::def_var(f, {.name = "point_x", .dims = {d}, .units = "m"});
        vy_ = cf::def_var(f, {.name = "point_y", .dims = {d}, .units = "m"});
        vheading_ = cf::def_var(f, {.name = "point_heading",
                                    .dims = {d},
                                    .units = "degree",
                                    .long_name = "debris long axis from +x, counter-clockwise"});
    }
    void put() const {
        if (vname_ < 0) return;
        f_.put(vname_, names_);
        f_.put(vkind_, kinds_);
        f_.put(vx_, x_);
        f_.put(vy_, y_);
        f_.put(vheading_, heading_);
    }

private:
    nc::File& f_;
    std::vector<std::string> names_, kinds_;
    std::vector<double> x_, y_, heading_;
    int vname_ = -1, vkind_ = -1, vx_ = -1, vy_ = -1, vheading_ = -1;
};

// The cross-sections debris passages are counted at.
class SectionTable {
public:
    SectionTable(nc::File& f, const std::vector<Section>& sections) : f_(f) {
        if (sections.empty()) return;
        for (const auto& c : sections) {
            names_.push_back(c.name);
            x_.push_back(c.x);
            y_min_.push_back(c.y_min);
            y_max_.push_back(c.y_max);
        }
        const int d = f.def_dim("section", sections.size());
        vname_ = f.def_text_var("section_name", {d}, cf::longest(names_));
        vx_ = cf::def_var(f, {.name = "section_x", .dims = {d}, .units = "m"});
        vy_min_ = cf::def_var(f, {.name = "section_y_min", .dims = {d}, .units = "m"});
        vy_max_ = cf::def_var(f, {.name = "section_y_max", .dims = {d}, .units = "m"});
    }
    void put() const {
        if (vname_ < 0) return;
        f_.put(vname_, names_);
        f_.put(vx_, x_);
        f_.put(vy_min_, y_min_);
        f_.put(vy_max_, y_max_);
    }

private:
    nc::File& f_;
    std::vector<std::string> names_;
    std::vector<double> x_, y_min_, y_max_;
    int vname_ = -1, vx_ = -1, vy_min_ = -1, vy_max_ = -1;
};

// The named regions (polygons), their vertices in one ragged array.
class RegionTable {
public:
    RegionTable(nc::File& f, const std::vector<Region>& regions) : f_(f) {
        if (regions.empty()) return;
        for (const auto& r : regions) {
            names_.push_back(r.name);
            start_.push_back(int(x_.size()));
            count_.push_back(int(r.polygon.size()));
            for (const auto& p : r.polygon) {
                x_.push_back(p[0]);
                y_.push_back(p[1]);
            }
        }
        const int d = f.def_dim("region", regions.size());
        const int dv = f.def_dim("region_vertex", x_.size());
        vname_ = f.def_text_var("region_name", {d}, cf::longest(names_));
        vstart_ = f.def_var("region_vertex_start", NC_INT, {d});
        vcount_ = f.def_var("region_vertex_count", NC_INT, {d});
        vx_ = cf::def_var(f, {.name = "region_vertex_x", .dims = {dv}, .units = "m"});
        vy_ = cf::def_var(f, {.name = "region_vertex_y", .dims = {dv}, .units = "m"});
    }
    void put() const {
        if (vname_ < 0) return;
        f_.put(vname_, names_);
        f_.put(vstart_, start_);
        f_.put(vcount_, count_);
        f_.put(vx_, x_);
        f_.put(vy_, y_);
    }

private:
    nc::File& f_;
    std::vector<std::string> names_;
    std::vector<int> start_, count_;
    std::vector<double> x_, y_;
    int vname_ = -1, vstart_ = -1, vcount_ = -1, vx_ = -1, vy_ = -1;
};

void put_scene_attributes(nc::File& f, const Scene& s, const std::string& history) {
    cf::put_conventions(f);
    cf::put_kind(f, "scene");
    f.put_att(NC_GLOBAL, "title", s.title);
    f.put_att(NC_GLOBAL, "source", s.source.empty() ? version_string() : s.source);
    f.put_att(NC_GLOBAL, "history", history);
    if (!s.comment.empty()) f.put_att(NC_GLOBAL, "comment", s.comment);
    f.put_att(NC_GLOBAL, "flotsam_synthetic", std::string(s.synthetic ? "true" : "false"));
    if (!s.hydro_defaults.empty()) f.put_att(NC_GLOBAL, "flotsam_hydro_defaults", s.hydro_defaults);
}

}  // namespace

void write_scene(const std::string& path, const Scene& s, const std::string& history) {
    const Grid& g = s.grid;
    if (s.z.size() != g.size()) fail(path, "variable 'z'", "size does not match the grid");
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        const int dx = f.def_dim("x", g.nx), dy = f.def_dim("y", g.ny);
        const cf::XYAxes axes = cf::def_xy(f, dx, dy, "cell centre");
        cf::def_crs(f, s.crs);
        const SceneFields fields(f, s, dx, dy);
        const PointTable points(f, s.points);
        const SectionTable sections(f, s.sections);
        const RegionTable regions(f, s.regions);
        put_scene_attributes(f, s, history);
        f.enddef();
        f.put(axes.x, g.xs());
        f.put(axes.y, g.ys());
        fields.put();
        points.put();
        sections.put();
        regions.put();
        f.close();
    }
    out.commit();
}

}  // namespace flotsam
