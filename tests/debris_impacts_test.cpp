// Impacts on buildings: the ASCE 7-16 force of a head-on impact by hand, a resting
// contact counted once, stable building ids, and impact statistics of merged shards equal
// to those of the whole sweep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cases/debris_flows.hpp"
#include "common/netcdf.hpp"
#include "data/gdal_support.hpp"
#include "debris/catalogue.hpp"
#include "debris/impacts.hpp"
#include "debris/world.hpp"
#include "formats/scene.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

const Grid grid{120, 120, -0.595, -0.595, 0.01, 0.01};  // 1.2 m square, 1 cm cells

// A wall of cells whose centres lie east of x = 0.3 m (its face at x = 0.300 m).
std::vector<std::uint8_t> east_wall() {
    std::vector<std::uint8_t> m(grid.size(), 0);
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) m[grid.index(i, j)] = grid.x(i) > 0.3 ? 1 : 0;
    return m;
}


}  // namespace

// The paper's box, afloat and carried at the speed of a uniform 0.3 m/s current (no
// relative flow: no drag, no inertia force, no friction in 0.1 m of water), strikes a
// wall square on. Its approach speed is the current's, and the force is by hand
// F = C_o u √(k m) = 0.65 × 0.3 m/s × √(38.4 N/m × 0.625 kg) = 0.195 × √24 = 0.95530 N.
TEST(DebrisImpacts, HeadOnIntoAWallGivesTheAsceForceByHand) {
    const auto dir = test::scratch_dir("impact_head_on");
    const auto path = test::uniform_flow(dir + "/flow.nc", grid, 3, 0.1, 0.3, 0.0);
    World w(path, east_wall());
    BodyDef b = catalogue_body_def("paper_box", "test");
    EXPECT_DOUBLE_EQ(b.impact_stiffness, 38.4);
    b.x = 0.0;  // front face at 0.125 m: 0.175 m from the wall
    w.add_body(b);
    w.states()[0].flags |= flag_released;
    w.states()[0].vx = 0.3;
    w.advance_to(1.0);
    const std::vector<Impact> impacts = w.impacts();
    ASSERT_EQ(impacts.size(), 1u);
    const Impact& i = impacts[0];
    EXPECT_EQ(i.trajectory, 0);
    EXPECT_EQ(i.building, 1);  // the only component of the mask
    EXPECT_NEAR(i.speed, 0.3, 0.003);
    EXPECT_NEAR(i.force, 0.95530, 0.0095530);  // 1 %
    EXPECT_DOUBLE_EQ(i.mass, 0.625);
    EXPECT_NEAR(i.x, 0.300, 1e-6);              // on the wall's face
    EXPECT_NEAR(i.time, 0.175 / 0.3, 0.02);     // 0.583 s
    EXPECT_DOUBLE_EQ(impact_force(2.0, 2300.0, 1.5e7), 0.65 * 2.0 * std::sqrt(1.5e7 * 2300.0));
}

// Carried into the wall by a 0.2 m/s current, the box bounces a few times (restitution
// 0.5, the current bringing it back; the impulses at its two corners also turn it, so a
// later bounce can be faster than the one before) and then rests against the wall,
// touching it at nearly every step. The resting contact is one episode: no impact
// after the bounces, while the collision steps go on.
TEST(DebrisImpacts, RestingContactIsNotCountedAsRepeatedImpacts) {
    const auto dir = test::scratch_dir("impact_resting");
    const auto path = test::uniform_flow(dir + "/flow.nc", grid, 40, 0.1, 0.2, 0.0);
    World w(path, east_wall());
    BodyDef b = default_body_def();
    b.x = 0.1;
    w.add_body(b);
    w.states()[0].flags |= flag_released;
    w.states()[0].vx = 0.2;
    w.advance_to(20.0);
    const std::vector<Impact> bounces = w.impacts();
    const long collisions_at_20 = w.stats()[0].collisions;
    w.advance_to(40.0);
    ASSERT_GE(bounces.size(), 1u);
    EXPECT_LE(bounces.size(), 8u);
    EXPECT_NEAR(bounces.front().speed, 0.2, 0.01);
    for (const Impact& i : bounces) EXPECT_LT(i.time, 10.0);  // the bounces are over within seconds
    EXPECT_EQ(w.impacts().size(), bounces.size());           // resting from 20 s to 40 s: no new impact
    EXPECT_GT(w.stats()[0].collisions - collisions_at_20, 100);  // though it touches the wall all along
}

// Components under 4-connectivity, numbered by their first cell in the row-major scan
// from the south-west; a diagonal neighbour is another building. Footprint ids given by
// the scene are kept through a file; a mask without ids gets the components on writing
// and on reading.
TEST(DebrisImpacts, ConnectedComponentIdsAreStable) {
    // y rows from the south (row 0) up; x from the west.
    const std::vector<std::int8_t> mask = {
        0, 1, 1, 0, 0,  //
        0, 0, 1, 0, 1,  //
        1, 0, 0, 1, 1,  //
        1, 0, 1, 0, 0,  //
    };
    const std::vector<std::int32_t> expected = {
        0, 1, 1, 0, 0,  //
        0, 0, 1, 0, 2,  //
        3, 0, 0, 2, 2,  //
        3, 0, 4, 0, 0,  //
    };
    EXPECT_EQ(building_components(5, 4, mask), expected);
    // The same mask shifted one cell east keeps the same numbers (they follow the scan order).
    std::vector<std::int8_t> shifted(mask.size(), 0);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i + 1 < 5; ++i) shifted[j * 5 + i + 1] = mask[j * 5 + i];
    const auto again = building_components(5, 4, shifted);
    EXPECT_EQ(again[2], 1);
    EXPECT_EQ(again[15 + 3], 4);

    const auto dir = test::scratch_dir("impact_ids");
    Scene s;
    s.grid = Grid{5, 4, 0.5, 0.5, 1.0, 1.0};
    s.z.assign(s.grid.size(), 0.0);
    s.building = mask;
    write_scene(dir + "/components.nc", s, "test");
    EXPECT_EQ(read_scene(dir + "/components.nc").building_id, expected);
    // Footprint numbers (two touching footprints stay two buildings).
    s.building_id = expected;
    for (auto& id : s.building_id) id = id == 2 ? 7 : id;
    s.building_id[0 * 5 + 2] = 5;
    write_scene(dir + "/footprints.nc", s, "test");
    EXPECT_EQ(read_scene(dir + "/footprints.nc").building_id, s.building_id);
    // Ids that disagree with the mask give way to its components.
    s.building_id[0] = 9;
    write_scene(dir + "/bad.nc", s, "test");  // written as components: the ids do not fit the mask
    EXPECT_EQ(read_scene(dir + "/bad.nc").building_id, expected);
    // A scene without buildings is written without the variable.
    Scene open;
    open.grid = s.grid;
    open.z = s.z;
    write_scene(dir + "/open.nc", open, "test");
    EXPECT_TRUE(read_scene(dir + "/open.nc").building_id.empty());
}

// A sweep whose bodies hit two buildings: the shards merge to the bytes of the whole run,
// impacts included, and the statistics of the merged file are those of the whole run.
TEST(DebrisImpacts, ImpactStatisticsOfMergedShardsAreThoseOfTheWholeRun) {
    const auto dir = test::scratch_dir("impact_shards");
    const Grid g{60, 40, 0.01, 0.01, 0.02, 0.02};  // 1.2 m × 0.8 m
    const std::string f0 = test::uniform_flow(dir + "/f0.nc", g, 12.0, 0.06, 0.15, 0.0);
    const std::string f1 = test::uniform_flow(dir + "/f1.nc", g, 12.0, 0.06, 0.12, 0.02);
    Scene scene;
    scene.grid = g;
    scene.z.assign(g.size(), -0.1);
    scene.building.assign(g.size(), 0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            if (g.x(i) > 0.8 && g.x(i) < 0.9 && std::fabs(g.y(j) - 0.4) > 0.03) scene.building[g.index(i, j)] = 1;  // two blocks
    write_scene(dir + "/scene.nc", scene, "test");
    const std::string spec = test::write_file(
        dir, "spec.toml",
        "[sweep]\noutput-interval = 0.5\nscene = \"" + dir + "/scene.nc\"\n[flows]\npaths = [\"" + f0 + "\", \"" + f1 +
            "\"]\n[[body]]\nname = \"A\"\nat = [0.35, 0.25, 0]\n[[body]]\nname = \"B\"\nat = [0.40, 0.55, 0]\n"
            "[variants]\nnames = [\"CC+SC\", \"LC+MC\"]\n[perturbation]\ncount = 2\nposition-std = 0.01\nheading-std = 5\nseed = 3\n");
    std::string out;
    ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --out " + dir + "/whole.nc --quiet --threads 1", &out), 0) << out;
    for (int i = 0; i < 3; ++i)
        ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --shard " + std::to_string(i) + "/3 --out " + dir + "/part" +
                                    std::to_string(i) + ".nc --quiet --threads 1",
                                &out),
                  0)
            << out;
    ASSERT_EQ(test::run_cli("sweep merge " + dir + "/part2.nc " + dir + "/part0.nc " + dir + "/part1.nc --out " + dir + "/merged.nc",
                            &out),
              0)
        << out;
    EXPECT_EQ(test::read_text(dir + "/whole.nc"), test::read_text(dir + "/merged.nc"));
    const std::string impacts = test::read_text(dir + "/whole_impacts.csv");
    EXPECT_EQ(impacts, test::read_text(dir + "/merged_impacts.csv"));
    EXPECT_GT(std::count(impacts.begin(), impacts.end(), '\n'), 4);  // header and impacts on both blocks
    EXPECT_NE(impacts.find(",1,"), std::string::npos);
    EXPECT_NE(impacts.find(",2,"), std::string::npos);
    for (const char* name : {"whole", "merged"})
        ASSERT_EQ(test::run_cli(std::string("stats --sweep ") + dir + "/" + name + ".nc --scene " + dir + "/scene.nc --out " + dir +
                                    "/" + name + "_stats.nc --csv " + dir + "/" + name + "_csv",
                                &out),
                  0)
            << out;
    const std::string buildings = test::read_text(dir + "/whole_csv/buildings.csv");
    EXPECT_EQ(buildings, test::read_text(dir + "/merged_csv/buildings.csv"));
    EXPECT_NE(buildings.find("all,all,1,"), std::string::npos) << buildings;

    // The footprints layer for QGIS: one polygon per building, its area that of its 2 cm
    // cells, and the statistics of the NetCDF file; the two blocks hold 5 columns × 37
    // rows (40 less the 3 rows of the opening at y = 0.4 m).
    ASSERT_EQ(test::run_cli("export --stats " + dir + "/whole_stats.nc --scene " + dir + "/scene.nc --out-dir " + dir + "/gis", &out),
              0)
        << out;
    gdal::init();
    gdal::Dataset layer_file = gdal::open_vector(dir + "/gis/buildings.gpkg");
    OGRLayer* layer = layer_file->GetLayerByName("buildings");
    ASSERT_NE(layer, nullptr);
    EXPECT_EQ(layer->GetFeatureCount(), 2);
    const nc::File st = nc::File::open_read(dir + "/whole_stats.nc");
    const std::vector<int> ids = st.get_int(st.var("building_id"));
    const std::vector<double> p_hit = st.get_double(st.var("building_hit_probability_all"));
    const std::vector<double> f90 = st.get_double(st.var("building_impact_force_p90_all"));
    int cells = 0;
    for (OGRFeature* raw; (raw = layer->GetNextFeature()) != nullptr;) {
        std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(raw, OGRFeature::DestroyFeature);
        const int id = f->GetFieldAsInteger("building_id");
        const auto k = std::size_t(std::find(ids.begin(), ids.end(), id) - ids.begin());
        ASSERT_LT(k, ids.size()) << id;
        EXPECT_DOUBLE_EQ(f->GetFieldAsDouble("hit_probability"), p_hit[k]) << id;
        EXPECT_DOUBLE_EQ(f->GetFieldAsDouble("force_p90_N"), f90[k]) << id;
        EXPECT_NEAR(f->GetFieldAsDouble("area_m2"), f->GetFieldAsInteger("cells") * 4e-4, 1e-12) << id;
        EXPECT_NEAR(f->GetGeometryRef()->toMultiPolygon()->get_Area(), f->GetFieldAsDouble("area_m2"), 1e-9) << id;
        cells += f->GetFieldAsInteger("cells");
    }
    EXPECT_EQ(cells, 5 * 37);
}
