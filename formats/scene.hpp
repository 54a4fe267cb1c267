// A scene: the static world both stages share. Bed elevation, roughness, buildings,
// an optional initial state, and the named points, sections and regions that runs and
// statistics refer to.
//
// File format (NetCDF): coordinates x(x), y(y) [m, cell centres, uniform, increasing];
// z(y, x) bed elevation above still water [m, positive up] (buildings included);
// optional manning_n(y, x) [s m^-1/3]; optional building(y, x) [0/1 byte mask] with
// building_id(y, x) [int: the building each cell belongs to, 0 = none; written with every
// mask, computed on read where an older file lacks it];
// optional eta0, u0, v0 (y, x) initial level [m] and velocity [m/s];
// optional feature tables (see write_scene): points, sections, regions; optional CF
// grid-mapping variable `crs` (common/cf.hpp) when x and y are coordinates of a map
// projection (a scene imported from GIS data), which every gridded field names.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/grid.hpp"

namespace flotsam {

struct ScenePoint {
    std::string name;          // e.g. "WG1", "FD"
    std::string kind;          // "gauge" (record a time series) or "start" (a debris start)
    double x = 0.0;            // [m]
    double y = 0.0;            // [m]
    double heading_deg = 0.0;  // debris long axis from +x, counter-clockwise [degrees]
};

// A north-south line x = const between y_min and y_max, for passage statistics.
struct Section {
    std::string name;
    double x = 0.0;      // [m]
    double y_min = 0.0;  // [m]
    double y_max = 0.0;  // [m]
};

// A named closed polygon (vertices in order, not repeated), for arrival counts.
struct Region {
    std::string name;
    std::vector<std::array<double, 2>> polygon;  // [m]
    bool contains(double x, double y) const;
};

struct Scene {
    Grid grid;
    std::vector<double> z;              // bed elevation above still water [m], size grid.size()
    std::vector<double> manning_n;      // [s m^-1/3]; empty: use the run's default
    std::vector<std::int8_t> building;  // 1 where a building stands; empty: none marked
    // The building each cell belongs to (1, 2, ...; 0 where none stands), size grid.size()
    // where `building` is given: a footprint's number when the scene was imported with
    // footprints, else the connected components of the mask (building_components). Empty:
    // the components, computed where needed (scene_building_ids).
    std::vector<std::int32_t> building_id;
    std::vector<double> eta0, u0, v0;   // initial level [m] and velocity [m/s]; empty: still water
    std::vector<ScenePoint> points;
    std::vector<Section> sections;
    std::vector<Region> regions;
    std::string title;
    std::string source;
    std::string comment;
    bool synthetic = false;  // generated analogue, not a measured layout
    cf::GridMapping crs;     // coordinate reference system of x, y; empty: local metres (the flume)
    // Hydro settings this scene recommends (option = value, one per line, TOML), for the
    // settings whose defaults are tuned to the flume's scale (max-dt, arrival-depth, ...):
    // `flotsam hydro` applies those the command line leaves out. Empty: none.
    std::string hydro_defaults;
    std::string path;  // the file it was read from (for messages)

    const ScenePoint* find_point(const std::string& name) const;
};

// The connected components of a building mask (nx × ny cells, row-major from the
// south-west corner, nonzero = building) under 4-connectivity, numbered 1, 2, ... in the
// order of each component's first cell in that row-major scan (south row first, west to
// east): the same mask always gives the same numbers. 0 where no building stands.
template <class Cell>
std::vector<std::int32_t> building_components(int nx, int ny, const std::vector<Cell>& mask);
extern template std::vector<std::int32_t> building_components(int, int, const std::vector<std::int8_t>&);
extern template std::vector<std::int32_t> building_components(int, int, const std::vector<std::uint8_t>&);

// The scene's building ids: `building_id` where it matches the mask (nonzero exactly on
// building cells), else the mask's components. Empty where no mask is given.
std::vector<std::int32_t> scene_building_ids(const Scene& scene);

// Reads and validates a scene. Errors name the file and variable: a file of another kind
// (a flow), missing x/y/z, non-uniform or non-monotonic coordinates, NaN or fill values,
// a bed outside [-11000, 9000] m, shapes that do not match (y, x), non-positive Manning n,
// a building mask with values other than 0/1 or with no open cell, a building_id without
// a mask or with values that are not whole numbers >= 0 (ids that are not > 0 exactly on
// the mask's cells, a mask edited without them, give way to the mask's components), a
// point kind other
// than gauge or start, empty or repeated names, a section with y_min >= y_max. Lengths
// in other units (km, ft: the units attribute) are converted to metres, a z with
// positive = "down" is negated; units flotsam cannot convert are refused by name.
Scene read_scene(const std::string& path);

// The SHA-256 of the scene's grid size and building mask (not of its file: a scene written
// again elsewhere, with another `history`, or in other units, gives the same). Flows,
// sweeps, trajectories and statistics record it as `scene_buildings_sha256`, and the
// commands that combine them compare it: the bed and the grid are compared value by value
// where the files hold them, the buildings only through this.
std::string scene_buildings_sha256(const Scene& scene);

// Writes a scene atomically (CF-1.11 NetCDF-4).
void write_scene(const std::string& path, const Scene& scene, const std::string& history);

}  // namespace flotsam
