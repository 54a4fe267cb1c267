// The trajectory file: CF-1.11 featureType "trajectory", one trajectory per body, all
// sampled at the same output times (the orthogonal multidimensional representation).
//
//   time(time)                 double, "seconds since 2000-01-01 00:00:00"
//   trajectory_id(trajectory)  string, cf_role = trajectory_id ("FD", "LD", "body3", ...)
//   x, y (trajectory, time)    double [m] centre
//   yaw (trajectory, time)     double [degree] long axis from +x, counter-clockwise (unwrapped)
//   u, v (trajectory, time)    double [m s-1] centre velocity
//   omega (trajectory, time)   double [rad s-1] yaw rate (about the contact centroid while pivoting)
//   status (trajectory, time)  byte flags: released moving grounded colliding pivoting
//   per trajectory: start_name, contact_model, collision_model (strings), cd1, cd2, cm, mu,
//                   restitution, length, width, height, specific_gravity (double),
//                   collision_steps, unresolved_collisions, axis_shift_steps (int)
// No time stamps anywhere: the same inputs give the same bytes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "common/netcdf.hpp"
#include "debris/world.hpp"

namespace flotsam::debris {

struct Track {
    std::vector<double> x, y, yaw_deg, u, v, omega;
    std::vector<std::int8_t> status;
};

struct TrajectorySeries {
    std::vector<double> time;  // [s]
    std::vector<Track> tracks; // one per body
};

// Appends the bodies' current states at world.time() and clears their event bits.
void record(World& world, TrajectorySeries& series);

struct TrajectoryFileDef {
    std::string history;                      // the command line
    std::string flow_file;                    // the replayed flow
    std::vector<std::string> start_names;     // per body: the scene point, or "" for --at
};

// The time axis and the per-time variables of a trajectory file (time; x, y, yaw, u, v,
// omega, status over (trajectory, time)), with their CF attributes. Shared by
// `flotsam debris` and `flotsam sweep`, whose files differ only in the per-trajectory
// variables.
struct TrackVariables {
    int time, x, y, yaw, u, v, omega, status;
};
TrackVariables define_track_variables(nc::File& f, int trajectory_dim, int time_dim);
// Writes the track of trajectory `index` (its series must have one value per time).
void put_track(nc::File& f, const TrackVariables& vars, std::size_t index, const Track& track);

// Writes atomically (temporary file, then rename).
void write_trajectory_file(const std::string& path, const World& world, const TrajectorySeries& series, const TrajectoryFileDef& def);

}  // namespace flotsam::debris
