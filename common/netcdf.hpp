// A thin, checked layer over NetCDF-C. Every call checks its status and throws
// flotsam::Error naming the file, the variable and NetCDF's own message: no return code
// is ever dropped.
#pragma once
#include <netcdf.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace flotsam::nc {

class File {
public:
    static File open_read(const std::string& path);   // nc::probe_structure() first (common/netcdf_probe.hpp)
    static File open_write(const std::string& path);  // an existing file, for appending data
    static File create(const std::string& path);      // NetCDF-4 (HDF5), replacing any file there
    File(File&& other) noexcept;
    File& operator=(File&& other) noexcept;
    File(const File&) = delete;
    File& operator=(const File&) = delete;
    ~File();
    void close();

    int id() const { return id_; }
    const std::string& path() const { return path_; }
    // Throws Error("<path>: <what>: <netcdf message>") when status is not NC_NOERR.
    void check(int status, const std::string& what) const;

    // ---- definition mode ----
    int def_dim(const std::string& name, std::size_t length);
    int def_var(const std::string& name, nc_type type, const std::vector<int>& dims);
    // Strings as a character array (NC_CHAR) over `dims` plus a dimension "<name>_strlen" of
    // `length` (at least 1): strings of up to `length` bytes, padded with NUL. flotsam
    // stores its strings so (never as NC_STRING, whose variable-length data libhdf5 keeps
    // in a global heap: a damaged heap crashed libhdf5 when reading or closing).
    int def_text_var(const std::string& name, const std::vector<int>& dims, std::size_t length);
    void def_chunking(int var, const std::vector<std::size_t>& chunks);
    void def_deflate(int var, int level, bool shuffle);
    void def_fill(int var, double fill);  // _FillValue of the variable's own type
    void put_att(int var, const std::string& name, const std::string& value);
    void put_att(int var, const std::string& name, double value);
    void put_att(int var, const std::string& name, int value);
    void put_att(int var, const std::string& name, const std::vector<double>& values);
    void put_att(int var, const std::string& name, const std::vector<std::int8_t>& values);
    void enddef();
    void redef();

    // ---- data ----
    void put(int var, const std::vector<double>& values);
    void put(int var, const std::vector<float>& values);
    void put(int var, const std::vector<int>& values);
    void put(int var, const std::vector<std::int8_t>& values);
    void put(int var, const std::vector<std::string>& values);  // a character array (def_text_var), or NC_STRING
    void put_slab(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count, const float* data);
    void put_slab(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count, const double* data);
    void put_slab(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count, const std::int8_t* data);
    void sync();

    // ---- inquiry and reading ----
    bool has_var(const std::string& name) const;
    int var(const std::string& name) const;  // throws naming the missing variable
    std::optional<int> find_var(const std::string& name) const;
    // The variable whose standard_name attribute equals `standard_name`.
    std::optional<int> find_by_standard_name(const std::string& standard_name) const;
    std::string var_name(int var) const;
    std::vector<std::string> dim_names(int var) const;
    std::vector<std::size_t> shape(int var) const;
    std::size_t dim_length(const std::string& name) const;
    bool has_dim(const std::string& name) const;
    std::vector<double> get_double(int var) const;
    std::vector<float> get_float(int var) const;
    std::vector<int> get_int(int var) const;
    // The strings of a character array (its last dimension the string length; NUL padding
    // removed) or of an NC_STRING variable (files written by earlier versions).
    std::vector<std::string> get_strings(int var) const;
    // A variable's dimensions and shape as its values go: those of a character array
    // without its string-length dimension (the last); of any other variable, all.
    std::vector<std::string> value_dims(int var) const;
    std::vector<std::size_t> value_shape(int var) const;
    void get_slab(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count, float* out) const;
    void get_slab(int var, const std::vector<std::size_t>& start, const std::vector<std::size_t>& count, double* out) const;
    // Attributes (var = NC_GLOBAL for the file's): none when absent. One that is present
    // but cannot be read, or is of the other kind (a number where text is read, text where
    // a number is), is a named error, never taken for absent.
    std::optional<std::string> att_text(int var, const std::string& name) const;
    std::optional<double> att_double(int var, const std::string& name) const;
    std::optional<std::vector<double>> att_doubles(int var, const std::string& name) const;
    // The attribute's type (and its number of values), none when absent; for readers that
    // take either kind.
    std::optional<nc_type> att_type(int var, const std::string& name, std::size_t* length = nullptr) const;
    bool att_is_text(int var, const std::string& name) const;
    std::vector<std::string> att_names(int var) const;  // in the file's order

private:
    File(int id, std::string path) : id_(id), path_(std::move(path)) {}
    std::string var_label(int var) const;
    std::string att_label(int var, const std::string& name) const;  // "global attribute 'a'", "variable 'v' attribute 'a'"
    int id_ = -1;
    std::string path_;
};

// Reads a whole variable as double and throws, naming file and variable, if any value
// is NaN or infinite (NetCDF fill values count as missing and are rejected too).
std::vector<double> read_finite(const File& f, const std::string& name);

}  // namespace flotsam::nc
