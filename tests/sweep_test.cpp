// flotsam sweep: the parameter designs, the member list and its shards, one World per
// flow (frames read once whatever the member count), merged shards byte-identical to the
// unsharded run, and spec errors that name the file, line and key.
#include "sweep/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

#include "cases/debris_flows.hpp"
#include "common/error.hpp"
#include "common/sha256.hpp"
#include "formats/scene.hpp"
#include "sweep/members.hpp"
#include "sweep/spec_file.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::sweep;

namespace {

const Grid grid{60, 40, 0.01, 0.01, 0.02, 0.02};  // 1.2 m × 0.8 m

// Two slow steady currents, 20 s with frames every second.
std::vector<std::string> two_flows(const std::string& dir) {
    return {test::uniform_flow(dir + "/f0.nc", grid, 20.0, 0.06, 0.02, 0.0),
            test::uniform_flow(dir + "/f1.nc", grid, 20.0, 0.06, 0.015, 0.01)};
}

std::string small_spec(const std::string& dir, const std::vector<std::string>& flows) {
    return test::write_file(dir, "spec.toml",
                            "[sweep]\noutput-interval = 0.5\n"
                            "[flows]\npaths = [\"" +
                                flows[0] + "\",\n  \"" + flows[1] +
                                "\"]  # two flows\n"
                                "[[body]]\nname = \"A\"\nat = [0.35, 0.30, 0]\n"
                                "[[body]]\nname = \"B\"\nat = [0.40, 0.55, 90]\n"
                                "[variants]\nnames = [\"CC+SC\", \"LC+MC\"]\n"
                                "[parameters]\ndesign = \"one_at_a_time\"\nvary = [\"cd1\"]\n"
                                "[perturbation]\ncount = 1\nposition-std = 0.01\nheading-std = 5\nseed = 3\n");
}

}  // namespace

TEST(SweepDesign, OneAtATimeIsThePapersNineSets) {
    const auto sets = one_at_a_time(paper_control(), {0, 1, 2, 3}, 1.5);
    ASSERT_EQ(sets.size(), 9u);
    EXPECT_EQ(sets[0].label, "control");
    EXPECT_TRUE(sets[0].is_control);
    EXPECT_DOUBLE_EQ(sets[0].values[0], 0.8);
    EXPECT_DOUBLE_EQ(sets[0].values[1], 0.4);
    EXPECT_DOUBLE_EQ(sets[0].values[2], 2.0);
    EXPECT_DOUBLE_EQ(sets[0].values[3], 0.4);
    EXPECT_EQ(sets[1].label, "cd1x1.5");
    EXPECT_DOUBLE_EQ(sets[1].values[0], 1.2);
    EXPECT_EQ(sets[2].label, "cd1/1.5");
    EXPECT_DOUBLE_EQ(sets[2].values[0], 0.8 / 1.5);
    EXPECT_EQ(sets[6].label, "cm/1.5");
    EXPECT_DOUBLE_EQ(sets[6].values[2], 2.0 / 1.5);
    EXPECT_DOUBLE_EQ(sets[7].values[3], 0.6);  // mu × 1.5
    for (std::size_t k = 1; k < 9; ++k) {
        EXPECT_FALSE(sets[k].is_control);
        int changed = 0;
        for (std::size_t p = 0; p < 5; ++p) changed += sets[k].values[p] != sets[0].values[p];
        EXPECT_EQ(changed, 1) << sets[k].label;
    }
}

TEST(SweepDesign, FactorialLastParameterFastestAndFindsTheControl) {
    std::vector<std::vector<double>> levels(5);
    levels[0] = {0.6, 0.8};
    levels[2] = {1.5, 2.0, 3.0};
    const auto sets = factorial(paper_control(), levels);
    ASSERT_EQ(sets.size(), 6u);
    EXPECT_DOUBLE_EQ(sets[0].values[0], 0.6);
    EXPECT_DOUBLE_EQ(sets[0].values[2], 1.5);
    EXPECT_DOUBLE_EQ(sets[1].values[2], 2.0);
    EXPECT_DOUBLE_EQ(sets[3].values[0], 0.8);
    EXPECT_DOUBLE_EQ(sets[3].values[2], 1.5);
    int controls = 0;
    for (const auto& s : sets) controls += s.is_control;
    EXPECT_EQ(controls, 1);
    EXPECT_TRUE(sets[4].is_control);  // (0.8, 2.0)
    EXPECT_EQ(sets[5].label, "grid05");
}

TEST(SweepDesign, LatinHypercubeUsesEveryStratumOnceAndIsSeeded) {
    const ParamRanges ranges{{0.5, 1.2}, {0.2, 0.6}, {1.5, 3.0}, {0.2, 0.6}, {0.5, 0.5}};
    const int n = 20;
    const auto a = latin_hypercube(ranges, n, 7), b = latin_hypercube(ranges, n, 7), c = latin_hypercube(ranges, n, 8);
    ASSERT_EQ(a.size(), std::size_t(n));
    for (std::size_t p = 0; p < 4; ++p) {
        std::set<int> strata;
        for (const auto& s : a) {
            const double u = (s.values[p] - ranges[p][0]) / (ranges[p][1] - ranges[p][0]);
            EXPECT_GE(u, 0.0);
            EXPECT_LT(u, 1.0);
            strata.insert(int(std::floor(u * n)));
        }
        EXPECT_EQ(strata.size(), std::size_t(n)) << "parameter " << p;
    }
    for (const auto& s : a) EXPECT_EQ(s.values[4], 0.5);  // a zero-width range is fixed
    bool differs = false;
    for (int k = 0; k < n; ++k) {
        EXPECT_EQ(a[std::size_t(k)].values, b[std::size_t(k)].values);
        differs |= a[std::size_t(k)].values != c[std::size_t(k)].values;
    }
    EXPECT_TRUE(differs);
    // Plain random samples stay in range and are reproducible too.
    const auto r1 = random_samples(ranges, 50, 3), r2 = random_samples(ranges, 50, 3);
    for (std::size_t k = 0; k < r1.size(); ++k) {
        EXPECT_EQ(r1[k].values, r2[k].values);
        for (std::size_t p = 0; p < 5; ++p) {
            EXPECT_GE(r1[k].values[p], ranges[p][0]);
            EXPECT_LE(r1[k].values[p], ranges[p][1]);
        }
    }
}

TEST(SweepDesign, ShardsCoverTheMembersOnceInOrder) {
    for (int members : {1, 7, 360})
        for (int n : {1, 2, 3, 8}) {
            int next = 0;
            for (int i = 0; i < n; ++i) {
                const auto r = shard_range(members, {i, n});
                EXPECT_EQ(r[0], next);
                EXPECT_LE(r[1] - r[0], members / n + 1);
                EXPECT_GE(r[1] - r[0], members / n);
                next = r[1];
            }
            EXPECT_EQ(next, members);
        }
    EXPECT_NE(test::error_of([] { parse_shard("3/3"); }).find("--shard"), std::string::npos);
    EXPECT_NE(test::error_of([] { parse_shard("1-3"); }).find("i/n"), std::string::npos);
}

TEST(SweepSpec, MembersPerturbationsAndVariantsFromTheFile) {
    const auto dir = test::scratch_dir("sweep_spec");
    const auto flows = two_flows(dir);
    const SweepSpec spec = read_sweep_spec(small_spec(dir, flows));
    ASSERT_EQ(spec.flows.size(), 2u);
    ASSERT_EQ(spec.params.size(), 3u);
    ASSERT_EQ(spec.variants.size(), 2u);
    EXPECT_EQ(spec.variants[0].contact, debris::ContactModel::center);
    EXPECT_EQ(spec.variants[0].collision, debris::CollisionModel::single);
    EXPECT_EQ(spec.variants[1].contact, debris::ContactModel::local);
    const auto members = enumerate_members(spec);
    ASSERT_EQ(members.size(), 2u * 2u * 2u * 2u * 3u);
    // Flow outermost, parameter set fastest.
    EXPECT_EQ(members[0].flow, 0);
    EXPECT_EQ(members[24].flow, 1);
    EXPECT_EQ(members[1].param_set, 1);
    EXPECT_EQ(members[3].variant, 1);
    EXPECT_EQ(members[6].perturbation, 1);
    EXPECT_EQ(members[12].body, 1);
    EXPECT_DOUBLE_EQ(members[1].def.cd1, 1.2);
    EXPECT_EQ(members[3].def.contact, debris::ContactModel::local);
    // Perturbation 0 is the exact start; k > 0 is the same offset on every flow and set.
    EXPECT_DOUBLE_EQ(members[0].def.x, 0.35);
    EXPECT_DOUBLE_EQ(members[12].def.heading, 90 * M_PI / 180);
    EXPECT_NE(members[6].def.x, 0.35);
    EXPECT_EQ(members[6].def.x, members[30].def.x);
    EXPECT_EQ(members[6].def.heading, members[11].def.heading);

    // The offsets are Gaussian with the given spreads: over many starts the sample
    // standard deviations come out within 10 %.
    SweepSpec many = spec;
    many.perturbation.count = 2000;
    double sx = 0, sh = 0;
    for (int k = 1; k <= 2000; ++k) {
        const auto s = perturbed_start(many, 0, k);
        sx += (s[0] - 0.35) * (s[0] - 0.35);
        sh += (s[2] * 180 / M_PI) * (s[2] * 180 / M_PI);
    }
    EXPECT_NEAR(std::sqrt(sx / 2000), 0.01, 0.001);
    EXPECT_NEAR(std::sqrt(sh / 2000), 5.0, 0.5);
}

TEST(SweepSpec, PatternListsFlowsSortedAndSampledDesignsAddTheControl) {
    const auto dir = test::scratch_dir("sweep_pattern");
    two_flows(dir);
    const std::string path =
        test::write_file(dir, "p.toml",
                         "[flows]\npattern = \"" + dir +
                             "/f*.nc\"\n[[body]]\nat = [0.3, 0.3, 0]\n"
                             "[parameters]\ndesign = \"latin_hypercube\"\nsamples = 4\nseed = 2\ncm = [1.5, 3.0]\nmu = 0.3\n");
    const SweepSpec spec = read_sweep_spec(path);
    ASSERT_EQ(spec.flows.size(), 2u);
    EXPECT_EQ(spec.flows[0], dir + "/f0.nc");
    EXPECT_EQ(spec.flows[1], dir + "/f1.nc");
    ASSERT_EQ(spec.params.size(), 5u);
    EXPECT_TRUE(spec.params[0].is_control);
    EXPECT_DOUBLE_EQ(spec.params[0].values[2], 2.0);  // the paper's Cm
    EXPECT_DOUBLE_EQ(spec.params[0].values[3], 0.3);  // a scalar sets the control and fixed value
    for (std::size_t k = 1; k < 5; ++k) {
        EXPECT_EQ(spec.params[k].label, "lhs0" + std::to_string(k - 1));
        EXPECT_DOUBLE_EQ(spec.params[k].values[3], 0.3);
        EXPECT_DOUBLE_EQ(spec.params[k].values[0], 0.8);
        EXPECT_GE(spec.params[k].values[2], 1.5);
        EXPECT_LT(spec.params[k].values[2], 3.0);
    }
}

// Reads sweep/examples/<name>.toml over a flat test scene with these points and `flows`.
SweepSpec read_example_spec(const std::string& name, const std::string& dir, const std::vector<std::string>& flows,
                            const std::vector<ScenePoint>& points) {
    Scene scene;
    scene.grid = grid;
    scene.z.assign(grid.size(), -0.1);
    scene.points = points;
    write_scene(dir + "/scene.nc", scene, "test");
    return read_sweep_spec(std::string(FLOTSAM_SOURCE_DIR) + "/sweep/examples/" + name + ".toml", dir + "/scene.nc", flows);
}

// The real-scale demo's spec reads with today's keys (it once kept the old snake_case
// spelling, which only the demo's sweep, minutes into the run, found).
TEST(SweepSpec, FullScaleExampleReads) {
    const auto dir = test::scratch_dir("sweep_full_scale_example");
    const auto flows = two_flows(dir);
    const SweepSpec spec = read_example_spec("kainan_full_scale", dir, flows,
                                             {{"FD", "start", 0.3, 0.3, 0.0}, {"LD", "start", 0.6, 0.5, 90.0}});
    ASSERT_EQ(spec.bodies.size(), 2u);  // and the port's layers, expanded when the sweep runs
    ASSERT_EQ(spec.sources.size(), 1u);
    EXPECT_EQ(spec.sources[0].file, "runs/kainan-full/port_layers.gpkg");
    EXPECT_TRUE(spec.sources[0].layers.empty());
    EXPECT_EQ(spec.perturbation.count, 4);
    EXPECT_DOUBLE_EQ(spec.perturbation.position_std, 5.0);
    EXPECT_DOUBLE_EQ(spec.end_time, 6640.0);
}

// The shipped example is the paper's sweep: FD and LD, both variants, nine sets.
TEST(SweepSpec, ExampleSpecIsThePapersSweep) {
    const auto dir = test::scratch_dir("sweep_example");
    const auto flows = two_flows(dir);
    const SweepSpec spec =
        read_example_spec("paper_sensitivity", dir, flows,
                          {{"FD", "start", 0.3, 0.3, 0.0}, {"LD", "start", 0.6, 0.5, 90.0}, {"WG2", "gauge", 0.1, 0.1, 0.0}});
    ASSERT_EQ(spec.bodies.size(), 2u);
    EXPECT_EQ(spec.bodies[1].name, "LD");
    EXPECT_DOUBLE_EQ(spec.bodies[1].x, 0.6);
    EXPECT_DOUBLE_EQ(spec.bodies[1].heading_deg, 90.0);
    ASSERT_EQ(spec.variants.size(), 2u);
    EXPECT_EQ(spec.variants[0].name, "CC+SC");
    EXPECT_EQ(spec.params.size(), 9u);
    EXPECT_EQ(spec.perturbation.count, 0);
    EXPECT_DOUBLE_EQ(spec.end_time, 420.0);
    EXPECT_EQ(enumerate_members(spec).size(), 2u * 2u * 2u * 9u);
}

// The drag factor cd multiplies cd1 and cd2 together (the paper's "Cd"): the set cdx1.5
// runs a body with Cd1 = 0.8 × 1.5 = 1.2 and Cd2 = 0.4 × 1.5 = 0.6, all else the control.
TEST(SweepDesign, DragFactorScalesBothDragCoefficients) {
    const std::size_t cd = design_parameters().size() - 1;
    ASSERT_EQ(design_parameters()[cd].key, "cd");
    const auto sets = one_at_a_time(paper_control(), {int(cd)}, 1.5);
    ASSERT_EQ(sets.size(), 3u);
    EXPECT_EQ(sets[1].label, "cdx1.5");
    EXPECT_EQ(sets[2].label, "cd/1.5");
    debris::BodyDef up, down;
    apply_parameters(sets[1].values, up);
    apply_parameters(sets[2].values, down);
    EXPECT_DOUBLE_EQ(up.cd1, 1.2);
    EXPECT_DOUBLE_EQ(up.cd2, 0.6);
    EXPECT_DOUBLE_EQ(down.cd1, 0.8 / 1.5);
    EXPECT_DOUBLE_EQ(down.cd2, 0.4 / 1.5);
    EXPECT_DOUBLE_EQ(up.cm, 2.0);
    EXPECT_DOUBLE_EQ(up.mu, 0.4);
}

// The paper's own design: control, then Cd, Cm, Fc × 1.5 and / 1.5 (7 sets).
TEST(SweepSpec, PaperDesignSpecHasSevenSets) {
    const auto dir = test::scratch_dir("sweep_example7");
    const auto flows = two_flows(dir);
    const SweepSpec spec =
        read_example_spec("paper_sensitivity_7", dir, flows, {{"FD", "start", 0.3, 0.3, 0.0}, {"LD", "start", 0.6, 0.5, 90.0}});
    ASSERT_EQ(spec.params.size(), 7u);
    const std::vector<std::string> labels = {"control", "cdx1.5", "cd/1.5", "cmx1.5", "cm/1.5", "mux1.5", "mu/1.5"};
    for (std::size_t k = 0; k < 7; ++k) EXPECT_EQ(spec.params[k].label, labels[k]);
    const auto members = enumerate_members(spec);
    ASSERT_EQ(members.size(), 2u * 2u * 2u * 7u);
    EXPECT_DOUBLE_EQ(members[1].def.cd1, 1.2);  // FD, CC+SC, cdx1.5
    EXPECT_DOUBLE_EQ(members[1].def.cd2, 0.6);
    EXPECT_DOUBLE_EQ(members[4].def.cm, 2.0 / 1.5);
    EXPECT_DOUBLE_EQ(members[4].def.cd1, 0.8);
    EXPECT_DOUBLE_EQ(members[5].def.mu, 0.6);
    EXPECT_TRUE(spec.dt_max_given);  // the step the scene needs (docs/sweep.md, "The step")
    EXPECT_DOUBLE_EQ(spec.world.step.dt_max, 0.02);
}

TEST(SweepSpec, ErrorsNameTheFileLineAndKey) {
    const auto dir = test::scratch_dir("sweep_errors");
    const auto flows = two_flows(dir);
    const std::string head = "[flows]\npaths = [\"" + flows[0] + "\"]\n";
    auto err = [&](const std::string& name, const std::string& body) {
        const std::string path = test::write_file(dir, name, body);
        return test::error_of([&] { read_sweep_spec(path); });
    };
    const std::string at = "[[body]]\nat = [0.3, 0.3, 0]\n";
    struct Case {
        std::string file, text;
        std::vector<std::string> says;  // parts of the message
    };
    const std::vector<Case> cases = {
        {"a.toml", head + at + "[parameters]\ndesign = \"one_at_a_time\"\nspeed = 2\n", {"a.toml: line 7", "'speed'"}},
        {"b.toml", head + at + "[variants]\nnames = [\"LC+MC\", \"XC+SC\"]\n", {"b.toml: line 6", "names", "XC+SC"}},
        {"c.toml", head + "[[body]]\nstart = \"FD\"\n", {"c.toml: line 4", "needs a scene"}},
        {"d.toml", head + at + "[parameters]\ndesign = \"random\"\nsamples = 4\ncd1 = [1.2, 0.5]\n", {"d.toml: line 8", "'cd1'"}},
        {"e.toml", "[flows]\npaths = [\"" + dir + "/missing.nc\"]\n" + at, {"e.toml: line 2", "missing.nc"}},
        {"f.toml", head + at + "[parameters]\ndesign = \"one_at_a_time\"\nmu = -0.4\n", {"f.toml: line 7", "mu"}},
        {"g.toml", head + at + "[bodies]\n", {"g.toml: line 5", "[bodies]"}},
    };
    for (const Case& c : cases) {
        const std::string e = err(c.file, c.text);
        for (const std::string& part : c.says) EXPECT_NE(e.find(part), std::string::npos) << part << " not in: " << e;
    }
}

// Every member of a flow advances in one World: the frames read are those of one
// replay per flow, the same for one member as for 24.
TEST(SweepRun, FramesReadOncePerFlowWhateverTheMemberCount) {
    const auto dir = test::scratch_dir("sweep_frames");
    const auto flows = two_flows(dir);
    const SweepSpec spec = read_sweep_spec(small_spec(dir, flows));
    SweepSpec one = spec;
    one.bodies.resize(1);
    one.variants.resize(1);
    one.params.resize(1);
    one.perturbation.count = 0;
    SweepRunDef def;
    def.quiet = true;
    SweepRunStats all_stats, one_stats;
    const SweepResult all = run_sweep(spec, def, &all_stats);
    run_sweep(one, def, &one_stats);
    EXPECT_EQ(all_stats.members, 48);
    EXPECT_EQ(one_stats.members, 2);
    EXPECT_EQ(all_stats.flows_opened, 2u);
    EXPECT_EQ(all_stats.frames_loaded, one_stats.frames_loaded);
    EXPECT_EQ(all_stats.frames_loaded, 2u * 21u);  // each of the 21 frames of each flow once
    ASSERT_EQ(all.time.size(), 41u);               // 0, 0.5, ..., 20 s
    EXPECT_DOUBLE_EQ(all.time.back(), 20.0);
    // The bodies drift with the current (afloat: depth 6 cm, draft 2.5 cm), never faster.
    const auto& t = all.members[0].track;
    EXPECT_GT(t.x.back() - t.x.front(), 0.05);
    EXPECT_LT(t.x.back() - t.x.front(), 0.02 * 20 + 1e-6);
}

TEST(SweepRun, MergedShardsGiveTheBytesOfTheWholeRun) {
    const auto dir = test::scratch_dir("sweep_shards");
    const auto flows = two_flows(dir);
    const std::string spec = small_spec(dir, flows);
    std::string out;
    ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --out " + dir + "/whole.nc --quiet --threads 2", &out), 0) << out;
    for (int i = 0; i < 3; ++i)
        ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --shard " + std::to_string(i) + "/3 --out " + dir + "/part" +
                                    std::to_string(i) + ".nc --quiet --threads 1",
                                &out),
                  0)
            << out;
    // Parts in any order.
    ASSERT_EQ(test::run_cli(
                  "sweep merge " + dir + "/part2.nc " + dir + "/part0.nc " + dir + "/part1.nc --out " + dir + "/merged.nc", &out),
              0)
        << out;
    EXPECT_EQ(sha256_file(dir + "/merged.nc"), sha256_file(dir + "/whole.nc"));
    EXPECT_EQ(sha256_file(dir + "/merged.csv"), sha256_file(dir + "/whole.csv"));

    const SweepResult whole = read_sweep_file(dir + "/whole.nc");
    const SweepResult part = read_sweep_file(dir + "/part1.nc");
    EXPECT_EQ(whole.members.size(), 48u);
    EXPECT_EQ(part.members.size(), 16u);
    EXPECT_EQ(part.members.front().id, 16);
    EXPECT_EQ(part.shard.index, 1);
    EXPECT_EQ(whole.members[17].track.x, part.members[1].track.x);

    // A missing or repeated part is refused, naming the member.
    EXPECT_NE(test::run_cli("sweep merge " + dir + "/part0.nc " + dir + "/part1.nc --out " + dir + "/bad.nc", &out), 0);
    EXPECT_NE(out.find("member 32"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("sweep merge " + dir + "/part0.nc " + dir + "/part0.nc --out " + dir + "/bad.nc", &out), 0);
    EXPECT_NE(out.find("also in another part"), std::string::npos) << out;

    // The summary has one row per trajectory.
    std::ifstream csv(dir + "/whole.csv");
    int rows = 0;
    for (std::string line; std::getline(csv, line);) ++rows;
    EXPECT_EQ(rows, 49);
}

// Every shard records the scene's building fingerprint, also a shard whose members are
// all on a later flow (the third of three: members 32-47 are on flow 1), so that the
// shards of a sweep over a scene merge.
TEST(SweepRun, ShardsOverASceneMergeWhateverFlowsTheirMembersAreOn) {
    const auto dir = test::scratch_dir("sweep_shards_scene");
    const auto flows = two_flows(dir);
    const std::string spec = small_spec(dir, flows);
    Scene scene;
    scene.grid = grid;
    scene.z.assign(grid.size(), -0.1);
    write_scene(dir + "/scene.nc", scene, "test");
    std::string out;
    for (int i = 0; i < 3; ++i)
        ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --scene " + dir + "/scene.nc --shard " + std::to_string(i) +
                                    "/3 --out " + dir + "/part" + std::to_string(i) + ".nc --quiet --threads 1",
                                &out),
                  0)
            << out;
    const SweepResult last = read_sweep_file(dir + "/part2.nc");
    ASSERT_FALSE(last.members.empty());
    EXPECT_EQ(last.members.front().flow, 1);
    EXPECT_EQ(last.scene_buildings_sha256, scene_buildings_sha256(scene));
    EXPECT_EQ(test::run_cli("sweep merge " + dir + "/part0.nc " + dir + "/part1.nc " + dir + "/part2.nc --out " + dir +
                                "/merged.nc",
                            &out),
              0)
        << out;
}

// A ground finer than the flows (--ground, or [sweep] ground): the sweep file names it,
// and shards run with different grounds are not one sweep.
TEST(SweepRun, GroundIsRecordedAndShardsMustShareIt) {
    const auto dir = test::scratch_dir("sweep_ground");
    const auto flows = two_flows(dir);
    const std::string spec = small_spec(dir, flows);
    Scene ground;
    ground.grid = Grid{120, 80, 0.005, 0.005, 0.01, 0.01};  // the flows' area at half their cells
    ground.z.assign(ground.grid.size(), -0.1);
    write_scene(dir + "/ground.nc", ground, "test");
    std::string out;
    ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --ground " + dir + "/ground.nc --shard 0/2 --out " + dir +
                                "/part0.nc --quiet --threads 1",
                            &out),
              0)
        << out;
    ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --shard 1/2 --out " + dir + "/part1.nc --quiet --threads 1", &out), 0)
        << out;
    EXPECT_EQ(read_sweep_file(dir + "/part0.nc").ground_file, dir + "/ground.nc");
    EXPECT_EQ(read_sweep_file(dir + "/part1.nc").ground_file, "");
    EXPECT_NE(test::run_cli("sweep merge " + dir + "/part0.nc " + dir + "/part1.nc --out " + dir + "/bad.nc", &out), 0);
    EXPECT_NE(out.find("not shards of one sweep"), std::string::npos) << out;
    // The same from the spec's [sweep] table.
    const std::string with_key = test::write_file(dir, "g.toml",
                                                  "[sweep]\nground = \"" + dir + "/ground.nc\"\n[flows]\npaths = [\"" + flows[0] +
                                                      "\"]\n[[body]]\nname = \"A\"\nat = [0.35, 0.30, 0]\n");
    EXPECT_EQ(read_sweep_spec(with_key).ground, dir + "/ground.nc");
}
