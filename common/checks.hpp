// Finite numbers in range, or a named error: the one check every numeric option,
// settings key and spec value goes through. A check is data — a name, a value
// and a Range — so a table of parameters can drive it:
//
//     check_range("--cfl", s.cfl, Range::open_closed(0, 0.5));
//     // --cfl: nan is not a finite number (allowed: (0, 0.5])
//     // --cfl: 0.7 is outside the allowed range (0, 0.5]
//
// And sizes before allocation: check_allocation() compares what an option would make a
// run allocate with the machine's memory and names the option when it cannot fit.
#pragma once
#include <cstddef>
#include <limits>
#include <string>

namespace flotsam {

struct Range {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false, max_open = false;  // (min, ... and ..., max)
    bool whole = false;                       // whole numbers only
    std::string unit;                         // for messages: "s", "m", "s m^-1/3"

    static Range closed(double a, double b, std::string unit = "") { return {a, b, false, false, false, std::move(unit)}; }
    static Range open_closed(double a, double b, std::string unit = "") { return {a, b, true, false, false, std::move(unit)}; }
    static Range positive(std::string unit = "");                   // (0, inf)
    static Range non_negative(std::string unit = "");               // [0, inf)
    static Range at_least(double a, std::string unit = "");         // [a, inf)
    static Range any(std::string unit = "");                        // any finite number
    static Range count(double a, double b, std::string unit = "");  // whole numbers in [a, b]
    Range& up_to(double b) {
        max = b;
        return *this;
    }  // then at most b
    Range& below(double b) {
        max = b;
        max_open = true;
        return *this;
    }
};

// A number for messages: "1e-09", "0.45", "1e+12" (6 significant digits).
std::string number_text(double v);
// A coordinate for messages, to the millimetre: "3779500.25", "1.375" (UTM northings
// have seven digits before the point, which number_text would round to metres).
std::string coordinate_text(double v);

// "(0, 0.5] s", "whole numbers in [1, 16]", "any finite number".
std::string describe(const Range& r);

// Empty when `value` is finite and in `r`; else what is wrong, naming the value and the
// range.
std::string range_problem(double value, const Range& r);

// Throws flotsam::Error "<file>: <name>: <problem>" (an empty file is left out).
void check_range(const std::string& name, double value, const Range& r, const std::string& file = "");

// The memory the process may use [bytes]: the physical memory, or the cgroup's limit
// when lower, or FLOTSAM_MEMORY_LIMIT_MB when that is lower still.
double memory_limit_bytes();

// Throws naming `name` (and the file, if any) when `count` items of `bytes_each` bytes
// would exceed memory_limit_bytes() (or overflow): "--output-interval: 1e-09 s would make
// 4.2e+11 frame times (3.3e+03 GB), more than this machine's 24 GB".
void check_allocation(const std::string& name, const std::string& value_text, double count, double bytes_each,
                      const std::string& what, const std::string& file = "");

// ---- bounded runs ----

// The bounds of the work a run may ask for without --allow-large-run (docs/reliability.md,
// "Every run is bounded"): generous for any study on one machine, far below what
// never ends.
inline constexpr double max_body_steps_per_body = 1e7;  // steps of one body (the paper's box: 4e4 to 3e5)
inline constexpr double max_body_steps = 1e10;          // steps of all bodies of a run (about 15 processor hours)
inline constexpr double max_boundary_samples = 1e8;     // samples of all records of `boundary generate`
inline constexpr double max_cell_updates = 1e13;        // cell updates of a hydro run (a 1 cm flow: about 1e11)
inline constexpr double max_yard_places = 1e7;          // places a GIS yard's layout tests (the full-scale demo's: about 2e3)

// Throws "<name>: <estimate_text>: <what> <estimate>, more than the <bound> flotsam runs
// without --allow-large-run ..." when `estimate` exceeds `bound` (or is not finite) and
// the run was not allowed to.
void check_work(const std::string& name, const std::string& estimate_text, double estimate, double bound, const std::string& what,
                bool allowed, const std::string& file = "");

// The number of threads to start: `requested` (0: the OpenMP default) capped at the
// processors this process may run on, with a note on stderr when capped (more threads
// than processors only slow a run down, and thousands cannot be started).
int capped_threads(int requested, const std::string& option, bool quiet);

// ---- files ----

// What a path is on disk ("a regular file", "a directory", "a character device", "a
// FIFO", ...); "" when it does not exist. Symbolic links are followed.
std::string file_type_of(const std::string& path);

// An input must be a regular file: a device, a FIFO or a socket is a stream that may never
// end (/dev/zero), a directory holds no data. Throws "<option>: <path>: is a FIFO, not a
// regular file ...". Empty paths are skipped.
void check_input_file(const std::string& option, const std::string& path);

// What GDAL opens (a vector layer, a raster) must be files too: a regular file, or a
// folder of regular files (a FileGDB, a folder of shapefiles); and so must the files GDAL
// opens beside it, whose names begin with its stem (a shapefile's .shx and .dbf, a
// GeoPackage's -wal and -journal, a raster's .aux.xml and .ovr). Paths that are not on
// disk (GDAL's /vsizip/..., a missing file) are left to GDAL's own message.
void check_gis_input(const std::string& option, const std::string& path);

// Whether a and b are the same file (device and inode: symbolic links, hard links and
// relative spellings); false when either does not exist.
bool same_file(const std::string& a, const std::string& b);

// An existing output (or its "<path>.part") must be a regular file: flotsam writes
// "<path>.part" and renames it over <path>, which would replace a device node such as
// /dev/null with a regular file. Throws naming the option and what the path is. A path
// that does not exist yet is fine.
void check_output_file(const std::string& option, const std::string& path);

// An input's size [bytes] against `max_bytes` (a text file read whole): throws naming the
// option, the file and both sizes.
void check_input_size(const std::string& option, const std::string& path, double max_bytes, const std::string& what);

// " (No space left on device: 0 bytes free of 204800 on the file system of /scratch)" when
// the file system `path` is written to is (nearly) full, else "": what a failed write adds
// to its message (NetCDF says "HDF error", GDAL "no such table", a stream nothing).
std::string disk_full_hint(const std::string& path);

}  // namespace flotsam
