// Fuzz targets, one per reader (docs/reliability.md, "Fuzzing"). Each takes one input
// of arbitrary bytes, turns it into a file the reader reads, runs the reader and what
// consumes its result, and returns normally: a flotsam::Error (a named error) is the
// expected answer to bad input. Anything else — a crash, a sanitizer report, another
// exception escaping, a hang, unbounded memory — is a defect.
//
// The NetCDF targets (scene, flow, sweep) take two kinds of input, chosen by the first
// byte. Below 0xF0, structure-aware edits (resize a dimension, move a variable onto a
// dimension of another length, set a value to NaN, infinity, a fill value or an absurd
// number, transpose, drop a variable or attribute, ...) applied to a small valid file, so
// the readers see files that HDF5 parses but whose contents are wrong. From 0xF0, byte
// mutations of the same file ((offset, value) pairs), read with the libhdf5 probe on:
// corrupted structure, where libhdf5 itself crashes or hangs (docs/reliability.md), must
// give a named error too. Either way the file is closed (the close path is where a
// damaged metadata cache crashed).
//
// Built two ways: as libFuzzer executables (fuzz/fuzz_main.cpp, `make -f
// Makefile.pipeline fuzz`) and into tests/fuzz_regression_test.cpp, which replays every
// input under tests/data/fuzz/<target>/.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace flotsam::fuzz {

void csv(const std::uint8_t* data, std::size_t size);       // time series CSV and ESRI ASCII DEM
void toml(const std::uint8_t* data, std::size_t size);      // sweep spec and scene-import features
void settings(const std::uint8_t* data, std::size_t size);  // --config settings of every command
void scene(const std::uint8_t* data, std::size_t size);     // scene NetCDF
void flow(const std::uint8_t* data, std::size_t size);      // flow NetCDF, replayed
void sweep(const std::uint8_t* data, std::size_t size);     // sweep NetCDF, with statistics

struct Target {
    const char* name;
    void (*run)(const std::uint8_t*, std::size_t);
};
const std::vector<Target>& targets();

// The small valid files the NetCDF targets start from ("scene", "flow", "sweep"), written
// into work_dir() on first use.
const std::string& base_file(const std::string& which);

// The flow target's reading: a replay of one body for 1.5 s (a named error is fine).
void flow_replay(const std::string& path);

// The working directory of the targets (created once per process): base files live
// there, and specs may name them relatively (scene.nc, flow.nc).
const std::string& work_dir();

}  // namespace flotsam::fuzz
