#include "data/dem_import.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/toml_lite.hpp"
#include "data/resample.hpp"

namespace flotsam {

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

void flip_rows(std::vector<double>& z, int nx, int ny) {
    for (int j = 0; j < ny / 2; ++j)
        std::swap_ranges(z.begin() + std::ptrdiff_t(j) * nx, z.begin() + std::ptrdiff_t(j + 1) * nx,
                         z.begin() + std::ptrdiff_t(ny - 1 - j) * nx);
}

Dem read_netcdf_dem(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    Dem d;
    d.path = path;
    std::vector<double> x = nc::read_finite(f, "x"), y = nc::read_finite(f, "y");
    const auto xdims = f.dim_names(f.var("x")), ydims = f.dim_names(f.var("y"));
    if (xdims.size() != 1) fail(path, "variable 'x'", "must be one-dimensional");
    if (ydims.size() != 1) fail(path, "variable 'y'", "must be one-dimensional");
    const int vz = f.var("z");
    // Matched by dimension name, not by shape: a square z(x, y) would pass a shape test and
    // be imported transposed. z(x, y) is read and transposed to (y, x).
    const auto zdims = f.dim_names(vz);
    const bool yx = zdims == std::vector<std::string>{ydims[0], xdims[0]};
    const bool xy = zdims == std::vector<std::string>{xdims[0], ydims[0]};
    if (!yx && !xy)
        fail(
            path, "variable 'z'",
            "must have the dimensions of y and x, (" + ydims[0] + ", " + xdims[0] + ") or (" + xdims[0] + ", " + ydims[0] +
                "), found (" +
                [&] {
                    std::string t;
                    for (std::size_t k = 0; k < zdims.size(); ++k) t += (k ? ", " : "") + zdims[k];
                    return t;
                }() +
                ")");
    d.z = nc::read_finite(f, "z");
    if (xy) {
        std::vector<double> t(d.z.size());
        for (std::size_t i = 0; i < x.size(); ++i)
            for (std::size_t j = 0; j < y.size(); ++j) t[j * x.size() + i] = d.z[i * y.size() + j];
        d.z = std::move(t);
    }
    const bool north_first = y.size() > 1 && y[1] < y[0];
    if (north_first) {
        std::reverse(y.begin(), y.end());
        flip_rows(d.z, int(x.size()), int(y.size()));
    }
    d.grid = grid_from_coordinates(x, y, path);
    d.title = f.att_text(NC_GLOBAL, "title").value_or("");
    d.crs = cf::read_crs(f, "z");
    return d;
}

// A NetCDF with the x, y, z layout that read_netcdf_dem reads.
bool has_xyz_layout(const std::string& path) {
    int id = -1;
    if (nc_open(path.c_str(), NC_NOWRITE, &id) != NC_NOERR) return false;
    int v = 0;
    const bool xyz =
        nc_inq_varid(id, "x", &v) == NC_NOERR && nc_inq_varid(id, "y", &v) == NC_NOERR && nc_inq_varid(id, "z", &v) == NC_NOERR;
    nc_close(id);
    return xyz;
}

// The six ESRI header keys, any order, any case; returns the first data line's number.
int read_ascii_header(std::ifstream& in, const std::string& path, std::map<std::string, double>& header, std::string& first_data) {
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        std::istringstream ss(line);
        std::string key, rest;
        double value = 0.0;
        if (!(ss >> key)) continue;
        if (!std::isalpha(static_cast<unsigned char>(key[0]))) {
            first_data = line;
            return lineno;
        }
        if (!(ss >> value) || (ss >> rest)) fail(path, "line " + std::to_string(lineno), "header '" + key + "' needs one number");
        header[lower(key)] = value;
    }
    fail(path, "", "no data rows after the header");
}

double header_value(const std::map<std::string, double>& h, const std::string& path, const std::string& key) {
    const auto it = h.find(key);
    if (it == h.end()) fail(path, "header '" + key + "'", "missing");
    return it->second;
}

}  // namespace

Dem read_ascii_grid(const std::string& path) {
    check_input_file("", path);
    std::ifstream in(path);
    if (!in) fail(path, "", "cannot open");
    std::map<std::string, double> h;
    std::string line;
    int lineno = read_ascii_header(in, path, h, line);
    const double ncols = header_value(h, path, "ncols"), nrows = header_value(h, path, "nrows");
    const double cell = header_value(h, path, "cellsize");
    if (ncols < 1 || nrows < 1 || ncols != std::floor(ncols) || nrows != std::floor(nrows))
        fail(path, "header 'ncols'/'nrows'", "must be positive whole numbers");
    if (!(cell > 0.0) || !std::isfinite(cell)) fail(path, "header 'cellsize'", "must be a positive number");
    check_allocation("header 'ncols' x 'nrows'", number_text(ncols) + " x " + number_text(nrows), ncols * nrows, sizeof(double) * 4,
                     "cells", path);
    if (ncols > 2e9 || nrows > 2e9) fail(path, "header 'ncols'/'nrows'", "more than 2e9 cells along one side");
    const bool x_corner = h.count("xllcorner"), y_corner = h.count("yllcorner");
    if (!x_corner && !h.count("xllcenter")) fail(path, "header 'xllcorner'", "missing (or give 'xllcenter')");
    if (!y_corner && !h.count("yllcenter")) fail(path, "header 'yllcorner'", "missing (or give 'yllcenter')");
    Dem d;
    d.path = path;
    d.grid.nx = int(ncols);
    d.grid.ny = int(nrows);
    d.grid.dx = d.grid.dy = cell;
    d.grid.x0 = x_corner ? h["xllcorner"] + 0.5 * cell : h["xllcenter"];
    d.grid.y0 = y_corner ? h["yllcorner"] + 0.5 * cell : h["yllcenter"];
    const bool has_nodata = h.count("nodata_value") > 0;
    const double nodata = has_nodata ? h["nodata_value"] : 0.0;
    d.z.reserve(d.grid.size());
    do {
        std::istringstream ss(line);
        std::string tok;
        while (ss >> tok) {
            char* end = nullptr;
            const double v = std::strtod(tok.c_str(), &end);
            const std::string here = "line " + std::to_string(lineno);
            if (end != tok.c_str() + tok.size() || !std::isfinite(v)) fail(path, here, "'" + tok + "' is not a finite number");
            if (has_nodata && v == nodata) fail(path, here, "NODATA value " + tok + ": the DEM must be complete");
            if (d.z.size() == d.grid.size()) fail(path, here, "more values than nrows x ncols = " + std::to_string(d.grid.size()));
            d.z.push_back(v);
        }
        ++lineno;
    } while (std::getline(in, line));
    if (d.z.size() != d.grid.size())
        fail(path, "data",
             "expected nrows x ncols = " + std::to_string(d.grid.size()) + " values, found " + std::to_string(d.z.size()));
    flip_rows(d.z, d.grid.nx, d.grid.ny);  // the file lists rows north to south
    return d;
}

Dem read_dem(const std::string& path) {
    if (!std::filesystem::exists(path)) fail(path, "", "no such file");
    if (lower(std::filesystem::path(path).extension().string()) == ".asc") return read_ascii_grid(path);
    return read_netcdf_dem(path);
}

Dem read_dem(const std::string& path, const GisImportDef& gis, double resolution) {
    if (!std::filesystem::exists(path)) fail(path, "", "no such file");
    const bool ascii = lower(std::filesystem::path(path).extension().string()) == ".asc";
    if ((ascii || has_xyz_layout(path)) && !gis.needs_gdal_raster()) {
        Dem d = read_dem(path);
        if (!gis.assign_crs.empty() || ascii) {
            const cf::GridMapping assigned = sidecar_or_assigned_crs(path, gis);
            if (!assigned.empty() || gis.assign_crs == "local") d.crs = assigned;
        }
        apply_extent_and_datum(d, gis);
        return d;
    }
    return read_gis_dem(path, gis, resolution);
}

const std::vector<std::string>& scene_hydro_options() {
    static const std::vector<std::string> keys = {"max-dt",          "dry-depth",     "arrival-depth", "gauge-interval",
                                                  "output-interval", "output-window", "nest-x",        "nest-ratio"};
    return keys;
}

ImportFeatures kainan_import_features() {
    ImportFeatures f;
    f.features = kainan_features(KainanLayout::measured);
    f.manning = kainan_manning();
    f.hydro_defaults = kainan_hydro_defaults();
    return f;
}

namespace {

std::optional<double> optional_number(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    if (!t.values.count(key)) return std::nullopt;
    return toml_number(doc, t, key);
}

ScenePoint read_point(const TomlDoc& doc, const TomlTable& t) {
    toml_allow_only(doc, t, {"name", "kind", "x", "y", "heading"});
    ScenePoint p{toml_string(doc, t, "name"), toml_string(doc, t, "kind"), toml_number(doc, t, "x"), toml_number(doc, t, "y"),
                 optional_number(doc, t, "heading").value_or(0.0)};
    if (p.kind != "gauge" && p.kind != "start")
        fail(doc.path, "line " + std::to_string(t.values.at("kind").line),
             "point kind must be \"gauge\" or \"start\", found \"" + p.kind + "\"");
    return p;
}

Section read_section(const TomlDoc& doc, const TomlTable& t) {
    toml_allow_only(doc, t, {"name", "x", "y_min", "y_max"});
    Section s{toml_string(doc, t, "name"), toml_number(doc, t, "x"), toml_number(doc, t, "y_min"), toml_number(doc, t, "y_max")};
    if (!(s.y_max > s.y_min))
        fail(doc.path, "line " + std::to_string(t.values.at("y_max").line), "section '" + s.name + "': y_max must exceed y_min");
    return s;
}

Region read_region(const TomlDoc& doc, const TomlTable& t) {
    toml_allow_only(doc, t, {"name", "x", "y"});
    Region r{toml_string(doc, t, "name"), {}};
    const auto xs = toml_numbers(doc, t, "x"), ys = toml_numbers(doc, t, "y");
    if (xs.size() != ys.size() || xs.size() < 3)
        fail(doc.path, "line " + std::to_string(t.values.at("y").line),
             "region '" + r.name + "': x and y need the same length, at least 3");
    for (std::size_t k = 0; k < xs.size(); ++k) r.polygon.push_back({xs[k], ys[k]});
    return r;
}

ManningRule read_manning(const TomlDoc& doc, const TomlTable& t) {
    toml_allow_only(doc, t, {"n", "x_min", "x_max", "y_min", "y_max"});
    ManningRule m{toml_number(doc, t, "n"), optional_number(doc, t, "x_min"), optional_number(doc, t, "x_max"),
                  optional_number(doc, t, "y_min"), optional_number(doc, t, "y_max")};
    if (!(m.n >= 0.0 && m.n < 1.0))
        fail(doc.path, "line " + std::to_string(t.values.at("n").line), "Manning n must be in [0, 1) s m^-1/3");
    return m;
}

// The shortest decimal that reads back as the same double (whole numbers in full: -300,
// not -3e+02).
std::string shortest_text(double v) {
    char buf[40];
    if (v == std::floor(v) && std::fabs(v) < 1e15) {
        std::snprintf(buf, sizeof buf, "%.0f", v);
        return buf;
    }
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

std::string read_hydro_defaults(const TomlDoc& doc, const TomlTable& t) {
    toml_allow_only(doc, t, scene_hydro_options());
    std::string lines;
    for (const std::string& key : scene_hydro_options()) {  // a fixed order: the same bytes for the same settings
        if (!t.values.count(key)) continue;
        const TomlValue& v = t.values.at(key);
        std::string text;
        if (v.kind == TomlValue::Kind::Number) {
            if (key != "nest-x" && !(v.number > 0.0)) fail(doc.path, "line " + std::to_string(v.line), key + " must be positive");
            text = shortest_text(v.number);
        } else if (v.kind == TomlValue::Kind::NumberArray && key == "output-window" && v.numbers.size() == 4) {
            for (std::size_t k = 0; k < 4; ++k) {
                if (k > 0) text += ',';
                text += shortest_text(v.numbers[k]);
            }
        } else {
            fail(doc.path, "line " + std::to_string(v.line),
                 key + (key == "output-window" ? " must be [x_min, x_max, y_min, y_max]" : " must be a number"));
        }
        lines += key + " = " + text + "\n";
    }
    return lines;
}

BuildingRule read_buildings(const TomlDoc& doc, const TomlTable& t, BuildingRule b) {
    toml_allow_only(doc, t, {"min_height", "window", "min_elevation"});
    b.min_height = optional_number(doc, t, "min_height").value_or(b.min_height);
    b.window = optional_number(doc, t, "window").value_or(b.window);
    b.min_elevation = optional_number(doc, t, "min_elevation");
    if (!(b.window >= 0.0)) fail(doc.path, "[buildings] at line " + std::to_string(t.line), "window must be >= 0");
    return b;
}

}  // namespace

ImportFeatures read_import_features(const std::string& path, const ImportFeatures& defaults) {
    const TomlDoc doc = read_toml_lite(path);
    ImportFeatures f = defaults;
    std::map<std::string, bool> seen;
    for (const TomlTable& t : doc.tables) {
        const bool first = !seen[t.name];
        seen[t.name] = true;
        if (t.name.empty())
            toml_allow_only(doc, t, {});
        else if (t.name == "point") {
            if (first) f.features.points.clear();
            f.features.points.push_back(read_point(doc, t));
        } else if (t.name == "section") {
            if (first) f.features.sections.clear();
            f.features.sections.push_back(read_section(doc, t));
        } else if (t.name == "region") {
            if (first) f.features.regions.clear();
            f.features.regions.push_back(read_region(doc, t));
        } else if (t.name == "manning") {
            if (first) f.manning.clear();
            f.manning.push_back(read_manning(doc, t));
        } else if (t.name == "buildings")
            f.buildings = read_buildings(doc, t, defaults.buildings);
        else if (t.name == "hydro")
            f.hydro_defaults = read_hydro_defaults(doc, t);
        else
            fail(path, "line " + std::to_string(t.line),
                 "unknown table '" + t.name + "' (known: [[point]], [[section]], [[region]], [[manning]], [buildings], [hydro])");
    }
    return f;
}

namespace {

// Separable running minimum over a square of half-width r cells.
std::vector<double> window_min(const Grid& g, std::vector<double> v, int r) {
    std::vector<double> tmp(v.size());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            double m = v[g.index(i, j)];
            for (int a = std::max(0, i - r); a <= std::min(g.nx - 1, i + r); ++a) m = std::min(m, v[g.index(a, j)]);
            tmp[g.index(i, j)] = m;
        }
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            double m = tmp[g.index(i, j)];
            for (int b = std::max(0, j - r); b <= std::min(g.ny - 1, j + r); ++b) m = std::min(m, tmp[g.index(i, b)]);
            v[g.index(i, j)] = m;
        }
    return v;
}

}  // namespace

std::vector<std::int8_t> building_mask(const Grid& g, const std::vector<double>& z, const BuildingRule& rule) {
    std::vector<std::int8_t> mask(g.size(), 0);
    if (rule.min_elevation) {
        for (std::size_t k = 0; k < z.size(); ++k) mask[k] = z[k] > *rule.min_elevation;
        return mask;
    }
    std::vector<double> dry(z.size());
    for (std::size_t k = 0; k < z.size(); ++k) dry[k] = std::max(z[k], 0.0);
    const auto ground = window_min(g, dry, int(std::lround(rule.window / g.dx)));
    for (std::size_t k = 0; k < z.size(); ++k) mask[k] = z[k] - ground[k] > rule.min_height;
    return mask;
}

Scene import_scene(const ImportDef& def) {
    if (!(def.resolution > 0.0)) fail("--resolution", "", "grid spacing must be positive");
    const Dem dem = read_dem(def.dem_path, def.gis, def.resolution);
    // A crop of the Kainan DEM (a box for a nested run) keeps the Kainan defaults that lie
    // inside it; the recommended hydro settings (nesting, output window) are for the
    // whole flume and are left out.
    const bool cropped = dem.source_grid.nx > 0;
    const bool kainan = dem.crs.empty() && matches_kainan_extent(cropped ? dem.source_grid : dem.grid);
    ImportFeatures defaults = kainan ? kainan_import_features() : ImportFeatures{};
    if (kainan && cropped) defaults.hydro_defaults.clear();
    const ImportFeatures f = def.features_path.empty() ? defaults : read_import_features(def.features_path, defaults);
    Scene s;
    s.grid =
        grid_covering(dem.grid.x_min_edge(), dem.grid.x_max_edge(), dem.grid.y_min_edge(), dem.grid.y_max_edge(), def.resolution);
    s.z = resample(dem.grid, dem.z, s.grid);
    s.crs = dem.crs;
    s.manning_n = manning_field(s.grid, f.manning);
    std::string notes;
    s.manning_n = manning_from_gis(s, def.gis, s.manning_n, notes);
    if (def.gis.buildings.empty())
        s.building = building_mask(s.grid, s.z, f.buildings);
    else
        notes += std::string(notes.empty() ? "" : "; ") + burn_building_footprints(s, def.gis);
    SceneFeatures inside = f.features;
    if (cropped) {  // points and sections off the cropped grid are left out, and named
        std::string left_out;
        auto off = [&](const std::string& name, bool out) {
            if (out) left_out += (left_out.empty() ? "" : ", ") + name;
            return out;
        };
        std::erase_if(inside.points, [&](const ScenePoint& p) { return off(p.name, !s.grid.contains(p.x, p.y)); });
        std::erase_if(inside.sections, [&](const Section& c) {
            return off(c.name, c.x < s.grid.x_min_edge() || c.x > s.grid.x_max_edge());
        });
        if (!left_out.empty()) notes += std::string(notes.empty() ? "" : "; ") + "outside --extent, left out: " + left_out;
    }
    apply_features(s, inside);
    s.hydro_defaults = f.hydro_defaults;
    s.title = dem.title.empty() ? "Scene imported from " + std::filesystem::path(def.dem_path).filename().string() : dem.title;
    s.comment =
        "Imported by flotsam scene import from " + def.dem_path + " at grid spacing " + std::to_string(def.resolution) +
        " m; features from " +
        (def.features_path.empty() ? (kainan ? std::string("the Kainan defaults") : std::string("none")) : def.features_path);
    if (!s.crs.empty()) s.comment += "; CRS " + s.crs.name();
    if (def.gis.still_water_level != 0.0)
        s.comment += "; still water at " + std::to_string(def.gis.still_water_level) + " m in the DEM's vertical datum";
    if (!notes.empty()) s.comment += "; " + notes;
    s.synthetic = false;
    return s;
}

}  // namespace flotsam
