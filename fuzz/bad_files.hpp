// Bad files for the command-line tests of bad input (tests/reliability_*_cli_test.cpp):
// a NetCDF file with one thing wrong, made from a good one the way the NetCDF fuzz targets
// edit theirs (fuzz/targets.hpp) or another program would. Errors are std::runtime_error.
#pragma once
#include <cstddef>
#include <string>

namespace flotsam::fuzz {

// ---- copies (in -> out) ----

// Variable `var` moved onto a new dimension of `length` (its table no longer matches).
void copy_with_short_column(const std::string& in, const std::string& out, const std::string& var, std::size_t length);
// Dimension `dim` resized to `length`; every variable on it follows.
void copy_with_dimension(const std::string& in, const std::string& out, const std::string& dim, std::size_t length);
// The two dimensions of the 2-D variable `var` swapped (x(trajectory, time) as x(time,
// trajectory)), its values kept in their order.
void copy_with_transposed(const std::string& in, const std::string& out, const std::string& var);
// Value `index` (flat) of variable `var` set to `value`.
void copy_with_value(const std::string& in, const std::string& out, const std::string& var, std::size_t index, double value);

// ---- edits in place ----
// `var` names a variable, or "global" for the file's attributes.

void set_text_attribute(const std::string& path, const std::string& var, const std::string& name, const std::string& text);
void set_number_attribute(const std::string& path, const std::string& var, const std::string& name, double value);
// Every value of `var` multiplied by `factor` (a file in other units), or set to `value`.
void scale_values(const std::string& path, const std::string& var, double factor);
void set_all(const std::string& path, const std::string& var, double value);
// Value `index` (flat) of `var`.
void set_value(const std::string& path, const std::string& var, std::size_t index, double value);
// Every value of `var` shifted by `offset` (positions moved off their scene).
void shift_values(const std::string& path, const std::string& var, double offset);
// String `index` of a character array (flotsam's strings), NUL-padded to its length.
void set_string(const std::string& path, const std::string& var, std::size_t index, const std::string& text);

}  // namespace flotsam::fuzz
