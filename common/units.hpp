// Units of the NetCDF files flotsam reads, honoured or refused by name.
//
// flotsam writes metres, seconds and metres per second, and its readers compute in them.
// A file that says other units (a scene's z in feet, x in km, a flow's time in "hours
// since ...", h in cm, u in "km h-1") is converted where CF and UDUNITS define the unit
// (the lengths m, cm, mm, km, ft, in, mi; the times s, min, h, d, optionally "since" a
// reference; a speed as length per time, or knots); any other unit is refused with the
// file, the variable and the unit. A variable without a units attribute is taken to be
// in flotsam's own units (m, s, m s-1). A vertical coordinate with positive = "down"
// counts downward and is negated; any positive other than "up" or "down" is refused.
#pragma once
#include <optional>
#include <string>

#include "common/netcdf.hpp"

namespace flotsam::units {

// The factor that turns a value in `u` into metres (seconds, metres per second); none when
// `u` is not such a unit.
std::optional<double> length_to_metres(const std::string& u);
std::optional<double> time_to_seconds(const std::string& u);  // "s", "hours", "hours since 2000-01-01", ...
std::optional<double> speed_to_metres_per_second(const std::string& u);

std::optional<double> angle_to_degrees(const std::string& u);  // "degree", "deg", "rad", "radians"
std::optional<double> angular_speed_to_radians_per_second(const std::string& u);  // "rad s-1", "degree/s", ...
std::optional<double> force_to_newtons(const std::string& u);                    // "N", "kN", "MN"

// The factor of variable `var`'s units attribute (1 when it has none); throws naming the
// file, the variable and its units when they are not a length (time, speed, angle,
// angular speed).
double length_factor(const nc::File& f, int var);
double time_factor(const nc::File& f, int var);
double speed_factor(const nc::File& f, int var);
double angle_factor(const nc::File& f, int var);          // to degrees
double angular_speed_factor(const nc::File& f, int var);  // to rad s-1

// The factor from `var`'s units to `unit` (1 when it has none or the same): converted
// where `unit` is one flotsam converts to ("m", "s", "m s-1", "degree", "rad s-1", "N",
// "s m-1", and "1" or "" for a number, which takes "1" or "%"); otherwise, and when the
// units do not convert, a named error naming the file, the variable and both units.
double factor_to(const nc::File& f, int var, const std::string& unit);

// +1 for a vertical coordinate whose `positive` attribute is "up" (or absent), -1 for
// "down"; throws naming the file and variable for anything else.
double vertical_sign(const nc::File& f, int var);

}  // namespace flotsam::units
