// The debris catalogue: every entry is a valid body whose mass and draft follow from its
// numbers; names are found by flotsam debris --body and by sweep specs ([[body]] type),
// where a parameter set scales the entry's own coefficients; unknown names are errors
// that list the known ones.
#include "debris/catalogue.hpp"

#include <gtest/gtest.h>

#include <set>

#include "debris/body.hpp"
#include "sweep/members.hpp"
#include "sweep/spec_file.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using test::error_of;
using test::write_file;

TEST(Catalogue, EntriesAreValidBodiesWithTheirMassAndDraft) {
    std::set<std::string> names;
    for (const auto& c : debris::catalogue()) {
        EXPECT_TRUE(names.insert(c.name).second) << c.name;
        EXPECT_FALSE(c.source.empty()) << c.name;
        const debris::BodyParams p = debris::make_body_params(debris::catalogue_body_def(c.name, "test"), 1000.0);
        EXPECT_NEAR(p.mass, c.mass, 1e-9 * c.mass) << c.name;
        EXPECT_NEAR(p.draft, c.mass / (1000.0 * c.length * c.width), 1e-12) << c.name;
        EXPECT_LT(p.draft, c.height) << c.name;  // it floats
    }
    // Hand-computed: the paper's box, s.g. 0.25 and a 2.5 cm draft; an empty 40 ft
    // container, 3750 kg over 12.192 x 2.438 m: 0.1262 m; its x250 twin, 6.25 m.
    const auto box = debris::make_body_params(debris::catalogue_body_def("paper_box", "test"), 1000.0);
    EXPECT_NEAR(box.def.specific_gravity, 0.25, 1e-15);
    EXPECT_NEAR(box.draft, 0.025, 1e-15);
    EXPECT_NEAR(debris::make_body_params(debris::catalogue_body_def("container_40ft", "test"), 1000.0).draft, 0.12616, 1e-5);
    EXPECT_NEAR(debris::make_body_params(debris::catalogue_body_def("paper_box_full_scale", "test"), 1000.0).draft, 6.25, 1e-12);
    const std::string e = error_of([] { debris::catalogue_body_def("container_45ft", "--body"); });
    EXPECT_NE(e.find("--body"), std::string::npos) << e;
    EXPECT_NE(e.find("container_45ft"), std::string::npos) << e;
    EXPECT_NE(e.find("container_40ft"), std::string::npos) << e;  // the known names
}

TEST(Catalogue, SweepSpecBodyTypeKeepsItsOwnCoefficientsScaledBySets) {
    const std::string dir = test::scratch_dir("catalogue_spec");
    const std::string flow = write_file(dir, "flow.nc", "not read");
    const std::string spec = write_file(dir, "spec.toml",
                                        "[[body]]\nat = [1, 2, 0]\ntype = \"car\"\n[[body]]\nat = [1, 2, 0]\nname = \"box\"\n"
                                        "[parameters]\ndesign = \"one_at_a_time\"\nvary = [\"cd1\", \"mu\"]\nfactor = 2\n");
    const sweep::SweepSpec s = sweep::read_sweep_spec(spec, "", {flow});
    EXPECT_EQ(s.bodies[0].type, "car");
    EXPECT_DOUBLE_EQ(s.bodies[0].def.length, 4.5);
    const auto members = sweep::enumerate_members(s);
    for (const auto& m : members) {
        const std::string& label = s.params[std::size_t(m.param_set)].label;
        if (m.body == 0) {  // the car: its own mu 0.5, cd1 0.8, scaled by the set's ratio to the control
            EXPECT_DOUBLE_EQ(m.def.mu, label == "mux2" ? 1.0 : label == "mu/2" ? 0.25 : 0.5) << label;
            EXPECT_DOUBLE_EQ(m.def.cd1, label == "cd1x2" ? 1.6 : label == "cd1/2" ? 0.4 : 0.8) << label;
            EXPECT_DOUBLE_EQ(m.def.length, 4.5);
        } else {  // no type: the set's values as they are, the paper's box
            EXPECT_DOUBLE_EQ(m.def.mu, s.params[std::size_t(m.param_set)].values[3]) << label;
            EXPECT_DOUBLE_EQ(m.def.length, 0.25);
        }
    }
    const std::string bad = write_file(dir, "bad.toml", "[[body]]\nat = [1, 2, 0]\ntype = \"bus\"\n");
    const std::string e = error_of([&] { sweep::read_sweep_spec(bad, "", {flow}); });
    EXPECT_NE(e.find("bad.toml"), std::string::npos) << e;
    EXPECT_NE(e.find("type"), std::string::npos) << e;
    EXPECT_NE(e.find("'bus'"), std::string::npos) << e;
}

TEST(Catalogue, DebrisCommandListsTheCatalogue) {
    std::string out;
    ASSERT_EQ(test::run_cli("debris --list-bodies", &out), 0) << out;
    for (const auto& c : debris::catalogue()) EXPECT_NE(out.find(c.name), std::string::npos) << c.name;
    EXPECT_NE(test::run_cli("debris --flow /nonexistent.nc --at 0,0,0 --body bus", &out), 0);
}
