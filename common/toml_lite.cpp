#include "common/toml_lite.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <utility>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam {

namespace {

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// Drops a '#' comment that is not inside a string.
std::string strip_comment(const std::string& s) {
    char quote = 0;
    for (std::size_t k = 0; k < s.size(); ++k) {
        if (s[k] == '"' || s[k] == '\'') {
            if (!quote)
                quote = s[k];
            else if (quote == s[k])
                quote = 0;
        }
        if (s[k] == '#' && !quote) return s.substr(0, k);
    }
    return s;
}

// "text" or 'text' (no escapes in either).
bool is_string(const std::string& s) { return s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front(); }

bool parse_number(const std::string& s, double& out) {
    if (s.empty()) return false;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && std::isfinite(out);
}

TomlValue parse_value(const std::string& path, int line, const std::string& key, const std::string& raw) {
    const std::string here = "line " + std::to_string(line);
    TomlValue v;
    v.line = line;
    v.raw = raw;
    if (is_string(raw)) {
        v.kind = TomlValue::Kind::String;
        v.text = raw.substr(1, raw.size() - 2);
    } else if (raw == "true" || raw == "false") {
        v.kind = TomlValue::Kind::Bool;
        v.flag = raw == "true";
    } else if (raw.size() >= 2 && raw.front() == '[' && raw.back() == ']') {
        const std::string body = raw.substr(1, raw.size() - 2);
        const bool strings = trim(body).starts_with("\"") || trim(body).starts_with("'");
        v.kind = strings ? TomlValue::Kind::StringArray : TomlValue::Kind::NumberArray;
        // Split at commas outside quotes.
        std::vector<std::string> items;
        std::string item;
        char quote = 0;
        for (char c : body) {
            if ((c == '"' || c == '\'') && (!quote || quote == c)) quote = quote ? 0 : c;
            if (c == ',' && !quote) {
                items.push_back(trim(item));
                item.clear();
            } else {
                item += c;
            }
        }
        items.push_back(trim(item));
        if (items.back().empty()) items.pop_back();  // trailing comma or empty array
        for (const auto& it : items) {
            if (strings) {
                if (!is_string(it))
                    fail(path, here, "key '" + key + "': array element '" + it + "' is not a \"string\" (arrays hold one kind)");
                v.texts.push_back(it.substr(1, it.size() - 2));
                v.items.push_back(v.texts.back());
            } else {
                double x = 0.0;
                if (!parse_number(it, x)) fail(path, here, "key '" + key + "': array element '" + it + "' is not a finite number");
                v.numbers.push_back(x);
                v.items.push_back(it);
            }
        }
    } else if (!parse_number(raw, v.number)) {
        fail(path, here,
             "key '" + key + "': value '" + raw + "' is not a number, \"string\", true/false, [numbers] or [\"strings\"]");
    }
    return v;
}

const TomlValue& need(const TomlDoc& doc, const TomlTable& t, const std::string& key, TomlValue::Kind kind, const char* what) {
    const auto it = t.values.find(key);
    const std::string table = t.name.empty() ? "top level" : "[" + t.name + "] at line " + std::to_string(t.line);
    if (it == t.values.end()) fail(doc.path, table, "missing key '" + key + "'");
    if (it->second.kind != kind) fail(doc.path, "line " + std::to_string(it->second.line), "key '" + key + "' must be " + what);
    return it->second;
}

}  // namespace

TomlDoc read_toml_lite(const std::string& path) {
    check_input_file("", path);  // a directory reads as empty, a FIFO may never end
    if (file_type_of(path).empty()) fail(path, "", "no such file");
    check_input_size("", path, 16e6, "a settings or spec file");
    std::ifstream in(path);
    if (!in) fail(path, "", "cannot open");
    TomlDoc doc;
    doc.path = path;
    doc.tables.push_back({"", 0, {}});
    std::string raw;
    int line = 0;
    while (std::getline(in, raw)) {
        ++line;
        // A UTF-8 byte-order mark (some Windows editors write one) is not part of the text.
        if (line == 1 && raw.rfind("\xEF\xBB\xBF", 0) == 0) raw.erase(0, 3);
        const std::string s = trim(strip_comment(raw));
        const std::string here = "line " + std::to_string(line);
        if (s.empty()) continue;
        if (s.starts_with("[[")) {
            if (!s.ends_with("]]")) fail(path, here, "unterminated [[table]] header");
            doc.tables.push_back({trim(s.substr(2, s.size() - 4)), line, {}});
            continue;
        }
        if (s.front() == '[') {
            if (s.back() != ']') fail(path, here, "unterminated [table] header");
            const std::string name = trim(s.substr(1, s.size() - 2));
            for (const auto& t : doc.tables)
                if (t.name == name)
                    fail(path, here, "table [" + name + "] defined twice (first at line " + std::to_string(t.line) + ")");
            doc.tables.push_back({name, line, {}});
            continue;
        }
        const auto eq = s.find('=');
        if (eq == std::string::npos) fail(path, here, "expected 'key = value', '[table]' or '[[table]]'");
        const std::string key = trim(s.substr(0, eq));
        if (key.empty()) fail(path, here, "missing key before '='");
        auto& values = doc.tables.back().values;
        if (values.count(key)) fail(path, here, "key '" + key + "' given twice in the same table");
        std::string value = trim(s.substr(eq + 1));
        // An array that is not closed on this line continues on the next ones.
        const int first_line = line;
        while (value.starts_with("[") && !value.ends_with("]")) {
            if (!std::getline(in, raw)) fail(path, here, "key '" + key + "': array not closed with ']'");
            ++line;
            value += ' ';
            value += trim(strip_comment(raw));
            value = trim(value);
        }
        values[key] = parse_value(path, first_line, key, value);
    }
    return doc;
}

double toml_number(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    return need(doc, t, key, TomlValue::Kind::Number, "a number").number;
}

std::string toml_string(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    return need(doc, t, key, TomlValue::Kind::String, "a \"string\"").text;
}

std::vector<double> toml_numbers(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    return need(doc, t, key, TomlValue::Kind::NumberArray, "an array of numbers").numbers;
}

std::string kebab_case(std::string key) {
    std::replace(key.begin(), key.end(), '_', '-');
    return key;
}

void toml_allow_only(const TomlDoc& doc, const TomlTable& t, const std::vector<std::string>& allowed) {
    auto known = [&](const std::string& key) { return std::find(allowed.begin(), allowed.end(), key) != allowed.end(); };
    std::vector<std::pair<int, std::string>> unknown, old;  // (line, key)
    for (const auto& [key, v] : t.values)
        if (!known(key)) (known(kebab_case(key)) ? old : unknown).emplace_back(v.line, key);
    const std::string in = t.name.empty() ? "" : " in [" + t.name + "]";
    if (!old.empty()) {  // every renamed key of the table at once, in file order
        std::sort(old.begin(), old.end());
        std::string keys, renames;
        for (const auto& [line, key] : old) {
            keys += (keys.empty() ? "'" : ", '") + key + "'";
            renames += (renames.empty() ? "'" : ", '") + kebab_case(key) + "'";
        }
        fail(doc.path, "line " + std::to_string(old.front().first),
             "key" + std::string(old.size() > 1 ? "s " : " ") + keys + in + (old.size() > 1 ? " are" : " is") +
                 " the old spelling: keys are kebab-case, as the command-line options; write " + renames);
    }
    if (unknown.empty()) return;
    std::sort(unknown.begin(), unknown.end());
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail(doc.path, "line " + std::to_string(unknown.front().first),
         "unknown key '" + unknown.front().second + "'" + in + " (allowed: " + list + ")");
}

void toml_fail(const TomlDoc& doc, const TomlTable& t, const std::string& key, const std::string& problem) {
    fail(toml_where(doc, t, key), (t.name.empty() ? "" : "[" + t.name + "] ") + "key '" + key + "'", problem);
}

std::vector<std::string> toml_strings(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    return need(doc, t, key, TomlValue::Kind::StringArray, "an array of \"strings\"").texts;
}

bool toml_bool(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    return need(doc, t, key, TomlValue::Kind::Bool, "true or false").flag;
}

std::string toml_where(const TomlDoc& doc, const TomlTable& t, const std::string& key) {
    const auto it = t.values.find(key);
    const int line = it != t.values.end() ? it->second.line : t.line;
    return doc.path + ": line " + std::to_string(line);
}

}  // namespace flotsam
