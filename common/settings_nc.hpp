// Settings (common/settings.hpp) recorded in NetCDF files: one variable per setting of a
// table, over the file's items (trajectories, parameter sets), named Setting::variable()
// with the setting's unit and its help as long_name. Numbers are doubles, switches
// bytes (1: on), whole numbers ints, choices strings (the value's name).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/columns.hpp"
#include "common/settings.hpp"
#include "common/units.hpp"

namespace flotsam {

template <class Def>
std::vector<int> def_setting_vars(nc::File& f, const Settings<Def>& table, const std::vector<int>& dims,
                                  const std::string& prefix = "") {
    std::vector<int> ids;
    for (const auto& s : table) {
        const nc_type type = s.is_switch() ? NC_BYTE : s.is_choice() ? NC_CHAR : s.is_whole() ? NC_INT : NC_DOUBLE;
        std::size_t length = 0;  // a choice: as long as its longest name ("a, b, c")
        if (s.is_choice()) {
            const std::string names = s.choice().names();
            for (std::size_t a = 0, b; a < names.size(); a = b + 2) {
                b = std::min(names.find(", ", a), names.size());
                length = std::max(length, b - a);
            }
        }
        ids.push_back(cf::def_var(f, {.name = prefix + s.variable(),
                                      .type = type,
                                      .dims = dims,
                                      .units = s.unit,
                                      .long_name = s.help,
                                      .text_length = length}));
    }
    return ids;
}

// Writes the settings of each row's definition, def_of(row), into the variables of
// def_setting_vars.
template <class Def, class Rows, class DefOf>
void put_setting_vars(nc::File& f, const std::vector<int>& ids, const Settings<Def>& table, const Rows& rows, DefOf def_of) {
    for (std::size_t p = 0; p < table.size(); ++p) {
        const Setting<Def>& s = table[p];
        if (s.is_switch())
            f.put(ids[p], column<std::int8_t>(rows, [&](const auto& r) { return s.flag(def_of(r)) ? 1 : 0; }));
        else if (s.is_choice())
            f.put(ids[p], column<std::string>(rows, [&](const auto& r) { return s.choice().get(def_of(r)); }));
        else if (s.is_whole())
            f.put(ids[p], column<int>(rows, [&](const auto& r) { return s.number(def_of(r)); }));
        else
            f.put(ids[p], column<double>(rows, [&](const auto& r) { return s.number(def_of(r)); }));
    }
}

// Reads the variables of def_setting_vars back into the definitions defs[k] (item k);
// `prefix` as when written. A missing variable is an error naming it, unless not
// `required` (then defs keep their values).
template <class Def>
void get_setting_vars(const nc::File& f, const Settings<Def>& table, std::vector<Def>& defs, const std::string& prefix = "",
                      bool required = true) {
    for (const auto& s : table) {
        const std::string name = prefix + s.variable();
        if (!required && !f.has_var(name)) continue;
        const int id = f.var(name);
        // One value per row, or a named error (never a read past the column's end).
        const std::vector<std::size_t> shape = f.value_shape(id);
        if (shape.empty() || shape[0] != defs.size())
            fail(f.path(), "variable '" + name + "'", "must have one value per row (" + std::to_string(defs.size()) + ")");
        if (s.is_choice()) {
            const std::vector<std::string> names = f.get_strings(id);
            for (std::size_t k = 0; k < defs.size() && k < names.size(); ++k)
                s.choice().set(defs[k], names[k], f.path() + ": variable '" + prefix + s.variable() + "'");
        } else if (s.is_switch()) {
            const std::vector<int> v = f.get_int(id);
            for (std::size_t k = 0; k < defs.size() && k < v.size(); ++k) s.set_flag(defs[k], v[k] != 0);
        } else if (s.is_whole()) {
            const std::vector<int> v = f.get_int(id);
            for (std::size_t k = 0; k < defs.size() && k < v.size(); ++k) s.set_number(defs[k], v[k]);
        } else {
            const std::vector<double> v = f.get_double(id);
            const double factor = units::factor_to(f, id, s.unit);  // the file's units, converted or refused
            for (std::size_t k = 0; k < defs.size() && k < v.size(); ++k) {
                check_range("variable '" + name + "'", factor * v[k], s.range, f.path());
                s.set_number(defs[k], factor * v[k]);
            }
        }
    }
}

}  // namespace flotsam
