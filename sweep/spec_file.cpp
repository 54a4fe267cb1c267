#include "sweep/spec_file.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <numbers>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/sha256.hpp"
#include "common/toml_lite.hpp"
#include "debris/catalogue.hpp"
#include "formats/scene.hpp"

namespace flotsam::sweep {

const Settings<debris::BodyDef>& design_parameters() {
    static const Settings<debris::BodyDef> table = [] {
        Settings<debris::BodyDef> t = debris::body_coefficient_settings();
        t.push_back({"cd", "1", "drag factor Cd: multiplies cd1 and cd2 together (the paper's sensitivity parameter Cd)",
                     Range::positive().up_to(100.0), Factor<debris::BodyDef>{{&debris::BodyDef::cd1, &debris::BodyDef::cd2}}});
        return t;
    }();
    return table;
}

ParamValues paper_control() {
    ParamValues out;
    for (const auto& p : design_parameters()) out.push_back(p.number(debris::default_body_def()));
    return out;
}

void apply_parameters(const ParamValues& values, debris::BodyDef& def) {
    const auto& table = design_parameters();
    // Members first, then the factors that scale them.
    for (bool factors : {false, true})
        for (std::size_t p = 0; p < table.size(); ++p)
            if (table[p].is_factor() == factors) table[p].set_number(def, values[p]);
}

Variant parse_variant(const std::string& name) {
    Variant v;
    v.name = name;
    const auto plus = name.find('+');
    const std::string c = plus == std::string::npos ? name : name.substr(0, plus);
    const std::string k = plus == std::string::npos ? std::string() : name.substr(plus + 1);
    if ((c != "CC" && c != "LC") || (k != "SC" && k != "MC"))
        fail("variant", "'" + name + "'", "expected CC+SC, LC+MC, CC+MC or LC+SC (friction + collision model)");
    v.contact = c == "CC" ? debris::ContactModel::center : debris::ContactModel::local;
    v.collision = k == "SC" ? debris::CollisionModel::single : debris::CollisionModel::multi;
    return v;
}

namespace {

const TomlTable* find_table(const TomlDoc& doc, const std::string& name) {
    for (const auto& t : doc.tables)
        if (t.name == name) return &t;
    return nullptr;
}

bool has(const TomlTable& t, const std::string& key) { return t.values.count(key) > 0; }

// A number of the spec in its range; the error names the file, line and key.
double number_in(const TomlDoc& doc, const TomlTable& t, const std::string& key, const Range& range) {
    const double v = toml_number(doc, t, key);
    const std::string problem = range_problem(v, range);
    if (!problem.empty()) toml_fail(doc, t, key, problem);
    return v;
}

std::uint64_t seed_of(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    return has(t, key) ? std::uint64_t(number_in(doc, t, key, Range::count(0, 9e15))) : 1;
}

std::vector<std::string> keys_with(std::vector<std::string> keys, const std::vector<std::string>& more) {
    keys.insert(keys.end(), more.begin(), more.end());
    return keys;
}

// Flow files matching "dir/prefix*suffix" (one '*' in the file name), sorted by name.
std::vector<std::string> glob_flows(const TomlDoc& doc, const TomlTable& t, const std::string& pattern) {
    const std::filesystem::path p(pattern);
    const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
    const std::string name = p.filename().string();
    const auto star = name.find('*');
    if (star == std::string::npos || name.find('*', star + 1) != std::string::npos)
        toml_fail(doc, t, "pattern", "expects exactly one '*' in the file name (e.g. runs/flows/flow_r*.nc)");
    const std::string pre = name.substr(0, star), post = name.substr(star + 1);
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
        const std::string f = e.path().filename().string();
        if (f.size() >= pre.size() + post.size() && f.starts_with(pre) && f.ends_with(post))
            out.push_back((p.has_parent_path() ? p.parent_path() / f : std::filesystem::path(f)).string());
    }
    if (ec) toml_fail(doc, t, "pattern", "cannot list directory '" + dir + "': " + ec.message());
    std::sort(out.begin(), out.end());
    if (out.empty()) toml_fail(doc, t, "pattern", "no file matches '" + pattern + "'");
    return out;
}

// The parameters a one-at-a-time design varies ("vary"; default cd1, cd2, cm, mu), as
// indices into design_parameters().
std::vector<int> varied_parameters(const TomlDoc& doc, const TomlTable& t) {
    const auto& table = design_parameters();
    std::vector<int> varied;
    const std::vector<std::string> names =
        has(t, "vary") ? toml_strings(doc, t, "vary") : std::vector<std::string>{"cd1", "cd2", "cm", "mu"};
    for (const auto& n : names) {
        const Setting<debris::BodyDef>* p = find_setting(table, n);
        if (!p) {
            std::string list;
            for (const auto& k : setting_keys(table)) list += (list.empty() ? "" : ", ") + k;
            toml_fail(doc, t, "vary", "unknown parameter '" + n + "' (" + list + ")");
        }
        varied.push_back(int(p - table.data()));
    }
    return varied;
}

// A factorial design is counted before a set is built: the product of the levels' counts,
// at most 1e6.
void check_factorial_size(const TomlDoc& doc, const TomlTable& t, const std::vector<std::vector<double>>& levels) {
    const auto& table = design_parameters();
    double sets = 1;
    std::string product;
    for (std::size_t p = 0; p < levels.size(); ++p)
        if (!levels[p].empty()) {
            sets *= double(levels[p].size());
            product += (product.empty() ? "" : " x ") + std::to_string(levels[p].size()) + " (" + table[p].key + ")";
        }
    if (sets > 1e6)
        toml_fail(doc, t, "design",
                  "a factorial of " + product + " levels is " + number_text(sets) +
                      " parameter sets, more than 1e6 (a random or latin_hypercube design samples a large space)");
}

// [parameters]: the design and the values of the design parameters. Scalars set the
// control (and fixed) values; arrays are levels (factorial) or [low, high] ranges
// (random, latin_hypercube).
void read_parameters(const TomlDoc& doc, const TomlTable* t, SweepSpec& spec) {
    const auto& table = design_parameters();
    const std::size_t np = table.size();
    ParamValues control = paper_control();
    if (!t) {
        spec.design = enum_name(Design::control);
        spec.params = {{"control", control, true}};
        return;
    }
    toml_allow_only(doc, *t, keys_with({"design", "factor", "vary", "samples", "seed", "include-control"}, setting_keys(table)));
    const Design d = has(*t, "design") ? toml_enum<Design>(doc, *t, "design") : Design::control;
    spec.design = enum_name(d);
    const bool sampled = d == Design::random || d == Design::latin_hypercube;
    for (const std::string key : {"factor", "vary"})
        if (has(*t, key) && d != Design::one_at_a_time) toml_fail(doc, *t, key, "only for design = \"one_at_a_time\"");
    for (const std::string key : {"samples", "seed"})
        if (has(*t, key) && !sampled) toml_fail(doc, *t, key, "only for design = \"random\" or \"latin_hypercube\"");

    std::vector<std::vector<double>> arrays(np);
    for (std::size_t p = 0; p < np; ++p) {
        const std::string& key = table[p].key;
        if (!has(*t, key)) continue;
        const TomlValue& v = t->values.at(key);
        if (v.kind == TomlValue::Kind::Number) {
            control[p] = v.number;
        } else if (v.kind == TomlValue::Kind::NumberArray) {
            if (d != Design::factorial && !sampled)
                toml_fail(doc, *t, key, "an array (levels or a range) needs a factorial, random or latin_hypercube design");
            if (v.numbers.empty()) toml_fail(doc, *t, key, "empty array");
            if (sampled && (v.numbers.size() != 2 || !(v.numbers[0] <= v.numbers[1])))
                toml_fail(doc, *t, key, "a range is [low, high] with low <= high");
            arrays[p] = v.numbers;
        } else {
            toml_fail(doc, *t, key, "must be a number or an array of numbers");
        }
    }
    spec.control = control;
    const bool include_control = has(*t, "include-control") ? toml_bool(doc, *t, "include-control") : true;
    if (d == Design::control) {
        spec.params = {{"control", control, true}};
    } else if (d == Design::one_at_a_time) {
        const double factor = has(*t, "factor") ? number_in(doc, *t, "factor", Range::positive()) : 1.5;
        spec.params = one_at_a_time(control, varied_parameters(doc, *t), factor);
    } else if (d == Design::factorial) {
        check_factorial_size(doc, *t, arrays);
        spec.params = factorial(control, arrays);
        const bool found = std::any_of(spec.params.begin(), spec.params.end(), [](const ParameterSet& s) { return s.is_control; });
        if (include_control && !found) spec.params.insert(spec.params.begin(), {"control", control, true});
        if (!include_control)
            for (auto& s : spec.params) s.is_control = false;
    } else {
        const int n = int(number_in(doc, *t, "samples", Range::count(1, 1e6)));
        ParamRanges ranges(np);
        for (std::size_t p = 0; p < np; ++p)
            ranges[p] = arrays[p].empty() ? std::array<double, 2>{control[p], control[p]}
                                          : std::array<double, 2>{arrays[p][0], arrays[p][1]};
        spec.params = d == Design::random ? random_samples(ranges, n, seed_of(doc, *t, "seed"))
                                          : latin_hypercube(ranges, n, seed_of(doc, *t, "seed"));
        if (include_control) spec.params.insert(spec.params.begin(), {"control", control, true});
    }
    // The body model rejects impossible values; check here to name the spec and key.
    for (const auto& s : spec.params)
        for (std::size_t p = 0; p < np; ++p) {
            const std::string problem = range_problem(s.values[p], table[p].range);
            if (!problem.empty())
                toml_fail(doc, *t, table[p].key, "parameter set '" + s.label + "' gets " + table[p].key + " = " + problem);
        }
}

// [sweep]: the scene, the output times, and the step, flow replay and body model
// settings for every member.
void read_sweep_table(const TomlDoc& doc, const TomlTable* t, SweepSpec& spec, debris::BodyDef& body_model) {
    if (!t) return;
    toml_allow_only(
        doc, *t,
        keys_with(keys_with(keys_with({"scene", "ground", "output-interval", "end-time"}, setting_keys(debris::step_settings())),
                            setting_keys(debris::flow_replay_settings())),
                  setting_keys(debris::body_model_settings())));
    if (has(*t, "scene")) spec.scene = toml_string(doc, *t, "scene");
    if (has(*t, "ground")) spec.ground = toml_string(doc, *t, "ground");
    if (has(*t, "output-interval")) spec.output_interval = number_in(doc, *t, "output-interval", Range::positive("s"));
    if (has(*t, "end-time")) spec.end_time = number_in(doc, *t, "end-time", Range::positive("s"));
    read_settings(doc, *t, debris::step_settings(), spec.world.step);
    spec.dt_max_given = has(*t, "dt-max");
    read_settings(doc, *t, debris::flow_replay_settings(), spec.world.flow);
    read_settings(doc, *t, debris::body_model_settings(), body_model);
}

}  // namespace

BodySpec body_at(const std::string& name, double x, double y, double heading_deg, const debris::BodyDef& def) {
    BodySpec b;
    b.name = name;
    b.x = x;
    b.y = y;
    b.heading_deg = heading_deg;
    b.heading = heading_deg * (std::numbers::pi / 180.0);
    b.def = def;
    b.def.name = name;
    b.def.x = x;
    b.def.y = y;
    b.def.heading = b.heading;
    return b;
}

const ScenePoint* scene_start(const Scene& scene, const std::string& name) {
    const ScenePoint* p = scene.find_point(name);
    return p && p->kind == "start" ? p : nullptr;
}

namespace {

// One [[body]]: where it starts (a scene point or coordinates), its name, and its shape
// and model settings over those of [sweep].
BodySpec read_body(const TomlDoc& doc, const TomlTable& t, SweepSpec& spec, const debris::BodyDef& body_model,
                   std::shared_ptr<const Scene>& scene) {
    toml_allow_only(doc, t,
                    keys_with(keys_with({"start", "at", "name", "type"}, setting_keys(debris::body_shape_settings())),
                              setting_keys(debris::body_model_settings())));
    debris::BodyDef def = body_model;
    std::string type;
    if (has(t, "type")) {  // a catalogue entry: its shape and coefficients
        type = toml_string(doc, t, "type");
        if (!debris::find_catalogue_body(type))
            toml_fail(doc, t, "type", "'" + type + "' is not in the debris catalogue (" + debris::catalogue_names() + ")");
        const debris::BodyDef entry = debris::catalogue_body_def(type, doc.path);
        for (const auto* table : {&debris::body_shape_settings(), &debris::body_coefficient_settings()})
            for (const auto& setting : *table) setting.set_number(def, setting.number(entry));
        def.impact_stiffness = entry.impact_stiffness;
    }
    read_settings(doc, t, debris::body_shape_settings(), def);
    read_settings(doc, t, debris::body_model_settings(), def);
    if (has(t, "start") == has(t, "at"))
        toml_fail(doc, t, "start", "give exactly one of start = \"NAME\" (a scene point) and at = [x, y, heading_deg]");
    BodySpec b;
    if (has(t, "start")) {
        const std::string start = toml_string(doc, t, "start");
        if (spec.scene.empty()) toml_fail(doc, t, "start", "a named start needs a scene ([sweep] scene = \"...\" or --scene)");
        if (!scene) scene = std::make_shared<const Scene>(read_scene(spec.scene));
        const ScenePoint* p = scene_start(*scene, start);
        if (!p) toml_fail(doc, t, "start", "scene '" + spec.scene + "' has no start point '" + start + "'");
        b = body_at(start, p->x, p->y, p->heading_deg, def);
        b.start = start;
    } else {
        const std::vector<double> at = toml_numbers(doc, t, "at");
        if (at.size() != 3) toml_fail(doc, t, "at", "expected [x, y, heading_deg]");
        b = body_at("body" + std::to_string(spec.bodies.size()), at[0], at[1], at[2], def);
    }
    b.type = type;
    if (has(t, "name")) b.name = toml_string(doc, t, "name");
    if (b.name.empty()) toml_fail(doc, t, "name", "must not be empty");
    for (const auto& other : spec.bodies)
        if (other.name == b.name)
            toml_fail(doc, t, has(t, "name") ? "name" : "start", "body name '" + b.name + "' used twice (set name = \"...\")");
    return b;
}

// One [[sources]]: a GIS file of debris sources, its layers, and model settings over [sweep]'s.
SourceFileSpec read_sources(const TomlDoc& doc, const TomlTable& t, const SweepSpec& spec, const debris::BodyDef& body_model) {
    toml_allow_only(doc, t, keys_with({"file", "layers"}, setting_keys(debris::body_model_settings())));
    SourceFileSpec s;
    s.line = t.line;
    s.model = body_model;
    if (!has(t, "file")) toml_fail(doc, t, "file", "missing: the GIS file of debris sources (points and yard polygons)");
    s.file = toml_string(doc, t, "file");
    if (has(t, "layers")) s.layers = toml_strings(doc, t, "layers");
    if (spec.scene.empty()) toml_fail(doc, t, "file", "sources need a scene ([sweep] scene = \"...\" or --scene): its CRS places them");
    read_settings(doc, t, debris::body_model_settings(), s.model);
    return s;
}

}  // namespace

ParamValues catalogue_values(const SweepSpec& spec, const BodySpec& body, const ParamValues& set) {
    const auto& table = design_parameters();
    ParamValues v = set;
    for (std::size_t p = 0; p < table.size(); ++p) {
        const double control = spec.control[p];
        if (table[p].is_factor() || !(control > 0)) continue;  // a factor scales every body alike
        v[p] = table[p].number(body.def) * (set[p] / control);
        v[p] = std::min(v[p], table[p].range.max);  // a scaled restitution stays at most 1
    }
    return v;
}

namespace {

void read_flows(const TomlDoc& doc, const TomlTable* t, SweepSpec& spec) {
    if (!t) fail(doc.path, "[flows]", "missing: give paths = [\"flow.nc\", ...] or pattern = \"dir/flow_r*.nc\" (or --flow)");
    toml_allow_only(doc, *t, {"paths", "pattern"});
    if (has(*t, "paths") == has(*t, "pattern")) toml_fail(doc, *t, "paths", "give exactly one of paths and pattern");
    spec.flows = has(*t, "paths") ? toml_strings(doc, *t, "paths") : glob_flows(doc, *t, toml_string(doc, *t, "pattern"));
    if (spec.flows.empty()) toml_fail(doc, *t, "paths", "no flow files listed");
    for (const auto& f : spec.flows)
        if (!std::filesystem::exists(f))
            toml_fail(doc, *t, has(*t, "paths") ? "paths" : "pattern", "flow file '" + f + "' does not exist");
}

void read_variants(const TomlDoc& doc, const TomlTable* t, SweepSpec& spec) {
    if (!t) {
        spec.variants = {parse_variant("LC+MC")};
        return;
    }
    toml_allow_only(doc, *t, {"names"});
    for (const auto& n : toml_strings(doc, *t, "names")) {
        try {
            spec.variants.push_back(parse_variant(n));
        } catch (const Error& e) {
            toml_fail(doc, *t, "names", e.what());
        }
        for (std::size_t k = 0; k + 1 < spec.variants.size(); ++k)
            if (spec.variants[k].name == n) toml_fail(doc, *t, "names", "variant '" + n + "' listed twice");
    }
    if (spec.variants.empty()) toml_fail(doc, *t, "names", "no variants listed");
}

void read_perturbation(const TomlDoc& doc, const TomlTable* t, SweepSpec& spec) {
    if (!t) return;
    toml_allow_only(doc, *t, {"count", "position-std", "heading-std", "seed"});
    if (has(*t, "count")) spec.perturbation.count = int(number_in(doc, *t, "count", Range::count(0, 1e6)));
    if (has(*t, "position-std")) spec.perturbation.position_std = number_in(doc, *t, "position-std", Range::non_negative("m"));
    if (has(*t, "heading-std")) spec.perturbation.heading_std = number_in(doc, *t, "heading-std", Range::non_negative("degree"));
    spec.perturbation.seed = seed_of(doc, *t, "seed");
}

}  // namespace

SweepSpec read_sweep_spec(const std::string& path, const std::string& scene_override,
                          const std::vector<std::string>& flow_override) {
    return read_sweep_spec(path, SpecOverrides{scene_override, "", flow_override}, nullptr);
}

SweepSpec read_sweep_spec(const std::string& path, const SpecOverrides& overrides, std::shared_ptr<const Scene>* scene_read) {
    const TomlDoc doc = read_toml_lite(path);
    SweepSpec spec;
    spec.path = path;
    spec.sha256 = sha256_file(path);
    for (const auto& t : doc.tables)
        if (t.name != "" && t.name != "sweep" && t.name != "flows" && t.name != "body" && t.name != "sources" &&
            t.name != "variants" && t.name != "parameters" && t.name != "perturbation")
            fail(path, "line " + std::to_string(t.line),
                 "unknown table [" + t.name + "] (sweep, flows, [[body]], [[sources]], variants, parameters, perturbation)");
    toml_allow_only(doc, doc.tables.front(), {});

    debris::BodyDef body_model = debris::default_body_def();
    read_sweep_table(doc, find_table(doc, "sweep"), spec, body_model);
    if (!overrides.scene.empty()) spec.scene = overrides.scene;
    if (!overrides.ground.empty()) spec.ground = overrides.ground;
    if (!overrides.flows.empty())
        spec.flows = overrides.flows;
    else
        read_flows(doc, find_table(doc, "flows"), spec);
    std::shared_ptr<const Scene> scene;  // read once, where a start point or the caller needs it
    for (const auto& t : doc.tables) {
        if (t.name == "body") spec.bodies.push_back(read_body(doc, t, spec, body_model, scene));
        if (t.name == "sources") spec.sources.push_back(read_sources(doc, t, spec, body_model));
    }
    if (spec.bodies.empty() && spec.sources.empty())
        fail(path, "[[body]]",
             "missing: give at least one [[body]] with start = \"FD\" or at = [x, y, heading_deg], or [[sources]] with file = "
             "\"layers.gpkg\"");
    read_variants(doc, find_table(doc, "variants"), spec);
    read_parameters(doc, find_table(doc, "parameters"), spec);
    read_perturbation(doc, find_table(doc, "perturbation"), spec);
    if (scene_read) {
        if (!scene && !spec.scene.empty()) scene = std::make_shared<const Scene>(read_scene(spec.scene));
        *scene_read = std::move(scene);
    }
    return spec;
}

}  // namespace flotsam::sweep
