#include "export/qgis_style.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "data/gdal_support.hpp"

namespace flotsam::gis::qgis {

namespace {

constexpr const char* qgis_version = "3.22.16";

std::string num(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.10g", v);
    return b;
}

// "#rrggbb" as QGIS's "r,g,b,a" (a from `opacity`).
std::string rgba(const std::string& hex, double opacity = 1.0) {
    unsigned r = 0, g = 0, b = 0;
    if (hex.size() != 7 || hex[0] != '#' || std::sscanf(hex.c_str() + 1, "%2x%2x%2x", &r, &g, &b) != 3)
        fail("style", "colour '" + hex + "'", "is not #rrggbb");
    return std::to_string(r) + "," + std::to_string(g) + "," + std::to_string(b) + "," +
           std::to_string(int(std::lround(255 * std::clamp(opacity, 0.0, 1.0))));
}

std::string option(const std::string& name, const std::string& value) {
    return "<Option type=\"QString\" name=\"" + xml_escape(name) + "\" value=\"" + xml_escape(value) + "\"/>";
}

std::string head(const std::string& attributes = "") {
    return "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n<qgis version=\"" + std::string(qgis_version) +
           "\" styleCategories=\"AllStyleCategories\"" + attributes + ">\n";
}

std::string colour_ramp_shader(const RasterStyle& s) {
    if (s.stops.empty()) fail("style", "colour ramp", "has no stops");
    std::string x = "<colorrampshader colorRampType=\"" + std::string(s.discrete ? "DISCRETE" : "INTERPOLATED") +
                    "\" classificationMode=\"1\" clip=\"0\" minimumValue=\"" + num(s.stops.front().value) + "\" maximumValue=\"" +
                    num(s.stops.back().value) + "\" labelPrecision=\"4\">\n";
    for (std::size_t k = 0; k < s.stops.size(); ++k) {
        const ColourStop& c = s.stops[k];
        // A discrete ramp's last class takes everything above as well.
        const double value = s.discrete && k + 1 == s.stops.size() ? INFINITY : c.value;
        x += "  <item value=\"" + num(value) + "\" color=\"" + c.colour + "\" alpha=\"" + std::to_string(c.alpha) + "\" label=\"" +
             xml_escape(c.label) + "\"/>\n";
    }
    return x + "</colorrampshader>\n";
}

std::string symbol_xml(const Symbol& s, const std::string& name) {
    std::string x;
    switch (s.kind) {
        case Symbol::Kind::fill:
            x = "<symbol type=\"fill\" name=\"" + name + "\" alpha=\"" + num(s.opacity) +
                "\" clip_to_extent=\"1\" force_rhr=\"0\">\n<layer class=\"SimpleFill\" enabled=\"1\" locked=\"0\" pass=\"0\">\n"
                "<Option type=\"Map\">" +
                option("color", s.colour.empty() ? "0,0,0,0" : rgba(s.colour)) +
                option("style", s.colour.empty() ? "no" : (s.hatched ? "b_diagonal" : "solid")) +
                option("outline_color", s.outline.empty() ? "0,0,0,0" : rgba(s.outline)) +
                option("outline_style", s.outline.empty() ? "no" : "solid") + option("outline_width", num(s.width_mm)) +
                option("outline_width_unit", "MM") + option("joinstyle", "miter") + "</Option>\n</layer>\n</symbol>\n";
            break;
        case Symbol::Kind::line:
            x = "<symbol type=\"line\" name=\"" + name + "\" alpha=\"" + num(s.opacity) +
                "\" clip_to_extent=\"1\" force_rhr=\"0\">\n<layer class=\"SimpleLine\" enabled=\"1\" locked=\"0\" pass=\"0\">\n"
                "<Option type=\"Map\">" +
                option("line_color", rgba(s.colour)) + option("line_style", "solid") + option("line_width", num(s.width_mm)) +
                option("line_width_unit", "MM") + option("capstyle", "round") + option("joinstyle", "round") +
                "</Option>\n</layer>\n</symbol>\n";
            break;
        case Symbol::Kind::marker:
            x = "<symbol type=\"marker\" name=\"" + name + "\" alpha=\"" + num(s.opacity) +
                "\" clip_to_extent=\"1\" force_rhr=\"0\">\n<layer class=\"SimpleMarker\" enabled=\"1\" locked=\"0\" pass=\"0\">\n"
                "<Option type=\"Map\">" +
                option("name", "circle") + option("color", rgba(s.colour)) +
                option("outline_color", s.outline.empty() ? "0,0,0,0" : rgba(s.outline)) +
                option("outline_style", s.outline.empty() ? "no" : "solid") + option("outline_width", num(s.width_mm)) +
                option("outline_width_unit", "MM") + option("size", num(s.size_mm)) + option("size_unit", "MM") +
                "</Option>\n</layer>\n</symbol>\n";
            break;
    }
    return x;
}

std::string labeling_xml(const Labels& l) {
    const std::string font_family = "DejaVu Sans";
    return "<labeling type=\"simple\">\n<settings calloutType=\"simple\">\n<text-style fieldName=\"" + xml_escape(l.expression) +
           "\" isExpression=\"1\" fontFamily=\"" + font_family + "\" fontSize=\"" + num(l.size_pt) +
           "\" fontSizeUnit=\"Point\" textColor=\"" + rgba(l.colour) +
           "\" textOpacity=\"1\" fontWeight=\"50\" fontItalic=\"0\" namedStyle=\"Book\" multilineHeight=\"1\" "
           "blendMode=\"0\" allowHtml=\"0\" capitalization=\"0\" textOrientation=\"horizontal\">\n"
           "<text-buffer bufferDraw=\"1\" bufferSize=\"0.7\" bufferSizeUnits=\"MM\" bufferColor=\"255,255,255,255\" "
           "bufferOpacity=\"0.85\" bufferNoFill=\"1\" bufferJoinStyle=\"128\" bufferBlendMode=\"0\"/>\n</text-style>\n"
           "<text-format wrapChar=\"\" multilineAlign=\"3\" formatNumbers=\"0\" decimals=\"3\" plussign=\"0\"/>\n"
           "<placement placement=\"" +
           std::string(l.polygon_inside ? "1" : "0") +
           "\" dist=\"0.5\" distUnits=\"MM\" offsetType=\"0\" centroidInside=\"1\" centroidWhole=\"0\" "
           "fitInPolygonOnly=\"0\" priority=\"5\"/>\n"
           "<rendering obstacle=\"1\" obstacleType=\"1\" scaleVisibility=\"0\" displayAll=\"0\" labelPerPart=\"0\" "
           "mergeLines=\"0\" limitNumLabels=\"0\" drawLabels=\"1\" upsidedownLabels=\"0\"/>\n"
           "</settings>\n</labeling>\n";
}

}  // namespace

std::string xml_escape(const std::string& s) {
    std::string out;
    for (char c : s) switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                out += c;
        }
    return out;
}

bool empty(const RasterStyle& s) { return s.stops.empty(); }

double round_ceiling(double largest) {
    if (!std::isfinite(largest) || largest <= 0) return 1.0;
    const double decade = std::pow(10.0, std::floor(std::log10(largest)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * decade >= largest * (1 - 1e-12)) return m * decade;
    return 10.0 * decade;
}

std::string value_label(double v, const std::string& units) {
    if (units == "1") {
        char b[32];
        std::snprintf(b, sizeof b, "%g %%", 100.0 * v);
        return b;
    }
    const std::string shown = units == "m s-1" ? "m/s" : units;
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return std::string(b) + (shown.empty() ? "" : " " + shown);
}

RasterStyle ramp(double top, const std::vector<std::string>& colours, const std::string& units, double opacity) {
    RasterStyle s;
    s.opacity = opacity;
    const std::size_t n = colours.size();
    for (std::size_t k = 0; k < n; ++k) {
        const double v = n == 1 ? top : top * double(k) / double(n - 1);
        s.stops.push_back({v, colours[k], value_label(v, units)});
    }
    return s;
}

RasterStyle probability_classes(const std::vector<std::string>& six_colours, double opacity) {
    if (six_colours.size() != 6) fail("style", "probability classes", "need six colours");
    const double upper[] = {0.01, 0.05, 0.10, 0.25, 0.50, 1.0};
    const char* labels[] = {"≤ 1 %", "1 – 5 %", "5 – 10 %", "10 – 25 %", "25 – 50 %", "50 – 100 %"};
    RasterStyle s;
    s.discrete = true;
    s.opacity = opacity;
    for (int k = 0; k < 6; ++k) s.stops.push_back({upper[k], six_colours[std::size_t(k)], labels[k]});
    return s;
}

std::string raster_qml(const RasterStyle& s) {
    return head() +
           "<pipe>\n<rasterrenderer type=\"singlebandpseudocolor\" band=\"1\" alphaBand=\"-1\" nodataColor=\"\" opacity=\"" +
           num(s.opacity) + "\" classificationMin=\"" + num(s.stops.front().value) + "\" classificationMax=\"" +
           num(s.stops.back().value) +
           "\">\n<rasterTransparency/>\n<minMaxOrigin><limits>None</limits><extent>WholeRaster</extent>"
           "<statAccuracy>Exact</statAccuracy><cumulativeCutLower>0.02</cumulativeCutLower>"
           "<cumulativeCutUpper>0.98</cumulativeCutUpper><stdDevFactor>2</stdDevFactor></minMaxOrigin>\n<rastershader>\n" +
           colour_ramp_shader(s) +
           "</rastershader>\n</rasterrenderer>\n<rasterresampler maxOversampling=\"2\"/>\n"
           "<resamplingStage>resamplingFilter</resamplingStage>\n</pipe>\n<blendMode>0</blendMode>\n</qgis>\n";
}

std::string vector_qml(const VectorStyle& s) {
    std::string renderer;
    std::string symbols;
    if (!s.categories.empty()) {
        renderer = "<renderer-v2 type=\"categorizedSymbol\" attr=\"" + xml_escape(s.field) +
                   "\" symbollevels=\"0\" enableorderby=\"0\" forceraster=\"0\">\n<categories>\n";
        for (std::size_t k = 0; k < s.categories.size(); ++k) {
            renderer += "<category render=\"true\" symbol=\"" + std::to_string(k) + "\" value=\"" +
                        xml_escape(s.categories[k].value) + "\" label=\"" + xml_escape(s.categories[k].label) + "\"/>\n";
            symbols += symbol_xml(s.categories[k].symbol, std::to_string(k));
        }
        // The "all other values" category.
        renderer += "<category render=\"true\" symbol=\"" + std::to_string(s.categories.size()) +
                    "\" value=\"\" label=\"other\"/>\n</categories>\n";
        symbols += symbol_xml(s.other, std::to_string(s.categories.size()));
    } else if (!s.classes.empty()) {
        renderer = "<renderer-v2 type=\"graduatedSymbol\" attr=\"" + xml_escape(s.field) +
                   "\" graduatedMethod=\"GraduatedColor\" symbollevels=\"0\" enableorderby=\"0\" forceraster=\"0\">\n<ranges>\n";
        for (std::size_t k = 0; k < s.classes.size(); ++k) {
            const Class& c = s.classes[k];
            renderer += "<range render=\"true\" symbol=\"" + std::to_string(k) + "\" lower=\"" + num(c.lower) + "\" upper=\"" +
                        num(c.upper) + "\" label=\"" + xml_escape(c.label) + "\"/>\n";
            symbols += symbol_xml(c.symbol, std::to_string(k));
        }
        renderer += "</ranges>\n";
    } else {
        renderer = "<renderer-v2 type=\"singleSymbol\" symbollevels=\"0\" enableorderby=\"0\" forceraster=\"0\">\n";
        symbols = symbol_xml(s.symbol, "0");
    }
    renderer += "<symbols>\n" + symbols + "</symbols>\n</renderer-v2>\n";
    const bool labels = !s.labels.expression.empty();
    return head(std::string(" labelsEnabled=\"") + (labels ? "1" : "0") + "\"") + renderer +
           (labels ? labeling_xml(s.labels) : "") +
           "<blendMode>0</blendMode>\n<featureBlendMode>0</featureBlendMode>\n<layerOpacity>1</layerOpacity>\n</qgis>\n";
}

std::string mesh_qml(const MeshStyle& s) {
    std::string x = head() + "<mesh-renderer-settings>\n<active-dataset-group scalar=\"" + std::to_string(s.scalar_group) +
                    "\" vector=\"" + std::to_string(s.vector_group) + "\"/>\n";
    if (s.scalar_group >= 0)
        x += "<scalar-settings group=\"" + std::to_string(s.scalar_group) + "\" opacity=\"" + num(s.scalar.opacity) +
             "\" interpolation-method=\"none\" min-val=\"" + num(s.scalar.stops.front().value) + "\" max-val=\"" +
             num(s.scalar.stops.back().value) + "\">\n" + colour_ramp_shader(s.scalar) +
             "<edge-settings stroke-width-unit=\"0\"/>\n</scalar-settings>\n";
    if (s.vector_group >= 0)
        x += "<vector-settings group=\"" + std::to_string(s.vector_group) +
             "\" color=\"20,20,20,255\" line-width=\"0.3\" coloring-method=\"0\" symbology=\"0\" filter-min=\"" +
             num(s.arrow_min_speed) + "\" filter-max=\"-1\" user-grid-enabled=\"1\" user-grid-width=\"" + num(s.arrow_spacing_px) +
             "\" user-grid-height=\"" + num(s.arrow_spacing_px) +
             "\">\n<vector-arrow-settings arrow-head-width-ratio=\"0.15\" arrow-head-length-ratio=\"0.4\">\n"
             "<shaft-length method=\"minmax\" min=\"1\" max=\"" +
             num(0.9 * s.arrow_spacing_px) + "\"/>\n</vector-arrow-settings>\n</vector-settings>\n";
    return x +
           "<mesh-settings-native enabled=\"0\" line-width=\"0.26\" line-width-unit=\"MM\" color=\"0,0,0,255\"/>\n"
           "<mesh-settings-triangular enabled=\"0\" line-width=\"0.26\" line-width-unit=\"MM\" color=\"0,0,0,255\"/>\n"
           "</mesh-renderer-settings>\n<blendMode>0</blendMode>\n<layerOpacity>1</layerOpacity>\n</qgis>\n";
}

std::string qml_body(const std::string& qml) {
    const auto root = qml.find("<qgis ");
    const auto open_end = root == std::string::npos ? root : qml.find('>', root);
    const auto close = qml.rfind("</qgis>");
    if (open_end == std::string::npos || close == std::string::npos || close < open_end) fail("style", "qml", "not a QGIS style");
    return qml.substr(open_end + 1, close - open_end - 1);
}

bool qml_labels_enabled(const std::string& qml) {
    const auto root = qml.find("<qgis ");
    const auto open_end = root == std::string::npos ? root : qml.find('>', root);
    return open_end != std::string::npos && qml.substr(root, open_end - root).find("labelsEnabled=\"1\"") != std::string::npos;
}

void write_qml(const std::string& path, const std::string& qml) { write_text_atomic(path, qml); }

void store_styles(GDALDataset& ds, const std::string& path, const std::string& layer, const std::vector<NamedStyle>& styles) {
    OGRLayer* target = ds.GetLayerByName(layer.c_str());
    if (!target) fail(path, "layer '" + layer + "'", "not found for its style");
    const std::string geometry_column = target->GetGeometryColumn();
    // The table as QGIS creates it (QgsOgrProviderUtils): one row per style of a layer.
    OGRLayer* table = ds.GetLayerByName("layer_styles");
    if (!table) {
        const char* options[] = {"FID=id", nullptr};
        table = ds.CreateLayer("layer_styles", nullptr, wkbNone, const_cast<char**>(options));
        if (!table) fail(path, "table 'layer_styles'", "cannot create: " + gdal::last_error());
        auto field = [&](const char* name, OGRFieldType type, int width = 0, OGRFieldSubType sub = OFSTNone) {
            OGRFieldDefn d(name, type);
            d.SetWidth(width);
            d.SetSubType(sub);
            if (table->CreateField(&d) != OGRERR_NONE)
                fail(path, std::string("table 'layer_styles' field '") + name + "'", "cannot create: " + gdal::last_error());
        };
        for (const char* name : {"f_table_catalog", "f_table_schema", "f_table_name", "f_geometry_column"})
            field(name, OFTString, 256);
        field("styleName", OFTString, 30);
        field("styleQML", OFTString);
        field("styleSLD", OFTString);
        field("useAsDefault", OFTInteger, 0, OFSTBoolean);
        field("description", OFTString);
        field("owner", OFTString, 30);
        field("ui", OFTString, 30);
        field("update_time", OFTDateTime);
    }
    for (const NamedStyle& s : styles) {
        OGRFeature f(table->GetLayerDefn());
        f.SetField("f_table_catalog", "");
        f.SetField("f_table_schema", "");
        f.SetField("f_table_name", layer.c_str());
        f.SetField("f_geometry_column", geometry_column.c_str());
        f.SetField("styleName", s.name.c_str());
        f.SetField("styleQML", s.qml.c_str());
        f.SetField("styleSLD", "");
        f.SetField("useAsDefault", s.is_default ? 1 : 0);
        f.SetField("description", s.description.c_str());
        f.SetField("owner", "flotsam");
        f.SetField("ui", "");
        f.SetField("update_time", 2000, 1, 1, 0, 0, 0.0f, 100);  // fixed: the same inputs give the same bytes
        if (table->CreateFeature(&f) != OGRERR_NONE)
            fail(path, "table 'layer_styles'", "cannot add the style '" + s.name + "' of '" + layer + "': " + gdal::last_error());
    }
}

std::string stored_style(const std::string& path, const std::string& layer) {
    gdal::Dataset ds = gdal::open_vector(path);
    OGRLayer* table = ds->GetLayerByName("layer_styles");
    if (!table) return "";
    table->ResetReading();
    for (OGRFeature* raw; (raw = table->GetNextFeature()) != nullptr;) {
        std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(raw, OGRFeature::DestroyFeature);
        if (layer == f->GetFieldAsString("f_table_name") && f->GetFieldAsInteger("useAsDefault") != 0)
            return f->GetFieldAsString("styleQML");
    }
    return "";
}

}  // namespace flotsam::gis::qgis
