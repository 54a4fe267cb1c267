#include "sweep/sweep_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/checks.hpp"
#include "common/columns.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/settings_nc.hpp"
#include "common/units.hpp"
#include "debris/impacts.hpp"
#include "debris/trajectory_output.hpp"
#include "formats/trajectory_file.hpp"
#include "sweep/trajectory_kernels.hpp"

namespace flotsam::sweep {

std::string trajectory_label(const SweepResult& r, const MemberRecord& m) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "/f%02d/p%02d", m.flow, m.perturbation);
    return m.body_name + "/" + m.variant_name + "/" + r.params[std::size_t(m.param_set)].label + buf;
}

// Every member's impacts, in member order, each naming its member's index in the file.
std::vector<Impact> file_impacts(const SweepResult& r) {
    std::vector<Impact> out;
    for (std::size_t b = 0; b < r.members.size(); ++b)
        for (Impact i : r.members[b].impacts) {
            i.trajectory = int(b);
            out.push_back(i);
        }
    return out;
}

ParameterSetVariables define_parameter_set_variables(nc::File& f, int dim, const std::vector<ParameterSet>& sets) {
    auto var = [&](const std::string& name, nc_type type, const char* long_name, std::size_t length = 0) {
        return cf::def_var(f, {.name = name, .type = type, .dims = {dim}, .long_name = long_name, .text_length = length});
    };
    ParameterSetVariables vars{};
    vars.label =
        var("param_set_label", NC_CHAR, "parameter set label", cf::longest(column<std::string>(sets, &ParameterSet::label)));
    vars.is_control = var("param_set_is_control", NC_BYTE, "1: the control set that R(t) compares against");
    vars.value = def_setting_vars(f, design_parameters(), {dim}, "param_set_");
    return vars;
}

void put_parameter_sets(nc::File& f, const ParameterSetVariables& vars, const std::vector<ParameterSet>& sets) {
    f.put(vars.label, column<std::string>(sets, &ParameterSet::label));
    f.put(vars.is_control, column<std::int8_t>(sets, [](const ParameterSet& s) { return s.is_control ? 1 : 0; }));
    for (std::size_t p = 0; p < design_parameters().size(); ++p)
        f.put(vars.value[p], column<double>(sets, [p](const ParameterSet& s) { return s.values[p]; }));
}

namespace {

// The per-trajectory string columns, known before they are defined (a character array is
// as long as its longest string).
struct MemberText {
    std::vector<std::string> ids, flows, bodies, starts, variants, contacts, collisions, labels;
};

MemberText member_text(const SweepResult& r) {
    const auto& ms = r.members;
    MemberText t;
    for (const auto& m : ms) t.ids.push_back(trajectory_label(r, m));
    t.flows = column<std::string>(ms, [&](const MemberRecord& m) { return r.flows[std::size_t(m.flow)]; });
    t.bodies = column<std::string>(ms, &MemberRecord::body_name);
    t.starts = column<std::string>(ms, &MemberRecord::start_name);
    t.variants = column<std::string>(ms, &MemberRecord::variant_name);
    t.contacts = column<std::string>(ms, [](const MemberRecord& m) { return std::string(enum_name(m.def.contact)); });
    t.collisions = column<std::string>(ms, [](const MemberRecord& m) { return std::string(enum_name(m.def.collision)); });
    t.labels = column<std::string>(ms, [&](const MemberRecord& m) { return r.params[std::size_t(m.param_set)].label; });
    return t;
}

// The per-trajectory variables' ids.
struct MemberVariables {
    int id, member, flow_index, flow, body, start, perturbation, variant, contact, collision, param_set, label;
    std::vector<int> coefficients, shape, model;
    int x0, y0, heading0, run;
    debris::StepCountVariables counts;
};

MemberVariables define_member_variables(nc::File& f, int dtraj, const MemberText& t) {
    auto var = [&](const char* name, nc_type type, const char* units, const char* long_name) {
        return cf::def_var(f, {.name = name, .type = type, .dims = {dtraj}, .units = units, .long_name = long_name});
    };
    auto text = [&](const char* name, const std::vector<std::string>& values, const char* long_name) {
        return cf::def_var(
            f, {.name = name, .type = NC_CHAR, .dims = {dtraj}, .long_name = long_name, .text_length = cf::longest(values)});
    };
    MemberVariables v;
    v.id = text("trajectory_id", t.ids, "body/variant/parameter set/flow/perturbation");
    f.put_att(v.id, "cf_role", std::string("trajectory_id"));
    v.member = var("member_id", NC_INT, "", "position in the sweep's full member list");
    v.flow_index = var("flow_index", NC_INT, "", "index of the flow (dimension flow)");
    v.flow = text("flow", t.flows, "flow file replayed");
    v.body = text("body", t.bodies, "body name");
    v.start = text("start_name", t.starts, "scene start point (empty: given by coordinates)");
    v.perturbation = var("perturbation", NC_INT, "", "start perturbation: 0 exact start, k > 0 the k-th perturbed start");
    v.variant = text("variant", t.variants, "model variant: friction + collision (CC+SC, LC+MC)");
    v.contact = text("contact_model", t.contacts, "friction model: center (CC) or local (LC)");
    v.collision = text("collision_model", t.collisions, "collision model: single (SC) or multi (MC)");
    v.param_set = var("param_set", NC_INT, "", "index of the parameter set (dimension param_set)");
    v.label = text("param_label", t.labels, "label of the parameter set");
    v.coefficients = def_setting_vars(f, debris::body_coefficient_settings(), {dtraj});
    v.shape = def_setting_vars(f, debris::body_shape_settings(), {dtraj});
    v.model = def_setting_vars(f, debris::body_model_settings(), {dtraj});
    v.x0 = var("x0", NC_DOUBLE, "m", "start x of the centre (perturbation included)");
    v.y0 = var("y0", NC_DOUBLE, "m", "start y of the centre (perturbation included)");
    v.heading0 = var("heading0", NC_DOUBLE, "degree", "start heading of the long axis from +x, counter-clockwise");
    v.run = var("run", NC_INT, "", "the run the member was part of: members of one run shared a world and met each other");
    v.counts = debris::define_step_count_variables(f, dtraj);
    return v;
}

void put_member_variables(nc::File& f, const MemberVariables& v, const MemberText& t, const std::vector<MemberRecord>& ms) {
    f.put(v.id, t.ids);
    f.put(v.member, column<int>(ms, &MemberRecord::id));
    f.put(v.flow_index, column<int>(ms, &MemberRecord::flow));
    f.put(v.flow, t.flows);
    f.put(v.body, t.bodies);
    f.put(v.start, t.starts);
    f.put(v.perturbation, column<int>(ms, &MemberRecord::perturbation));
    f.put(v.variant, t.variants);
    f.put(v.contact, t.contacts);
    f.put(v.collision, t.collisions);
    f.put(v.param_set, column<int>(ms, &MemberRecord::param_set));
    f.put(v.label, t.labels);
    const auto def_of = [](const MemberRecord& m) -> const debris::BodyDef& { return m.def; };
    put_setting_vars(f, v.coefficients, debris::body_coefficient_settings(), ms, def_of);
    put_setting_vars(f, v.shape, debris::body_shape_settings(), ms, def_of);
    put_setting_vars(f, v.model, debris::body_model_settings(), ms, def_of);
    f.put(v.x0, column<double>(ms, [](const MemberRecord& m) { return m.def.x; }));
    f.put(v.y0, column<double>(ms, [](const MemberRecord& m) { return m.def.y; }));
    f.put(v.heading0, column<double>(ms, &MemberRecord::heading0_deg));
    f.put(v.run, column<int>(ms, &MemberRecord::run));
    debris::put_step_counts(f, v.counts, column<debris::BodyStats>(ms, &MemberRecord::counts));
}

void put_sweep_attributes(nc::File& f, const SweepResult& r) {
    cf::put_conventions(f, "trajectory");
    cf::put_kind(f, "sweep");
    f.put_att(NC_GLOBAL, "title", std::string("flotsam sweep trajectories"));
    f.put_att(NC_GLOBAL, "source", std::string("flotsam sweep: rigid boxes replayed through stored shallow-water flows"));
    f.put_att(NC_GLOBAL, "spec_file", r.spec_file);
    f.put_att(NC_GLOBAL, "spec_sha256", r.spec_sha256);
    f.put_att(NC_GLOBAL, "scene_file", r.scene_file);
    if (!r.scene_buildings_sha256.empty()) f.put_att(NC_GLOBAL, "scene_buildings_sha256", r.scene_buildings_sha256);
    if (!r.ground_file.empty()) f.put_att(NC_GLOBAL, "ground_file", r.ground_file);
    f.put_att(NC_GLOBAL, "design", r.design);
    f.put_att(NC_GLOBAL, "member_count", r.member_count);
    f.put_att(NC_GLOBAL, "shard", std::to_string(r.shard.index) + "/" + std::to_string(r.shard.count));
    f.put_att(NC_GLOBAL, "output_interval_s", r.output_interval);
    debris::put_world_attributes(f, r.world);
    f.put_att(NC_GLOBAL, "perturbation_count", r.perturbation.count);
    f.put_att(NC_GLOBAL, "perturbation_position_std_m", r.perturbation.position_std);
    f.put_att(NC_GLOBAL, "perturbation_heading_std_deg", r.perturbation.heading_std);
    f.put_att(NC_GLOBAL, "perturbation_seed", double(r.perturbation.seed));
}

}  // namespace

void write_sweep_file(const std::string& path, const SweepResult& r) {
    ensure_parent_dir(path);
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        const std::size_t nm = r.members.size(), nt = r.time.size();
        const int dtraj = f.def_dim("trajectory", nm), dtime = f.def_dim("time", nt);
        const int dflow = f.def_dim("flow", r.flows.size()), dset = f.def_dim("param_set", r.params.size());
        const int dbody = f.def_dim("body", r.bodies.size()), dvar = f.def_dim("variant", r.variants.size());
        const debris::TrackVariables track_vars = debris::define_track_variables(f, dtraj, dtime, r.crs);
        const MemberText text = member_text(r);
        const MemberVariables member_vars = define_member_variables(f, dtraj, text);
        const std::vector<Impact> impacts = file_impacts(r);
        const std::vector<int> vimpact = define_impact_variables(f, impacts.size(), r.crs, debris::impact_force_formula);
        auto table = [&](const char* name, int dim, const std::vector<std::string>& values, const char* long_name) {
            return cf::def_var(
                f, {.name = name, .type = NC_CHAR, .dims = {dim}, .long_name = long_name, .text_length = cf::longest(values)});
        };
        const int vflowpath = table("flow_path", dflow, r.flows, "flow files of the sweep, in order");
        const int vbodyname = table("body_name", dbody, r.bodies, "bodies of the sweep, in order");
        std::vector<std::string> types = r.body_types, sources = r.body_sources;  // "" where not set
        types.resize(r.bodies.size());
        sources.resize(r.bodies.size());
        const int vbodytype = table("body_type", dbody, types, "debris catalogue entry of each body (empty: none)");
        const int vbodysource =
            table("body_source", dbody, sources, "GIS feature each body came from, layer/feature id (empty: none)");
        const int vvarname = table("variant_name", dvar, r.variants, "model variants of the sweep, in order");
        const ParameterSetVariables set_vars = define_parameter_set_variables(f, dset, r.params);
        put_sweep_attributes(f, r);
        f.enddef();

        f.put(track_vars.time, r.time);
        put_member_variables(f, member_vars, text, r.members);
        for (std::size_t b = 0; b < nm && nt > 0; ++b) {
            if (r.members[b].track.x.size() != nt)
                fail(path, "member " + std::to_string(r.members[b].id), "track length does not match the time axis");
            debris::put_track(f, track_vars, b, r.members[b].track);
        }
        f.put(vflowpath, r.flows);
        f.put(vbodyname, r.bodies);
        f.put(vbodytype, types);
        f.put(vbodysource, sources);
        f.put(vvarname, r.variants);
        put_parameter_sets(f, set_vars, r.params);
        put_impacts(f, vimpact, impacts);
        f.close();
    }
    out.commit();
}

namespace {

// A table column of the sweep file, checked to be one-dimensional on `dim` before it is
// read: a short column is a named error, never a read past its end.
int column_var(nc::File& f, const std::string& path, const std::string& name, const std::string& dim) {
    const int v = f.var(name);
    const auto dims = f.value_dims(v);  // a string column's: without its string length
    if (dims != std::vector<std::string>{dim})
        fail(path, "variable '" + name + "'", "must be one-dimensional on dimension '" + dim + "'");
    return v;
}

// The global attributes: the spec, the scene, the design, the shard, the world and the
// perturbations.
void read_sweep_attributes(nc::File& f, const std::string& path, SweepResult& r) {
    auto text = [&](const char* name) {
        const auto a = f.att_text(NC_GLOBAL, name);
        if (!a) fail(path, std::string("attribute '") + name + "'", "missing");
        return *a;
    };
    auto number = [&](const char* name, const Range& range) {
        const auto a = f.att_double(NC_GLOBAL, name);
        if (!a) fail(path, std::string("attribute '") + name + "'", "missing");
        check_range(std::string("attribute '") + name + "'", *a, range, path);
        return *a;
    };
    r.spec_file = text("spec_file");
    r.spec_sha256 = text("spec_sha256");
    r.scene_file = text("scene_file");
    r.scene_buildings_sha256 = f.att_text(NC_GLOBAL, "scene_buildings_sha256").value_or("");
    r.ground_file = f.att_text(NC_GLOBAL, "ground_file").value_or("");
    r.design = text("design");
    r.member_count = int(number("member_count", Range::count(0, 2e9)));
    r.shard = parse_shard(text("shard"));
    r.output_interval = number("output_interval_s", Range::positive("s"));
    r.world = debris::get_world_attributes(f);
    r.perturbation.count = int(number("perturbation_count", Range::count(0, 2e9)));
    r.perturbation.position_std = number("perturbation_position_std_m", Range::non_negative("m"));
    r.perturbation.heading_std = number("perturbation_heading_std_deg", Range::non_negative("degree"));
    r.perturbation.seed = std::uint64_t(number("perturbation_seed", Range::count(0, 1.8e19)));
}

// The sweep's tables: flows, bodies, variants, parameter sets; the CRS.
void read_sweep_tables(nc::File& f, const std::string& path, SweepResult& r) {
    r.flows = f.get_strings(column_var(f, path, "flow_path", "flow"));
    r.bodies = f.get_strings(column_var(f, path, "body_name", "body"));
    // Optional: a file without them reads as empty entries.
    for (auto [name, column] : {std::pair{"body_type", &r.body_types}, std::pair{"body_source", &r.body_sources}})
        *column = f.has_var(name) ? f.get_strings(column_var(f, path, name, "body")) : std::vector<std::string>(r.bodies.size());
    r.variants = f.get_strings(column_var(f, path, "variant_name", "variant"));
    const auto labels = f.get_strings(column_var(f, path, "param_set_label", "param_set"));
    const auto ctrl = f.get_int(column_var(f, path, "param_set_is_control", "param_set"));
    std::vector<std::vector<double>> set_values;
    for (const auto& p : design_parameters()) {
        const std::string name = "param_set_" + p.variable();
        // A parameter added since the file was written (the drag factor): its control value.
        if (!f.has_var(name)) {
            set_values.push_back(std::vector<double>(labels.size(), p.number(debris::default_body_def())));
            continue;
        }
        column_var(f, path, name, "param_set");
        set_values.push_back(nc::read_finite(f, name));
    }
    r.crs = cf::read_crs(f, "yaw");
    for (std::size_t s = 0; s < labels.size(); ++s) {
        ParameterSet ps{labels[s], {}, ctrl[s] != 0};
        for (const auto& v : set_values) ps.values.push_back(v[s]);
        r.params.push_back(ps);
    }
}

// The per-trajectory columns of the members, read whole.
struct MemberColumns {
    std::vector<int> id, flow, perturbation, param_set, collision_steps, unresolved, axis_shift_steps, jammed, run, body_contacts;
    std::vector<std::string> body, start, variant, contact, collision;
    std::vector<double> x0, y0, heading0, residual, body_overlap;
    std::vector<debris::BodyDef> defs;

    MemberColumns(nc::File& f, const std::string& path, std::size_t nm) : defs(nm) {
        const auto ints = [&](const char* n) { return f.get_int(column_var(f, path, n, "trajectory")); };
        const auto doubles = [&](const char* n) {
            column_var(f, path, n, "trajectory");
            return nc::read_finite(f, n);
        };
        const auto strings = [&](const char* n) { return f.get_strings(column_var(f, path, n, "trajectory")); };
        id = ints("member_id"), flow = ints("flow_index"), perturbation = ints("perturbation"), param_set = ints("param_set");
        collision_steps = ints("collision_steps"), unresolved = ints("unresolved_collisions"),
        axis_shift_steps = ints("axis_shift_steps");
        body = strings("body"), start = strings("start_name"), variant = strings("variant"), contact = strings("contact_model"),
        collision = strings("collision_model");
        x0 = doubles("x0"), y0 = doubles("y0"), heading0 = doubles("heading0");
        for (auto [column, unit] : {std::pair{&x0, "m"}, std::pair{&y0, "m"}, std::pair{&heading0, "degree"}}) {
            const double factor = units::factor_to(f, f.var(column == &x0 ? "x0" : column == &y0 ? "y0" : "heading0"), unit);
            for (double& value : *column) value *= factor;
        }
        // Optional: a file without it reads as no overlap left.
        residual = f.has_var("largest_residual_overlap") ? doubles("largest_residual_overlap") : std::vector<double>(nm, 0.0);
        jammed = f.has_var("jammed_steps") ? ints("jammed_steps") : std::vector<int>(nm, 0);
        // Optional: a file without them had every member alone in its world.
        run = f.has_var("run") ? ints("run") : id;
        body_contacts = f.has_var("body_contact_steps") ? ints("body_contact_steps") : std::vector<int>(nm, 0);
        body_overlap = f.has_var("largest_body_overlap") ? doubles("largest_body_overlap") : std::vector<double>(nm, 0.0);
        get_setting_vars(f, debris::body_coefficient_settings(), defs);
        get_setting_vars(f, debris::body_shape_settings(), defs);
        get_setting_vars(f, debris::body_model_settings(), defs, "", false);  // recorded since the settings tables
    }
};

// Member b's record from the columns, checked against the sweep's tables.
MemberRecord member_of(const MemberColumns& c, std::size_t b, const SweepResult& r, const std::string& path) {
    MemberRecord m;
    m.id = c.id[b];
    m.flow = c.flow[b];
    m.perturbation = c.perturbation[b];
    m.param_set = c.param_set[b];
    m.body_name = c.body[b];
    m.start_name = c.start[b];
    m.variant_name = c.variant[b];
    m.def = c.defs[b];
    m.def.name = m.body_name;
    m.def.contact = parse_enum<debris::ContactModel>(c.contact[b], path + ": variable 'contact_model'");
    m.def.collision = parse_enum<debris::CollisionModel>(c.collision[b], path + ": variable 'collision_model'");
    const auto bi = std::find(r.bodies.begin(), r.bodies.end(), m.body_name);
    const auto vi = std::find(r.variants.begin(), r.variants.end(), m.variant_name);
    if (bi == r.bodies.end() || vi == r.variants.end() || m.flow < 0 || m.flow >= int(r.flows.size()) || m.param_set < 0 ||
        m.param_set >= int(r.params.size()))
        fail(path, "trajectory " + std::to_string(b), "body, variant, flow or parameter set not in the sweep's tables");
    m.body = int(bi - r.bodies.begin());
    m.variant = int(vi - r.variants.begin());
    m.def.x = c.x0[b];
    m.def.y = c.y0[b];
    m.heading0_deg = c.heading0[b];
    m.def.heading = c.heading0[b] * std::numbers::pi / 180.0;
    m.counts.collisions = c.collision_steps[b];
    m.counts.unresolved = c.unresolved[b];
    m.counts.max_residual_overlap = c.residual[b];
    m.counts.jams = c.jammed[b];
    m.counts.axis_shifts = c.axis_shift_steps[b];
    m.run = c.run[b];
    m.counts.body_contacts = c.body_contacts[b];
    m.counts.max_body_overlap = c.body_overlap[b];
    return m;
}

}  // namespace

namespace {

// The sweep file, its member table checked against the sweep's tables; the tracks read
// (and checked, formats/trajectory_file.hpp) when `with_tracks`.
SweepResult read_sweep(const std::string& path, bool with_tracks) {
    nc::File f = nc::File::open_read(path);
    cf::require_kind(f, {"sweep"});
    for (const char* v : {"member_id", "flow_path", "param_set_label", "variant"})
        if (!f.has_var(v)) fail(path, std::string("variable '") + v + "'", "missing: not a file written by `flotsam sweep`");
    SweepResult r;
    r.path = path;
    read_sweep_attributes(f, path, r);
    const debris::TrackReader tracks(f, true);
    r.time = tracks.time();
    read_sweep_tables(f, path, r);
    const std::size_t nm = tracks.size();
    const MemberColumns columns(f, path, nm);
    std::set<int> seen;
    for (std::size_t b = 0; b < nm; ++b) {
        // Members are named by their place in the sweep's member list: each once, inside it.
        const int id = columns.id[b];
        if (id < 0 || id >= r.member_count)
            fail(path, "variable 'member_id'",
                 "trajectory " + std::to_string(b) + " has member_id " + std::to_string(id) + ", outside [0, " +
                     std::to_string(r.member_count) + ") (member_count)");
        if (!seen.insert(id).second)
            fail(path, "variable 'member_id'",
                 "member_id " + std::to_string(id) + " is given twice (trajectory " + std::to_string(b) + " and an earlier one)");
        MemberRecord m = member_of(columns, b, r, path);
        if (with_tracks) m.track = tracks.read(b);
        r.members.push_back(std::move(m));
    }
    for (const Impact& i : read_impacts(f, nm)) r.members[std::size_t(i.trajectory)].impacts.push_back(i);
    return r;
}

}  // namespace

SweepResult read_sweep_file(const std::string& path) { return read_sweep(path, true); }

SweepResult read_sweep_tables(const std::string& path) { return read_sweep(path, false); }

void check_tracks_on(const SweepResult& r, const Grid& g, const std::string& what) {
    const double tx = 1e-6 * g.dx, ty = 1e-6 * g.dy;
    for (std::size_t m = 0; m < r.members.size(); ++m)
        debris::check_track_within(r.path.empty() ? "--sweep" : r.path, m, r.members[m].track, g.x_min_edge() - tx,
                                   g.x_max_edge() + tx, g.y_min_edge() - ty, g.y_max_edge() + ty, what);
}

SweepResult merge_sweeps(const std::vector<SweepResult>& parts, const std::vector<std::string>& paths) {
    if (parts.empty()) fail("sweep merge", "parts", "none given");
    SweepResult out = parts.front();
    out.members.clear();
    out.shard = {0, 1};
    std::map<int, const MemberRecord*> by_id;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const SweepResult& p = parts[k];
        const std::string& name = paths[k];
        if (p.spec_sha256 != out.spec_sha256) fail(name, "spec_sha256", "comes from another spec than " + paths[0]);
        if (p.member_count != out.member_count || p.time != out.time || p.flows != out.flows || p.bodies != out.bodies ||
            p.body_types != out.body_types || p.body_sources != out.body_sources || p.variants != out.variants ||
            p.params.size() != out.params.size() || p.scene_file != out.scene_file || p.ground_file != out.ground_file ||
            p.scene_buildings_sha256 != out.scene_buildings_sha256)
            fail(name, "sweep tables", "differ from those of " + paths[0] + " (not shards of one sweep)");
        for (const auto& m : p.members)
            if (!by_id.emplace(m.id, &m).second) fail(name, "member " + std::to_string(m.id), "also in another part");
    }
    if (int(by_id.size()) != out.member_count) {
        int missing = 0;
        while (by_id.count(missing)) ++missing;
        fail("sweep merge", "member " + std::to_string(missing),
             "missing: the parts hold " + std::to_string(by_id.size()) + " of " + std::to_string(out.member_count) + " members");
    }
    for (const auto& [id, m] : by_id) out.members.push_back(*m);
    return out;
}

}  // namespace flotsam::sweep
