// One definition per setting (common/settings.hpp): the tables that drive the options of
// `flotsam debris`, the keys of sweep specs and `--config` files, and the variables of the
// files; and the one TOML dialect (kebab-case keys) with its message for old keys.
#include "common/settings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "cases/debris_flows.hpp"
#include "common/netcdf.hpp"
#include "debris/body.hpp"
#include "debris/world.hpp"
#include "hydro/run_settings.hpp"
#include "sweep/members.hpp"
#include "sweep/spec_file.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;

namespace {

const Grid grid{40, 40, 0.0125, 0.0125, 0.025, 0.025};

template <class Def>
void expect_sound(const Settings<Def>& table, std::set<std::string>& keys) {
    static const Def defaults{};
    for (const auto& s : table) {
        EXPECT_TRUE(keys.insert(s.key).second) << "key used twice: " << s.key;
        EXPECT_EQ(s.key.find('_'), std::string::npos) << s.key << ": keys are kebab-case";
        EXPECT_FALSE(s.help.empty()) << s.key;
        if (s.is_number() && !s.is_factor() && !s.form.no_default) {
            EXPECT_EQ(range_problem(s.number(defaults), s.range), "") << s.key << ": default";
        }
    }
}

}  // namespace

// Every key is kebab-case and used once; every numeric default lies in its own range.
TEST(Settings, TablesAreSoundAndDefaultsInRange) {
    std::set<std::string> keys;
    expect_sound(debris::body_shape_settings(), keys);
    expect_sound(debris::body_coefficient_settings(), keys);
    expect_sound(debris::body_model_settings(), keys);
    expect_sound(debris::body_variant_settings(), keys);
    expect_sound(debris::step_settings(), keys);
    expect_sound(debris::flow_replay_settings(), keys);
    const auto* sg = find_setting(debris::body_shape_settings(), "specific-gravity");
    ASSERT_NE(sg, nullptr);
    EXPECT_EQ(sg->variable(), "specific_gravity");
    EXPECT_NE(range_problem(1.0, sg->range), "");  // a body that does not float
    // The design parameters are the body's coefficients and the drag factor; the control is
    // BodyDef's defaults and a factor of 1.
    EXPECT_EQ(sweep::paper_control(), (sweep::ParamValues{0.8, 0.4, 2.0, 0.4, 0.5, 1.0}));
}

// Every setting of the tables is an option of `flotsam debris`, shown with its default.
TEST(Settings, EveryTableSettingIsAnOptionOfFlotsamDebris) {
    std::string help;
    ASSERT_EQ(test::run_cli("debris --help", &help), 0) << help;
    for (const auto* table : {&debris::body_shape_settings(), &debris::body_coefficient_settings(), &debris::body_model_settings(),
                              &debris::body_variant_settings()})
        for (const auto& s : *table) EXPECT_NE(help.find("--" + s.key), std::string::npos) << s.key;
    for (const auto& s : debris::step_settings()) EXPECT_NE(help.find("--" + s.key), std::string::npos) << s.key;
    EXPECT_NE(help.find("--time-interpolation"), std::string::npos);
    EXPECT_NE(help.find("--cm FLOAT:[1, 100]=2"), std::string::npos) << help;
}

// The hydro table is sound too, each of its settings is an option of `flotsam hydro`, and
// the recorded settings (settings_toml) name every one but those left out, the study
// options last, as their --help section.
TEST(Settings, EveryHydroTableSettingIsAnOptionOfFlotsamHydro) {
    std::set<std::string> keys;
    expect_sound(hydro::hydro_settings(), keys);
    std::string help;
    ASSERT_EQ(test::run_cli("hydro --help", &help), 0) << help;
    for (const auto& s : hydro::hydro_settings())
        EXPECT_TRUE(help.find("--" + s.key + " ") != std::string::npos || help.find("--" + s.key + "\n") != std::string::npos)
            << s.key;
    EXPECT_NE(help.find("--nest-ratio INT:whole numbers in [1, 16]=[1] ..."), std::string::npos) << help;
    const std::string toml = settings_toml(hydro::hydro_settings(), hydro::HydroDef{}, {"out", "label"});
    EXPECT_EQ(toml.find("out="), std::string::npos);
    EXPECT_NE(toml.find("\nnest-ratio=1\nnest-x=-2\n"), std::string::npos) << toml;
    EXPECT_NE(toml.find("\nlevel-mode=\"\"\nwest-level-mode=\"total\"\n"), std::string::npos) << toml;
    EXPECT_LT(toml.find("pump-length="), toml.find("friction="));
}

// A --config file is TOML with the option names as keys: a number, a choice, a list, a
// flag; the command line wins; out of range and old snake_case keys are errors that name
// the file and the key.
TEST(Settings, ConfigFileSetsDebrisOptionsAndTheCommandLineWins) {
    const auto dir = test::scratch_dir("settings_config");
    const std::string flow = test::uniform_flow(dir + "/f.nc", grid, 2.0, 0.06, 0.02, 0.0);
    const std::string cfg = test::write_file(dir, "d.toml",
                                             "# shared by several commands\n[hydro]\nduration = 10\n\n[debris]\n"
                                             "at = [\"0.3,0.3,0\", \"0.6,0.6,90\"]\ncd1 = 0.9\ncontact = 'center'\n"
                                             "quiet = true\nend-time = 1\n");
    std::string out;
    ASSERT_EQ(test::run_cli("debris --config " + cfg + " --flow " + flow + " --cd2 0.3 --out " + dir + "/t.nc", &out), 0) << out;
    EXPECT_EQ(out.find("debris done"), std::string::npos) << "quiet = true was not applied: " << out;
    const nc::File f = nc::File::open_read(dir + "/t.nc");
    EXPECT_EQ(f.get_double(f.var("cd1")), (std::vector<double>{0.9, 0.9}));
    EXPECT_EQ(f.get_double(f.var("cd2")), (std::vector<double>{0.3, 0.3}));
    EXPECT_EQ(f.get_strings(f.var("contact_model"))[1], "center");
    ASSERT_EQ(test::run_cli("debris --config " + cfg + " --flow " + flow + " --cd1 1.1 --out " + dir + "/u.nc", &out), 0) << out;
    EXPECT_EQ(nc::File::open_read(dir + "/u.nc").get_double(nc::File::open_read(dir + "/u.nc").var("cd1"))[0], 1.1);

    const std::string old = test::write_file(dir, "old.toml", "[debris]\nend_time = 1\n");
    EXPECT_NE(test::run_cli("debris --config " + old + " --flow " + flow + " --at 0.3,0.3,0 --out " + dir + "/v.nc", &out), 0);
    EXPECT_NE(out.find("old.toml: line 2"), std::string::npos) << out;
    EXPECT_NE(out.find("write 'end-time'"), std::string::npos) << out;
    const std::string bad = test::write_file(dir, "bad.toml", "cm = 0.5\n");
    EXPECT_NE(test::run_cli("debris --config " + bad + " --flow " + flow + " --at 0.3,0.3,0 --out " + dir + "/v.nc", &out), 0);
    EXPECT_NE(out.find("0.5 is outside the allowed range [1, 100]"), std::string::npos) << out;
    EXPECT_FALSE(std::filesystem::exists(dir + "/v.nc"));
}

// Every `flotsam debris` setting can be given to a sweep: the step and flow replay in
// [sweep], the body model in [sweep] (every body) and [[body]] (that body), the shape in
// [[body]]; old snake_case keys name their new spelling.
TEST(Settings, EveryDebrisSettingIsAvailableToASweep) {
    const auto dir = test::scratch_dir("settings_sweep");
    const std::string flow = test::uniform_flow(dir + "/f.nc", grid, 2.0, 0.06, 0.02, 0.0);
    const std::string head = "[flows]\npaths = [\"" + flow + "\"]\n";
    const std::string path = test::write_file(
        dir, "s.toml",
        head +
            "[sweep]\ndt-max = 0.005\nvertex-step-fraction = 0.2\nintegrator = \"heun\"\ntime-interpolation = \"cubic\"\n"
            "added-mass = \"explicit\"\naxis-shift = false\nsamples-per-face = 2\n"
            "[[body]]\nat = [0.3, 0.3, 0]\nstep-tolerance = 0.3\nspecific-gravity = 0.5\n"
            "[[body]]\nat = [0.6, 0.6, 0]\nsamples-per-face = 6\n");
    const sweep::SweepSpec spec = sweep::read_sweep_spec(path);
    EXPECT_EQ(spec.world.step.dt_max, 0.005);
    EXPECT_EQ(spec.world.step.vertex_step_fraction, 0.2);
    EXPECT_EQ(spec.world.step.integrator, debris::Integrator::heun);
    EXPECT_EQ(spec.world.flow.time_interpolation, debris::TimeInterpolation::cubic);
    const auto members = sweep::enumerate_members(spec);
    ASSERT_EQ(members.size(), 2u);
    const debris::BodyDef &a = members[0].def, &b = members[1].def;
    EXPECT_EQ(a.added_mass, debris::AddedMass::explicit_);
    EXPECT_FALSE(a.axis_shift);
    EXPECT_EQ(a.samples_per_face, 2);
    EXPECT_EQ(a.step_tolerance, 0.3);
    EXPECT_EQ(a.specific_gravity, 0.5);
    EXPECT_EQ(b.samples_per_face, 6);  // [[body]] over [sweep]
    EXPECT_EQ(b.added_mass, debris::AddedMass::explicit_);
    EXPECT_EQ(b.step_tolerance, debris::BodyDef{}.step_tolerance);

    const std::string e = test::error_of([&] {
        sweep::read_sweep_spec(test::write_file(
            dir, "old.toml", head + "[sweep]\noutput_interval = 0.5\ndt_max = 0.01\n[[body]]\nat = [0.3, 0.3, 0]\n"));
    });
    EXPECT_NE(e.find("old.toml: line 4"), std::string::npos) << e;
    EXPECT_NE(e.find("'output_interval', 'dt_max'"), std::string::npos) << e;
    EXPECT_NE(e.find("write 'output-interval', 'dt-max'"), std::string::npos) << e;
    const std::string r = test::error_of([&] {
        sweep::read_sweep_spec(test::write_file(dir, "range.toml", head + "[[body]]\nat = [0.3, 0.3, 0]\nsamples-per-face = 20\n"));
    });
    EXPECT_NE(r.find("range.toml: line 5"), std::string::npos) << r;
    EXPECT_NE(r.find("whole numbers in [1, 16]"), std::string::npos) << r;
    const std::string c = test::error_of([&] {
        sweep::read_sweep_spec(
            test::write_file(dir, "choice.toml", head + "[sweep]\nintegrator = \"rk4\"\n[[body]]\nat = [0.3, 0.3, 0]\n"));
    });
    EXPECT_NE(c.find("choice.toml: line 4"), std::string::npos) << c;
    EXPECT_NE(c.find("'rk4' (euler, heun)"), std::string::npos) << c;
}
