// Reading a NetCDF file first in a child process: libhdf5 can crash or hang on a
// corrupted file (docs/reliability.md, "libhdf5 and corrupted files"), so the child reads
// it the way the readers will (its structure, every attribute, every string, every
// variable up to 16 MB and one value of the larger ones, the close, and the chunk index
// of every variable through libhdf5), and a crash, a hang or a stored chunk past the end
// of the file becomes a named error in the parent. nc::File::open_read calls it.
#pragma once
#include <string>

namespace flotsam::nc {

// Throws naming the file, and what was being read, when libhdf5 crashes or hangs on it in
// the child or a stored chunk lies past the end of the file. A file that passed is not
// probed again by the process while it is unchanged.
void probe_structure(const std::string& path);
// Whether probe_structure() probes: FLOTSAM_NO_PROBE=1 turns it off, and so may the
// caller (the fuzz targets, for the files they write themselves).
bool probe_enabled();
void set_probe_enabled(bool on);

}  // namespace flotsam::nc
