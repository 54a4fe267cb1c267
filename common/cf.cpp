#include "common/cf.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "common/error.hpp"

namespace flotsam::cf {

std::size_t longest(const std::vector<std::string>& values) {
    std::size_t n = 0;
    for (const auto& s : values) n = std::max(n, s.size());
    return n;
}

int def_var(nc::File& f, const VarDef& v) {
    const int id = v.type == NC_CHAR ? f.def_text_var(v.name, v.dims, v.text_length) : f.def_var(v.name, v.type, v.dims);
    if (!v.chunks.empty()) f.def_chunking(id, v.chunks);
    if (v.deflate > 0) f.def_deflate(id, v.deflate, true);
    if (!v.standard_name.empty()) f.put_att(id, "standard_name", v.standard_name);
    if (!v.units.empty()) f.put_att(id, "units", v.units);
    if (!v.long_name.empty()) f.put_att(id, "long_name", v.long_name);
    if (!v.coordinates.empty()) f.put_att(id, "coordinates", v.coordinates);
    if (!v.grid_mapping.empty()) f.put_att(id, "grid_mapping", v.grid_mapping);
    if (v.fill) f.def_fill(id, fill_value);
    return id;
}

const GridMapping::Attribute* GridMapping::find(const std::string& name) const {
    for (const auto& a : attributes)
        if (a.name == name) return &a;
    return nullptr;
}

std::string GridMapping::wkt() const {
    const Attribute* a = find("crs_wkt");
    return a ? a->text : std::string();
}

std::string GridMapping::name() const {
    // The last AUTHORITY["EPSG","n"] (WKT1) or ID["EPSG",n] (WKT2) is the CRS's own.
    const std::string w = wkt();
    for (const char* key : {"AUTHORITY[\"EPSG\",\"", "ID[\"EPSG\","}) {
        const auto at = w.rfind(key);
        if (at == std::string::npos) continue;
        std::string code;
        for (std::size_t k = at + std::char_traits<char>::length(key); k < w.size() && std::isdigit((unsigned char)w[k]); ++k)
            code += w[k];
        if (!code.empty()) return "EPSG:" + code;
    }
    const Attribute* g = find("grid_mapping_name");
    return g ? g->text : std::string(empty() ? "" : "custom");
}

int def_crs(nc::File& f, const GridMapping& crs) {
    if (crs.empty()) return -1;
    const int id = f.def_var(crs_variable, NC_INT, {});
    for (const auto& a : crs.attributes) {
        if (a.numbers.empty())
            f.put_att(id, a.name, a.text);
        else
            f.put_att(id, a.name, a.numbers);
    }
    return id;
}

GridMapping read_crs(const nc::File& f, const std::string& data_var) {
    GridMapping crs;
    const auto v = f.find_var(data_var);
    if (!v) return crs;
    const auto name = f.att_text(*v, "grid_mapping");
    if (!name) return crs;
    const auto g = f.find_var(*name);
    if (!g)
        fail(f.path(), "variable '" + data_var + "' attribute 'grid_mapping'", "names '" + *name + "', which is not in the file");
    for (const auto& att : f.att_names(*g)) {
        GridMapping::Attribute a{att, {}, {}};
        if (f.att_is_text(*g, att))
            a.text = f.att_text(*g, att).value_or("");
        else
            a.numbers = f.att_doubles(*g, att).value_or(std::vector<double>{});
        crs.attributes.push_back(std::move(a));
    }
    return crs;
}

int def_time(nc::File& f, int dim, const std::string& name, const std::string& long_name, bool axis) {
    const int id = f.def_var(name, NC_DOUBLE, {dim});
    f.put_att(id, "standard_name", std::string("time"));
    f.put_att(id, "units", std::string(time_units));
    f.put_att(id, "calendar", std::string("standard"));
    if (axis) f.put_att(id, "axis", std::string("T"));
    if (!long_name.empty()) f.put_att(id, "long_name", long_name);
    f.put_att(id, "comment", std::string(time_origin));
    return id;
}

XYAxes def_xy(nc::File& f, int x_dim, int y_dim, const std::string& what) {
    auto axis = [&](const char* name, int dim, const char* standard_name, const char* axis_name, const std::string& long_name) {
        const int id = f.def_var(name, NC_DOUBLE, {dim});
        f.put_att(id, "standard_name", std::string(standard_name));
        f.put_att(id, "units", std::string("m"));
        f.put_att(id, "axis", std::string(axis_name));
        f.put_att(id, "long_name", long_name);
        return id;
    };
    const int x = axis("x", x_dim, "projection_x_coordinate", "X", "x of " + what + " (east)");
    const int y = axis("y", y_dim, "projection_y_coordinate", "Y", "y of " + what + " (north)");
    return {x, y};
}

void put_conventions(nc::File& f, const std::string& feature_type) {
    f.put_att(NC_GLOBAL, "Conventions", std::string(conventions));
    if (!feature_type.empty()) f.put_att(NC_GLOBAL, "featureType", feature_type);
}

void check_same_crs(const std::string& a_path, const cf::GridMapping& a, const std::string& b_path, const cf::GridMapping& b) {
    if (a.wkt() == b.wkt() && a.name() == b.name()) return;
    const auto label = [](const cf::GridMapping& c) { return c.empty() ? std::string("none (local metres)") : c.name(); };
    fail(a_path, "crs",
         "is " + label(a) + ", that of " + b_path + " is " + label(b) +
             ": files in different coordinate reference systems do not combine (positions would mean other places)");
}

void put_kind(nc::File& f, const std::string& kind) { f.put_att(NC_GLOBAL, kind_attribute, kind); }

namespace {

const char* kind_description(const std::string& kind) {
    if (kind == "scene") return "a scene (written by `flotsam scene generate` or `scene import`)";
    if (kind == "flow") return "a flow file (written by `flotsam hydro`)";
    if (kind == "trajectories") return "a trajectory file (written by `flotsam debris`)";
    if (kind == "sweep") return "a sweep file (written by `flotsam sweep`)";
    if (kind == "stats") return "a statistics file (written by `flotsam stats`)";
    if (kind == "boundary") return "boundary values (written by `flotsam hydro --boundary-output`)";
    return nullptr;
}

}  // namespace

std::string kind_of(const nc::File& f) {
    if (const auto k = f.att_text(NC_GLOBAL, kind_attribute)) {
        if (!kind_description(*k))
            fail(f.path(), std::string("attribute '") + kind_attribute + "'",
                 "'" + *k + "' is not a kind of flotsam file (scene, flow, trajectories, sweep, stats, boundary)");
        return *k;
    }
    // Files written before the attribute: what their variables say.
    if (f.has_var("pass_probability") && f.has_var("group_body")) return "stats";
    if (f.has_var("member_id") && f.has_var("flow_path")) return "sweep";
    if (f.has_dim("trajectory") && f.has_var("trajectory_id")) return "trajectories";
    if (f.has_dim("time") && f.has_var("h") && f.has_var("max_depth")) return "flow";
    if (f.has_var("z") && f.has_var("x") && f.has_var("y") && !f.has_dim("time")) return "scene";
    return "";
}

void require_kind(const nc::File& f, const std::vector<std::string>& accepted, const std::string& option) {
    const std::string k = kind_of(f);
    if (k.empty()) return;
    for (const auto& a : accepted)
        if (k == a) return;
    std::string wanted;
    for (std::size_t n = 0; n < accepted.size(); ++n)
        wanted += std::string(n == 0 ? "" : n + 1 == accepted.size() ? " or " : ", ") + kind_description(accepted[n]);
    fail(option.empty() ? f.path() : option + " " + f.path(), "", std::string("is ") + kind_description(k) + ", not " + wanted);
}

std::vector<double> filled(std::vector<double> v) {
    for (double& a : v)
        if (std::isnan(a)) a = fill_value;
    return v;
}

std::vector<float> filled(std::vector<float> v) {
    for (float& a : v)
        if (std::isnan(a)) a = float(fill_value);
    return v;
}

}  // namespace flotsam::cf
