// A QGIS project (.qgz) of a study's GIS export: its layers in groups, each with its
// style, paths relative to the project (the folder can be moved or shared), the scene's
// CRS, the study's extent, and the flow as a time-aware mesh on the temporal controller.
// QGIS opens it with a double-click. Written without QGIS: the project XML zipped as
// QGIS does (export/qgis_style.hpp has the styles).
#pragma once
#include <string>
#include <vector>

#include "common/cf.hpp"

namespace flotsam::gis::qgis {

struct ProjectLayer {
    enum class Kind { raster, vector, mesh } kind = Kind::raster;
    std::string path;   // the file (absolute or relative to the working directory)
    std::string layer;  // vector: the layer in the file
    std::string name;   // as QGIS lists it
    std::string group;  // the layer tree group it goes in
    bool visible = true;
    std::string qml;                      // its style (qgis_style.hpp)
    double time_start = 0, time_end = 0;  // mesh: its first and last time [s from the run's start]
};

struct Project {
    std::string title;
    cf::GridMapping crs;                                // the scene's; empty: a local scene (no CRS)
    double x_min = 0, y_min = 0, x_max = 0, y_max = 0;  // the view it opens on [m]
    std::vector<std::string> groups;                    // top (drawn last) first
    std::vector<ProjectLayer> layers;                   // top first within each group
    double time_step = 0;                               // temporal controller step [s]; 0: no time-aware layer
};

// The project XML with paths relative to `folder` (the .qgz's folder).
std::string project_xml(const Project& p, const std::string& folder);
// Writes the project as <path> (a .qgz: the XML zipped), atomically.
void write_project(const std::string& path, const Project& p);

// The .qgz container: a zip archive with the named files (deflated, fixed dates, so the
// same project gives the same bytes).
void write_zip(const std::string& path, const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace flotsam::gis::qgis
