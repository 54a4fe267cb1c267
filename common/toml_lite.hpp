// A reader for the small TOML subset the feature files use: comments, `key = value`,
// `[table]` and `[[array-of-tables]]`; values are numbers, "strings", true/false and
// arrays of numbers or of "strings" (an array may run over several lines). Errors name
// the file and line.
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
// Fails when the table has a key outside `allowed`.
void toml_allow_only(const TomlDoc& doc, const TomlTable& t, const std::vector<std::string>& allowed);

}  // namespace flotsam
