// Styles a planner's QGIS opens with: raster colour ramps over fixed physical ranges with
// their units in the legend, vector renderers (one symbol, categories, graduated classes)
// with labels, and a time-aware mesh's depth and velocity arrows, written as QGIS style
// XML (.qml). They travel with the data: a .qml beside each GeoTIFF (QGIS loads it with
// the raster), the layer_styles table of a GeoPackage (QGIS's "styles in the database"),
// and the project's layers (export/qgis_project.hpp).
#pragma once
#include <string>
#include <vector>

class GDALDataset;

namespace flotsam::gis::qgis {

// ---- rasters ----

struct ColourStop {
    double value = 0.0;  // in the map's units; a discrete ramp's class holds values up to it
    std::string colour;  // "#rrggbb"
    std::string label;   // legend text with units, e.g. "2 m", "≤ 1 %"
    int alpha = 255;     // 0 (clear) .. 255
};

struct RasterStyle {
    std::vector<ColourStop> stops;  // ascending values
    bool discrete = false;          // classes (up to each stop) instead of a ramp between the stops
    double opacity = 1.0;           // 0..1
};
bool empty(const RasterStyle& s);

// A ramp from 0 to `top` in `units` through `colours` (at even steps), its stops labelled
// with their values and units ("0 m", "5 m", ...).
RasterStyle ramp(double top, const std::vector<std::string>& colours, const std::string& units, double opacity = 1.0);
// The top of a fixed range for values up to `largest`: the smallest of 1, 2, 5 x 10^k at
// or above it (0 and non-finite values give 1).
double round_ceiling(double largest);
// A fraction (0..1) in classes: up to 1 %, 5 %, 10 %, 25 %, 50 % and 100 %.
RasterStyle probability_classes(const std::vector<std::string>& six_colours, double opacity = 1.0);
// Legend text of a value with its units: "0.3 m", "12 %", "1.5 m/s", "600 s".
std::string value_label(double v, const std::string& units);

// ---- vectors ----

struct Symbol {
    enum class Kind { fill, line, marker } kind = Kind::fill;
    std::string colour = "#808080";   // fill, line or marker colour; "" for a hollow fill
    std::string outline = "#404040";  // fill or marker outline; "" for none
    double width_mm = 0.26;           // line width or outline width [mm]
    double size_mm = 2.0;             // marker size [mm]
    double opacity = 1.0;             // of the whole symbol, 0..1
    bool hatched = false;             // fill: diagonal hatching in `colour` instead of a solid fill
};

struct Category {
    std::string value;  // the attribute's value
    std::string label;
    Symbol symbol;
};

struct Class {
    double lower = 0.0, upper = 0.0;  // inclusive; a value takes the first class that holds it
    std::string label;
    Symbol symbol;
};

struct Labels {
    std::string expression;  // QGIS expression of the text, e.g. "layer" or format_number("x", 1)
    double size_pt = 8.0;
    std::string colour = "#202020";
    bool polygon_inside = true;  // polygons: horizontal text over the inside; else around the point/line
};

struct VectorStyle {
    std::string field;  // the attribute classified (categories, classes); "" for one symbol
    Symbol symbol;      // with neither categories nor classes
    std::vector<Category> categories;
    Symbol other;  // categories: features whose value is in none (an empty value)
    std::vector<Class> classes;
    Labels labels;  // none when the expression is empty
};

// ---- a flow as a time-aware mesh ----

struct MeshStyle {
    int scalar_group = -1;         // the dataset group drawn as colours (QGIS's order of the file's variables)
    RasterStyle scalar;            // its ramp (a clear first stop leaves dry cells clear)
    int vector_group = -1;         // the dataset group drawn as arrows; -1: none
    double arrow_spacing_px = 30;  // arrows on a grid of this spacing [pixels]
    double arrow_min_speed = 0;    // [m s-1] no arrow below it (dry cells have none)
};

// The style XML, as the content of a .qml file or a layer_styles row.
std::string raster_qml(const RasterStyle& s);
std::string vector_qml(const VectorStyle& s);
std::string mesh_qml(const MeshStyle& s);

// Text as XML attribute or element content (& < > " ' escaped).
std::string xml_escape(const std::string& s);

// The layer-level part of a style (everything inside the .qml's root element) and whether
// it enables labels: what a project embeds in its <maplayer>.
std::string qml_body(const std::string& qml);
bool qml_labels_enabled(const std::string& qml);

// Writes `qml` as <path> atomically (a GeoTIFF's "<stem>.qml").
void write_qml(const std::string& path, const std::string& qml);

// One style of a GeoPackage layer in its layer_styles table (created when missing, as QGIS
// creates it). `is_default` marks the style QGIS applies when the layer is opened.
struct NamedStyle {
    std::string name;
    std::string description;
    std::string qml;
    bool is_default = false;
};
// The default style of `layer` in the GeoPackage at `path` ("" when it has none).
std::string stored_style(const std::string& path, const std::string& layer);
// Adds `styles` for `layer` to the open GeoPackage `ds` (written as `path`, for messages).
void store_styles(GDALDataset& ds, const std::string& path, const std::string& layer, const std::vector<NamedStyle>& styles);

}  // namespace flotsam::gis::qgis
