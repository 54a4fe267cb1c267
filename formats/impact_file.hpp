// Impacts of bodies on buildings, as trajectory and sweep files hold them: a ragged list
// on its own dimension `impact`, one row per impact (docs/debris.md, "Impacts on
// buildings"), ordered by trajectory and then by time.
//
//   impact_time(impact)        double, the file's time units: when the impact was resolved
//   impact_trajectory(impact)  int, index along the file's trajectory dimension
//   impact_building(impact)    int, the building (the scene's building_id, from 1)
//   impact_x, impact_y         double [m]: the contact point
//   impact_speed(impact)       double [m s-1]: approach speed along the contact normal
//   impact_force(impact)       double [N]: the impact-force estimate (attribute `formula`)
//   impact_mass(impact)        double [kg]: the body's mass
//
// The dimension and the variables are there only where some impact was recorded, so a
// file of a run without impacts is what it was before impacts were recorded.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/netcdf.hpp"

namespace flotsam {

struct Impact {
    double time = 0.0;         // [s] the end of the step that resolved the contact
    int trajectory = 0;        // index of the body in its file (its World index while running)
    std::int32_t building = 0; // the scene's building_id (> 0)
    double x = 0.0, y = 0.0;   // contact point [m], the file's coordinates
    double speed = 0.0;        // approach speed along the contact normal before the impulse [m/s]
    double force = 0.0;        // impact-force estimate [N]
    double mass = 0.0;         // the body's mass [kg]
};

// The names of the variables, in the order of the file.
const std::vector<std::string>& impact_variable_names();

// Defines the dimension and the variables (nothing where `count` is 0); `formula` goes
// into impact_force's attributes. Returns the variable ids (empty where none).
std::vector<int> define_impact_variables(nc::File& f, std::size_t count, const cf::GridMapping& crs, const std::string& formula);
void put_impacts(nc::File& f, const std::vector<int>& vars, const std::vector<Impact>& impacts);

// The impacts of a file (none where it has no `impact` dimension); errors name the file
// and the variable: a trajectory index outside [0, trajectories), a building below 1, a
// value that is not finite or a negative speed, force or mass.
std::vector<Impact> read_impacts(const nc::File& f, std::size_t trajectories);

// One row per impact: trajectory, its label, building, time_s, x_m, y_m, speed_m_s,
// force_N, mass_kg. Written atomically.
void write_impacts_csv(const std::string& path, const std::vector<Impact>& impacts, const std::vector<std::string>& labels);

}  // namespace flotsam
