#include "export/qgis_project.hpp"

#include <libdeflate.h>

#include <cmath>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "data/gdal_support.hpp"
#include "export/qgis_style.hpp"

namespace flotsam::gis::qgis {

namespace {

std::string num(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

// The project's CRS as QGIS stores it; QGIS builds it from the WKT (which names the
// authority when there is one).
std::string spatial_ref_xml(const cf::GridMapping& crs) {
    if (crs.empty())
        return "<spatialrefsys><wkt></wkt><proj4></proj4><srsid>0</srsid><srid>0</srid><authid></authid>"
               "<description></description></spatialrefsys>\n";
    const OGRSpatialReference s = gdal::spatial_ref(crs, "project");
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2_2018", nullptr};
    s.exportToWkt(&wkt, options);
    const std::string wkt_text = wkt ? wkt : "";
    CPLFree(wkt);
    char* proj4 = nullptr;
    s.exportToProj4(&proj4);
    const std::string proj4_text = proj4 ? proj4 : "";
    CPLFree(proj4);
    const char* authority = s.GetAuthorityName(nullptr);
    const char* code = s.GetAuthorityCode(nullptr);
    const std::string authid = authority && code ? std::string(authority) + ":" + code : "";
    return "<spatialrefsys><wkt>" + xml_escape(wkt_text) + "</wkt><proj4>" + xml_escape(proj4_text) + "</proj4><srid>" +
           (code ? xml_escape(code) : "0") + "</srid><authid>" + xml_escape(authid) + "</authid><description>" +
           xml_escape(s.GetName() ? s.GetName() : "") + "</description><geographicflag>" + (s.IsGeographic() ? "true" : "false") +
           "</geographicflag></spatialrefsys>\n";
}

// Seconds from the files' epoch (2000-01-01 00:00:00 UTC, which stands for the start of
// the run: common/cf.hpp) as ISO 8601.
std::string iso_time(double seconds) {
    const std::time_t t = std::time_t(946684800) + std::time_t(std::llround(seconds));
    std::tm tm{};
    gmtime_r(&t, &tm);
    char b[32];
    std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return b;
}

std::string relative_to(const std::string& path, const std::string& folder) {
    namespace fs = std::filesystem;
    const fs::path rel = fs::absolute(path).lexically_normal().lexically_relative(fs::absolute(folder).lexically_normal());
    const std::string r = rel.generic_string();
    return r.rfind("..", 0) == 0 ? r : "./" + r;
}

std::string layer_id(std::size_t k, const ProjectLayer& l) {
    std::string id = "flotsam_" + std::to_string(k) + "_";
    for (char c : l.name) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return id;
}

const char* provider_of(ProjectLayer::Kind k) {
    return k == ProjectLayer::Kind::raster ? "gdal" : k == ProjectLayer::Kind::vector ? "ogr" : "mdal";
}

const char* type_of(ProjectLayer::Kind k) {
    return k == ProjectLayer::Kind::raster ? "raster" : k == ProjectLayer::Kind::vector ? "vector" : "mesh";
}

void put_u16(std::string& s, unsigned v) {
    s += char(v & 0xff);
    s += char((v >> 8) & 0xff);
}
void put_u32(std::string& s, std::uint32_t v) {
    put_u16(s, v & 0xffff);
    put_u16(s, v >> 16);
}

}  // namespace

std::string project_xml(const Project& p, const std::string& folder) {
    const std::string srs = spatial_ref_xml(p.crs);
    std::string tree, layers;
    for (const std::string& group : p.groups) {
        std::string members;
        for (std::size_t k = 0; k < p.layers.size(); ++k) {
            const ProjectLayer& l = p.layers[k];
            if (l.group != group) continue;
            std::string source = relative_to(l.path, folder);
            if (l.kind == ProjectLayer::Kind::vector) source += "|layername=" + l.layer;
            members += "<layer-tree-layer id=\"" + layer_id(k, l) + "\" name=\"" + xml_escape(l.name) + "\" source=\"" +
                       xml_escape(source) + "\" providerKey=\"" + provider_of(l.kind) + "\" checked=\"" +
                       (l.visible ? "Qt::Checked" : "Qt::Unchecked") + "\" expanded=\"" + (l.visible ? "1" : "0") +
                       "\"><customproperties/></layer-tree-layer>\n";
            layers += std::string("<maplayer type=\"") + type_of(l.kind) + "\" labelsEnabled=\"" +
                      (qml_labels_enabled(l.qml) ? "1" : "0") + "\" styleCategories=\"AllStyleCategories\">\n<id>" +
                      layer_id(k, l) + "</id>\n<datasource>" + xml_escape(source) + "</datasource>\n<layername>" +
                      xml_escape(l.name) + "</layername>\n<srs>" + srs + "</srs>\n";
            if (l.kind == ProjectLayer::Kind::mesh)
                layers += "<provider time-unit=\"3\">mdal</provider>\n<temporal reference-time=\"" + iso_time(0) +
                          "\" start-time-extent=\"" + iso_time(l.time_start) + "\" end-time-extent=\"" + iso_time(l.time_end) +
                          "\" matching-method=\"0\" temporal-active=\"1\"/>\n";
            else
                layers += std::string("<provider>") + provider_of(l.kind) + "</provider>\n";
            layers += qml_body(l.qml) + "</maplayer>\n";
        }
        if (members.empty()) continue;
        tree += "<layer-tree-group name=\"" + xml_escape(group) +
                "\" checked=\"Qt::Checked\" expanded=\"1\">\n<customproperties/>\n" + members + "</layer-tree-group>\n";
    }
    const std::string extent =
        "xmin=\"" + num(p.x_min) + "\" ymin=\"" + num(p.y_min) + "\" xmax=\"" + num(p.x_max) + "\" ymax=\"" + num(p.y_max) + "\"";
    std::string x = "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n<qgis projectname=\"" + xml_escape(p.title) +
                    "\" version=\"3.22.16\">\n<homePath path=\"\"/>\n<title>" + xml_escape(p.title) + "</title>\n<projectCrs>" +
                    srs + "</projectCrs>\n<layer-tree-group>\n<customproperties/>\n" + tree +
                    "<custom-order enabled=\"0\"/>\n</layer-tree-group>\n<projectlayers>\n" + layers +
                    "</projectlayers>\n<mapcanvas name=\"theMapCanvas\" annotationsVisible=\"1\">\n<units>meters</units>\n"
                    "<extent><xmin>" +
                    num(p.x_min) + "</xmin><ymin>" + num(p.y_min) + "</ymin><xmax>" + num(p.x_max) + "</xmax><ymax>" +
                    num(p.y_max) + "</ymax></extent>\n<rotation>0</rotation>\n<destinationsrs>" + srs +
                    "</destinationsrs>\n<rendermaptile>0</rendermaptile>\n</mapcanvas>\n"
                    "<ProjectViewSettings UseProjectScales=\"0\" rotation=\"0\">\n<Scales/>\n<DefaultViewExtent " +
                    extent + ">" + srs + "</DefaultViewExtent>\n</ProjectViewSettings>\n";
    double start = 0, end = 0;
    bool timed = false;
    for (const ProjectLayer& l : p.layers)
        if (l.kind == ProjectLayer::Kind::mesh) {
            start = timed ? std::min(start, l.time_start) : l.time_start;
            end = timed ? std::max(end, l.time_end) : l.time_end;
            timed = true;
        }
    if (timed && p.time_step > 0)
        x += "<ProjectTimeSettings timeStepUnit=\"s\" timeStep=\"" + num(p.time_step) +
             "\" frameRate=\"1\" cumulativeTemporalRange=\"0\">\n<TemporalRange><start>" + iso_time(start) + "</start><end>" +
             iso_time(end) + "</end></TemporalRange>\n</ProjectTimeSettings>\n";
    x += "<properties>\n<Paths><Absolute type=\"bool\">false</Absolute></Paths>\n"
         "<SpatialRefSys><ProjectionsEnabled type=\"int\">1</ProjectionsEnabled></SpatialRefSys>\n"
         "<Measurement><DistanceUnits type=\"QString\">meters</DistanceUnits><AreaUnits type=\"QString\">m2</AreaUnits>"
         "</Measurement>\n</properties>\n</qgis>\n";
    return x;
}

void write_zip(const std::string& path, const std::vector<std::pair<std::string, std::string>>& files) {
    // Local headers and data, then the central directory and its end record (PKWARE
    // APPNOTE 4.3); deflate (method 8), 1980-01-01 00:00 as every file's date.
    struct Compressor {
        libdeflate_compressor* c = libdeflate_alloc_compressor(6);
        ~Compressor() { libdeflate_free_compressor(c); }
    } compressor;
    if (!compressor.c) fail(path, "zip", "cannot allocate a compressor");
    const unsigned dos_time = 0, dos_date = (0u << 9) | (1u << 5) | 1u;
    std::string out, central;
    for (const auto& [name, data] : files) {
        std::string packed(libdeflate_deflate_compress_bound(compressor.c, data.size()), '\0');
        const std::size_t n = libdeflate_deflate_compress(compressor.c, data.data(), data.size(), packed.data(), packed.size());
        if (n == 0) fail(path, name, "cannot compress");
        packed.resize(n);
        const std::uint32_t crc = libdeflate_crc32(0, data.data(), data.size());
        const std::uint32_t offset = std::uint32_t(out.size());
        auto common = [&](std::string& s) {
            put_u16(s, 20);      // version needed: 2.0
            put_u16(s, 0x0800);  // UTF-8 names
            put_u16(s, 8);
            put_u16(s, dos_time);
            put_u16(s, dos_date);
            put_u32(s, crc);
            put_u32(s, std::uint32_t(packed.size()));
            put_u32(s, std::uint32_t(data.size()));
            put_u16(s, unsigned(name.size()));
            put_u16(s, 0);  // extra field
        };
        put_u32(out, 0x04034b50);
        common(out);
        out += name;
        out += packed;
        put_u32(central, 0x02014b50);
        put_u16(central, 20);  // made by
        common(central);
        put_u16(central, 0);  // comment
        put_u16(central, 0);  // disk
        put_u16(central, 0);  // internal attributes
        put_u32(central, 0);  // external attributes
        put_u32(central, offset);
        central += name;
    }
    const std::uint32_t directory = std::uint32_t(out.size());
    out += central;
    put_u32(out, 0x06054b50);
    put_u16(out, 0);
    put_u16(out, 0);
    put_u16(out, unsigned(files.size()));
    put_u16(out, unsigned(files.size()));
    put_u32(out, std::uint32_t(central.size()));
    put_u32(out, directory);
    put_u16(out, 0);
    write_text_atomic(path, out);
}

void write_project(const std::string& path, const Project& p) {
    const std::filesystem::path file(path);
    const std::string folder = file.parent_path().empty() ? "." : file.parent_path().string();
    write_zip(path, {{file.stem().string() + ".qgs", project_xml(p, folder)}});
}

}  // namespace flotsam::gis::qgis
