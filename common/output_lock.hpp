// One writer per output, and no output over an input.
//
// OutputLock holds an exclusive flock(2) on "<out>.lock" while a run writes <out> (and
// its "<out>.part", checkpoint and summaries). A second run that wants the same output
// stops at once with "another run is writing <out> (pid N on HOST)" and touches nothing
// of the first. The lock is the kernel's: it goes with the process, however that ends
// (kill -9 included), so a stale "<out>.lock" file never blocks anyone. It does not
// depend on HDF5's own file locking, so it holds with HDF5_USE_FILE_LOCKING=FALSE too.
// On NFS, Linux maps flock to POSIX byte-range locks, which the server arbitrates; on
// Lustre it needs the `flock` mount option (docs/reliability.md).
//
// Locks are per process and re-entrant: a command takes the lock of its outputs at its
// start, and AtomicOutput takes it again (a count) when it writes.
#pragma once
#include <string>
#include <vector>

namespace flotsam {

class OutputLock {
public:
    explicit OutputLock(const std::string& out_path);  // throws flotsam::Error when another process holds it
    ~OutputLock();
    OutputLock(OutputLock&& other) noexcept;
    OutputLock& operator=(OutputLock&&) = delete;
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

private:
    std::string key_;  // the resolved output path; empty once moved from
};

// A path given for an option, for messages ("--out", "runs/f.nc").
struct NamedPath {
    std::string option;
    std::string path;
    bool gis = false;  // an input GDAL opens: a folder of files will do (common/checks.hpp, check_gis_input)
};

// Refuses an input that is not a regular file (a device, a FIFO: a stream that may never
// end) and an existing output that is not one (a device, a FIFO, a directory), then an
// output that is one of the inputs (the same file: same device and inode, so
// symbolic links, hard links and relative spellings are caught), whose ".part" is an
// input, or that is another output of the same command; then takes the lock of every
// output. Empty paths are skipped. Errors name both options and the path.
class OutputGuard {
public:
    OutputGuard(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

private:
    std::vector<OutputLock> locks_;
};

}  // namespace flotsam
