// The statistics file against its schema (formats/stats_file.hpp): a file that
// `flotsam stats` writes holds exactly the schema's dimensions, variables and global
// attributes, as the schema describes them, and the names the Python scripts read
// (pipelines/stats_file.py) are the schema's.
#include "formats/stats_file.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/cf.hpp"
#include "common/netcdf.hpp"
#include "sweep/sweep_stats.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
namespace schema = flotsam::stats_file;

namespace {

// Two members of one group with two parameter sets, crossing one section into one region.
sweep::SweepResult small_sweep() {
    sweep::SweepResult r;
    r.flows = {"f0.nc"};
    r.bodies = {"FD"};
    r.variants = {"LC+MC"};
    r.params = {{"control", sweep::paper_control(), true}, {"other", sweep::paper_control(), false}};
    for (int k = 0; k <= 20; ++k) r.time.push_back(double(k));
    for (int m = 0; m < 2; ++m) {
        sweep::MemberRecord rec;
        rec.id = m;
        rec.param_set = m;
        rec.body_name = "FD";
        rec.variant_name = "LC+MC";
        for (double t : r.time) {
            rec.track.x.push_back(0.1 * t);
            rec.track.y.push_back(0.01 * (m + 1) * t);
            rec.track.yaw_deg.push_back(5.0 * m);
            rec.track.u.push_back(0.1);
            rec.track.v.push_back(0.01 * (m + 1));
            rec.track.omega.push_back(0.0);
            rec.track.status.push_back(3);
        }
        r.members.push_back(rec);
    }
    r.member_count = 2;
    return r;
}

std::vector<std::string> words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> w;
    for (std::string s; in >> s;) w.push_back(s);
    return w;
}

}  // namespace

TEST(StatsFile, WrittenFileHoldsTheSchema) {
    const auto dir = test::scratch_dir("stats_file");
    Scene scene;
    scene.grid = Grid{30, 20, 0.05, -0.45, 0.1, 0.1};
    scene.z.assign(scene.grid.size(), 0.0);
    scene.sections = {{"s1", 1.05, -1.0, 1.0}};
    scene.regions = {{"r", {{{0, -1}}, {{3, -1}}, {{3, 1}}, {{0, 1}}}}};
    const sweep::SweepStats s = sweep::compute_stats(small_sweep(), scene);
    sweep::write_stats_file(dir + "/st.nc", s, sweep::default_stats_def(), "sweep.nc", "scene.nc", "test");

    const nc::File f = nc::File::open_read(dir + "/st.nc");
    EXPECT_EQ(cf::kind_of(f), schema::kind);
    for (const std::string& d : schema::dimension_names()) EXPECT_TRUE(f.has_dim(d)) << d;

    // The variables in the file's order, less the per-parameter columns of the
    // parameter-set table, which the sweep's design decides.
    int nvars = 0;
    nc_inq_nvars(f.id(), &nvars);
    std::vector<std::string> names;
    for (int id = 0; id < nvars; ++id) {
        const std::string name = f.var_name(id);
        const bool parameter_column = name.rfind(schema::param_set_value_prefix, 0) == 0 && name != schema::param_set_label &&
                                      name != schema::param_set_is_control;
        if (!parameter_column) names.push_back(name);
    }
    EXPECT_EQ(names, schema::variable_names());

    for (const schema::Variable* v : schema::variables()) {
        const int id = f.var(v->name);
        nc_type type{};
        nc_inq_vartype(f.id(), id, &type);
        EXPECT_EQ(type, v->type) << v->name;
        EXPECT_EQ(f.value_dims(id), std::vector<std::string>(v->dims.begin(), v->dims.end())) << v->name;
        EXPECT_EQ(f.att_text(id, "units").value_or(""), v->units) << v->name;
        EXPECT_EQ(f.att_text(id, "long_name").value_or(""), v->long_name) << v->name;
        EXPECT_EQ(f.att_double(id, "_FillValue").has_value(), v->fill) << v->name;
    }

    std::vector<std::string> attributes = {"Conventions", "flotsam_file_kind"};
    attributes.insert(attributes.end(), schema::attribute_names().begin(), schema::attribute_names().end());
    EXPECT_EQ(f.att_names(NC_GLOBAL), attributes);
}

// The charts read the file by pipelines/stats_file.py's names: they must be the schema's.
TEST(StatsFile, PythonNamesAreTheSchemas) {
    const auto dir = test::scratch_dir("stats_file_python");
    const std::string cmd = "cd " FLOTSAM_SOURCE_DIR
                            " && /usr/bin/python3 -c 'from pipelines import stats_file as s; print(*s.VARIABLES); "
                            "print(*s.DIMENSIONS); print(*s.ATTRIBUTES); print(s.KIND)' > " +
                            dir + "/names.txt 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream in(dir + "/names.txt");
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    ASSERT_EQ(rc, 0) << (lines.empty() ? "" : lines.back());
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(words(lines[0]), schema::variable_names());
    EXPECT_EQ(words(lines[1]), schema::dimension_names());
    EXPECT_EQ(words(lines[2]), schema::attribute_names());
    EXPECT_EQ(lines[3], schema::kind);
}
