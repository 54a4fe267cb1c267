#include "sweep/sweep_spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "common/error.hpp"
#include "common/sha256.hpp"
#include "common/toml_lite.hpp"
#include "debris/catalogue.hpp"
#include "formats/scene.hpp"

namespace flotsam::sweep {

ParamValues paper_control() { return {0.8, 0.4, 2.0, 0.4, 0.5}; }

namespace {

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string numbered(const char* prefix, int k, int count) {
    const std::size_t digits = std::max<std::size_t>(2, std::to_string(std::max(count - 1, 0)).size());
    std::string n = std::to_string(k);
    return prefix + std::string(digits > n.size() ? digits - n.size() : 0, '0') + n;
}

}  // namespace

std::uint64_t Rng::next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

double Rng::uniform() { return double(next() >> 11) * 0x1.0p-53; }

double Rng::normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();  // u1 in (0, 1]
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::vector<ParameterSet> one_at_a_time(const ParamValues& control, const std::vector<int>& varied, double factor) {
    std::vector<ParameterSet> out{{"control", control, true}};
    for (int p : varied) {
        ParameterSet up{std::string(parameter_names[p]) + "x" + fmt(factor), control, false};
        up.values[p] = control[p] * factor;
        ParameterSet down{std::string(parameter_names[p]) + "/" + fmt(factor), control, false};
        down.values[p] = control[p] / factor;
        out.push_back(up);
        out.push_back(down);
    }
    return out;
}

std::vector<ParameterSet> factorial(const ParamValues& control, const std::array<std::vector<double>, 5>& levels) {
    std::array<std::vector<double>, 5> lv;
    std::size_t total = 1;
    for (std::size_t p = 0; p < 5; ++p) {
        lv[p] = levels[p].empty() ? std::vector<double>{control[p]} : levels[p];
        total *= lv[p].size();
    }
    std::vector<ParameterSet> out;
    for (std::size_t k = 0; k < total; ++k) {
        ParameterSet s{numbered("grid", int(k), int(total)), {}, false};
        std::size_t rest = k;
        for (int p = 4; p >= 0; --p) {  // last parameter fastest
            s.values[p] = lv[p][rest % lv[p].size()];
            rest /= lv[p].size();
        }
        s.is_control = s.values == control;
        out.push_back(s);
    }
    return out;
}

std::vector<ParameterSet> random_samples(const std::array<std::array<double, 2>, 5>& ranges, int count, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<ParameterSet> out;
    for (int k = 0; k < count; ++k) {
        ParameterSet s{numbered("random", k, count), {}, false};
        for (std::size_t p = 0; p < 5; ++p) s.values[p] = ranges[p][0] + (ranges[p][1] - ranges[p][0]) * rng.uniform();
        out.push_back(s);
    }
    return out;
}

std::vector<ParameterSet> latin_hypercube(const std::array<std::array<double, 2>, 5>& ranges, int count, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<ParameterSet> out(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) out[std::size_t(k)].label = numbered("lhs", k, count);
    for (std::size_t p = 0; p < 5; ++p) {
        std::vector<int> strata(static_cast<std::size_t>(count));
        for (int k = 0; k < count; ++k) strata[std::size_t(k)] = k;
        for (int k = count - 1; k > 0; --k)
            std::swap(strata[std::size_t(k)], strata[std::size_t(rng.next() % std::uint64_t(k + 1))]);  // Fisher–Yates
        for (int k = 0; k < count; ++k) {
            const double u = (strata[std::size_t(k)] + rng.uniform()) / count;
            out[std::size_t(k)].values[p] = ranges[p][0] + (ranges[p][1] - ranges[p][0]) * u;
        }
    }
    return out;
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

[[noreturn]] void bad(const TomlDoc& doc, const TomlTable& t, const std::string& key, const std::string& problem) {
    fail(toml_where(doc, t, key), (t.name.empty() ? "" : "[" + t.name + "] ") + "key '" + key + "'", problem);
}

double positive(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    const double v = toml_number(doc, t, key);
    if (!(v > 0)) bad(doc, t, key, "must be positive");
    return v;
}

int count_of(const TomlDoc& doc, const TomlTable& t, const std::string& key, int min) {
    const double v = toml_number(doc, t, key);
    if (v != std::floor(v) || v < min || v > 1e6) bad(doc, t, key, "must be a whole number >= " + std::to_string(min));
    return int(v);
}

std::uint64_t seed_of(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    if (!has(t, key)) return 1;
    const double v = toml_number(doc, t, key);
    if (v != std::floor(v) || v < 0 || v > 9e15) bad(doc, t, key, "must be a whole number >= 0");
    return std::uint64_t(v);
}

// Flow files matching "dir/prefix*suffix" (one '*' in the file name), sorted by name.
std::vector<std::string> glob_flows(const TomlDoc& doc, const TomlTable& t, const std::string& pattern) {
    const std::filesystem::path p(pattern);
    const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
    const std::string name = p.filename().string();
    const auto star = name.find('*');
    if (star == std::string::npos || name.find('*', star + 1) != std::string::npos)
        bad(doc, t, "pattern", "expects exactly one '*' in the file name (e.g. runs/flows/flow_r*.nc)");
    const std::string pre = name.substr(0, star), post = name.substr(star + 1);
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
        const std::string f = e.path().filename().string();
        if (f.size() >= pre.size() + post.size() && f.starts_with(pre) && f.ends_with(post))
            out.push_back((p.has_parent_path() ? p.parent_path() / f : std::filesystem::path(f)).string());
    }
    if (ec) bad(doc, t, "pattern", "cannot list directory '" + dir + "': " + ec.message());
    std::sort(out.begin(), out.end());
    if (out.empty()) bad(doc, t, "pattern", "no file matches '" + pattern + "'");
    return out;
}

void read_parameters(const TomlDoc& doc, const TomlTable* t, SweepSpec& spec) {
    ParamValues control = paper_control();
    if (!t) {
        spec.design = "control";
        spec.params = {{"control", control, true}};
        return;
    }
    std::vector<std::string> allowed = {"design", "factor", "vary", "samples", "seed", "include_control"};
    for (const char* p : parameter_names) allowed.emplace_back(p);
    toml_allow_only(doc, *t, allowed);
    spec.design = has(*t, "design") ? toml_string(doc, *t, "design") : std::string("control");
    const std::string& d = spec.design;
    if (d != "control" && d != "one_at_a_time" && d != "factorial" && d != "random" && d != "latin_hypercube")
        bad(doc, *t, "design", "unknown design '" + d + "' (control, one_at_a_time, factorial, random, latin_hypercube)");
    const bool sampled = d == "random" || d == "latin_hypercube";
    for (const std::string key : {"factor", "vary"})
        if (has(*t, key) && d != "one_at_a_time") bad(doc, *t, key, "only for design = \"one_at_a_time\"");
    for (const std::string key : {"samples", "seed"})
        if (has(*t, key) && !sampled) bad(doc, *t, key, "only for design = \"random\" or \"latin_hypercube\"");

    // Scalars set the control (and fixed) values; arrays are levels (factorial) or
    // [low, high] ranges (random, latin_hypercube).
    std::array<std::vector<double>, 5> arrays;
    for (std::size_t p = 0; p < 5; ++p) {
        const std::string key = parameter_names[p];
        if (!has(*t, key)) continue;
        const TomlValue& v = t->values.at(key);
        if (v.kind == TomlValue::Kind::Number) {
            control[p] = v.number;
        } else if (v.kind == TomlValue::Kind::NumberArray) {
            if (d != "factorial" && !sampled)
                bad(doc, *t, key, "an array (levels or a range) needs a factorial, random or latin_hypercube design");
            if (v.numbers.empty()) bad(doc, *t, key, "empty array");
            if (sampled && (v.numbers.size() != 2 || !(v.numbers[0] <= v.numbers[1])))
                bad(doc, *t, key, "a range is [low, high] with low <= high");
            arrays[p] = v.numbers;
        } else {
            bad(doc, *t, key, "must be a number or an array of numbers");
        }
    }
    spec.control = control;
    const bool include_control = has(*t, "include_control") ? toml_bool(doc, *t, "include_control") : true;
    if (d == "control") {
        spec.params = {{"control", control, true}};
    } else if (d == "one_at_a_time") {
        const double factor = has(*t, "factor") ? positive(doc, *t, "factor") : 1.5;
        std::vector<int> varied;
        const std::vector<std::string> names =
            has(*t, "vary") ? toml_strings(doc, *t, "vary") : std::vector<std::string>{"cd1", "cd2", "cm", "mu"};
        for (const auto& n : names) {
            const auto it = std::find(parameter_names.begin(), parameter_names.end(), n);
            if (it == parameter_names.end()) bad(doc, *t, "vary", "unknown parameter '" + n + "' (cd1, cd2, cm, mu, restitution)");
            varied.push_back(int(it - parameter_names.begin()));
        }
        spec.params = one_at_a_time(control, varied, factor);
    } else if (d == "factorial") {
        spec.params = factorial(control, arrays);
        const bool found = std::any_of(spec.params.begin(), spec.params.end(), [](const ParameterSet& s) { return s.is_control; });
        if (include_control && !found) spec.params.insert(spec.params.begin(), {"control", control, true});
        if (!include_control)
            for (auto& s : spec.params) s.is_control = false;
    } else {
        const int n = count_of(doc, *t, "samples", 1);
        std::array<std::array<double, 2>, 5> ranges;
        for (std::size_t p = 0; p < 5; ++p)
            ranges[p] = arrays[p].empty() ? std::array<double, 2>{control[p], control[p]}
                                          : std::array<double, 2>{arrays[p][0], arrays[p][1]};
        spec.params = d == "random" ? random_samples(ranges, n, seed_of(doc, *t, "seed"))
                                    : latin_hypercube(ranges, n, seed_of(doc, *t, "seed"));
        if (include_control) spec.params.insert(spec.params.begin(), {"control", control, true});
    }
    // The body model rejects impossible values; check here to name the spec and key.
    for (const auto& s : spec.params)
        for (std::size_t p = 0; p < 5; ++p) {
            const double v = s.values[p];
            const bool ok = p == 4 ? (v >= 0 && v <= 1) : (p == 3 ? v >= 0 : v > 0);
            if (!ok)
                bad(doc, *t, parameter_names[p],
                    "parameter set '" + s.label + "' gets " + parameter_names[p] + " = " + fmt(v) +
                        (p == 4   ? " (restitution must lie in [0, 1])"
                         : p == 3 ? " (must be >= 0)"
                                  : " (must be positive)"));
        }
}

}  // namespace

SweepSpec read_sweep_spec(const std::string& path, const std::string& scene_override,
                          const std::vector<std::string>& flow_override) {
    const TomlDoc doc = read_toml_lite(path);
    SweepSpec spec;
    spec.path = path;
    spec.sha256 = sha256_file(path);
    for (const auto& t : doc.tables)
        if (t.name != "" && t.name != "sweep" && t.name != "flows" && t.name != "body" && t.name != "variants" &&
            t.name != "parameters" && t.name != "perturbation")
            fail(path, "line " + std::to_string(t.line),
                 "unknown table [" + t.name + "] (sweep, flows, [[body]], variants, parameters, perturbation)");
    toml_allow_only(doc, doc.tables.front(), {});

    if (const TomlTable* t = find_table(doc, "sweep")) {
        toml_allow_only(doc, *t, {"scene", "output_interval", "end_time", "dt_max"});
        if (has(*t, "scene")) spec.scene = toml_string(doc, *t, "scene");
        if (has(*t, "output_interval")) spec.output_interval = positive(doc, *t, "output_interval");
        if (has(*t, "end_time")) spec.end_time = positive(doc, *t, "end_time");
        if (has(*t, "dt_max")) spec.dt_max = positive(doc, *t, "dt_max");
    }
    if (!scene_override.empty()) spec.scene = scene_override;

    if (!flow_override.empty()) {
        spec.flows = flow_override;
    } else {
        const TomlTable* t = find_table(doc, "flows");
        if (!t) fail(path, "[flows]", "missing: give paths = [\"flow.nc\", ...] or pattern = \"dir/flow_r*.nc\" (or --flow)");
        toml_allow_only(doc, *t, {"paths", "pattern"});
        if (has(*t, "paths") == has(*t, "pattern")) bad(doc, *t, "paths", "give exactly one of paths and pattern");
        spec.flows = has(*t, "paths") ? toml_strings(doc, *t, "paths") : glob_flows(doc, *t, toml_string(doc, *t, "pattern"));
        if (spec.flows.empty()) bad(doc, *t, "paths", "no flow files listed");
        for (const auto& f : spec.flows)
            if (!std::filesystem::exists(f))
                bad(doc, *t, has(*t, "paths") ? "paths" : "pattern", "flow file '" + f + "' does not exist");
    }

    std::unique_ptr<Scene> scene;
    for (const auto& t : doc.tables) {
        if (t.name != "body") continue;
        toml_allow_only(doc, t, {"start", "at", "name", "type", "length", "width", "height", "specific_gravity"});
        BodySpec b;
        if (has(t, "type")) {
            b.type = toml_string(doc, t, "type");
            if (!debris::find_catalogue_body(b.type))
                bad(doc, t, "type", "'" + b.type + "' is not in the debris catalogue (" + debris::catalogue_names() + ")");
            b.shape = debris::catalogue_body_def(b.type, path);
        }
        if (has(t, "start") == has(t, "at"))
            bad(doc, t, "start", "give exactly one of start = \"NAME\" (a scene point) and at = [x, y, heading_deg]");
        if (has(t, "start")) {
            b.start = toml_string(doc, t, "start");
            if (spec.scene.empty()) bad(doc, t, "start", "a named start needs a scene ([sweep] scene = \"...\" or --scene)");
            if (!scene) scene = std::make_unique<Scene>(read_scene(spec.scene));
            const ScenePoint* p = scene->find_point(b.start);
            if (!p || p->kind != "start") bad(doc, t, "start", "scene '" + spec.scene + "' has no start point '" + b.start + "'");
            b.name = b.start;
            b.x = p->x;
            b.y = p->y;
            b.heading_deg = p->heading_deg;
        } else {
            const std::vector<double> at = toml_numbers(doc, t, "at");
            if (at.size() != 3) bad(doc, t, "at", "expected [x, y, heading_deg]");
            b.x = at[0];
            b.y = at[1];
            b.heading_deg = at[2];
            b.name = "body" + std::to_string(spec.bodies.size());
        }
        if (has(t, "name")) b.name = toml_string(doc, t, "name");
        if (b.name.empty()) bad(doc, t, "name", "must not be empty");
        for (const auto& other : spec.bodies)
            if (other.name == b.name)
                bad(doc, t, has(t, "name") ? "name" : "start", "body name '" + b.name + "' used twice (set name = \"...\")");
        if (has(t, "length")) b.shape.length = positive(doc, t, "length");
        if (has(t, "width")) b.shape.width = positive(doc, t, "width");
        if (has(t, "height")) b.shape.height = positive(doc, t, "height");
        if (has(t, "specific_gravity")) b.shape.specific_gravity = positive(doc, t, "specific_gravity");
        spec.bodies.push_back(b);
    }
    if (spec.bodies.empty())
        fail(path, "[[body]]", "missing: give at least one [[body]] with start = \"FD\" or at = [x, y, heading_deg]");

    if (const TomlTable* t = find_table(doc, "variants")) {
        toml_allow_only(doc, *t, {"names"});
        for (const auto& n : toml_strings(doc, *t, "names")) {
            try {
                spec.variants.push_back(parse_variant(n));
            } catch (const Error& e) {
                bad(doc, *t, "names", e.what());
            }
            for (std::size_t k = 0; k + 1 < spec.variants.size(); ++k)
                if (spec.variants[k].name == n) bad(doc, *t, "names", "variant '" + n + "' listed twice");
        }
        if (spec.variants.empty()) bad(doc, *t, "names", "no variants listed");
    } else {
        spec.variants = {parse_variant("LC+MC")};
    }

    read_parameters(doc, find_table(doc, "parameters"), spec);

    if (const TomlTable* t = find_table(doc, "perturbation")) {
        toml_allow_only(doc, *t, {"count", "position_std", "heading_std", "seed"});
        if (has(*t, "count")) spec.perturbation.count = count_of(doc, *t, "count", 0);
        for (const std::string key : {"position_std", "heading_std"})
            if (has(*t, key) && !(toml_number(doc, *t, key) >= 0)) bad(doc, *t, key, "must be >= 0");
        if (has(*t, "position_std")) spec.perturbation.position_std = toml_number(doc, *t, "position_std");
        if (has(*t, "heading_std")) spec.perturbation.heading_std = toml_number(doc, *t, "heading_std");
        spec.perturbation.seed = seed_of(doc, *t, "seed");
    }
    return spec;
}

std::array<double, 3> perturbed_start(const SweepSpec& spec, int body, int k) {
    const BodySpec& b = spec.bodies[std::size_t(body)];
    const double deg = std::numbers::pi / 180.0;
    if (k == 0) return {b.x, b.y, b.heading_deg * deg};
    // Its own stream per (body, k): the same offsets whatever the flows, variants or sets.
    Rng rng(spec.perturbation.seed * 0x100000001b3ULL + std::uint64_t(body) * 0x10001ULL + std::uint64_t(k));
    const double dx = spec.perturbation.position_std * rng.normal();
    const double dy = spec.perturbation.position_std * rng.normal();
    const double dh = spec.perturbation.heading_std * rng.normal();
    return {b.x + dx, b.y + dy, (b.heading_deg + dh) * deg};
}

std::vector<Member> enumerate_members(const SweepSpec& spec) {
    std::vector<Member> out;
    const int np = spec.perturbation.count + 1;
    for (int f = 0; f < int(spec.flows.size()); ++f)
        for (int b = 0; b < int(spec.bodies.size()); ++b)
            for (int k = 0; k < np; ++k) {
                const auto start = perturbed_start(spec, b, k);
                for (int v = 0; v < int(spec.variants.size()); ++v)
                    for (int p = 0; p < int(spec.params.size()); ++p) {
                        Member m;
                        m.id = int(out.size());
                        m.flow = f;
                        m.body = b;
                        m.perturbation = k;
                        m.variant = v;
                        m.param_set = p;
                        debris::BodyDef& d = m.def;
                        d = spec.bodies[std::size_t(b)].shape;
                        d.name = spec.bodies[std::size_t(b)].name;
                        d.x = start[0];
                        d.y = start[1];
                        d.heading = start[2];
                        d.contact = spec.variants[std::size_t(v)].contact;
                        d.collision = spec.variants[std::size_t(v)].collision;
                        const ParamValues& pv = spec.params[std::size_t(p)].values;
                        const BodySpec& body = spec.bodies[std::size_t(b)];
                        if (body.type.empty()) {
                            d.cd1 = pv[0];
                            d.cd2 = pv[1];
                            d.cm = pv[2];
                            d.mu = pv[3];
                            d.restitution = pv[4];
                        } else {  // the entry's own coefficients, scaled as the set scales the control
                            const ParamValues& c = spec.control;
                            d.cd1 = body.shape.cd1 * (pv[0] / c[0]);
                            d.cd2 = body.shape.cd2 * (pv[1] / c[1]);
                            d.cm = body.shape.cm * (pv[2] / c[2]);
                            d.mu = c[3] > 0 ? body.shape.mu * (pv[3] / c[3]) : pv[3];
                            d.restitution = c[4] > 0 ? std::min(1.0, body.shape.restitution * (pv[4] / c[4])) : pv[4];
                        }
                        out.push_back(m);
                    }
            }
    return out;
}

Shard parse_shard(const std::string& text) {
    const auto slash = text.find('/');
    Shard s;
    try {
        std::size_t a = 0, b = 0;
        if (slash == std::string::npos) throw std::invalid_argument(text);
        s.index = std::stoi(text.substr(0, slash), &a);
        s.count = std::stoi(text.substr(slash + 1), &b);
        if (a != slash || b != text.size() - slash - 1) throw std::invalid_argument(text);
    } catch (const std::exception&) {
        fail("--shard", text, "expected i/n (e.g. 0/4)");
    }
    if (s.count < 1 || s.index < 0 || s.index >= s.count) fail("--shard", text, "needs 0 <= i < n");
    return s;
}

std::array<int, 2> shard_range(int members, const Shard& shard) {
    const auto bound = [&](int i) { return int((long long)members * i / shard.count); };
    return {bound(shard.index), bound(shard.index + 1)};
}

}  // namespace flotsam::sweep
