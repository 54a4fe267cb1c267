// The trajectory file: CF-1.11 featureType "trajectory", one trajectory per body, all
// sampled at the same output times (the orthogonal multidimensional representation).
//
//   time(time)                 double, "seconds since 2000-01-01 00:00:00"
//   trajectory_id(trajectory)  string, cf_role = trajectory_id ("FD", "LD", "body3", ...)
//   x, y (trajectory, time)    double [m] centre
//   yaw (trajectory, time)     double [degree] long axis from +x, counter-clockwise (unwrapped)
//   u, v (trajectory, time)    double [m s-1] centre velocity over the last step (pivoting
//                              and collision moves included)
//   omega (trajectory, time)   double [rad s-1] yaw rate (about the contact centroid while pivoting)
//   status (trajectory, time)  byte flags: released moving grounded colliding pivoting
//   per trajectory: start_name, source, body_type, contact_model, collision_model (strings), cd1, cd2, cm, mu,
//                   restitution, length, width, height, specific_gravity (double),
//                   added_yaw_inertia, collision_steps, unresolved_collisions,
//                   axis_shift_steps, jammed_steps, body_contact_steps (int), largest_residual_overlap,
//                   largest_body_overlap (double [m])
//   impact_*(impact)           the impacts on buildings, where there were any
//                              (formats/impact_file.hpp)
//   crs                        the flow's CF grid mapping, when it has one (yaw ... status
//                              name it: x and y are then projection coordinates)
// No time stamps anywhere: the same inputs give the same bytes.
#pragma once
#include <cstdint>
#include <vector>

#include "common/cf.hpp"
#include "common/netcdf.hpp"

namespace flotsam::debris {

// Status bits of a body: BodyState::flags in debris/, the `status` variable in the file.
enum BodyFlag : std::uint8_t {
    flag_released = 1,   // the depth at the centre has exceeded the draft at least once
    flag_moving = 2,     // translating or turning
    flag_grounded = 4,   // bottom touches the ground (some friction patch active)
    flag_colliding = 8,  // touched an obstacle since the last output
    flag_pivoting = 16,  // rotating about the contact centroid (axis shift)
};

struct Track {
    std::vector<double> x, y, yaw_deg, u, v, omega;
    std::vector<std::int8_t> status;
};

// The time axis and the per-time variables of a trajectory file (time; x, y, yaw, u, v,
// omega, status over (trajectory, time)), with their CF attributes. Shared by
// `flotsam debris` and `flotsam sweep`, whose files differ only in the per-trajectory
// variables.
struct TrackVariables {
    int time, x, y, yaw, u, v, omega, status;
};
// With a CRS, also defines the grid-mapping variable that the track variables name.
TrackVariables define_track_variables(nc::File& f, int trajectory_dim, int time_dim, const cf::GridMapping& crs = {});
// Writes the track of trajectory `index` (its series must have one value per time).
void put_track(nc::File& f, const TrackVariables& vars, std::size_t index, const Track& track);

}  // namespace flotsam::debris
