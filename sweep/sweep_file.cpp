#include "sweep/sweep_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "sweep/trajectory_kernels.hpp"

namespace flotsam::sweep {

namespace {

std::string trajectory_label(const SweepResult& r, const MemberRecord& m) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "/f%02d/p%02d", m.flow, m.perturbation);
    return m.body_name + "/" + m.variant_name + "/" + r.params[std::size_t(m.param_set)].label + buf;
}

template <class T, class F>
std::vector<T> column(const std::vector<MemberRecord>& ms, F f) {
    std::vector<T> out;
    out.reserve(ms.size());
    for (const auto& m : ms) out.push_back(T(f(m)));
    return out;
}

// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace

std::string summary_path_for(const std::string& nc_path) {
    std::filesystem::path p(nc_path);
    p.replace_extension(".csv");
    return p.string();
}

ParameterSetVariables define_parameter_set_variables(nc::File& f, int dim) {
    auto var = [&](const std::string& name, nc_type type, const char* units, const char* long_name) {
        return cf::def_var(f, {.name = name, .type = type, .dims = {dim}, .units = units, .long_name = long_name});
    };
    ParameterSetVariables vars{};
    vars.label = var("param_set_label", NC_STRING, "", "parameter set label");
    vars.is_control = var("param_set_is_control", NC_BYTE, "", "1: the control set that R(t) compares against");
    for (std::size_t p = 0; p < parameter_names.size(); ++p)
        vars.value[p] = var(std::string("param_set_") + parameter_names[p], NC_DOUBLE, "1", parameter_long_names[p]);
    return vars;
}

void put_parameter_sets(nc::File& f, const ParameterSetVariables& vars, const std::vector<ParameterSet>& sets) {
    std::vector<std::string> labels;
    std::vector<std::int8_t> control;
    for (const ParameterSet& s : sets) {
        labels.push_back(s.label);
        control.push_back(s.is_control ? 1 : 0);
    }
    f.put(vars.label, labels);
    f.put(vars.is_control, control);
    for (std::size_t p = 0; p < parameter_names.size(); ++p) {
        std::vector<double> values;
        for (const ParameterSet& s : sets) values.push_back(s.values[p]);
        f.put(vars.value[p], values);
    }
}

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
        auto var = [&](const char* name, nc_type type, std::vector<int> dims, const char* units, const char* long_name) {
            return cf::def_var(f, {.name = name, .type = type, .dims = std::move(dims), .units = units, .long_name = long_name});
        };
        const int vid = var("trajectory_id", NC_STRING, {dtraj}, "", "body/variant/parameter set/flow/perturbation");
        f.put_att(vid, "cf_role", std::string("trajectory_id"));
        const int vmember = var("member_id", NC_INT, {dtraj}, "", "position in the sweep's full member list");
        const int vflowi = var("flow_index", NC_INT, {dtraj}, "", "index of the flow (dimension flow)");
        const int vflow = var("flow", NC_STRING, {dtraj}, "", "flow file replayed");
        const int vbody = var("body", NC_STRING, {dtraj}, "", "body name");
        const int vstart = var("start_name", NC_STRING, {dtraj}, "", "scene start point (empty: given by coordinates)");
        const int vpert =
            var("perturbation", NC_INT, {dtraj}, "", "start perturbation: 0 exact start, k > 0 the k-th perturbed start");
        const int vvariant = var("variant", NC_STRING, {dtraj}, "", "model variant: friction + collision (CC+SC, LC+MC)");
        const int vcontact = var("contact_model", NC_STRING, {dtraj}, "", "friction model: center (CC) or local (LC)");
        const int vcoll = var("collision_model", NC_STRING, {dtraj}, "", "collision model: single (SC) or multi (MC)");
        const int vset = var("param_set", NC_INT, {dtraj}, "", "index of the parameter set (dimension param_set)");
        const int vlabel = var("param_label", NC_STRING, {dtraj}, "", "label of the parameter set");
        std::array<int, 5> vparam{};
        for (std::size_t p = 0; p < 5; ++p) vparam[p] = var(parameter_names[p], NC_DOUBLE, {dtraj}, "1", parameter_long_names[p]);
        const int vl = var("length", NC_DOUBLE, {dtraj}, "m", "body length");
        const int vw = var("width", NC_DOUBLE, {dtraj}, "m", "body width");
        const int vh = var("height", NC_DOUBLE, {dtraj}, "m", "body height");
        const int vsg = var("specific_gravity", NC_DOUBLE, {dtraj}, "1", "body specific gravity");
        const int vx0 = var("x0", NC_DOUBLE, {dtraj}, "m", "start x of the centre (perturbation included)");
        const int vy0 = var("y0", NC_DOUBLE, {dtraj}, "m", "start y of the centre (perturbation included)");
        const int vh0 = var("heading0", NC_DOUBLE, {dtraj}, "degree", "start heading of the long axis from +x, counter-clockwise");
        const int vnc = var("collision_steps", NC_INT, {dtraj}, "", "steps with an obstacle contact");
        const int vnu = var("unresolved_collisions", NC_INT, {dtraj}, "", "steps whose collision passes left an overlap");
        const int vns = var("axis_shift_steps", NC_INT, {dtraj}, "", "steps rotated about the contact centroid");

        const int vflowpath = var("flow_path", NC_STRING, {dflow}, "", "flow files of the sweep, in order");
        const int vbodyname = var("body_name", NC_STRING, {dbody}, "", "bodies of the sweep, in order");
        const int vvarname = var("variant_name", NC_STRING, {dvar}, "", "model variants of the sweep, in order");
        const ParameterSetVariables set_vars = define_parameter_set_variables(f, dset);

        cf::put_conventions(f, "trajectory");
        f.put_att(NC_GLOBAL, "title", std::string("flotsam sweep trajectories"));
        f.put_att(NC_GLOBAL, "source", std::string("flotsam sweep: rigid boxes replayed through stored shallow-water flows"));
        f.put_att(NC_GLOBAL, "spec_file", r.spec_file);
        f.put_att(NC_GLOBAL, "spec_sha256", r.spec_sha256);
        f.put_att(NC_GLOBAL, "scene_file", r.scene_file);
        f.put_att(NC_GLOBAL, "design", r.design);
        f.put_att(NC_GLOBAL, "member_count", r.member_count);
        f.put_att(NC_GLOBAL, "shard", std::to_string(r.shard.index) + "/" + std::to_string(r.shard.count));
        f.put_att(NC_GLOBAL, "output_interval_s", r.output_interval);
        f.put_att(NC_GLOBAL, "dt_max_s", r.dt_max);
        f.put_att(NC_GLOBAL, "perturbation_count", r.perturbation.count);
        f.put_att(NC_GLOBAL, "perturbation_position_std_m", r.perturbation.position_std);
        f.put_att(NC_GLOBAL, "perturbation_heading_std_deg", r.perturbation.heading_std);
        f.put_att(NC_GLOBAL, "perturbation_seed", double(r.perturbation.seed));
        f.enddef();

        f.put(track_vars.time, r.time);
        const auto& ms = r.members;
        std::vector<std::string> ids;
        for (const auto& m : ms) ids.push_back(trajectory_label(r, m));
        f.put(vid, ids);
        f.put(vmember, column<int>(ms, [](const MemberRecord& m) { return m.id; }));
        f.put(vflowi, column<int>(ms, [](const MemberRecord& m) { return m.flow; }));
        f.put(vflow, column<std::string>(ms, [&](const MemberRecord& m) { return r.flows[std::size_t(m.flow)]; }));
        f.put(vbody, column<std::string>(ms, [](const MemberRecord& m) { return m.body_name; }));
        f.put(vstart, column<std::string>(ms, [](const MemberRecord& m) { return m.start_name; }));
        f.put(vpert, column<int>(ms, [](const MemberRecord& m) { return m.perturbation; }));
        f.put(vvariant, column<std::string>(ms, [](const MemberRecord& m) { return m.variant_name; }));
        f.put(vcontact, column<std::string>(ms, [](const MemberRecord& m) { return m.contact; }));
        f.put(vcoll, column<std::string>(ms, [](const MemberRecord& m) { return m.collision; }));
        f.put(vset, column<int>(ms, [](const MemberRecord& m) { return m.param_set; }));
        f.put(vlabel, column<std::string>(ms, [&](const MemberRecord& m) { return r.params[std::size_t(m.param_set)].label; }));
        for (std::size_t p = 0; p < 5; ++p)
            f.put(vparam[p], column<double>(ms, [p](const MemberRecord& m) { return m.params[p]; }));
        f.put(vl, column<double>(ms, [](const MemberRecord& m) { return m.length; }));
        f.put(vw, column<double>(ms, [](const MemberRecord& m) { return m.width; }));
        f.put(vh, column<double>(ms, [](const MemberRecord& m) { return m.height; }));
        f.put(vsg, column<double>(ms, [](const MemberRecord& m) { return m.specific_gravity; }));
        f.put(vx0, column<double>(ms, [](const MemberRecord& m) { return m.x0; }));
        f.put(vy0, column<double>(ms, [](const MemberRecord& m) { return m.y0; }));
        f.put(vh0, column<double>(ms, [](const MemberRecord& m) { return m.heading0_deg; }));
        f.put(vnc, column<int>(ms, [](const MemberRecord& m) { return m.collision_steps; }));
        f.put(vnu, column<int>(ms, [](const MemberRecord& m) { return m.unresolved_collisions; }));
        f.put(vns, column<int>(ms, [](const MemberRecord& m) { return m.axis_shift_steps; }));
        for (std::size_t b = 0; b < nm && nt > 0; ++b) {
            if (ms[b].track.x.size() != nt)
                fail(path, "member " + std::to_string(ms[b].id), "track length does not match the time axis");
            debris::put_track(f, track_vars, b, ms[b].track);
        }
        f.put(vflowpath, r.flows);
        f.put(vbodyname, r.bodies);
        f.put(vvarname, r.variants);
        put_parameter_sets(f, set_vars, r.params);
        f.close();
    }
    out.commit();
}

SweepResult read_sweep_file(const std::string& path) {
    nc::File f = nc::File::open_read(path);
    for (const char* v : {"member_id", "flow_path", "param_set_label", "variant"})
        if (!f.has_var(v)) fail(path, std::string("variable '") + v + "'", "missing: not a file written by `flotsam sweep`");
    SweepResult r;
    auto text = [&](const char* name) {
        const auto a = f.att_text(NC_GLOBAL, name);
        if (!a) fail(path, std::string("attribute '") + name + "'", "missing");
        return *a;
    };
    auto number = [&](const char* name) {
        const auto a = f.att_double(NC_GLOBAL, name);
        if (!a) fail(path, std::string("attribute '") + name + "'", "missing");
        return *a;
    };
    r.spec_file = text("spec_file");
    r.spec_sha256 = text("spec_sha256");
    r.scene_file = text("scene_file");
    r.design = text("design");
    r.member_count = int(number("member_count"));
    r.shard = parse_shard(text("shard"));
    r.output_interval = number("output_interval_s");
    r.dt_max = number("dt_max_s");
    r.perturbation.count = int(number("perturbation_count"));
    r.perturbation.position_std = number("perturbation_position_std_m");
    r.perturbation.heading_std = number("perturbation_heading_std_deg");
    r.perturbation.seed = std::uint64_t(number("perturbation_seed"));
    r.time = f.get_double(f.var("time"));
    r.crs = cf::read_crs(f, "yaw");
    r.flows = f.get_strings(f.var("flow_path"));
    r.bodies = f.get_strings(f.var("body_name"));
    r.variants = f.get_strings(f.var("variant_name"));
    const auto labels = f.get_strings(f.var("param_set_label"));
    const auto ctrl = f.get_int(f.var("param_set_is_control"));
    std::array<std::vector<double>, 5> setp;
    for (std::size_t p = 0; p < 5; ++p) setp[p] = f.get_double(f.var(std::string("param_set_") + parameter_names[p]));
    for (std::size_t s = 0; s < labels.size(); ++s) {
        ParameterSet ps{labels[s], {}, ctrl[s] != 0};
        for (std::size_t p = 0; p < 5; ++p) ps.values[p] = setp[p][s];
        r.params.push_back(ps);
    }

    const std::size_t nm = f.dim_length("trajectory"), nt = r.time.size();
    const auto ints = [&](const char* n) { return f.get_int(f.var(n)); };
    const auto doubles = [&](const char* n) { return f.get_double(f.var(n)); };
    const auto strings = [&](const char* n) { return f.get_strings(f.var(n)); };
    const auto id = ints("member_id"), flow = ints("flow_index"), pert = ints("perturbation"), set = ints("param_set");
    const auto nc_ = ints("collision_steps"), nu = ints("unresolved_collisions"), ns = ints("axis_shift_steps");
    const auto body = strings("body"), start = strings("start_name"), variant = strings("variant"),
               contact = strings("contact_model"), coll = strings("collision_model");
    std::array<std::vector<double>, 5> par;
    for (std::size_t p = 0; p < 5; ++p) par[p] = doubles(parameter_names[p]);
    const auto len = doubles("length"), wid = doubles("width"), hei = doubles("height"), sg = doubles("specific_gravity");
    const auto x0 = doubles("x0"), y0 = doubles("y0"), h0 = doubles("heading0");
    const int vx = f.var("x"), vy = f.var("y"), vyaw = f.var("yaw"), vu = f.var("u"), vv = f.var("v"), vom = f.var("omega"),
              vst = f.var("status");
    std::vector<double> statusd(nt);
    for (std::size_t b = 0; b < nm; ++b) {
        MemberRecord m;
        m.id = id[b];
        m.flow = flow[b];
        m.perturbation = pert[b];
        m.param_set = set[b];
        m.body_name = body[b];
        m.start_name = start[b];
        m.variant_name = variant[b];
        m.contact = contact[b];
        m.collision = coll[b];
        const auto bi = std::find(r.bodies.begin(), r.bodies.end(), m.body_name);
        const auto vi = std::find(r.variants.begin(), r.variants.end(), m.variant_name);
        if (bi == r.bodies.end() || vi == r.variants.end() || m.flow < 0 || m.flow >= int(r.flows.size()) || m.param_set < 0 ||
            m.param_set >= int(r.params.size()))
            fail(path, "trajectory " + std::to_string(b), "body, variant, flow or parameter set not in the sweep's tables");
        m.body = int(bi - r.bodies.begin());
        m.variant = int(vi - r.variants.begin());
        for (std::size_t p = 0; p < 5; ++p) m.params[p] = par[p][b];
        m.length = len[b];
        m.width = wid[b];
        m.height = hei[b];
        m.specific_gravity = sg[b];
        m.x0 = x0[b];
        m.y0 = y0[b];
        m.heading0_deg = h0[b];
        m.collision_steps = nc_[b];
        m.unresolved_collisions = nu[b];
        m.axis_shift_steps = ns[b];
        debris::Track& t = m.track;
        for (auto* series : {&t.x, &t.y, &t.yaw_deg, &t.u, &t.v, &t.omega}) series->resize(nt);
        if (nt > 0) {
            const std::vector<std::size_t> st = {b, 0}, count = {1, nt};
            f.get_slab(vx, st, count, t.x.data());
            f.get_slab(vy, st, count, t.y.data());
            f.get_slab(vyaw, st, count, t.yaw_deg.data());
            f.get_slab(vu, st, count, t.u.data());
            f.get_slab(vv, st, count, t.v.data());
            f.get_slab(vom, st, count, t.omega.data());
            f.get_slab(vst, st, count, statusd.data());
        }
        for (double s : statusd) t.status.push_back(std::int8_t(s));
        r.members.push_back(std::move(m));
    }
    return r;
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
            p.variants != out.variants || p.params.size() != out.params.size() || p.scene_file != out.scene_file)
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

void write_summary_csv(const std::string& path, const SweepResult& r) {
    std::string s =
        "member,flow,flow_path,body,start_name,variant,param_set,param_label,perturbation,cd1,cd2,cm,mu,restitution,"
        "x0_m,y0_m,heading0_deg,motion_start_s,final_x_m,final_y_m,final_yaw_deg,net_displacement_m,travel_distance_m,"
        "max_speed_m_s,time_of_max_speed_s,collision_steps,unresolved_collisions,axis_shift_steps\n";
    char buf[512];
    for (const auto& m : r.members) {
        const debris::Track& t = m.track;
        const int k0 = t.x.empty() ? -1 : motion_start_index(t.x, t.y, motion_threshold * body_scale(m.length));
        double vmax = 0.0, tmax = r.time.empty() ? 0.0 : r.time.front();
        for (std::size_t k = 0; k < t.u.size(); ++k) {
            const double sp = std::hypot(t.u[k], t.v[k]);
            if (sp > vmax) {
                vmax = sp;
                tmax = r.time[k];
            }
        }
        const bool any = !t.x.empty();
        s += std::to_string(m.id) + "," + std::to_string(m.flow) + "," + csv_field(r.flows[std::size_t(m.flow)]) + "," +
             csv_field(m.body_name) + "," + csv_field(m.start_name) + "," + m.variant_name + "," + std::to_string(m.param_set) +
             "," + csv_field(r.params[std::size_t(m.param_set)].label) + "," + std::to_string(m.perturbation);
        for (double p : m.params) {
            std::snprintf(buf, sizeof buf, ",%.10g", p);
            s += buf;
        }
        std::snprintf(buf, sizeof buf, ",%.10g,%.10g,%.10g,", m.x0, m.y0, m.heading0_deg);
        s += buf;
        if (k0 >= 0) {
            std::snprintf(buf, sizeof buf, "%.10g", r.time[std::size_t(k0)]);
            s += buf;
        }  // empty: never moved
        std::snprintf(buf, sizeof buf, ",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%d,%d\n", any ? t.x.back() : m.x0,
                      any ? t.y.back() : m.y0, any ? t.yaw_deg.back() : m.heading0_deg,
                      any ? std::hypot(t.x.back() - t.x.front(), t.y.back() - t.y.front()) : 0.0, any ? path_length(t.x, t.y) : 0.0,
                      vmax, tmax, m.collision_steps, m.unresolved_collisions, m.axis_shift_steps);
        s += buf;
    }
    write_text_atomic(path, s);
}

}  // namespace flotsam::sweep
