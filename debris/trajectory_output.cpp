#include "debris/trajectory_output.hpp"

#include <cmath>
#include <numbers>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"

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

void write_trajectory_file(const std::string& path, const World& world, const TrajectorySeries& series,
                           const TrajectoryFileDef& def) {
    ensure_parent_dir(path);
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        const std::size_t nb = world.size(), nt = series.time.size();
        const int dtraj = f.def_dim("trajectory", nb), dtime = f.def_dim("time", nt);
        const TrackVariables track_vars = define_track_variables(f, dtraj, dtime, def.crs);
        const int vid = cf::def_var(f, {.name = "trajectory_id", .type = NC_STRING, .dims = {dtraj}});
        f.put_att(vid, "cf_role", std::string("trajectory_id"));
        f.put_att(vid, "long_name", std::string("body name"));

        auto per_double = [&](const char* name, const char* units, const char* long_name) {
            return cf::def_var(f, {.name = name, .dims = {dtraj}, .units = units, .long_name = long_name});
        };
        auto per_string = [&](const char* name, const char* long_name) {
            return cf::def_var(f, {.name = name, .type = NC_STRING, .dims = {dtraj}, .long_name = long_name});
        };
        auto per_int = [&](const char* name, const char* long_name) {
            return cf::def_var(f, {.name = name, .type = NC_INT, .dims = {dtraj}, .long_name = long_name});
        };
        const int vstart = per_string("start_name", "scene start point of the body (empty: given by coordinates)");
        const int vcontact = per_string("contact_model", "friction model: center (CC) or local (LC, with axis shift)");
        const int vcoll = per_string("collision_model", "collision model: single (SC) or multi (MC)");
        const int vcd1 = per_double("cd1", "1", "drag coefficient, flow toward a face");
        const int vcd2 = per_double("cd2", "1", "drag coefficient, flow leaving a face");
        const int vcm = per_double("cm", "1", "inertia coefficient");
        const int vmu = per_double("mu", "1", "friction coefficient");
        const int ve = per_double("restitution", "1", "coefficient of restitution against obstacles");
        const int vl = per_double("length", "m", "body length");
        const int vw = per_double("width", "m", "body width");
        const int vh = per_double("height", "m", "body height");
        const int vsg = per_double("specific_gravity", "1", "body specific gravity");
        const int vnc = per_int("collision_steps", "steps with an obstacle contact");
        const int vnu = per_int("unresolved_collisions", "steps whose collision passes left an overlap");
        const int vns = per_int("axis_shift_steps", "steps rotated about the contact centroid");

        cf::put_conventions(f, "trajectory");
        f.put_att(NC_GLOBAL, "title", std::string("flotsam debris trajectories"));
        f.put_att(NC_GLOBAL, "source", std::string("flotsam debris: rigid box replayed through a stored shallow-water flow"));
        f.put_att(NC_GLOBAL, "flow_file", def.flow_file);
        f.put_att(NC_GLOBAL, "history", def.history);
        f.put_att(NC_GLOBAL, "dt_max_s", world.def().step.dt_max);
        f.put_att(NC_GLOBAL, "vertex_step_fraction", world.def().step.vertex_step_fraction);
        f.put_att(NC_GLOBAL, "max_collision_passes", world.def().step.max_collision_passes);
        f.put_att(NC_GLOBAL, "integrator", std::string(to_string(world.def().step.integrator)));
        f.put_att(NC_GLOBAL, "time_interpolation", std::string(to_string(world.def().flow.time_interpolation)));
        f.enddef();

        f.put(track_vars.time, series.time);
        std::vector<std::string> ids, starts, contacts, collisions;
        std::vector<double> cd1, cd2, cm, mu, e, len, wid, hei, sg;
        std::vector<int> nc_, nu, ns;
        for (std::size_t b = 0; b < nb; ++b) {
            const BodyDef& d = world.params()[b].def;
            ids.push_back(d.name);
            starts.push_back(b < def.start_names.size() ? def.start_names[b] : std::string());
            contacts.push_back(to_string(d.contact));
            collisions.push_back(to_string(d.collision));
            cd1.push_back(d.cd1);
            cd2.push_back(d.cd2);
            cm.push_back(d.cm);
            mu.push_back(d.mu);
            e.push_back(d.restitution);
            len.push_back(d.length);
            wid.push_back(d.width);
            hei.push_back(d.height);
            sg.push_back(d.specific_gravity);
            nc_.push_back(int(world.stats()[b].collisions));
            nu.push_back(int(world.stats()[b].unresolved));
            ns.push_back(int(world.stats()[b].axis_shifts));
        }
        f.put(vid, ids);
        f.put(vstart, starts);
        f.put(vcontact, contacts);
        f.put(vcoll, collisions);
        f.put(vcd1, cd1);
        f.put(vcd2, cd2);
        f.put(vcm, cm);
        f.put(vmu, mu);
        f.put(ve, e);
        f.put(vl, len);
        f.put(vw, wid);
        f.put(vh, hei);
        f.put(vsg, sg);
        f.put(vnc, nc_);
        f.put(vnu, nu);
        f.put(vns, ns);
        for (std::size_t b = 0; b < nb && nt > 0; ++b) put_track(f, track_vars, b, series.tracks[b]);
        f.close();
    }
    out.commit();
}

}  // namespace flotsam::debris
