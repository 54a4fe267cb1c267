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
#include <functional>
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

// ---- reading, checked ----

// The bounds of a stored track (docs/reliability.md, "Bad input and what it gets"): no
// projected CRS reaches 1e8 m (the Earth's circumference is 4e7 m), no debris moves at
// 1000 m/s, an unwrapped heading of 1e9 degrees is 3e6 turns.
inline constexpr double max_track_coordinate = 1e8;  // [m] |x|, |y|
inline constexpr double max_track_speed = 1000.0;    // [m s-1] |u|, |v|, and the speed from one sample to the next
inline constexpr double max_track_yaw = 1e9;         // [degree] |yaw|
inline constexpr double max_track_yaw_rate = 1e4;    // [rad s-1] |omega|

// The tracks of a trajectory file (flotsam debris) or a sweep file (flotsam sweep), read
// and checked: the time axis one-dimensional, in a unit of time, finite and increasing;
// x and y on (trajectory, time) (yaw, u, v, omega and status too where the file has them,
// all of them with `complete`); units converted to flotsam's (x, y lengths to m; u, v
// speeds to m s-1; yaw an angle to degree; omega to rad s-1) or refused by name. Each
// track is checked as it is read: every value finite (no fill value) and within the
// bounds above, no step between samples faster than max_track_speed, status a
// combination of the five flags. Errors name the file, the variable, the trajectory and
// the time index.
class TrackReader {
public:
    TrackReader(const nc::File& f, bool complete);
    const std::vector<double>& time() const { return time_; }  // [s]
    std::size_t size() const { return trajectories_; }
    // Track b; series the file does not have are empty.
    Track read(std::size_t b) const;

private:
    struct Series {
        const char* name;
        int var = -1;         // -1: not in the file
        double factor = 1.0;  // the file's units to flotsam's
        double bound = 0.0;   // largest magnitude
        const char* what;     // "a position", ...
    };
    void read_series(const Series& s, std::size_t b, std::vector<double>& out) const;
    const nc::File& f_;
    std::vector<double> time_;
    std::size_t trajectories_ = 0;
    Series x_, y_, yaw_, u_, v_, omega_;
    int status_ = -1;
};

// Throws naming the file and the trajectory when a track's positions leave the rectangle
// [x_min, x_max] x [y_min, y_max] [m] of `what` (a flow's grid, a scene's): a body never
// leaves the grid its flow was replayed on.
void check_track_within(const std::string& path, std::size_t trajectory, const Track& track, double x_min, double x_max,
                        double y_min, double y_max, const std::string& what);

// A per-trajectory variable of the file (start_name, cd1, ...), for GIS attributes.
struct TrajectoryColumn {
    std::string name;
    nc_type type = NC_DOUBLE;        // NC_STRING for text (a character array or NC_STRING)
    std::vector<std::string> text;   // text columns
    std::vector<double> number;      // number columns
};

// A trajectory or sweep file read whole and checked (TrackReader), with every
// per-trajectory variable (one-dimensional on trajectory; numbers finite), its CRS and
// its scene's fingerprint.
struct TrajectoryTable {
    std::string path;
    std::string kind;                // "trajectories" or "sweep" (cf::kind_of)
    std::vector<double> time;        // [s]
    std::vector<Track> tracks;       // one per trajectory
    std::vector<TrajectoryColumn> columns;  // in the file's order
    cf::GridMapping crs;
    std::string scene_buildings_sha256;     // formats/scene.hpp; "" when not recorded
};
// `check_columns(file, trajectories)`, when given, checks the per-trajectory columns it
// knows (the body settings: export passes debris's tables) while the file is open.
TrajectoryTable read_trajectory_table(const std::string& path,
                                      const std::function<void(const nc::File&, std::size_t)>& check_columns = {});

}  // namespace flotsam::debris
