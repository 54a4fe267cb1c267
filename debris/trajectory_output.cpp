#include "debris/trajectory_output.hpp"

#include <cmath>
#include <numbers>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/columns.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/settings_nc.hpp"
#include "debris/impacts.hpp"
#include "formats/impact_file.hpp"

namespace flotsam::debris {

void record(World& world, TrajectorySeries& series) {
    series.time.push_back(world.time());
    series.tracks.resize(world.size());
    for (std::size_t b = 0; b < world.size(); ++b) {
        const BodyState& s = world.states()[b];
        Track& t = series.tracks[b];
        t.x.push_back(s.x + world.origin_x());
        t.y.push_back(s.y + world.origin_y());
        t.yaw_deg.push_back(s.theta * 180.0 / std::numbers::pi);
        t.u.push_back(s.vx);
        t.v.push_back(s.vy);
        t.omega.push_back(s.omega + s.pivot_rate);
        t.status.push_back(std::int8_t(s.flags));
    }
    world.clear_event_flags();
}

StepCountVariables define_step_count_variables(nc::File& f, int dim) {
    const auto count = [&](const char* name, const char* long_name) {
        return cf::def_var(f, {.name = name, .type = NC_INT, .dims = {dim}, .long_name = long_name});
    };
    const auto depth = [&](const char* name, const char* long_name) {
        return cf::def_var(f, {.name = name, .type = NC_DOUBLE, .dims = {dim}, .units = "m", .long_name = long_name});
    };
    StepCountVariables v;
    v.collisions = count("collision_steps", "steps with an obstacle contact");
    v.unresolved = count("unresolved_collisions", "steps whose collision passes left an overlap");
    v.axis_shifts = count("axis_shift_steps", "steps rotated about the contact centroid");
    v.jams = count("jammed_steps", "steps undone because the collision passes could not clear the overlap");
    v.residual = depth("largest_residual_overlap", "deepest obstacle overlap left after collision handling");
    v.body_contacts = count("body_contact_steps", "steps with a contact with another body of its run");
    v.body_overlap = depth("largest_body_overlap", "deepest overlap with another body left after collision handling");
    return v;
}

void put_step_counts(nc::File& f, const StepCountVariables& v, const std::vector<BodyStats>& counts) {
    f.put(v.collisions, column<int>(counts, &BodyStats::collisions));
    f.put(v.unresolved, column<int>(counts, &BodyStats::unresolved));
    f.put(v.axis_shifts, column<int>(counts, &BodyStats::axis_shifts));
    f.put(v.jams, column<int>(counts, &BodyStats::jams));
    f.put(v.residual, column<double>(counts, &BodyStats::max_residual_overlap));
    f.put(v.body_contacts, column<int>(counts, &BodyStats::body_contacts));
    f.put(v.body_overlap, column<double>(counts, &BodyStats::max_body_overlap));
}

void put_world_attributes(nc::File& f, const WorldDef& def) {
    f.put_att(NC_GLOBAL, "dt_max_s", def.step.dt_max);
    f.put_att(NC_GLOBAL, "vertex_step_fraction", def.step.vertex_step_fraction);
    f.put_att(NC_GLOBAL, "max_collision_passes", def.step.max_collision_passes);
    f.put_att(NC_GLOBAL, "integrator", std::string(enum_name(def.step.integrator)));
    f.put_att(NC_GLOBAL, "time_interpolation", std::string(enum_name(def.flow.time_interpolation)));
    f.put_att(NC_GLOBAL, "body_contact", def.step.body_contact ? 1 : 0);
}

WorldDef get_world_attributes(const nc::File& f) {
    WorldDef def = default_world_def();
    if (const auto v = f.att_double(NC_GLOBAL, "dt_max_s")) def.step.dt_max = *v;
    if (const auto v = f.att_double(NC_GLOBAL, "vertex_step_fraction")) def.step.vertex_step_fraction = *v;
    if (const auto v = f.att_double(NC_GLOBAL, "max_collision_passes")) def.step.max_collision_passes = int(*v);
    if (const auto v = f.att_double(NC_GLOBAL, "body_contact"))
        def.step.body_contact = *v != 0.0;  // absent: files from before bodies met: off
    else
        def.step.body_contact = false;
    const std::string where = f.path() + ": attribute ";
    if (const auto v = f.att_text(NC_GLOBAL, "integrator"))
        def.step.integrator = parse_enum<Integrator>(*v, where + "'integrator'");
    if (const auto v = f.att_text(NC_GLOBAL, "time_interpolation"))
        def.flow.time_interpolation = parse_enum<TimeInterpolation>(*v, where + "'time_interpolation'");
    return def;
}

void write_trajectory_file(const std::string& path, const std::vector<TrajectoryRecord>& records, const std::vector<double>& time,
                           const std::vector<Impact>& impacts, const WorldDef& world, const TrajectoryFileDef& def) {
    ensure_parent_dir(path);
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        const std::size_t nb = records.size(), nt = time.size();
        const int dtraj = f.def_dim("trajectory", nb), dtime = f.def_dim("time", nt);
        const TrackVariables track_vars = define_track_variables(f, dtraj, dtime, def.crs);
        // The strings, known before they are defined (character arrays are as long as the longest).
        const std::vector<BodyDef> bodies = column<BodyDef>(records, &TrajectoryRecord::def);
        std::vector<std::string> starts = def.start_names, sources = def.sources, types = def.body_types;
        starts.resize(nb);
        sources.resize(nb);
        types.resize(nb);
        const std::vector<std::string> ids = column<std::string>(bodies, [](const BodyDef& d) { return d.name; });
        const std::vector<std::string> contacts =
            column<std::string>(bodies, [](const BodyDef& d) { return std::string(enum_name(d.contact)); });
        const std::vector<std::string> collisions =
            column<std::string>(bodies, [](const BodyDef& d) { return std::string(enum_name(d.collision)); });
        const int vid = f.def_text_var("trajectory_id", {dtraj}, cf::longest(ids));
        f.put_att(vid, "cf_role", std::string("trajectory_id"));
        f.put_att(vid, "long_name", std::string("body name"));

        auto per_string = [&](const char* name, const char* long_name, const std::vector<std::string>& values) {
            return cf::def_var(
                f, {.name = name, .type = NC_CHAR, .dims = {dtraj}, .long_name = long_name, .text_length = cf::longest(values)});
        };
        const int vstart = per_string("start_name", "scene start point of the body (empty: given by coordinates)", starts);
        const int vsource = per_string("source", "GIS feature the body came from, layer/feature id (empty: none)", sources);
        const int vtype = per_string("body_type", "debris catalogue entry of the body (empty: none)", types);
        const int vcontact = per_string("contact_model", "friction model: center (CC) or local (LC, with axis shift)", contacts);
        const int vcoll = per_string("collision_model", "collision model: single (SC) or multi (MC)", collisions);
        const std::vector<int> vcoef = def_setting_vars(f, body_coefficient_settings(), {dtraj});
        const std::vector<int> vshape = def_setting_vars(f, body_shape_settings(), {dtraj});
        const std::vector<int> vmodel = def_setting_vars(f, body_model_settings(), {dtraj});
        const StepCountVariables vcounts = define_step_count_variables(f, dtraj);
        const std::vector<int> vimpact = define_impact_variables(f, impacts.size(), def.crs, impact_force_formula);

        cf::put_conventions(f, "trajectory");
        cf::put_kind(f, "trajectories");
        f.put_att(NC_GLOBAL, "title", std::string("flotsam debris trajectories"));
        f.put_att(NC_GLOBAL, "source", std::string("flotsam debris: rigid box replayed through a stored shallow-water flow"));
        f.put_att(NC_GLOBAL, "flow_file", def.flow_file);
        if (!def.scene_buildings_sha256.empty()) f.put_att(NC_GLOBAL, "scene_buildings_sha256", def.scene_buildings_sha256);
        f.put_att(NC_GLOBAL, "history", def.history);
        put_world_attributes(f, world);
        f.enddef();

        f.put(track_vars.time, time);
        const auto def_of = [](const BodyDef& d) -> const BodyDef& { return d; };
        f.put(vid, ids);
        f.put(vstart, starts);
        f.put(vsource, sources);
        f.put(vtype, types);
        f.put(vcontact, contacts);
        f.put(vcoll, collisions);
        put_setting_vars(f, vcoef, body_coefficient_settings(), bodies, def_of);
        put_setting_vars(f, vshape, body_shape_settings(), bodies, def_of);
        put_setting_vars(f, vmodel, body_model_settings(), bodies, def_of);
        put_step_counts(f, vcounts, column<BodyStats>(records, &TrajectoryRecord::stats));
        for (std::size_t b = 0; b < nb && nt > 0; ++b) put_track(f, track_vars, b, records[b].track);
        put_impacts(f, vimpact, impacts);
        f.close();
    }
    out.commit();
}

}  // namespace flotsam::debris
