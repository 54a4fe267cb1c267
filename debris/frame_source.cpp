// Reading a flow file's frames (debris/frame_source.hpp).
#include "debris/frame_source.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <optional>

#include "common/error.hpp"
#include "common/units.hpp"
#include "formats/flow_file.hpp"

namespace flotsam::debris {

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

namespace {

// A flow field found by standard_name, with dims (time, y, x).
int find_field(const nc::File& f, const char* standard_name, const char* short_name) {
    int nvars = 0;
    f.check(nc_inq_nvars(f.id(), &nvars), "number of variables");
    for (int v = 0; v < nvars; ++v) {
        const auto sn = f.att_text(v, "standard_name");
        if (!sn || *sn != standard_name) continue;
        if (f.dim_names(v) == std::vector<std::string>{"time", "y", "x"}) return v;
    }
    fail(f.path(), "",
         std::string("not a flow file: no variable (time, y, x) with standard_name '") + standard_name + "' (the " + short_name +
             " of a stage-one flow)");
}

// The run's dry tolerance from the file's global attribute (text, as flotsam's hydro
// writes it, or a number); the fallback where the file has none.
double read_dry_depth(const nc::File& f) {
    const char* name = flow_names::dry_depth_attribute;
    std::optional<double> value;
    if (!f.att_is_text(NC_GLOBAL, name)) value = f.att_double(NC_GLOBAL, name);
    if (!value) {
        const auto text = f.att_text(NC_GLOBAL, name);
        if (!text) return flow_names::fallback_dry_depth;
        char* end = nullptr;
        const double v = std::strtod(text->c_str(), &end);
        if (end != text->c_str() && *end == '\0') value = v;
        if (!value) fail(f.path(), std::string("attribute '") + name + "'", "'" + *text + "' is not a number");
    }
    if (!(*value > 0.0) || !std::isfinite(*value))
        fail(f.path(), std::string("attribute '") + name + "'",
             "the dry tolerance must be a positive depth [m], got " + std::to_string(*value));
    return *value;
}

// The largest speed of the flow's max_speed map [m/s] (0 when the file has none).
double largest_speed(const nc::File& f, const Grid& g) {
    const auto v = f.find_var("max_speed");
    if (!v || f.shape(*v) != std::vector<std::size_t>{std::size_t(g.ny), std::size_t(g.nx)}) return 0.0;
    const double factor = units::speed_factor(f, *v);
    double largest = 0.0;
    for (float s : f.get_float(*v))
        if (std::isfinite(s) && std::fabs(s) < 1e3f) largest = std::max(largest, double(std::fabs(s)) * factor);
    return largest;
}

// The chunk cache of a field to one frame's chunks over the whole grid. A frame is read
// once (its chunks are not wanted again), so a larger cache only costs time: libhdf5
// walks its list of cached chunks for each chunk it adds once the cache is full, and with
// netCDF's default cache (16 MB, a thousand 64 x 64 tiles) that walk took 4 % of the
// 4 cm sweep bench. Chunks spanning several frames are cached whole.
void size_chunk_cache(const nc::File& f, int var) {
    int storage = 0;
    std::size_t chunk[3] = {0, 0, 0};
    f.check(nc_inq_var_chunking(f.id(), var, &storage, chunk), "chunking of '" + f.var_name(var) + "'");
    if (storage != NC_CHUNKED) return;
    const std::vector<std::size_t> shape = f.shape(var);
    const std::size_t tiles = ((shape[1] + chunk[1] - 1) / chunk[1]) * ((shape[2] + chunk[2] - 1) / chunk[2]);
    const std::size_t bytes = tiles * chunk[0] * chunk[1] * chunk[2] * sizeof(double);  // the widest numeric type
    f.check(nc_set_var_chunk_cache(f.id(), var, bytes, 1009, 0.75f), "chunk cache of '" + f.var_name(var) + "'");
}

}  // namespace

FrameSource::FrameSource(const std::string& path, bool decode_tiles, int decode_threads)
    : file_(nc::File::open_read(path)), decode_threads_(decode_threads) {
    cf::require_kind(file_, {"flow"});
    var_h_ = find_field(file_, flow_names::depth, "depth h");
    var_u_ = find_field(file_, flow_names::x_velocity, "x velocity u");
    var_v_ = find_field(file_, flow_names::y_velocity, "y velocity v");
    for (const char* name : {"time", "x", "y", "z"})
        if (!file_.has_var(name)) fail(path, "", std::string("not a flow file: no variable '") + name + "'");
    // Other units than flotsam's (time in hours, x in km, h in cm, u in km h-1) are
    // converted to seconds, metres and metres per second; units it cannot convert are refused.
    std::vector<double>& times = desc_.frame_times;
    times = nc::read_finite(file_, "time");
    if (const double ft = units::time_factor(file_, file_.var("time")); ft != 1.0)
        for (double& t : times) t *= ft;
    std::vector<double> xs = nc::read_finite(file_, "x"), ys = nc::read_finite(file_, "y");
    if (const double fx = units::length_factor(file_, file_.var("x")); fx != 1.0)
        for (double& a : xs) a *= fx;
    if (const double fy = units::length_factor(file_, file_.var("y")); fy != 1.0)
        for (double& a : ys) a *= fy;
    grid_ = grid_from_coordinates(xs, ys, path);
    scale_h_ = float(units::length_factor(file_, var_h_));
    scale_u_ = float(units::speed_factor(file_, var_u_));
    scale_v_ = float(units::speed_factor(file_, var_v_));
    if (grid_.nx < 2 || grid_.ny < 2) fail(path, "x, y", "a flow needs at least 2 x 2 cells");
    if (times.size() < 2)
        fail(path, "variable 'time'",
             std::to_string(times.size()) +
                 " frame(s): a flow to replay needs at least two (store frames with --output-interval "
                 "shorter than --duration)");
    for (std::size_t k = 1; k < times.size(); ++k)
        if (!(times[k] > times[k - 1]))
            fail(path, "variable 'time'", "frame times must increase (frame " + std::to_string(k) + ")");
    const int vz = file_.var("z");
    if (file_.shape(vz) != std::vector<std::size_t>{std::size_t(grid_.ny), std::size_t(grid_.nx)} ||
        file_.dim_names(vz) != std::vector<std::string>{"y", "x"})
        fail(path, "variable 'z'", "must have dimensions (y, x) of the flow's grid");
    std::vector<double> z = nc::read_finite(file_, "z");
    if (const double fz = units::length_factor(file_, vz) * units::vertical_sign(file_, vz); fz != 1.0)
        for (double& a : z) a *= fz;
    for (std::size_t k = 0; k < z.size(); ++k)
        if (!(z[k] >= -11000.0 && z[k] <= 9000.0))
            fail(path, "variable 'z'",
                 "bed " + std::to_string(z[k]) + " m at flat index " + std::to_string(k) +
                     " is outside [-11000, 9000] m (no bed on Earth is deeper or higher: a fill value?)");
    desc_.bed.assign(z.begin(), z.end());
    // The fields themselves must be (time, y, x) on this grid and time axis.
    for (int v : {var_h_, var_u_, var_v_})
        if (file_.shape(v) != std::vector<std::size_t>{times.size(), std::size_t(grid_.ny), std::size_t(grid_.nx)})
            fail(path, "variable '" + file_.var_name(v) + "'", "shape does not match (time, y, x) of the coordinates");
    desc_.path = path;
    desc_.dry_depth = read_dry_depth(file_);
    desc_.largest_speed = largest_speed(file_, grid_);
    desc_.scene_sha256 = file_.att_text(NC_GLOBAL, "scene_sha256").value_or("");
    desc_.scene_buildings_sha256 = file_.att_text(NC_GLOBAL, "scene_buildings_sha256").value_or("");
    desc_.crs = cf::read_crs(file_, file_.var_name(var_h_));
    for (int v : {var_h_, var_u_, var_v_}) size_chunk_cache(file_, v);
    int storage = 0;
    std::size_t chunk[3] = {0, 0, 0};
    file_.check(nc_inq_var_chunking(file_.id(), var_h_, &storage, chunk), "chunking of '" + file_.var_name(var_h_) + "'");
    if (storage == NC_CHUNKED && chunk[1] > 0 && chunk[2] > 0) {
        tile_y_ = int(chunk[1]);
        tile_x_ = int(chunk[2]);
    }
    if (decode_tiles) decoder_ = TileDecoder::open(path, {file_.var_name(var_h_), file_.var_name(var_u_), file_.var_name(var_v_)});
    if (decoder_ && (decoder_->tile_x() != tile_x_ || decoder_->tile_y() != tile_y_)) decoder_.reset();
}

double FrameSource::next_frame_time(double t) const {
    const std::vector<double>& times = desc_.frame_times;
    const auto it = std::upper_bound(times.begin(), times.end(), t);
    return it == times.end() ? times.back() : *it;
}

TileRange FrameSource::tiles_of(const CellWindow& w) const {
    const int ti0 = w.i0 / tile_x_, tj0 = w.j0 / tile_y_;
    return TileRange{ti0, tj0, (w.i1 - 1) / tile_x_ + 1 - ti0, (w.j1 - 1) / tile_y_ + 1 - tj0};
}

CellWindow FrameSource::tile_cells(const CellWindow& w, int ti, int tj) const {
    return CellWindow{std::max(w.i0, ti * tile_x_), std::min(w.i1, (ti + 1) * tile_x_), std::max(w.j0, tj * tile_y_),
                      std::min(w.j1, (tj + 1) * tile_y_)};
}

std::vector<CellWindow> FrameSource::read_rects(const FrameArea& a) const {
    if (a.tiles.empty()) return {a.window};
    // Each row of tiles as runs of tiles side by side: one read per run and field.
    std::vector<CellWindow> runs;
    const TileRange t = tiles_of(a.window);
    for (int tj = 0; tj < t.ntj; ++tj)
        for (int ti = 0; ti < t.nti;) {
            int end = ti;
            while (end < t.nti && a.tiles[std::size_t(tj * t.nti + end)]) ++end;
            if (end == ti) {
                ++ti;
                continue;
            }
            const CellWindow first = tile_cells(a.window, t.ti0 + ti, t.tj0 + tj),
                             last = tile_cells(a.window, t.ti0 + end - 1, t.tj0 + tj);
            runs.push_back(CellWindow{first.i0, last.i1, first.j0, first.j1});
            ti = end;
        }
    return runs;
}

void FrameSource::read_rect(Frame& f, std::size_t frame, const CellWindow& w, const CellWindow& r, bool decoded) const {
    const std::size_t ni = std::size_t(r.i1 - r.i0), nj = std::size_t(r.j1 - r.j0), wnx = std::size_t(w.i1 - w.i0);
    const std::vector<std::size_t> start = {frame, std::size_t(r.j0), std::size_t(r.i0)}, count = {1, nj, ni};
    const std::size_t offset = std::size_t(r.j0 - w.j0) * wnx + std::size_t(r.i0 - w.i0);
    const std::pair<int, std::vector<float>*> fields[] = {{var_h_, &f.h}, {var_u_, &f.qx}, {var_v_, &f.qy}};
    for (const auto& [var, field] : fields) {
        if (decoded) continue;  // decode_tiles placed them
        if (r == w) {
            file_.get_slab(var, start, count, field->data());
            continue;
        }
        f.slab.resize(ni * nj);
        file_.get_slab(var, start, count, f.slab.data());
        for (std::size_t j = 0; j < nj; ++j) std::copy_n(f.slab.data() + j * ni, ni, field->data() + offset + j * wnx);
    }
    if (scale_h_ != 1.0f || scale_u_ != 1.0f || scale_v_ != 1.0f)  // the file's units to m and m/s
        for (std::size_t j = 0; j < nj; ++j)
            for (std::size_t k = offset + j * wnx; k < offset + j * wnx + ni; ++k) {
                f.h[k] *= scale_h_;
                f.qx[k] *= scale_u_;
                f.qy[k] *= scale_v_;
            }
    for (std::size_t j = 0; j < nj; ++j)
        for (std::size_t k = offset + j * wnx; k < offset + j * wnx + ni; ++k) {
            const float h = f.h[k], u = f.qx[k], v = f.qy[k];
            // A stored flow has 0 where dry, never NaN, a fill value or a negative depth.
            if (!(h >= 0.0f && h < 1.1e4f && std::fabs(u) < 1e3f && std::fabs(v) < 1e3f)) {
                const std::size_t i = std::size_t(w.i0) + k % wnx, jj = std::size_t(w.j0) + k / wnx;
                const char* what = !(h >= 0.0f && h < 1.1e4f) ? "h" : !(std::fabs(u) < 1e3f) ? "u" : "v";
                const float value = what[0] == 'h' ? h : what[0] == 'u' ? u : v;
                fail(path(),
                     "frame " + std::to_string(frame) + ", cell (i " + std::to_string(i) + ", j " + std::to_string(jj) + ")",
                     std::string(what) + " = " + std::to_string(value) +
                         " is not a depth or velocity (NaN, a fill value, negative or absurd); a flow file stores 0 where dry");
            }
            f.qx[k] *= h;  // u → hu
            f.qy[k] *= h;
        }
}

double FrameSource::decode_tiles(Frame& f, std::size_t frame, const CellWindow& w, const std::vector<CellWindow>& rects) const {
    struct Job {
        int field, ti, tj;
        CellWindow cells;  // the tile's cells within its rect
        bool stored;
    };
    std::vector<Job> jobs;
    for (const CellWindow& r : rects) {
        const TileRange t = tiles_of(r);
        for (int tj = t.tj0; tj < t.tj0 + t.ntj; ++tj)
            for (int ti = t.ti0; ti < t.ti0 + t.nti; ++ti)
                for (int k = 0; k < 3; ++k) jobs.push_back(Job{k, ti, tj, tile_cells(r, ti, tj), false});
    }
    // libhdf5 is not thread-safe: the stored bytes are read here, in turn, and decoded below.
    if (f.stored.size() < jobs.size()) f.stored.resize(jobs.size());
    for (std::size_t n = 0; n < jobs.size(); ++n)
        jobs[n].stored = decoder_->fetch(std::size_t(jobs[n].field), frame, jobs[n].ti, jobs[n].tj, f.stored[n]);
    float* const out[3] = {f.h.data(), f.qx.data(), f.qy.data()};
    const std::size_t wnx = std::size_t(w.i1 - w.i0), tx = std::size_t(tile_x_);
    const auto place = [&](const Job& job, const float* tile, std::size_t tile_nx, int i0, int j0) {
        for (int j = job.cells.j0; j < job.cells.j1; ++j)
            std::copy_n(tile + std::size_t(j - j0) * tile_nx + std::size_t(job.cells.i0 - i0), job.cells.i1 - job.cells.i0,
                        out[job.field] + std::size_t(j - w.j0) * wnx + std::size_t(job.cells.i0 - w.i0));
    };
    // An Error thrown inside the parallel region is kept per job and the first rethrown
    // after it (an exception must not leave an OpenMP region).
    std::vector<std::exception_ptr> failed(jobs.size());
    const long n_jobs = long(jobs.size());
    double helpers_cpu = 0.0;  // the team's CPU time but the calling thread's [s]
#pragma omp parallel num_threads(std::max(1, decode_threads_)) reduction(+ : helpers_cpu)
    {
        const double start_cpu = thread_cpu_seconds();
        std::optional<TileDecoder::Inflater> inflater;
        std::vector<float> tile;
#pragma omp for schedule(dynamic, 8)
        for (long n = 0; n < n_jobs; ++n) {
            const Job& job = jobs[std::size_t(n)];
            if (!job.stored) continue;
            try {
                if (!inflater) {
                    inflater.emplace();
                    tile.resize(tx * std::size_t(tile_y_));
                }
                decoder_->decode(std::size_t(job.field), frame, job.ti, job.tj, f.stored[std::size_t(n)], *inflater, tile.data());
                place(job, tile.data(), tx, job.ti * tile_x_, job.tj * tile_y_);
            } catch (...) {
                failed[std::size_t(n)] = std::current_exception();
            }
        }
        if (omp_get_thread_num() != 0) helpers_cpu += thread_cpu_seconds() - start_cpu;
    }
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
    const int vars[3] = {var_h_, var_u_, var_v_};
    for (const Job& job : jobs) {  // chunks never written: netCDF gives their fill
        if (job.stored) continue;
        const std::size_t ni = std::size_t(job.cells.i1 - job.cells.i0), nj = std::size_t(job.cells.j1 - job.cells.j0);
        f.slab.resize(ni * nj);
        file_.get_slab(vars[job.field], {frame, std::size_t(job.cells.j0), std::size_t(job.cells.i0)}, {1, nj, ni}, f.slab.data());
        place(job, f.slab.data(), ni, job.cells.i0, job.cells.j0);
    }
    return helpers_cpu;
}

double FrameSource::read_frame(Frame& f, std::size_t frame, const FrameArea& a) const {
    const double start_cpu = thread_cpu_seconds();
    const CellWindow& w = a.window;
    const std::size_t n = std::size_t(w.i1 - w.i0) * std::size_t(w.j1 - w.j0);
    f.index = no_frame;
    for (std::vector<float>* field : {&f.h, &f.qx, &f.qy}) {
        field->resize(n);
        if (!a.tiles.empty()) std::fill(field->begin(), field->end(), 0.0f);  // cells not read: dry, never sampled
    }
    const double helpers_cpu = read_cells(f, frame, w, read_rects(a));
    f.index = frame;
    f.area = a;
    return thread_cpu_seconds() - start_cpu + helpers_cpu;
}

bool FrameSource::tile_loaded(const FrameArea& a, int ti, int tj) const {
    const TileRange t = tiles_of(a.window);
    if (ti < t.ti0 || ti >= t.ti0 + t.nti || tj < t.tj0 || tj >= t.tj0 + t.ntj) return false;
    return a.tiles.empty() || a.tiles[std::size_t((tj - t.tj0) * t.nti + (ti - t.ti0))];
}

double FrameSource::read_cells(Frame& f, std::size_t frame, const CellWindow& w, const std::vector<CellWindow>& rects) const {
    const double helpers_cpu = decoder_ ? decode_tiles(f, frame, w, rects) : 0.0;
    for (const CellWindow& r : rects) read_rect(f, frame, w, r, decoder_ != nullptr);
    return helpers_cpu;
}

void FrameReadAhead::start(std::size_t frame, FrameArea a, Reader read) {
    wanted_ = frame;
    area_ = std::move(a);
    cpu_seconds_ = 0.0;
    task_.start([this, frame, read = std::move(read)] { cpu_seconds_ = read(frame_, frame, area_); });
}

void FrameReadAhead::wait() {
    if (wanted_ != no_frame) task_.wait();
}

FrameReadAhead::Finished FrameReadAhead::finish() {
    Finished done{task_.wait(), cpu_seconds_};
    wanted_ = no_frame;
    return done;
}

}  // namespace flotsam::debris
