#include "debris/flow_reader.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <optional>

#include <omp.h>

#include "common/background_task.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/units.hpp"
#include "debris/kernels.hpp"
#include "formats/flow_file.hpp"

namespace flotsam::debris {

FlowReaderDef default_flow_reader_def() { return FlowReaderDef{}; }

namespace {

// CPU time of the calling thread [s] (reading runs on one thread, between the parallel
// stepping sweeps).
double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

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
    std::optional<double> value = f.att_double(NC_GLOBAL, name);
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

FlowReader::FlowReader(const std::string& path, const FlowReaderDef& def) : file_(nc::File::open_read(path)), def_(def) {
    cf::require_kind(file_, {"flow"});
    var_h_ = find_field(file_, flow_names::depth, "depth h");
    var_u_ = find_field(file_, flow_names::x_velocity, "x velocity u");
    var_v_ = find_field(file_, flow_names::y_velocity, "y velocity v");
    for (const char* name : {"time", "x", "y", "z"})
        if (!file_.has_var(name)) fail(path, "", std::string("not a flow file: no variable '") + name + "'");
    // Other units than flotsam's (time in hours, x in km, h in cm, u in km h-1) are
    // converted to seconds, metres and metres per second; units it cannot convert are refused.
    times_ = nc::read_finite(file_, "time");
    if (const double ft = units::time_factor(file_, file_.var("time")); ft != 1.0)
        for (double& t : times_) t *= ft;
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
    if (times_.size() < 2)
        fail(path, "variable 'time'",
             std::to_string(times_.size()) +
                 " frame(s): a flow to replay needs at least two (store frames with --output-interval "
                 "shorter than --duration)");
    for (std::size_t k = 1; k < times_.size(); ++k)
        if (!(times_[k] > times_[k - 1]))
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
    z_.assign(z.begin(), z.end());
    // The fields themselves must be (time, y, x) on this grid and time axis.
    for (int v : {var_h_, var_u_, var_v_})
        if (file_.shape(v) != std::vector<std::size_t>{times_.size(), std::size_t(grid_.ny), std::size_t(grid_.nx)})
            fail(path, "variable '" + file_.var_name(v) + "'", "shape does not match (time, y, x) of the coordinates");
    dry_depth_ = read_dry_depth(file_);
    window_ = CellWindow{0, grid_.nx, 0, grid_.ny};
    for (int v : {var_h_, var_u_, var_v_}) size_chunk_cache(file_, v);
    int storage = 0;
    std::size_t chunk[3] = {0, 0, 0};
    file_.check(nc_inq_var_chunking(file_.id(), var_h_, &storage, chunk), "chunking of '" + file_.var_name(var_h_) + "'");
    if (storage == NC_CHUNKED && chunk[1] > 0 && chunk[2] > 0) {
        tile_y_ = int(chunk[1]);
        tile_x_ = int(chunk[2]);
    }
    if (def_.decode_tiles)
        decoder_ = TileDecoder::open(path, {file_.var_name(var_h_), file_.var_name(var_u_), file_.var_name(var_v_)});
    if (decoder_ && (decoder_->tile_x() != tile_x_ || decoder_->tile_y() != tile_y_)) decoder_.reset();
}

double FlowReader::largest_speed() const {
    const auto v = file_.find_var("max_speed");
    if (!v || file_.shape(*v) != std::vector<std::size_t>{std::size_t(grid_.ny), std::size_t(grid_.nx)}) return 0.0;
    const double factor = units::speed_factor(file_, *v);
    double largest = 0.0;
    for (float s : file_.get_float(*v))
        if (std::isfinite(s) && std::fabs(s) < 1e3f) largest = std::max(largest, double(std::fabs(s)) * factor);
    return largest;
}

double FlowReader::next_frame_time(double t) const {
    const auto it = std::upper_bound(times_.begin(), times_.end(), t);
    return it == times_.end() ? times_.back() : *it;
}

FlowReader::TileRange FlowReader::tiles_of(const CellWindow& w) const {
    const int ti0 = w.i0 / tile_x_, tj0 = w.j0 / tile_y_;
    return TileRange{ti0, tj0, (w.i1 - 1) / tile_x_ + 1 - ti0, (w.j1 - 1) / tile_y_ + 1 - tj0};
}

CellWindow FlowReader::tile_cells(const CellWindow& w, int ti, int tj) const {
    return CellWindow{std::max(w.i0, ti * tile_x_), std::min(w.i1, (ti + 1) * tile_x_), std::max(w.j0, tj * tile_y_),
                      std::min(w.j1, (tj + 1) * tile_y_)};
}

std::vector<CellWindow> FlowReader::read_rects(const Area& a) const {
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

void FlowReader::read_cells(Frame& f, std::size_t frame, const CellWindow& w, const CellWindow& r, bool decoded) const {
    const std::size_t ni = std::size_t(r.i1 - r.i0), nj = std::size_t(r.j1 - r.j0), wnx = std::size_t(w.i1 - w.i0);
    const std::vector<std::size_t> start = {frame, std::size_t(r.j0), std::size_t(r.i0)}, count = {1, nj, ni};
    const std::size_t offset = std::size_t(r.j0 - w.j0) * wnx + std::size_t(r.i0 - w.i0);
    const std::pair<int, std::vector<float>*> fields[] = {{var_h_, &f.h}, {var_u_, &f.qx}, {var_v_, &f.qy}};
    for (const auto& [var, field] : fields) {
        if (decoded) continue;  // decode_frame placed them
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

double FlowReader::decode_frame(Frame& f, std::size_t frame, const CellWindow& w, const std::vector<CellWindow>& rects) const {
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
#pragma omp parallel num_threads(std::max(1, def_.decode_threads)) reduction(+ : helpers_cpu)
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
        file_.get_slab(vars[job.field], {frame, std::size_t(job.cells.j0), std::size_t(job.cells.i0)}, {1, nj, ni},
                       f.slab.data());
        place(job, f.slab.data(), ni, job.cells.i0, job.cells.j0);
    }
    return helpers_cpu;
}

double FlowReader::read_frame(Frame& f, std::size_t frame, const Area& a) const {
    const double start_cpu = thread_cpu_seconds();
    const CellWindow& w = a.window;
    const std::size_t n = std::size_t(w.i1 - w.i0) * std::size_t(w.j1 - w.j0);
    f.index = no_frame;
    for (std::vector<float>* field : {&f.h, &f.qx, &f.qy}) {
        field->resize(n);
        if (!a.tiles.empty()) std::fill(field->begin(), field->end(), 0.0f);  // cells not read: dry, never sampled
    }
    const std::vector<CellWindow> rects = read_rects(a);
    const double helpers_cpu = decoder_ ? decode_frame(f, frame, w, rects) : 0.0;
    for (const CellWindow& r : rects) read_cells(f, frame, w, r, decoder_ != nullptr);
    if (has_ground()) depth_over_ground(f, a);
    f.index = frame;
    f.area = a;
    return thread_cpu_seconds() - start_cpu + helpers_cpu;
}

bool FlowReader::tile_loaded(const Area& a, int ti, int tj) const {
    const TileRange t = tiles_of(a.window);
    if (ti < t.ti0 || ti >= t.ti0 + t.nti || tj < t.tj0 || tj >= t.tj0 + t.ntj) return false;
    return a.tiles.empty() || a.tiles[std::size_t((tj - t.tj0) * t.nti + (ti - t.ti0))];
}

double FlowReader::refit_frame(Frame& f, const Area& to) {
    const double start_cpu = thread_cpu_seconds();
    double helpers_cpu = 0.0;
    if (!(f.area == to)) {
        const CellWindow &w = to.window, old = f.area.window;
        const std::size_t n = std::size_t(w.i1 - w.i0) * std::size_t(w.j1 - w.j0);
        const std::size_t wnx = std::size_t(w.i1 - w.i0), onx = std::size_t(old.i1 - old.i0);
        std::vector<float>* fields[3] = {&f.h, &f.qx, &f.qy};
        std::vector<float>* olds[3] = {&refit_spare_.h, &refit_spare_.qx, &refit_spare_.qy};
        for (int k = 0; k < 3; ++k) {
            std::swap(*fields[k], *olds[k]);
            fields[k]->assign(n, 0.0f);  // as read_frame: cells not read are dry and never sampled
        }
        // A tile the old window held whole within the new one is copied; the rest are read.
        const TileRange t = tiles_of(w);
        Area fresh{w, std::vector<char>(std::size_t(t.nti * t.ntj), 0)};
        for (int tj = t.tj0; tj < t.tj0 + t.ntj; ++tj)
            for (int ti = t.ti0; ti < t.ti0 + t.nti; ++ti) {
                if (!tile_loaded(to, ti, tj)) continue;
                const CellWindow c = tile_cells(w, ti, tj);
                if (!tile_loaded(f.area, ti, tj) || !old.contains(c)) {
                    fresh.tiles[std::size_t((tj - t.tj0) * t.nti + (ti - t.ti0))] = 1;
                    continue;
                }
                for (int k = 0; k < 3; ++k)
                    for (int j = c.j0; j < c.j1; ++j)
                        std::copy_n(olds[k]->data() + std::size_t(j - old.j0) * onx + std::size_t(c.i0 - old.i0), c.i1 - c.i0,
                                    fields[k]->data() + std::size_t(j - w.j0) * wnx + std::size_t(c.i0 - w.i0));
            }
        const std::vector<CellWindow> rects = read_rects(fresh);
        try {
            if (decoder_) helpers_cpu = decode_frame(f, f.index, w, rects);
            for (const CellWindow& r : rects) {
                read_cells(f, f.index, w, r, decoder_ != nullptr);
                cells_read_ += std::size_t(r.i1 - r.i0) * std::size_t(r.j1 - r.j0);
            }
        } catch (...) {
            f.index = no_frame;  // half refit: held by no role, read anew if needed again
            throw;
        }
        f.area = to;
        ++frames_refit_;
    }
    if (has_ground()) depth_over_ground(f, to);  // on the new window, or over a new ground
    return thread_cpu_seconds() - start_cpu + helpers_cpu;
}

void FlowReader::load(Frame& f, std::size_t frame) {
    const auto start_clock = std::chrono::steady_clock::now();
    if (!take_read_ahead(f, frame)) {
        wait_read_ahead();  // one netCDF caller at a time; a frame read ahead stays for a later role
        load_cpu_seconds_ += read_frame(f, frame, area());
        count_read(area());
    }
    load_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
}

// The read-ahead thread and what it hands over. Between task.start() and task.wait()
// only the thread touches `frame` and `cpu_seconds`.
struct FlowReader::ReadAhead {
    Frame frame;                    // the frame read
    Area area;                      // the area it is read on
    double cpu_seconds = 0.0;       // CPU time of the read [s]
    std::size_t wanted = no_frame;  // the frame started and not yet taken or dropped; no_frame: none
    BackgroundTask task;            // last: destroyed (its job waited for) first
};

FlowReader::~FlowReader() {
    if (ahead_) ahead_->task.wait();  // its job writes into *ahead_ and reads the file
}

// Never moved with a read under way: World::advance_to finishes each read it starts.
FlowReader::FlowReader(FlowReader&&) noexcept = default;

void FlowReader::read_ahead(double t) {
    if (!loaded_) return;
    std::size_t need[4];
    frames_needed(t, need);
    std::size_t next = no_frame;
    for (int r = 0; r < 4 && next == no_frame; ++r) {
        bool held = false;
        for (int q = 0; q < 4; ++q) held = held || role(q).index == need[r];
        if (!held) next = need[r];
    }
    if (next == no_frame) return;
    if (!ahead_) ahead_ = std::make_unique<ReadAhead>();
    if (ahead_->wanted == next) return;  // under way already; on an earlier window, refit when taken
    drop_read_ahead();
    ReadAhead* a = ahead_.get();
    a->wanted = next;
    a->area = area();
    a->cpu_seconds = 0.0;
    a->task.start([this, a, next] { a->cpu_seconds = read_frame(a->frame, next, a->area); });
}

void FlowReader::wait_read_ahead() {
    if (ahead_ && ahead_->wanted != no_frame) ahead_->task.wait();
}

void FlowReader::finish_read_ahead() {
    const auto start_clock = std::chrono::steady_clock::now();
    wait_read_ahead();  // the frame (or its error) stays for prepare()
    load_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
}

bool FlowReader::take_read_ahead(Frame& f, std::size_t frame) {
    if (!ahead_ || ahead_->wanted != frame) return false;
    const std::exception_ptr error = ahead_->task.wait();
    ahead_->wanted = no_frame;
    count_read(ahead_->area);
    load_cpu_seconds_ += ahead_->cpu_seconds;
    if (error) {
        // A frame that fails its checks is reported where it is needed, as without
        // read-ahead; one never needed is never reported. Read on a window since moved,
        // the bad cells may lie outside the new one: read it there instead.
        if (ahead_->area == area()) std::rethrow_exception(error);
        return false;
    }
    std::swap(f, ahead_->frame);  // f's arrays are the next read's
    ++frames_read_ahead_;
    if (!(f.area == area())) load_cpu_seconds_ += refit_frame(f, area());  // the window moved since the read began
    return true;
}

void FlowReader::drop_read_ahead() {
    if (!ahead_ || ahead_->wanted == no_frame) return;
    ahead_->task.wait();  // an error here is of a frame not needed
    ahead_->wanted = no_frame;
    count_read(ahead_->area);
    load_cpu_seconds_ += ahead_->cpu_seconds;
}

void FlowReader::count_read(const Area& a) {
    ++frames_loaded_;
    const auto cells = [](const CellWindow& c) { return std::size_t(c.i1 - c.i0) * std::size_t(c.j1 - c.j0); };
    window_cells_ += cells(a.window);
    for (const CellWindow& r : read_rects(a)) cells_read_ += cells(r);
}

void FlowReader::hold(const std::size_t (&need)[4]) {
    const bool cubic = def_.time_interpolation == TimeInterpolation::cubic;
    const int r0 = cubic ? 0 : 1, r1 = cubic ? 4 : 3;
    Frame held[4];
    for (int r = 0; r < 4; ++r) held[r] = std::move(frames_[r]);
    // A held frame that no role needs lends its arrays to a frame read anew: reading then
    // neither allocates nor touches fresh pages.
    bool spare[4];
    for (int q = 0; q < 4; ++q) {
        spare[q] = true;
        for (int r = r0; r < r1; ++r) spare[q] = spare[q] && held[q].index != need[r];
    }
    for (int r = r0; r < r1; ++r) {
        Frame& f = frames_[r];
        f.index = no_frame;
        for (int q = r0; q < r && f.index == no_frame; ++q)  // the same frame in an earlier role (at the ends)
            if (frames_[q].index == need[r]) f = frames_[q];
        for (int q = 0; q < 4 && f.index == no_frame; ++q)  // held already: keep it
            if (held[q].index == need[r]) {
                f = std::move(held[q]);
                held[q].index = no_frame;
            }
        if (f.index != no_frame) continue;
        for (int q = 0; q < 4; ++q)
            if (spare[q] && held[q].h.capacity() > 0) {
                f = std::move(held[q]);
                f.index = no_frame;
                spare[q] = false;
                break;
            }
        load(f, need[r]);
    }
    for (int r = 0; r < 4; ++r) {
        role_slot_[r] = cubic ? r : std::clamp(r, 1, 2);
        h_.role[r] = role(r).h.data();
        qx_.role[r] = role(r).qx.data();
        qy_.role[r] = role(r).qy.data();
        ground_depth_.role[r] = role(r).ground_depth.data();
    }
    loaded_ = true;
}

void FlowReader::frames_needed(double t, std::size_t (&need)[4]) const {
    const std::size_t n = times_.size();
    std::size_t k = std::size_t(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
    k = k == 0 ? 0 : k - 1;
    const std::size_t k1 = std::min(k + 1, n - 1);
    const bool cubic = def_.time_interpolation == TimeInterpolation::cubic;
    need[0] = cubic && k > 0 ? k - 1 : k;
    need[1] = k;
    need[2] = k1;
    need[3] = cubic ? std::min(k1 + 1, n - 1) : k1;
}

void FlowReader::prepare(double t) {
    std::size_t need[4];
    frames_needed(t, need);
    if (loaded_) {
        bool same = true;
        for (int r = 0; r < 4; ++r) same = same && role(r).index == need[r];
        if (same) return;
    }
    hold(need);
}

void FlowReader::set_window(const CellWindow& w) {
    CellWindow c{std::clamp(w.i0, 0, grid_.nx - 2), std::clamp(w.i1, 2, grid_.nx), std::clamp(w.j0, 0, grid_.ny - 2),
                 std::clamp(w.j1, 2, grid_.ny)};
    c.i1 = std::max(c.i1, c.i0 + 2);
    c.j1 = std::max(c.j1, c.j0 + 2);
    set_area(Area{c, {}});
}

namespace {
CellWindow widened(const CellWindow& w, int by) { return CellWindow{w.i0 - by, w.i1 + by, w.j0 - by, w.j1 + by}; }
}  // namespace

void FlowReader::set_regions(const std::vector<CellWindow>& regions) {
    if (regions.empty()) return;
    CellWindow box{grid_.nx, 0, grid_.ny, 0};
    std::vector<CellWindow> wide;
    for (const CellWindow& r : regions) {
        const CellWindow c = widened(r, region_margin);
        wide.push_back(CellWindow{std::clamp(c.i0, 0, grid_.nx - 2), std::clamp(c.i1, 2, grid_.nx),
                                  std::clamp(c.j0, 0, grid_.ny - 2), std::clamp(c.j1, 2, grid_.ny)});
        box = CellWindow{std::min(box.i0, wide.back().i0), std::max(box.i1, wide.back().i1), std::min(box.j0, wide.back().j0),
                         std::max(box.j1, wide.back().j1)};
    }
    // Whole tiles (cut only by the grid's edge): a tile is then the same cells in every
    // window that loads it, and a refit keeps it.
    box = CellWindow{box.i0 / tile_x_ * tile_x_, std::min(grid_.nx, (box.i1 + tile_x_ - 1) / tile_x_ * tile_x_),
                     box.j0 / tile_y_ * tile_y_, std::min(grid_.ny, (box.j1 + tile_y_ - 1) / tile_y_ * tile_y_)};
    Area a{box, {}};
    const TileRange t = tiles_of(box);
    a.tiles.assign(std::size_t(t.nti * t.ntj), 0);
    for (const CellWindow& r : wide) {
        const TileRange u = tiles_of(r);
        for (int tj = u.tj0; tj < u.tj0 + u.ntj; ++tj)
            for (int ti = u.ti0; ti < u.ti0 + u.nti; ++ti) a.tiles[std::size_t((tj - t.tj0) * t.nti + (ti - t.ti0))] = 1;
    }
    if (std::all_of(a.tiles.begin(), a.tiles.end(), [](char c) { return c != 0; })) a.tiles.clear();
    set_area(std::move(a));
}

bool FlowReader::covers(const CellWindow& w) const {
    const CellWindow c = widened(w, region_margin);
    const CellWindow need{std::max(c.i0, 0), std::min(c.i1, grid_.nx), std::max(c.j0, 0), std::min(c.j1, grid_.ny)};
    if (!window_.contains(need)) return false;
    if (window_tiles_.empty()) return true;
    const TileRange t = tiles_of(window_), u = tiles_of(need);
    for (int tj = u.tj0; tj < u.tj0 + u.ntj; ++tj)
        for (int ti = u.ti0; ti < u.ti0 + u.nti; ++ti)
            if (!window_tiles_[std::size_t((tj - t.tj0) * t.nti + (ti - t.ti0))]) return false;
    return true;
}

std::size_t FlowReader::tiles_loaded() const {
    const TileRange t = tiles_of(window_);
    return window_tiles_.empty() ? std::size_t(t.nti * t.ntj)
                                 : std::size_t(std::count(window_tiles_.begin(), window_tiles_.end(), char(1)));
}

void FlowReader::set_area(Area a) {
    if (a.window == window_ && a.tiles == window_tiles_ && loaded_) return;
    window_ = a.window;
    window_tiles_ = std::move(a.tiles);
    if (has_ground()) ground_window_ = ground_window(window_);
    reload();
}

void FlowReader::reload() {
    if (!loaded_) return;
    const auto start_clock = std::chrono::steady_clock::now();
    wait_read_ahead();  // one netCDF caller at a time; the frame read ahead is refit when taken
    for (Frame& f : frames_)
        if (f.index != no_frame) load_cpu_seconds_ += refit_frame(f, area());
    load_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
    const std::size_t need[4] = {role(0).index, role(1).index, role(2).index, role(3).index};
    hold(need);  // the roles' arrays moved
}

CellWindow FlowReader::cells_for(double x0, double x1, double y0, double y1) const {
    // The bilinear stencil of x uses nodes floor(fx) and floor(fx) + 1.
    const Double4 f =
        Double4{x0 - grid_.x0, x1 - grid_.x0, y0 - grid_.y0, y1 - grid_.y0} / Double4{grid_.dx, grid_.dx, grid_.dy, grid_.dy};
    const int i0 = int(std::floor(f[0])), i1 = int(std::floor(f[1])) + 2;
    const int j0 = int(std::floor(f[2])), j1 = int(std::floor(f[3])) + 2;
    return CellWindow{std::clamp(i0, 0, grid_.nx - 2), std::clamp(i1, 2, grid_.nx), std::clamp(j0, 0, grid_.ny - 2),
                      std::clamp(j1, 2, grid_.ny)};
}

FlowReader::TimeStencil FlowReader::at_time(double t) const {
    // Every sample goes through here: without frames it would read unallocated memory.
    if (!loaded_) fail(path(), "", "sampled at t = " + std::to_string(t) + " s before prepare() loaded any frame");
    TimeStencil ts;
    const double t0 = times_[role(1).index], t1 = times_[role(2).index];
    if (t1 > t0) {
        ts.a = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
        if (t >= t0 && t <= t1) ts.inv_dt = 1.0 / (t1 - t0);
        if (def_.time_interpolation == TimeInterpolation::cubic) {
            const double tp = times_[role(0).index], tn = times_[role(3).index];
            ts.cubic_weights = catmull_rom_time_weights(ts.a, ts.inv_dt, (t1 - t0) / (t1 - tp), (t1 - t0) / (tn - t0));
            ts.cubic = true;
        }
    }
    return ts;
}

struct FlowReader::Stencil {
    std::size_t n[4] = {0, 0, 0, 0};               // node offsets in the window arrays: 00, 10, 01, 11
    double wx = 0.0, wy = 0.0;                     // bilinear weights of the +1 nodes
    double a = 0.0;                                // linear: weight of frame k+1
    double inv_dt = 0.0;                           // 1 / frame interval, 0 where the flow is held
    bool cubic[4] = {false, false, false, false};  // node c uses the cubic (it passed the guard)
    const TimeWeights* cubic_weights = nullptr;    // set where the cubic interpolant is on
    bool inside_x = true, inside_y = true;         // false where the point was clamped to the grid
};

FlowReader::Stencil FlowReader::stencil(double x, double y, const TimeStencil& ts) const {
    Stencil s;
    stencil_on(grid_, window_, x, y, ts, h_, s);
    return s;
}

// Fills `s` in place, every field: the batched samplers keep arrays of stencils, and a
// stencil returned by value and copied into one was read back as a whole right after
// being written field by field, which stalled the load (a third of the depth sampling).
void FlowReader::stencil_on(const Grid& g, const CellWindow& w, double x, double y, const TimeStencil& ts, const Field& depth,
                            Stencil& s) const {
    const Double2 f = Double2{x - g.x0, y - g.y0} / Double2{g.dx, g.dy};  // one packed division
    const double fx = f[0], fy = f[1];
    const int wnx = w.i1 - w.i0, wny = w.j1 - w.j0;
    int i = int(std::floor(fx)) - w.i0, j = int(std::floor(fy)) - w.j0;
    s.inside_x = i >= 0 && i <= wnx - 2;
    s.inside_y = j >= 0 && j <= wny - 2;
    i = std::clamp(i, 0, wnx - 2);
    j = std::clamp(j, 0, wny - 2);
    s.wx = std::clamp(fx - double(i + w.i0), 0.0, 1.0);
    s.wy = std::clamp(fy - double(j + w.j0), 0.0, 1.0);
    s.n[0] = std::size_t(j) * std::size_t(wnx) + std::size_t(i);
    s.n[1] = s.n[0] + 1;
    s.n[2] = s.n[0] + std::size_t(wnx);
    s.n[3] = s.n[2] + 1;
    s.a = ts.a;
    s.inv_dt = ts.inv_dt;
    s.cubic_weights = ts.cubic ? &ts.cubic_weights : nullptr;
    for (int c = 0; c < 4; ++c) {
        s.cubic[c] = false;
        if (!ts.cubic) continue;
        const std::size_t n = s.n[c];
        const double h[4] = {depth.role[0][n], depth.role[1][n], depth.role[2][n], depth.role[3][n]};
        s.cubic[c] = cubic_depth_admissible(apply_time_weights(ts.cubic_weights.w, h[0], h[1], h[2], h[3]), h, dry_depth_);
    }
}

namespace {
// Value, and its x, y, t derivatives, of one field interpolated in time and bilinearly
// in space.
struct Interp {
    double val, ddx, ddy, ddt;
};
template <class S>
inline double bilinear(const double (&v)[4], const S& s) {
    return (1.0 - s.wy) * ((1.0 - s.wx) * v[0] + s.wx * v[1]) + s.wy * ((1.0 - s.wx) * v[2] + s.wx * v[3]);
}
}  // namespace

// One field at node c of the stencil, in time: its value and its d/dt, from the cubic
// where the node passed the guard, else from the two frames around t.
template <class S, class F>
inline double value_in_time(const S& s, const F& f, int c) {
    const std::size_t n = s.n[c];
    if (s.cubic[c]) return apply_time_weights(s.cubic_weights->w, f.role[0][n], f.role[1][n], f.role[2][n], f.role[3][n]);
    return linear_in_time(s.a, f.role[1][n], f.role[2][n]);
}
template <class S, class F>
inline double rate_in_time(const S& s, const F& f, int c) {
    const std::size_t n = s.n[c];
    if (s.cubic[c]) return apply_time_weights(s.cubic_weights->dw, f.role[0][n], f.role[1][n], f.role[2][n], f.role[3][n]);
    return linear_rate(s.inv_dt, f.role[1][n], f.role[2][n]);
}

// One field at the stencil's point: in time at each node, then bilinear in space.
template <class S, class F>
inline double value_at(const S& s, const F& f) {
    const double v[4] = {value_in_time(s, f, 0), value_in_time(s, f, 1), value_in_time(s, f, 2), value_in_time(s, f, 3)};
    return bilinear(v, s);
}

namespace {
// Points sampled together: their stencils and divisions are independent, so the
// processor overlaps them instead of waiting on each in turn.
constexpr int points_in_flight = 8;
}  // namespace

void FlowReader::set_ground(const Grid& grid, std::vector<float> z) {
    if (z.size() != grid.size()) fail(path(), "ground", "elevation does not match its grid");
    drop_read_ahead();  // read without this ground
    ground_grid_ = grid;
    ground_z_ = std::move(z);
    ground_window_ = ground_window(window_);
    reload();
}

CellWindow FlowReader::ground_window(const CellWindow& w) const {
    // A point sampled in w lies between the nodes x(w.i0) and x(w.i1 − 1) (cells_for), and
    // its bilinear stencil on the ground takes the centres either side of it: one more
    // centre each way covers round-off.
    const Grid& g = ground_grid_;
    const auto below = [](double f) { return int(std::floor(f)) - 1; };
    const int i0 = below((grid_.x(w.i0) - g.x0) / g.dx), i1 = below((grid_.x(w.i1 - 1) - g.x0) / g.dx) + 4;
    const int j0 = below((grid_.y(w.j0) - g.y0) / g.dy), j1 = below((grid_.y(w.j1 - 1) - g.y0) / g.dy) + 4;
    CellWindow c{std::clamp(i0, 0, g.nx - 2), std::clamp(i1, 2, g.nx), std::clamp(j0, 0, g.ny - 2), std::clamp(j1, 2, g.ny)};
    c.i1 = std::max(c.i1, c.i0 + 2);
    c.j1 = std::max(c.j1, c.j0 + 2);
    return c;
}

void FlowReader::depth_over_ground(Frame& f, const Area& a) const {
    const CellWindow& w = a.window;
    const CellWindow gw = ground_window(w);
    f.ground_depth.resize(std::size_t(gw.i1 - gw.i0) * std::size_t(gw.j1 - gw.j0));
    if (!a.tiles.empty()) std::fill(f.ground_depth.begin(), f.ground_depth.end(), 0.0f);  // under tiles not read: never sampled
    for (const CellWindow& r : read_rects(a)) depth_over_ground(f, w, r);
}

void FlowReader::depth_over_ground(Frame& f, const CellWindow& w, const CellWindow& r) const {
    const Grid& g = ground_grid_;
    const CellWindow gw = ground_window(w), gr = ground_window(r);
    const int wnx = w.i1 - w.i0, wny = w.j1 - w.j0, gnx = gw.i1 - gw.i0, rnx = gr.i1 - gr.i0;
    // A ground column's flow stencil (column i of the window, weight wx of column i + 1)
    // is the same in every row: worked out once per column.
    std::vector<int> column(static_cast<std::size_t>(rnx));
    std::vector<double> wx_of(static_cast<std::size_t>(rnx));
    for (int k = 0; k < rnx; ++k) {
        const double fx = (g.x(gr.i0 + k) - grid_.x0) / grid_.dx;
        column[std::size_t(k)] = std::clamp(int(std::floor(fx)) - w.i0, 0, wnx - 2);
        wx_of[std::size_t(k)] = std::clamp(fx - double(column[std::size_t(k)] + w.i0), 0.0, 1.0);
    }
    // Per flow node of the two rows in use: the level h + z and whether it is wet.
    std::vector<double> level_of(2 * std::size_t(wnx));
    std::vector<char> wet_of(2 * std::size_t(wnx));
    int rows_held = -1;  // the window row j whose pair (j, j + 1) the arrays hold
    for (int gj = gr.j0; gj < gr.j1; ++gj) {
        const double fy = (g.y(gj) - grid_.y0) / grid_.dy;
        const int j = std::clamp(int(std::floor(fy)) - w.j0, 0, wny - 2);
        const double wy = std::clamp(fy - double(j + w.j0), 0.0, 1.0);
        if (j != rows_held) {
            for (int row = 0; row < 2; ++row)
                for (int i = 0; i < wnx; ++i) {
                    const std::size_t n = std::size_t(j + row) * std::size_t(wnx) + std::size_t(i);
                    const double h = f.h[n];
                    wet_of[std::size_t(row * wnx + i)] = h > dry_depth_;
                    level_of[std::size_t(row * wnx + i)] = h + double(z_[grid_.index(w.i0 + i, w.j0 + j + row)]);
                }
            rows_held = j;
        }
        float* out = f.ground_depth.data() + std::size_t(gj - gw.j0) * std::size_t(gnx) + std::size_t(gr.i0 - gw.i0);
        const float* ground_z = ground_z_.data() + g.index(gr.i0, gj);
        for (int k = 0; k < rnx; ++k) {
            const int i = column[std::size_t(k)];
            const double wx = wx_of[std::size_t(k)];
            const double wc[4] = {(1.0 - wx) * (1.0 - wy), wx * (1.0 - wy), (1.0 - wx) * wy, wx * wy};
            const std::size_t node[4] = {std::size_t(i), std::size_t(i + 1), std::size_t(wnx + i), std::size_t(wnx + i + 1)};
            // The level bilinear over the wet nodes, their weights renormalised. A dry
            // node adds a zero to both sums (never -0: they start at +0), which leaves
            // them as they are: the same bits as skipping it, without the branch.
            double wet = 0.0, level = 0.0;
            for (int c = 0; c < 4; ++c) {
                const double weight = wet_of[node[c]] ? wc[c] : 0.0;
                wet += weight;
                level += weight * level_of[node[c]];
            }
            out[k] = wet > 0.0 ? float(std::max(0.0, level / wet - double(ground_z[k]))) : 0.0f;
        }
    }
}

double FlowReader::ground_depth(double x, double y, const TimeStencil& ts) const {
    // Bilinear over the ground's cell centres, as a flow stored on the ground's grid is
    // sampled.
    Stencil s;
    stencil_on(ground_grid_, ground_window_, x, y, ts, ground_depth_, s);
    return value_at(s, ground_depth_);
}

double FlowReader::depth(double x, double y, const TimeStencil& ts) const {
    double h = 0.0;
    const Vec2 p{x, y};
    depth(&p, 1, ts, &h);
    return h;
}

namespace {
// Depths at the points p[0..n) (n ≤ points_per_block) bilinear on grid g's cells `w`
// and linear in time between frames k (`now`) and k + 1 (`next`), weight `a` of k + 1:
// stencil_on and value_at for the linear interpolant, the same operations point by
// point (so the same bits), written as loops over the points that the compiler
// vectorises.
constexpr int points_per_block = 64;
void linear_depths(const Grid& g, const CellWindow& w, const float* now, const float* next, double a, const Vec2* p, int n,
                   double* out) {
    const int wnx = w.i1 - w.i0, wny = w.j1 - w.j0;
    double wx[points_per_block], wy[points_per_block];
    int node[points_per_block];  // the 00 node's offset in the window arrays
    // std::clamp and int(std::floor(v)) spelled out in selects and a truncation (the same
    // values), which vectorise.
    const auto unit = [](double v) { return v < 0.0 ? 0.0 : (1.0 < v ? 1.0 : v); };
    const auto floor_int = [](double v) {
        const int t = int(v);  // toward zero
        return double(t) > v ? t - 1 : t;
    };
    double px[points_per_block], py[points_per_block];  // the points as arrays of x and y, for the vectoriser
    for (int k = 0; k < n; ++k) {
        px[k] = p[k].x;
        py[k] = p[k].y;
    }
    const double x0 = g.x0, y0 = g.y0, dx = g.dx, dy = g.dy;
    const int i0 = w.i0, j0 = w.j0;
    for (int k = 0; k < n; ++k) {
        const double fx = (px[k] - x0) / dx, fy = (py[k] - y0) / dy;
        const int i = std::min(std::max(floor_int(fx) - i0, 0), wnx - 2);
        const int j = std::min(std::max(floor_int(fy) - j0, 0), wny - 2);
        wx[k] = unit(fx - double(i + i0));
        wy[k] = unit(fy - double(j + j0));
        node[k] = j * wnx + i;
    }
    for (int k = 0; k < n; ++k) {
        const std::size_t n0 = std::size_t(node[k]), n2 = n0 + std::size_t(wnx);
        const double v[4] = {linear_in_time(a, now[n0], next[n0]), linear_in_time(a, now[n0 + 1], next[n0 + 1]),
                             linear_in_time(a, now[n2], next[n2]), linear_in_time(a, now[n2 + 1], next[n2 + 1])};
        out[k] = (1.0 - wy[k]) * ((1.0 - wx[k]) * v[0] + wx[k] * v[1]) + wy[k] * ((1.0 - wx[k]) * v[2] + wx[k] * v[3]);
    }
}
}  // namespace

void FlowReader::depth(const Vec2* p, int n, const TimeStencil& ts, double* out) const {
    // Over a ground its depths on its centres, else the flow's own, sampled alike.
    const bool g = has_ground();
    const Grid& grid = g ? ground_grid_ : grid_;
    const CellWindow& window = g ? ground_window_ : window_;
    const Field& depth = g ? ground_depth_ : h_;
    if (!ts.cubic) {
        for (int k0 = 0; k0 < n; k0 += points_per_block)
            linear_depths(grid, window, depth.role[1], depth.role[2], ts.a, p + k0, std::min(points_per_block, n - k0), out + k0);
        return;
    }
    for (int k0 = 0; k0 < n; k0 += points_in_flight) {
        const int m = std::min(points_in_flight, n - k0);
        Stencil s[points_in_flight];
        for (int k = 0; k < m; ++k) stencil_on(grid, window, p[k0 + k].x, p[k0 + k].y, ts, depth, s[k]);
        for (int k = 0; k < m; ++k) out[k0 + k] = value_at(s[k], depth);
    }
}

FlowPoint FlowReader::sample(double x, double y, const TimeStencil& ts) const {
    FlowPoint out;
    const Vec2 p{x, y};
    sample(&p, 1, ts, &out);
    return out;
}

void FlowReader::sample(const Vec2* p, int n, const TimeStencil& ts, FlowPoint* out) const {
    for (int k0 = 0; k0 < n; k0 += points_in_flight) {
        const int m = std::min(points_in_flight, n - k0);
        Stencil s[points_in_flight];
        double h[points_in_flight], qx[points_in_flight], qy[points_in_flight];
        for (int k = 0; k < m; ++k) stencil_on(grid_, window_, p[k0 + k].x, p[k0 + k].y, ts, h_, s[k]);
        for (int k = 0; k < m; ++k) {
            h[k] = value_at(s[k], h_);
            qx[k] = value_at(s[k], qx_);
            qy[k] = value_at(s[k], qy_);
            out[k0 + k] = FlowPoint{has_ground() ? ground_depth(p[k0 + k].x, p[k0 + k].y, ts) : h[k], 0.0, 0.0};
        }
        for (int k = 0; k < m; ++k) {
            FlowPoint& q = out[k0 + k];
            if (h[k] < dry_depth_) continue;
            const Double2 uv = Double2{qx[k], qy[k]} / Double2{h[k], h[k]};
            q.u = uv[0];
            q.v = uv[1];
        }
    }
}

FlowPointAccel FlowReader::sample_accel(double x, double y, double t) const {
    const TimeStencil ts = at_time(t);
    FlowPointAccel p = flow_accel(stencil(x, y, ts));
    if (has_ground()) p.depth = ground_depth(x, y, ts);
    return p;
}

FlowPointAccel FlowReader::flow_accel(const Stencil& s) const {
    const double gx = s.inside_x ? 1.0 / grid_.dx : 0.0, gy = s.inside_y ? 1.0 / grid_.dy : 0.0;
    auto interp = [&](const Field& f) {
        const double v[4] = {value_in_time(s, f, 0), value_in_time(s, f, 1), value_in_time(s, f, 2), value_in_time(s, f, 3)};
        const double rate[4] = {rate_in_time(s, f, 0), rate_in_time(s, f, 1), rate_in_time(s, f, 2), rate_in_time(s, f, 3)};
        Interp r;
        r.val = bilinear(v, s);
        r.ddx = ((1.0 - s.wy) * (v[1] - v[0]) + s.wy * (v[3] - v[2])) * gx;
        r.ddy = ((1.0 - s.wx) * (v[2] - v[0]) + s.wx * (v[3] - v[1])) * gy;
        r.ddt = bilinear(rate, s);
        return r;
    };
    const Interp h = interp(h_);
    FlowPointAccel p;
    p.depth = h.val;
    if (h.val < dry_depth_) return p;
    const Interp qx = interp(qx_), qy = interp(qy_);
    const Double2 uv = Double2{qx.val, qy.val} / Double2{h.val, h.val};
    p.u = uv[0];
    p.v = uv[1];
    if (h.val < def_.accel_depth) return p;
    // u = q / h, so ∂u = (∂q − u ∂h) / h for each of ∂t, ∂x, ∂y.
    const Double4 d4 = Double4{qx.ddt - p.u * h.ddt, qx.ddx - p.u * h.ddx, qx.ddy - p.u * h.ddy, qy.ddt - p.v * h.ddt} /
                       Double4{h.val, h.val, h.val, h.val};
    const Double2 d2 = Double2{qy.ddx - p.v * h.ddx, qy.ddy - p.v * h.ddy} / Double2{h.val, h.val};
    const double ut = d4[0], ux = d4[1], uy = d4[2], vt = d4[3], vx = d2[0], vy = d2[1];
    p.du_dt = ut + p.u * ux + p.v * uy;
    p.dv_dt = vt + p.u * vx + p.v * vy;
    return p;
}

double FlowReader::smallest_depth(const Field& depth, const CellWindow& window, const CellWindow& w) {
    const int i0 = std::max(w.i0, window.i0) - window.i0, i1 = std::min(w.i1, window.i1) - window.i0;
    const int j0 = std::max(w.j0, window.j0) - window.j0, j1 = std::min(w.j1, window.j1) - window.j0;
    const int wnx = window.i1 - window.i0;
    float m = 1e30f;
    for (int r = 1; r <= 2; ++r)
        for (int j = j0; j < j1; ++j) {
            const float* row = depth.role[r] + std::size_t(j) * std::size_t(wnx);
#pragma omp simd reduction(min : m)
            for (int i = i0; i < i1; ++i) m = std::min(m, row[i]);
        }
    return double(m);
}

// Over the ground (set_ground) the depth at a point is a bilinear mean of the ground
// centres' depths around it, interpolated in time between the frames around t (the cubic
// only where it stays above the shallower of those two): at least the smallest of those
// centres' depths in the two frames; likewise the flow's own.
double FlowReader::min_depth(const CellWindow& w) const {
    return has_ground() ? smallest_depth(ground_depth_, ground_window_, ground_window(w)) : smallest_depth(h_, window_, w);
}

}  // namespace flotsam::debris
