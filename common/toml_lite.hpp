// The one TOML reader of flotsam (settings files given with --config, sweep specs): the
// subset those use: comments, `key = value`, `[table]` (dotted names such as
// [scene.generate] are one name) and `[[array-of-tables]]`; values are numbers,
// "strings" or 'literal strings', true/false and arrays of numbers or of strings (an
// array may run over several lines). Keys are kebab-case (common/settings.hpp). Errors
// name the file and line.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace flotsam {

// One value and the line it came from.
struct TomlValue {
    enum class Kind { Number, String, Bool, NumberArray, StringArray } kind = Kind::Number;
    double number = 0.0;
    std::string text;
    bool flag = false;
    std::vector<double> numbers;
    std::vector<std::string> texts;  // StringArray
    std::string raw;                 // the value as written (a number's digits, true/false)
    std::vector<std::string> items;  // an array's elements as written (numbers) or their text (strings)
    int line = 0;                    // 1-based line in the file
};

// A table: the root (name ""), a [name] table, or one element of an [[name]] array.
struct TomlTable {
    std::string name;
    int line = 0;  // line of the header (0 for the root)
    std::map<std::string, TomlValue> values;
};

// All tables in file order; `path` for messages.
struct TomlDoc {
    std::string path;
    std::vector<TomlTable> tables;
};

TomlDoc read_toml_lite(const std::string& path);

// Typed access that fails naming file, line and key.
double toml_number(const TomlDoc& doc, const TomlTable& t, const std::string& key);
std::string toml_string(const TomlDoc& doc, const TomlTable& t, const std::string& key);
std::vector<double> toml_numbers(const TomlDoc& doc, const TomlTable& t, const std::string& key);
std::vector<std::string> toml_strings(const TomlDoc& doc, const TomlTable& t, const std::string& key);
bool toml_bool(const TomlDoc& doc, const TomlTable& t, const std::string& key);
// "file: line N" of a key, or of the table header when the key is absent (for messages).
std::string toml_where(const TomlDoc& doc, const TomlTable& t, const std::string& key);
// Fails "file: line N: [table] key 'k': problem".
[[noreturn]] void toml_fail(const TomlDoc& doc, const TomlTable& t, const std::string& key, const std::string& problem);
// Fails when the table has a key outside `allowed`; a key in the old snake_case spelling
// of an allowed kebab-case one (output_interval for output-interval) is told the new key.
void toml_allow_only(const TomlDoc& doc, const TomlTable& t, const std::vector<std::string>& allowed);
// The kebab-case spelling of a key: '_' becomes '-'.
std::string kebab_case(std::string key);

}  // namespace flotsam
