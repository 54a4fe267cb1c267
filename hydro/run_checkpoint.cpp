// Reading the bookkeeping of hydro checkpoints (run_checkpoint.hpp).
#include "hydro/run_checkpoint.hpp"

namespace flotsam::hydro {

double read_checkpoint_time(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    return f.att_double(NC_GLOBAL, "time").value_or(-1.0);
}

std::string read_checkpoint_key(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    const auto key = f.att_text(NC_GLOBAL, "restart_key");
    if (!key) fail(path, "attribute 'restart_key'", "missing: written by an older flotsam, whose checkpoints cannot be continued");
    return *key;
}

}  // namespace flotsam::hydro
