#include "hydro/restart_key.hpp"

#include <map>
#include <sstream>

#include "common/sha256.hpp"
#include "hydro/run.hpp"

namespace flotsam::hydro {

namespace {

// name -> value of "name=value" lines (blank lines and lines without '=' are skipped).
std::map<std::string, std::string> settings_of(const std::string& text) {
    std::map<std::string, std::string> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        const auto eq = line.find('=');
        if (eq == std::string::npos) continue;
        auto trim = [](std::string s) {
            const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
            return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
        };
        out[trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
    }
    return out;
}

}  // namespace

std::string restart_key(const RunDef& run, const PhysicsDef& solver) {
    std::map<std::string, std::string> key = settings_of(run.config_text);
    // Paths say where the inputs are, not what they hold: their bytes go in instead.
    key.erase("scene");
    key["scene sha256"] = sha256_file(run.scene_file);
    const BoundaryDef* sides[4] = {&solver.west, &solver.east, &solver.south, &solver.north};
    const char* names[4] = {"west", "east", "south", "north"};
    for (int k = 0; k < 4; ++k) {
        key.erase(std::string(names[k]) + "-series");
        if (!sides[k]->series_file.empty()) key[std::string(names[k]) + "-series sha256"] = sha256_file(sides[k]->series_file);
        key.erase(std::string(names[k]) + "-forcing");
        if (!sides[k]->forcing_file.empty())
            key[std::string(names[k]) + "-forcing sha256"] = sha256_file(sides[k]->forcing_file);
    }
    std::string text;
    for (const auto& [name, value] : key) text += name + " = " + value + "\n";
    return text;
}

std::string differing_settings(const std::string& checkpoint_key, const std::string& current_key) {
    const auto a = settings_of(checkpoint_key), b = settings_of(current_key);
    std::string out;
    auto add = [&](const std::string& name, const std::string& then, const std::string& now) {
        out += (out.empty() ? "" : "; ") + name + ": " + then + " in the checkpoint, " + now + " now";
    };
    for (const auto& [name, value] : a) {
        const auto it = b.find(name);
        if (it == b.end())
            add(name, value, "not set");
        else if (it->second != value)
            add(name, value, it->second);
    }
    for (const auto& [name, value] : b)
        if (!a.count(name)) add(name, "not set", value);
    return out;
}

}  // namespace flotsam::hydro
