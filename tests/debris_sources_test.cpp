// Debris sources from GIS layers: yards filled with bodies (counts by hand, no overlap,
// holes kept clear), points carried from longitude/latitude into a UTM scene, the source
// feature and type on every trajectory, and the errors a port engineer meets, each
// naming the file, layer and feature.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "common/netcdf.hpp"
#include "data/gdal_support.hpp"
#include "debris/catalogue.hpp"
#include "debris/source_layout.hpp"
#include "formats/flow_file.hpp"
#include "formats/scene.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using debris::Pose;
using debris::Ring;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// A rectangle of `length` x `width` [m] from (x0, y0), its long side at `heading_deg`.
Ring rectangle(double x0, double y0, double length, double width, double heading_deg) {
    const double c = std::cos(heading_deg * deg), s = std::sin(heading_deg * deg);
    return {{x0, y0},
            {x0 + c * length, y0 + s * length},
            {x0 + c * length - s * width, y0 + s * length + c * width},
            {x0 - s * width, y0 + c * width}};
}

// Two bodies of one lattice (same heading) do not overlap: apart by a body plus the gap
// along the heading or across it.
void expect_apart(const std::vector<Pose>& poses, double length, double width, double gap) {
    for (std::size_t a = 0; a < poses.size(); ++a)
        for (std::size_t b = a + 1; b < poses.size(); ++b) {
            const double dx = poses[b].x - poses[a].x, dy = poses[b].y - poses[a].y, h = poses[a].heading;
            const double du = std::fabs(dx * std::cos(h) + dy * std::sin(h)), dv = std::fabs(-dx * std::sin(h) + dy * std::cos(h));
            EXPECT_TRUE(du >= length + gap - 1e-6 || dv >= width + gap - 1e-6) << a << " and " << b << " overlap";
        }
}

}  // namespace

// 40 ft containers (12.19 x 2.44 m) in a 100 x 30 m yard at a 1 m gap: 7 along
// (7 x 12.19 + 6 = 91.33 <= 100 < 8 x 12.19 + 7) by 9 across (9 x 2.44 + 8 = 29.96 <= 30):
// 63. A 30 x 10 m hole over x 35..65, y 10..20 takes the 3 x 3 bodies whose footprints
// reach into it (worked out in docs/gis.md's layout rule: centres 9.93 + 13.19 k along,
// 1.24 + 3.44 k across): 54. Rotating the yard by 30 degrees changes nothing.
TEST(SourceLayout, AYardOfKnownSizeAndGapHoldsTheCountByHand) {
    const double L = 12.19, B = 2.44;
    for (const double heading : {0.0, 30.0}) {
        const Ring yard = rectangle(1000.0, 2000.0, 100.0, 30.0, heading);
        EXPECT_NEAR(debris::polygon_area({yard}), 3000.0, 1e-6);
        const debris::YardLayout all = debris::lay_out_yard({{yard}, std::nan(""), 1.0, 0}, L, B);
        EXPECT_NEAR(all.heading_deg, heading, 1e-9);  // the longest edge
        ASSERT_EQ(all.poses.size(), 63u) << heading;
        expect_apart(all.poses, L, B, 1.0);
        for (const Pose& p : all.poses) EXPECT_TRUE(debris::rectangle_inside({yard}, p, L * 0.999, B * 0.999));
        EXPECT_EQ(all.capacity, 8 * 12);  // gap 0: 8 x 12.19 = 97.5, 12 x 2.44 = 29.3
    }
    const Ring yard = rectangle(0.0, 0.0, 100.0, 30.0, 0.0);
    const Ring hole = rectangle(35.0, 10.0, 30.0, 10.0, 0.0);
    const debris::YardLayout holed = debris::lay_out_yard({{yard, hole}, 0.0, 1.0, 0}, L, B);
    ASSERT_EQ(holed.poses.size(), 54u);
    EXPECT_NEAR(debris::polygon_area({yard, hole}), 2700.0, 1e-9);
    for (const Pose& p : holed.poses) {  // no footprint reaches into the hole
        const bool apart_x = p.x + L / 2 <= 35.0 || p.x - L / 2 >= 65.0, apart_y = p.y + B / 2 <= 10.0 || p.y - B / 2 >= 20.0;
        EXPECT_TRUE(apart_x || apart_y) << p.x << ", " << p.y;
    }
}

// A count without a gap: the widest gap whose lattice holds it. 20 containers in the
// 100 x 30 m yard: 5 along needs g <= (100 - 5 x 12.19) / 4 = 9.7625, 4 across
// g <= (30 - 4 x 2.44) / 3 = 6.74667; every other split (7 x 3, 4 x 5, 6 x 4, ...) needs
// a narrower gap. So 5 x 4 at 6.74667 m.
TEST(SourceLayout, ACountSpreadsTheBodiesAtTheWidestGapThatHoldsThem) {
    const Ring yard = rectangle(0.0, 0.0, 100.0, 30.0, 0.0);
    const debris::YardLayout l = debris::lay_out_yard({{yard}, std::nan(""), std::nan(""), 20}, 12.19, 2.44);
    ASSERT_EQ(l.poses.size(), 20u);
    EXPECT_NEAR(l.gap, (30.0 - 4 * 2.44) / 3.0, 1e-4);
    expect_apart(l.poses, 12.19, 2.44, l.gap);
    // More than the yard holds: the places at gap 0 come back, fewer than asked.
    const debris::YardLayout over = debris::lay_out_yard({{yard}, std::nan(""), std::nan(""), 97}, 12.19, 2.44);
    EXPECT_EQ(over.poses.size(), 96u);
    EXPECT_NEAR(debris::longest_edge_heading_deg(rectangle(0, 0, 10, 30, 0)), 90.0, 1e-9);
}

namespace {

// A UTM 53N scene near Kainan, 200 x 120 m of 2 m cells, 2 m of still water, one 20 x 20 m
// building; a steady 0.5 m/s current east over it; and a GeoJSON layer in longitude and
// latitude (GeoJSON's own CRS) whose features are given in the scene's metres.
struct UtmPort {
    std::string dir, scene, flow;
    Grid grid{100, 60, 518001.0, 3779001.0, 2.0, 2.0};
    OGRSpatialReference utm, wgs84;

    explicit UtmPort(const std::string& name, int seconds = 4, float current = 0.5f) : dir(test::scratch_dir(name)) {
        gdal::init();
        utm.importFromEPSG(32653);
        wgs84.importFromEPSG(4326);
        utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        Scene s;
        s.grid = grid;
        s.z.assign(grid.size(), -2.0);
        s.building.assign(grid.size(), 0);
        for (int j = 0; j < grid.ny; ++j)
            for (int i = 0; i < grid.nx; ++i)
                if (grid.x(i) > 518150.0 && grid.x(i) < 518170.0 && grid.y(j) > 3779080.0 && grid.y(j) < 3779100.0) {
                    s.building[grid.index(i, j)] = 1;
                    s.z[grid.index(i, j)] = 10.0;
                }
        s.crs = gdal::grid_mapping(utm);
        scene = dir + "/scene.nc";
        write_scene(scene, s, "test");
        FlowFileDef def;
        def.window = grid;
        def.crs = s.crs;
        for (int k = 0; k <= seconds; ++k) def.frame_times.push_back(k);
        def.z.assign(s.z.begin(), s.z.end());
        flow = dir + "/flow.nc";
        FlowWriter w(flow, def);
        std::vector<float> h(grid.size()), u(grid.size()), v(grid.size(), 0.0f);
        for (std::size_t c = 0; c < grid.size(); ++c) {
            h[c] = s.building[c] ? 0.0f : 2.0f;
            u[c] = s.building[c] ? 0.0f : current;
        }
        for (std::size_t k = 0; k < def.frame_times.size(); ++k) w.write_frame(k, h, u, v);
        w.write_summary(v, v, v);
        w.close();
    }
    // "[lon,lat]" of a point given in the scene's metres.
    std::string lonlat(double x, double y) const {
        std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&utm, &wgs84));
        EXPECT_TRUE(t->Transform(1, &x, &y));
        char buf[80];
        std::snprintf(buf, sizeof buf, "[%.12f,%.12f]", x, y);
        return buf;
    }
    std::string point(double x, double y, const std::string& props) const {
        return R"({"type":"Feature","properties":{)" + props + R"(},"geometry":{"type":"Point","coordinates":)" + lonlat(x, y) +
               "}}";
    }
    std::string polygon(const Ring& r, const std::string& props) const {
        std::string c;
        for (std::size_t k = 0; k <= r.size(); ++k) c += (k ? "," : "") + lonlat(r[k % r.size()][0], r[k % r.size()][1]);
        return R"({"type":"Feature","properties":{)" + props + R"(},"geometry":{"type":"Polygon","coordinates":[[)" + c + "]]}}";
    }
    std::string layer(const std::string& name, const std::vector<std::string>& features) const {
        std::string s = R"({"type":"FeatureCollection","features":[)";
        for (std::size_t k = 0; k < features.size(); ++k) s += (k ? "," : "") + features[k];
        return test::write_file(dir, name + ".geojson", s + "]}");
    }
    std::string debris(const std::string& sources, const std::string& out) const {
        return "debris --flow " + flow + " --scene " + scene + " --sources " + sources + " --end-time 2 --quiet --out " + out;
    }
};

}  // namespace

// A yard of 40 ft containers (92 x 13.2 m at 30 degrees, gap 1 m: 7 along, 7 x 12.192 + 6
// = 91.34 m, by 4 across, 4 x 2.438 + 3 = 12.75 m: 28) and a car by its bearing, both given in longitude/latitude: the
// bodies start where the layout puts them in the scene's metres, each trajectory names
// its feature and catalogue entry, and the car's heading is 90 - bearing.
TEST(DebrisSourcesCli, YardsAndPointsFromALonLatLayerStartInTheUtmScene) {
    const UtmPort port("sources_cli");
    const Ring yard = rectangle(518030.0, 3779010.0, 92.0, 13.2, 30.0);
    const std::string layer = port.layer("port", {port.polygon(yard, R"("type":"container_40ft","gap":1.0)"),
                                                  port.point(518120.0, 3779030.0, R"("type":"car","bearing":30)")});
    std::string out;
    const std::string traj = port.dir + "/traj.nc";
    ASSERT_EQ(test::run_cli(port.debris(layer, traj), &out), 0) << out;
    nc::File f = nc::File::open_read(traj);
    const auto sources = f.get_strings(f.var("source")), types = f.get_strings(f.var("body_type"));
    const auto names = f.get_strings(f.var("trajectory_id"));
    ASSERT_EQ(sources.size(), 29u);
    const debris::CatalogueBody& container = *debris::find_catalogue_body("container_40ft");  // 12.192 x 2.438 m
    const debris::YardLayout expected = debris::lay_out_yard({{yard}, std::nan(""), 1.0, 0}, container.length, container.width);
    ASSERT_EQ(expected.poses.size(), 28u);
    const std::vector<double> x = f.get_double(f.var("x")), y = f.get_double(f.var("y")), yaw = f.get_double(f.var("yaw"));
    const std::size_t nt = x.size() / 29;
    for (std::size_t k = 0; k < 28; ++k) {
        EXPECT_EQ(sources[k], "port/0");
        EXPECT_EQ(names[k], "port/0/" + std::to_string(k + 1));
        EXPECT_EQ(types[k], "container_40ft");
        EXPECT_NEAR(x[k * nt], expected.poses[k].x, 1e-4);
        EXPECT_NEAR(y[k * nt], expected.poses[k].y, 1e-4);
        EXPECT_NEAR(yaw[k * nt], 30.0, 1e-6);
    }
    EXPECT_EQ(sources[28], "port/1");
    EXPECT_EQ(types[28], "car");
    EXPECT_NEAR(x[28 * nt], 518120.0, 1e-4);
    EXPECT_NEAR(yaw[28 * nt], 60.0, 1e-6);
    EXPECT_NEAR(f.get_double(f.var("length"))[28], 4.5, 1e-12);  // the catalogue's car
}

// What a port engineer gets wrong, each named with the file, layer and feature, and no
// trajectory file left behind.
TEST(DebrisSourcesCli, BadSourcesAreNamedByFeature) {
    const UtmPort port("sources_errors");
    struct Case {
        std::string feature, expect;
    };
    const std::vector<Case> cases = {
        {port.point(518160.0, 3779090.0, R"("type":"car")"), "port/0"},  // in the building: the body name is the feature
        {port.point(518040.0, 3779040.0, R"("type":"sofa")"), "feature 0: attribute 'type' = 'sofa': not in the debris catalogue"},
        {port.point(518040.0, 3779040.0, R"("kind":"car")"), "attribute 'type': missing"},
        {port.point(518040.0, 3779040.0, R"("type":"car","count":3)"), "attribute 'count': given on a point"},
        {port.point(518040.0, 3779040.0, R"("type":"car","heading":0,"bearing":90)"), "both given"},
        {port.point(518040.0, 3779040.0, R"("type":"car","mass":-5)"), "attribute 'mass' = -5: must be a positive number"},
        {port.polygon(rectangle(518030.0, 3779010.0, 30.0, 10.0, 0.0), R"("type":"container_40ft","count":50)"),
         "holds 8 bodies of type container_40ft"},
        {port.polygon(rectangle(518030.0, 3779010.0, 30.0, 10.0, 0.0), R"("type":"container_40ft")"), "neither given"},
        {port.point(518400.0, 3779040.0, R"("type":"car")"), "outside the domain"},
    };
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const std::string layer = port.layer("port", {cases[k].feature});
        const std::string traj = port.dir + "/bad" + std::to_string(k) + ".nc";
        std::string out;
        EXPECT_NE(test::run_cli(port.debris(layer, traj), &out), 0) << k;
        EXPECT_NE(out.find(cases[k].expect), std::string::npos) << k << ": " << out;
        EXPECT_NE(out.find("port.geojson"), std::string::npos) << k << ": " << out;
        EXPECT_FALSE(std::filesystem::exists(traj)) << k;
    }
    std::string out;
    EXPECT_NE(
        test::run_cli("debris --flow " + port.flow + " --sources " +
                          port.layer("port", {port.point(518040, 3779040, R"("type":"car")")}) + " --out " + port.dir + "/x.nc",
                      &out),
        0);
    EXPECT_NE(out.find("needs --scene"), std::string::npos) << out;
}

// A sweep spec's [[sources]]: the yard's bodies become the sweep's bodies, their feature
// and type recorded per body, their statistics one group per variant, and shards merge
// to the bytes of the whole sweep.
TEST(DebrisSourcesCli, ASweepTakesItsBodiesFromSourceLayers) {
    const UtmPort port("sources_sweep");
    const std::string layer = port.layer(
        "yards", {port.polygon(rectangle(518030.0, 3779010.0, 40.0, 12.0, 0.0), R"("type":"car","count":6,"heading":0)")});
    const std::string spec = test::write_file(port.dir, "spec.toml",
                                              "[sweep]\noutput-interval = 1\nend-time = 2\nscene = \"" + port.scene +
                                                  "\"\n[flows]\npaths = [\"" + port.flow + "\"]\n[[sources]]\nfile = \"" + layer +
                                                  "\"\nlayers = [\"yards\"]\n[variants]\nnames = [\"CC+SC\", \"LC+MC\"]\n");
    std::string out;
    ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --out " + port.dir + "/whole.nc --quiet --threads 1", &out), 0) << out;
    for (int i = 0; i < 2; ++i)
        ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --shard " + std::to_string(i) + "/2 --out " + port.dir + "/part" +
                                    std::to_string(i) + ".nc --quiet --threads 1",
                                &out),
                  0)
            << out;
    ASSERT_EQ(
        test::run_cli("sweep merge " + port.dir + "/part1.nc " + port.dir + "/part0.nc --out " + port.dir + "/merged.nc", &out), 0)
        << out;
    nc::File f = nc::File::open_read(port.dir + "/whole.nc");
    const auto bodies = f.get_strings(f.var("body_name")), sources = f.get_strings(f.var("body_source"));
    const auto types = f.get_strings(f.var("body_type"));
    ASSERT_EQ(bodies.size(), 6u);
    for (std::size_t k = 0; k < 6; ++k) {
        EXPECT_EQ(bodies[k], "yards/0/" + std::to_string(k + 1));
        EXPECT_EQ(sources[k], "yards/0");
        EXPECT_EQ(types[k], "car");
    }
    // The statistics group a yard's bodies as one source, per variant.
    ASSERT_EQ(test::run_cli("stats --sweep " + port.dir + "/whole.nc --out " + port.dir + "/stats.nc", &out), 0) << out;
    nc::File st = nc::File::open_read(port.dir + "/stats.nc");
    EXPECT_EQ(st.get_strings(st.var("group_body")), (std::vector<std::string>{"yards/0", "yards/0"}));
    EXPECT_EQ(st.get_int(st.var("group_members")), (std::vector<int>{6, 6}));
    std::ifstream a(port.dir + "/whole.nc", std::ios::binary), b(port.dir + "/merged.nc", std::ios::binary);
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), {}, std::istreambuf_iterator<char>(b), {}));
}

namespace {

bool same_bytes(const std::string& a, const std::string& b) {
    std::ifstream x(a, std::ios::binary), y(b, std::ios::binary);
    return x && y && std::equal(std::istreambuf_iterator<char>(x), {}, std::istreambuf_iterator<char>(y), {});
}

}  // namespace

// A yard of 40 ft containers packed 0.5 m apart (3 along x by 6 across: 18) 1.5 m from a
// building's west face, carried onto it by a 1 m/s current over 40 s: its bodies share one world per
// run and meet, the ones behind stopped by those in front. The sweep (two flows, the exact
// start and one perturbed, the yard moved as a whole) gives the same bytes on 1 and 2
// threads and from two shards merged; `flotsam debris` of the same layer lets them meet
// too, and with --no-body-contact they pass through each other.
TEST(DebrisSourcesCli, AYardsBodiesMeetInOneRunWithTheSameBytesOnAnyThreadsAndShards) {
    const UtmPort port("sources_meet", 40, 1.0f);
    const Ring yard = rectangle(518110.0, 3779080.5, 38.5, 17.5, 0.0);
    const std::string layer = port.layer("yards", {port.polygon(yard, R"("type":"container_40ft","gap":0.5)")});
    const std::string spec = test::write_file(port.dir, "meet.toml",
                                              "[sweep]\noutput-interval = 1\nscene = \"" + port.scene + "\"\n[flows]\npaths = [\"" +
                                                  port.flow + "\", \"" + port.flow + "\"]\n[[sources]]\nfile = \"" + layer +
                                                  "\"\n[perturbation]\ncount = 1\nposition-std = 0.5\nheading-std = 2\nseed = 4\n");
    std::string out;
    const auto sweep = [&](const std::string& args, const std::string& file) {
        return test::run_cli("sweep --spec " + spec + " --quiet " + args + " --out " + port.dir + "/" + file, &out);
    };
    ASSERT_EQ(sweep("--threads 1", "one.nc"), 0) << out;
    ASSERT_EQ(sweep("--threads 2", "two.nc"), 0) << out;
    ASSERT_EQ(sweep("--threads 2 --shard 0/2", "part0.nc"), 0) << out;
    ASSERT_EQ(sweep("--threads 1 --shard 1/2", "part1.nc"), 0) << out;
    ASSERT_EQ(
        test::run_cli("sweep merge " + port.dir + "/part0.nc " + port.dir + "/part1.nc --out " + port.dir + "/merged.nc", &out), 0)
        << out;
    EXPECT_TRUE(same_bytes(port.dir + "/one.nc", port.dir + "/two.nc"));
    EXPECT_TRUE(same_bytes(port.dir + "/one.nc", port.dir + "/merged.nc"));
    EXPECT_TRUE(same_bytes(port.dir + "/one.csv", port.dir + "/merged.csv"));
    nc::File f = nc::File::open_read(port.dir + "/one.nc");
    const auto runs = f.get_int(f.var("run")), contacts = f.get_int(f.var("body_contact_steps"));
    const auto overlap = f.get_double(f.var("largest_body_overlap"));
    ASSERT_EQ(runs.size(), 72u);  // 2 flows x 2 starts x 18 bodies: 4 runs of 18
    for (std::size_t k = 0; k < runs.size(); ++k) EXPECT_EQ(runs[k], int(k / 18)) << k;
    int met = 0;
    for (std::size_t k = 0; k < runs.size(); ++k) {
        met += contacts[k] > 0 ? 1 : 0;
        EXPECT_LE(overlap[k], 1e-3 * 2.0) << k;  // a thousandth of the 2 m cells
    }
    EXPECT_GT(met, 36) << "most bodies meet another";
    // The perturbed start moves the yard as a whole: the same offset for all its bodies.
    const auto x0 = f.get_double(f.var("x0")), y0 = f.get_double(f.var("y0"));
    const double dx = x0[18] - x0[0], dy = y0[18] - y0[0];
    EXPECT_GT(std::hypot(dx, dy), 1e-3);
    // flotsam debris: the layer's bodies in one world; apart with --no-body-contact.
    const std::string debris = "debris --flow " + port.flow + " --scene " + port.scene + " --sources " + layer + " --quiet --out ";
    ASSERT_EQ(test::run_cli(debris + port.dir + "/together.nc", &out), 0) << out;
    ASSERT_EQ(test::run_cli(debris + port.dir + "/alone.nc --no-body-contact", &out), 0) << out;
    nc::File t = nc::File::open_read(port.dir + "/together.nc"), a = nc::File::open_read(port.dir + "/alone.nc");
    const auto together = t.get_int(t.var("body_contact_steps")), alone = a.get_int(a.var("body_contact_steps"));
    EXPECT_GT(*std::max_element(together.begin(), together.end()), 0);
    EXPECT_EQ(*std::max_element(alone.begin(), alone.end()), 0);
}
