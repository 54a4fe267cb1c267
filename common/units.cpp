#include "common/units.hpp"

#include <cctype>
#include <map>

#include "common/error.hpp"

namespace flotsam::units {

namespace {

std::string normalised(const std::string& u) {
    std::string s;
    for (char c : u) s += char(std::tolower(static_cast<unsigned char>(c)));
    const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

const std::map<std::string, double>& lengths() {
    static const std::map<std::string, double> m = {
        {"m", 1.0},          {"metre", 1.0},        {"metres", 1.0},      {"meter", 1.0},       {"meters", 1.0},
        {"cm", 0.01},        {"centimetre", 0.01},  {"centimetres", 0.01}, {"centimeter", 0.01}, {"centimeters", 0.01},
        {"mm", 0.001},       {"millimetre", 0.001}, {"millimetres", 0.001}, {"millimeter", 0.001}, {"millimeters", 0.001},
        {"km", 1000.0},      {"kilometre", 1000.0}, {"kilometres", 1000.0}, {"kilometer", 1000.0}, {"kilometers", 1000.0},
        {"ft", 0.3048},      {"foot", 0.3048},      {"feet", 0.3048},     {"international_foot", 0.3048},
        {"in", 0.0254},      {"inch", 0.0254},      {"inches", 0.0254},   {"mi", 1609.344},     {"mile", 1609.344},
        {"miles", 1609.344}, {"nmile", 1852.0},
    };
    return m;
}

const std::map<std::string, double>& times() {
    static const std::map<std::string, double> m = {
        {"s", 1.0},         {"sec", 1.0},       {"secs", 1.0},      {"second", 1.0},  {"seconds", 1.0}, {"min", 60.0},
        {"mins", 60.0},     {"minute", 60.0},   {"minutes", 60.0},  {"h", 3600.0},    {"hr", 3600.0},   {"hrs", 3600.0},
        {"hour", 3600.0},   {"hours", 3600.0},  {"d", 86400.0},     {"day", 86400.0}, {"days", 86400.0},
    };
    return m;
}

std::optional<double> lookup(const std::map<std::string, double>& m, const std::string& key) {
    const auto it = m.find(key);
    if (it == m.end()) return std::nullopt;
    return it->second;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

}  // namespace

std::optional<double> length_to_metres(const std::string& u) { return lookup(lengths(), normalised(u)); }

std::optional<double> time_to_seconds(const std::string& u) {
    std::string s = normalised(u);
    // "<unit> since <reference>": only the unit matters to flotsam (it uses differences of
    // times and the file's own origin).
    const auto since = s.find(" since ");
    if (since != std::string::npos) s = s.substr(0, since);
    return lookup(times(), s);
}

std::optional<double> speed_to_metres_per_second(const std::string& u) {
    const std::string s = normalised(u);
    if (s == "knot" || s == "knots" || s == "kt" || s == "kn") return 1852.0 / 3600.0;
    if (s == "mph") return 1609.344 / 3600.0;
    // length/time, "length time-1", "length time^-1", "length time**-1", "length.time-1".
    std::string length, time;
    if (const auto slash = s.find('/'); slash != std::string::npos) {
        length = s.substr(0, slash);
        time = s.substr(slash + 1);
    } else {
        std::size_t split = s.find_first_of(" .");
        if (split == std::string::npos) return std::nullopt;
        length = s.substr(0, split);
        time = s.substr(split + 1);
        for (const char* suffix : {"**-1", "^-1", "-1"}) {
            const std::string sfx = suffix;
            if (time.size() > sfx.size() && time.compare(time.size() - sfx.size(), sfx.size(), sfx) == 0) {
                time.erase(time.size() - sfx.size());
                break;
            }
            if (std::string(suffix) == "-1") return std::nullopt;  // no exponent: not a speed
        }
    }
    const auto trim = [](std::string& x) {
        const auto a = x.find_first_not_of(" "), b = x.find_last_not_of(" ");
        x = a == std::string::npos ? std::string() : x.substr(a, b - a + 1);
    };
    trim(length);
    trim(time);
    const auto l = lookup(lengths(), length), t = lookup(times(), time);
    if (!l || !t) return std::nullopt;
    return *l / *t;
}

std::optional<double> angle_to_degrees(const std::string& u) {
    const std::string s = normalised(u);
    if (s == "degree" || s == "degrees" || s == "deg" || s == "degrees_true") return 1.0;
    if (s == "rad" || s == "radian" || s == "radians") return 180.0 / 3.14159265358979323846;
    return std::nullopt;
}

std::optional<double> angular_speed_to_radians_per_second(const std::string& u) {
    std::string s = normalised(u), angle, time;
    if (const auto slash = s.find('/'); slash != std::string::npos) {
        angle = s.substr(0, slash), time = s.substr(slash + 1);
    } else if (const auto space = s.find_first_of(" ."); space != std::string::npos) {
        angle = s.substr(0, space), time = s.substr(space + 1);
        bool exponent = false;
        for (const std::string sfx : {"**-1", "^-1", "-1"})
            if (!exponent && time.size() > sfx.size() && time.compare(time.size() - sfx.size(), sfx.size(), sfx) == 0) {
                time.erase(time.size() - sfx.size());
                exponent = true;
            }
        if (!exponent) return std::nullopt;
    } else {
        return std::nullopt;
    }
    const auto a = angle_to_degrees(angle), t = lookup(times(), time);
    if (!a || !t) return std::nullopt;
    return *a * (3.14159265358979323846 / 180.0) / *t;
}

std::optional<double> force_to_newtons(const std::string& u) {
    const std::string s = normalised(u);
    if (s == "n" || s == "newton" || s == "newtons") return 1.0;
    if (s == "kn" || s == "kilonewton" || s == "kilonewtons") return 1e3;
    if (s == "mn" || s == "meganewton" || s == "meganewtons") return 1e6;
    return std::nullopt;
}

namespace {

std::optional<double> number_factor(const std::string& u) {
    const std::string s = normalised(u);
    if (s == "1" || s == "-" || s == "") return 1.0;
    if (s == "%" || s == "percent") return 0.01;
    return std::nullopt;
}

// s m-1: the inverse of a speed.
std::optional<double> inverse_speed_factor(const std::string& u) {
    std::string s = normalised(u);
    for (const auto& [from, to] : {std::pair{"s m-1", "m s-1"}, std::pair{"s/m", "m/s"}, std::pair{"s m^-1", "m s^-1"}})
        if (s == from) s = to;
    if (s == normalised(u)) return std::nullopt;
    const auto v = speed_to_metres_per_second(s);
    if (!v) return std::nullopt;
    return 1.0 / *v;
}

double factor_of(const nc::File& f, int var, std::optional<double> (*convert)(const std::string&), const char* kind,
                 const char* accepted) {
    const auto u = f.att_text(var, "units");
    if (!u || normalised(*u).empty()) return 1.0;  // none: flotsam's own units
    if (const auto factor = convert(*u)) return *factor;
    fail(f.path(), "variable '" + f.var_name(var) + "' attribute 'units'",
         quoted(*u) + " is not a unit of " + kind + " flotsam can convert (" + accepted + ")");
}

}  // namespace

double length_factor(const nc::File& f, int var) { return factor_of(f, var, length_to_metres, "length", "m, cm, mm, km, ft, in, mi"); }

double time_factor(const nc::File& f, int var) {
    return factor_of(f, var, time_to_seconds, "time", "s, min, h or d, optionally followed by 'since <date>'");
}

double speed_factor(const nc::File& f, int var) {
    return factor_of(f, var, speed_to_metres_per_second, "speed", "a length per time such as m s-1, cm s-1 or km h-1, or knots");
}

double angle_factor(const nc::File& f, int var) { return factor_of(f, var, angle_to_degrees, "angle", "degree or rad"); }

double angular_speed_factor(const nc::File& f, int var) {
    return factor_of(f, var, angular_speed_to_radians_per_second, "angular speed", "rad s-1 or degree s-1");
}

double factor_to(const nc::File& f, int var, const std::string& unit) {
    const auto u = f.att_text(var, "units");
    if (!u || normalised(*u).empty() || normalised(*u) == normalised(unit)) return 1.0;
    if (unit == "m") return length_factor(f, var);
    if (unit == "s") return time_factor(f, var);
    if (unit == "m s-1") return speed_factor(f, var);
    if (unit == "degree") return angle_factor(f, var);
    if (unit == "rad s-1") return angular_speed_factor(f, var);
    if (unit == "N") return factor_of(f, var, force_to_newtons, "force", "N, kN or MN");
    if (unit == "s m-1") return factor_of(f, var, inverse_speed_factor, "inverse speed", "s m-1");
    if (unit == "1" || unit.empty()) return factor_of(f, var, number_factor, "a number", "1 or %");
    fail(f.path(), "variable '" + f.var_name(var) + "' attribute 'units'", quoted(*u) + " where flotsam reads " + quoted(unit));
}

double vertical_sign(const nc::File& f, int var) {
    const auto p = f.att_text(var, "positive");
    if (!p) return 1.0;
    const std::string s = normalised(*p);
    if (s == "up") return 1.0;
    if (s == "down") return -1.0;
    fail(f.path(), "variable '" + f.var_name(var) + "' attribute 'positive'", quoted(*p) + " is neither 'up' nor 'down'");
}

}  // namespace flotsam::units
