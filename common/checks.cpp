#include "common/checks.hpp"

#include <sched.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"

namespace flotsam {

namespace {
const double inf = std::numeric_limits<double>::infinity();

std::string num(double v) {
    if (v == inf) return "inf";
    if (v == -inf) return "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}
}  // namespace

std::string number_text(double v) { return num(v); }

std::string coordinate_text(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", std::round(v * 1000.0) / 1000.0);
    return buf;
}

Range Range::positive(std::string unit) { return {0.0, inf, true, false, false, std::move(unit)}; }
Range Range::non_negative(std::string unit) { return {0.0, inf, false, false, false, std::move(unit)}; }
Range Range::at_least(double a, std::string unit) { return {a, inf, false, false, false, std::move(unit)}; }
Range Range::any(std::string unit) { return {-inf, inf, false, false, false, std::move(unit)}; }
Range Range::count(double a, double b, std::string unit) { return {a, b, false, false, true, std::move(unit)}; }

std::string describe(const Range& r) {
    std::string s;
    if (r.min == -inf && r.max == inf)
        s = "any finite number";
    else
        s = (r.whole ? "whole numbers in " : std::string()) + (r.min_open || r.min == -inf ? "(" : "[") + num(r.min) + ", " +
            num(r.max) + (r.max_open || r.max == inf ? ")" : "]");
    if (!r.unit.empty()) s += " " + r.unit;
    return s;
}

std::string range_problem(double value, const Range& r) {
    if (!std::isfinite(value)) return num(value) + " is not a finite number (allowed: " + describe(r) + ")";
    const bool below = r.min_open ? !(value > r.min) : !(value >= r.min);
    const bool above = r.max_open ? !(value < r.max) : !(value <= r.max);
    if (below || above) return num(value) + " is outside the allowed range " + describe(r);
    if (r.whole && value != std::floor(value)) return num(value) + " is not a whole number (allowed: " + describe(r) + ")";
    return "";
}

void check_range(const std::string& name, double value, const Range& r, const std::string& file) {
    const std::string p = range_problem(value, r);
    if (!p.empty()) fail(file, name, p);
}

double memory_limit_bytes() {
    static const double limit = [] {
        double bytes = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
        std::ifstream cg("/sys/fs/cgroup/memory.max");
        std::string s;
        if (cg >> s && s != "max") {
            const double c = std::strtod(s.c_str(), nullptr);
            if (c > 0 && c < bytes) bytes = c;
        }
        // A lower limit on request (the fuzz targets use it so that a valid but huge input
        // gives its named error at once).
        if (const char* mb = std::getenv("FLOTSAM_MEMORY_LIMIT_MB"); mb && std::strtod(mb, nullptr) > 0)
            bytes = std::min(bytes, std::strtod(mb, nullptr) * 1024 * 1024);
        return bytes > 0 ? bytes : 1e12;
    }();
    return limit;
}

void check_allocation(const std::string& name, const std::string& value_text, double count, double bytes_each,
                      const std::string& what, const std::string& file) {
    const double bytes = count * bytes_each, limit = memory_limit_bytes();
    if (std::isfinite(bytes) && bytes >= 0 && bytes <= limit) return;
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s would make %.3g %s (%.3g GB), more than this machine's %.3g GB", value_text.c_str(), count,
                  what.c_str(), bytes / 1e9, limit / 1e9);
    fail(file, name, buf);
}

void check_work(const std::string& name, const std::string& estimate_text, double estimate, double bound, const std::string& what,
                bool allowed, const std::string& file) {
    if (allowed || (std::isfinite(estimate) && estimate <= bound)) return;
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "%s would make %.3g %s, more than the %.3g flotsam runs without being asked to; check the value, or pass "
                  "--allow-large-run to run it anyway (docs/reliability.md)",
                  estimate_text.c_str(), estimate, what.c_str(), bound);
    fail(file, name, buf);
}

int capped_threads(int requested, const std::string& option, bool quiet) {
    cpu_set_t set;
    CPU_ZERO(&set);
    int processors = ::sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 0;
    if (processors <= 0) processors = int(::sysconf(_SC_NPROCESSORS_ONLN));
    if (processors <= 0) processors = 1;
    if (requested <= processors) return requested;
    if (!quiet)
        std::fprintf(stderr, "flotsam: %s %d: capped at %d, the processors this run may use\n", option.c_str(), requested,
                     processors);
    return processors;
}

std::string file_type_of(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return "";
    if (S_ISREG(st.st_mode)) return "a regular file";
    if (S_ISDIR(st.st_mode)) return "a directory";
    if (S_ISCHR(st.st_mode)) return "a character device";
    if (S_ISBLK(st.st_mode)) return "a block device";
    if (S_ISFIFO(st.st_mode)) return "a FIFO (named pipe)";
    if (S_ISSOCK(st.st_mode)) return "a socket";
    return "not a regular file";
}

void check_input_file(const std::string& option, const std::string& path) {
    if (path.empty()) return;
    const std::string type = file_type_of(path);
    if (type.empty() || type == "a regular file") return;  // a missing file: the reader says so
    fail(option, path,
         "is " + type + ", not a regular file: flotsam reads its inputs from files (a device or a pipe may never end)");
}

void check_gis_input(const std::string& option, const std::string& path) {
    namespace fs = std::filesystem;
    const std::string type = file_type_of(path);
    if (path.empty() || type.empty()) return;
    const auto refuse = [&](const std::string& p, const std::string& t, const std::string& why) {
        fail(option, p, "is " + t + ", not a regular file: " + why + " (a device or a pipe may never end)");
    };
    std::error_code ec;
    if (type == "a directory") {
        for (const auto& e : fs::directory_iterator(path, ec))
            if (const std::string t = file_type_of(e.path().string()); !t.empty() && t != "a regular file" && t != "a directory")
                refuse(e.path().string(), t, "GDAL reads the files of the folder " + path);
        return;
    }
    if (type != "a regular file") refuse(path, type, "flotsam reads GIS layers and rasters from files");
    const fs::path p(path);
    const std::string stem = p.stem().string(), name = p.filename().string();
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string other = e.path().filename().string();
        if (other == name || other.rfind(stem, 0) != 0 || other.size() == stem.size() ||
            (other[stem.size()] != '.' && other[stem.size()] != '-'))
            continue;
        if (const std::string t = file_type_of(e.path().string()); !t.empty() && t != "a regular file")
            refuse(e.path().string(), t, "GDAL may read it with " + path);
    }
}

bool same_file(const std::string& a, const std::string& b) {
    struct stat sa {}, sb{};
    if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

void check_output_file(const std::string& option, const std::string& path) {
    if (path.empty()) return;
    for (const std::string& p : {path, path + ".part"}) {
        const std::string type = file_type_of(p);
        if (type.empty() || type == "a regular file") continue;
        fail(option, p,
             "is " + type + ", not a regular file: flotsam writes " + path + ".part and renames it over " + path +
                 ", which would replace it; give the path of a file");
    }
}

void check_input_size(const std::string& option, const std::string& path, double max_bytes, const std::string& what) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || double(st.st_size) <= max_bytes) return;
    char buf[200];
    std::snprintf(buf, sizeof buf, "%.3g bytes, more than the %.3g bytes %s may have", double(st.st_size), max_bytes, what.c_str());
    fail(option, path, buf);
}

std::string disk_full_hint(const std::string& path) {
    std::error_code ec;
    auto dir = std::filesystem::absolute(path, ec).parent_path();
    struct statvfs st {};
    if (ec || ::statvfs(dir.c_str(), &st) != 0) return "";
    const double free_bytes = double(st.f_bavail) * double(st.f_frsize);
    const double total = double(st.f_blocks) * double(st.f_frsize);
    if (free_bytes > 4.0 * 1024 * 1024 && free_bytes > 0.001 * total) return "";
    char buf[160];
    std::snprintf(buf, sizeof buf, " (No space left on device: %.0f bytes free of %.0f on the file system of %s)", free_bytes,
                  total, dir.c_str());
    return buf;
}

}  // namespace flotsam
