// A sweep's spec: flows × bodies × start perturbations × model variants × parameter
// sets, read and checked from a TOML file (docs/sweep.md). The parameter designs are
// pure functions of the spec (seeded, platform-independent random numbers), so every
// shard of a sweep reads the same sets. The members it makes: sweep/members.hpp.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/settings.hpp"
#include "debris/body.hpp"
#include "debris/world.hpp"
#include "formats/scene.hpp"

namespace flotsam::sweep {

// The parameters a design varies, in this order everywhere (files, CSV, grids): the
// body's coefficients (debris::body_coefficient_settings(): key, unit, help, range), then
// the drag factor `cd`, which multiplies cd1 and cd2 together (control 1): the paper's
// sensitivity parameter "Cd". A member's body gets the coefficients of its set with the
// factor applied (apply_parameters), so files record cd1 and cd2 as run.
const Settings<debris::BodyDef>& design_parameters();
using ParamValues = std::vector<double>;  // one value per design parameter [-]

struct ParameterSet {
    std::string label;   // "control", "cd1x1.5", "cm/1.5", "grid3", "lhs07", ...
    ParamValues values;  // [-]
    bool is_control = false;
};

// The control case: the defaults of debris::BodyDef, the paper's Cd1 0.8, Cd2 0.4,
// Cm 2.0, Fc (mu) 0.4, and restitution 0.5; drag factor 1.
ParamValues paper_control();

// Sets the design parameters' values on a body.
void apply_parameters(const ParamValues& values, debris::BodyDef& def);

// Control, then each varied parameter times `factor` and divided by it: 1 + 2 n sets.
std::vector<ParameterSet> one_at_a_time(const ParamValues& control, const std::vector<int>& varied, double factor);
// Every combination of the levels (levels[p] empty or absent: the control value), last parameter
// fastest.
std::vector<ParameterSet> factorial(const ParamValues& control, const std::vector<std::vector<double>>& levels);
// Uniform samples over [lo, hi] per parameter (lo == hi: fixed).
using ParamRanges = std::vector<std::array<double, 2>>;
std::vector<ParameterSet> random_samples(const ParamRanges& ranges, int count, std::uint64_t seed);
// Latin hypercube: each parameter's range cut into `count` equal strata, each stratum
// used exactly once, a uniform point inside it.
std::vector<ParameterSet> latin_hypercube(const ParamRanges& ranges, int count, std::uint64_t seed);

// How the parameter sets are chosen ([parameters] design = ...).
enum class Design { control, one_at_a_time, factorial, random, latin_hypercube };
inline constexpr EnumNames<Design, 7> design_names{"design",
                                                   {{{Design::control, "control"},
                                                     {Design::one_at_a_time, "one_at_a_time"},
                                                     {Design::factorial, "factorial"},
                                                     {Design::random, "random"},
                                                     {Design::latin_hypercube, "latin_hypercube"},
                                                     {Design::one_at_a_time, "one-at-a-time"},
                                                     {Design::latin_hypercube, "latin-hypercube"}}}};
constexpr const auto& enum_names(Design) { return design_names; }

// Deterministic random numbers (SplitMix64): same values on every platform and library.
struct Rng {
    std::uint64_t state;
    explicit Rng(std::uint64_t seed) : state(seed) {}
    std::uint64_t next();
    double uniform();  // [0, 1)
    double normal();   // standard normal (Box–Muller)
};

// "CC+SC", "LC+MC" (also CC+MC, LC+SC): friction model + collision model.
struct Variant {
    std::string name;
    debris::ContactModel contact = debris::ContactModel::local;
    debris::CollisionModel collision = debris::CollisionModel::multi;
};
Variant parse_variant(const std::string& name);  // throws naming the bad text

struct BodySpec {
    std::string name;                                  // label ("FD", or the [[body]] name)
    std::string start;                                 // scene start point, or "" when at = [x, y, heading]
    double x = 0.0, y = 0.0;                           // [m], from the scene point or `at`
    double heading_deg = 0.0;                          // long axis from +x, counter-clockwise [degree]
    double heading = 0.0;                              // the same [rad], as the unperturbed start uses it
    debris::BodyDef def = debris::default_body_def();  // shape and model settings ([[body]], [sweep])
    // Catalogue entry (debris/catalogue.hpp), "" for none. Such a body keeps the entry's
    // coefficients as its own control: a parameter set multiplies them by the set's
    // value over the spec's control value (so "cd1x1.5" is 1.5 x the body's own cd1).
    std::string type;
    std::string source;  // the GIS feature "layer/fid" it came from ([[sources]]), or ""
};

// A body at (x, y) with a heading in degrees, its shape and model from `def`: how specs'
// [[body]] tables and `flotsam debris` place a body (the name as given; no start point).
BodySpec body_at(const std::string& name, double x, double y, double heading_deg, const debris::BodyDef& def);
// The scene's start point of that name (null: none).
const ScenePoint* scene_start(const Scene& scene, const std::string& name);

// A [[sources]] table: a GIS file of debris sources (data/source_features.hpp), expanded
// into bodies by the command line (app/sourced_bodies.hpp, which reads GIS) before the
// sweep runs. `model` holds the [sweep] model settings and the table's own.
struct SourceFileSpec {
    std::string file;                 // vector file (GeoPackage, shapefile, GeoJSON, ...)
    std::vector<std::string> layers;  // its layers to read; empty: all
    debris::BodyDef model = debris::default_body_def();
    int line = 0;                     // of the [[sources]] header, for messages
};

struct PerturbationDef {
    int count = 0;              // perturbed starts per body besides the exact one [-]
    double position_std = 0.0;  // Gaussian offset of x and y [m]
    double heading_std = 0.0;   // Gaussian offset of the heading [degree]
    std::uint64_t seed = 1;
};

struct SweepSpec {
    std::string path;                // the spec file (for messages)
    std::string sha256;              // of the spec file's bytes
    std::string scene;               // scene file: start points and building mask ("" : none)
    std::string ground;              // a finer scene the bodies stand on (debris::Ground; "" : the flows' beds)
    std::vector<std::string> flows;  // flow files, in order
    std::vector<BodySpec> bodies;
    std::vector<SourceFileSpec> sources;  // not yet expanded into `bodies`
    std::vector<Variant> variants;
    std::vector<ParameterSet> params;
    ParamValues control = paper_control();  // the [parameters] control values
    std::string design;                     // "control", "one_at_a_time", "factorial", "random", "latin_hypercube"
    PerturbationDef perturbation;
    double output_interval = 1.0;                          // trajectory sample spacing [s]
    double end_time = -1.0;                                // [s]; < 0: the earliest last frame of the flows
    debris::WorldDef world = debris::default_world_def();  // step and flow replay settings ([sweep])
    bool dt_max_given = false;  // [sweep] dt-max set; else the step follows the bodies (debris::default_world_def)
    // The members keep their bodies' coefficients as given, no parameter set applied
    // (`flotsam debris`: a sweep of one control run). False for specs.
    bool bodies_as_given = false;
    // Every body of the spec is in one run (`flotsam debris`); false: the bodies of one GIS
    // source feature (a yard) share a run, any other body runs alone.
    bool one_world = false;
};

// What the command line sets over a spec's own: scene, ground and flows ("" and empty:
// the spec's).
struct SpecOverrides {
    std::string scene;
    std::string ground;
    std::vector<std::string> flows;
};

// Reads and checks a spec. Bodies given by a scene start name are placed from the scene
// (the spec's `scene`, or the override). Errors name the spec file, line and key. With
// `scene`, the scene the spec names is read (once) and handed back there (null: none).
SweepSpec read_sweep_spec(const std::string& path, const SpecOverrides& overrides, std::shared_ptr<const Scene>* scene);
SweepSpec read_sweep_spec(const std::string& path, const std::string& scene_override = "",
                          const std::vector<std::string>& flow_override = {});

// A parameter set's values for a catalogue body (BodySpec::type): each coefficient is the
// entry's own times the set's value over the spec's control value.
ParamValues catalogue_values(const SweepSpec& spec, const BodySpec& body, const ParamValues& set);

}  // namespace flotsam::sweep
