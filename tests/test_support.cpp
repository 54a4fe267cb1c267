#include "tests/test_support.hpp"

#include <sys/wait.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.hpp"

namespace flotsam::test {

std::string scratch_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("flotsam-test-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

std::string shared_data(const std::string& file) {
    const char* env = std::getenv("FLOTSAM_SHARED");
    const std::filesystem::path root =
        env ? std::filesystem::path(env) : std::filesystem::path(FLOTSAM_SOURCE_DIR) / ".." / "shared";
    const auto p = root / "data" / file;
    return std::filesystem::exists(p) ? p.string() : std::string();
}

int run_cli(const std::string& args, std::string* output) { return finish_cli(start_cli(args), output); }

FILE* start_cli(const std::string& args, const std::string& env) {
    return ::popen((env + " " + std::string(FLOTSAM_BINARY) + " " + args + " 2>&1").c_str(), "r");
}

int finish_cli(FILE* p, std::string* output) {
    if (!p) return -1;
    std::string out;
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    const int st = ::pclose(p);
    if (output) *output = out;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

std::string write_file(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string p = dir + "/" + name;
    std::ofstream(p) << text;
    return p;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void damage_chunk(const std::string& path, const std::string& var, std::size_t frame) {
    haddr_t address = 0;
    hsize_t bytes = 0;
    {
        const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
        const hid_t dataset = file < 0 ? -1 : H5Dopen2(file, var.c_str(), H5P_DEFAULT);
        const hsize_t offset[3] = {hsize_t(frame), 0, 0};
        unsigned mask = 0;
        const bool found = dataset >= 0 && H5Dget_chunk_info_by_coord(dataset, offset, &mask, &address, &bytes) >= 0;
        if (dataset >= 0) H5Dclose(dataset);
        if (file >= 0) H5Fclose(file);
        if (!found || bytes < 40) throw Error(path + ": no stored chunk of '" + var + "' at frame " + std::to_string(frame));
    }
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(address + bytes / 2 - 8));
    const char junk[16] = {'\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a',
                           '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a'};
    f.write(junk, sizeof junk);
    if (!f) throw Error(path + ": could not damage the chunk");
}

SmallCase small_case(const std::string& name) {
    SmallCase c;
    c.dir = scratch_dir(name);
    c.scene = c.dir + "/scene.nc";
    c.series = c.dir + "/bc/wg1_r00.csv";
    std::string out;
    if (run_cli("scene generate --resolution 0.16 --out " + c.scene, &out) != 0) throw Error("small_case: " + out);
    if (run_cli("boundary generate --count 1 --duration 30 --out-dir " + c.dir + "/bc", &out) != 0) throw Error("small_case: " + out);
    return c;
}

}  // namespace flotsam::test
