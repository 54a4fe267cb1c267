#include "formats/tile_decoder.hpp"

#include <hdf5.h>
#include <libdeflate.h>

#include <cstdint>
#include <cstring>

#include "common/error.hpp"

namespace flotsam {

// One variable: its dataset, shape and filter pipeline (in the order the writer applied it).
struct TileDecoder::Field {
    std::string name;
    hid_t dataset = -1;
    hsize_t frames = 0, ny = 0, nx = 0;
    std::vector<H5Z_filter_t> filters;
};

namespace {

// Keeps libhdf5 from printing its error stack while it lives: a failed call here is
// either a layout the caller reads through netCDF or an Error of ours that says more.
class QuietHdf5 {
public:
    QuietHdf5() {
        H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    }
    ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
    QuietHdf5(const QuietHdf5&) = delete;
    QuietHdf5& operator=(const QuietHdf5&) = delete;

private:
    H5E_auto2_t func_ = nullptr;
    void* data_ = nullptr;
};

bool describe_layout(hid_t dataset, hsize_t (&dims)[3], hsize_t (&chunk)[3], std::vector<H5Z_filter_t>& filters) {
    const hid_t type = H5Dget_type(dataset);
    const bool float32 = type >= 0 && H5Tequal(type, H5T_IEEE_F32LE) > 0;
    if (type >= 0) H5Tclose(type);
    if (!float32) return false;
    const hid_t space = H5Dget_space(dataset);
    const bool rank3 = space >= 0 && H5Sget_simple_extent_ndims(space) == 3 && H5Sget_simple_extent_dims(space, dims, nullptr) == 3;
    if (space >= 0) H5Sclose(space);
    if (!rank3) return false;
    const hid_t plist = H5Dget_create_plist(dataset);
    if (plist < 0) return false;
    bool ok = H5Pget_layout(plist) == H5D_CHUNKED && H5Pget_chunk(plist, 3, chunk) == 3 && chunk[0] == 1 && chunk[1] > 0 &&
              chunk[2] > 0;
    const int n = ok ? H5Pget_nfilters(plist) : 0;
    for (int k = 0; ok && k < n; ++k) {
        unsigned flags = 0, config = 0, values[4] = {0, 0, 0, 0};
        std::size_t n_values = 4;
        char name[64];
        const H5Z_filter_t id = H5Pget_filter2(plist, unsigned(k), &flags, &n_values, values, sizeof name, name, &config);
        // The shuffle's parameter, where libhdf5 lists it, is the value size: 4 bytes.
        ok = (id == H5Z_FILTER_SHUFFLE && (n_values == 0 || values[0] == sizeof(float))) || id == H5Z_FILTER_DEFLATE;
        filters.push_back(id);
    }
    H5Pclose(plist);
    return ok;
}

}  // namespace

std::unique_ptr<TileDecoder> TileDecoder::open(const std::string& path, const std::vector<std::string>& names) {
    const QuietHdf5 quiet;
    std::unique_ptr<TileDecoder> d(new TileDecoder());
    d->path_ = path;
    d->file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (d->file_ < 0) return nullptr;
    for (const std::string& name : names) {
        Field f;
        f.name = name;
        f.dataset = H5Dopen2(hid_t(d->file_), name.c_str(), H5P_DEFAULT);
        if (f.dataset < 0) return nullptr;
        d->fields_.push_back(f);  // closed by the destructor from here on
        hsize_t dims[3], chunk[3];
        if (!describe_layout(f.dataset, dims, chunk, d->fields_.back().filters)) return nullptr;
        d->fields_.back().frames = dims[0];
        d->fields_.back().ny = dims[1];
        d->fields_.back().nx = dims[2];
        if (d->tile_x_ == 0) {
            d->tile_x_ = int(chunk[2]);
            d->tile_y_ = int(chunk[1]);
        } else if (hsize_t(d->tile_x_) != chunk[2] || hsize_t(d->tile_y_) != chunk[1]) {
            return nullptr;
        }
    }
    return d;
}

TileDecoder::~TileDecoder() {
    for (const Field& f : fields_)
        if (f.dataset >= 0) H5Dclose(f.dataset);
    if (file_ >= 0) H5Fclose(hid_t(file_));
}

TileDecoder::Inflater::Inflater() : d_(libdeflate_alloc_decompressor()) {
    if (!d_) throw Error("libdeflate: out of memory for a decompressor");
}

TileDecoder::Inflater::~Inflater() { libdeflate_free_decompressor(d_); }

void TileDecoder::fail(std::size_t var, std::size_t frame, int ti, int tj, const std::string& what) const {
    flotsam::fail(path_,
                  "variable '" + fields_[var].name + "', frame " + std::to_string(frame) + ", tile (" + std::to_string(ti) + ", " +
                      std::to_string(tj) + ") of " + std::to_string(tile_x_) + " x " + std::to_string(tile_y_) + " cells",
                  what);
}

bool TileDecoder::fetch(std::size_t var, std::size_t frame, int ti, int tj, StoredTile& out) {
    const Field& f = fields_.at(var);
    if (frame >= f.frames || ti < 0 || tj < 0 || hsize_t(ti) * hsize_t(tile_x_) >= f.nx || hsize_t(tj) * hsize_t(tile_y_) >= f.ny)
        fail(var, frame, ti, tj, "outside the variable's (time, y, x) extent");
    const hsize_t offset[3] = {hsize_t(frame), hsize_t(tj) * hsize_t(tile_y_), hsize_t(ti) * hsize_t(tile_x_)};
    const QuietHdf5 quiet;
    hsize_t stored = 0;
    if (H5Dget_chunk_storage_size(f.dataset, offset, &stored) < 0 || stored == 0) return false;
    out.bytes.resize(std::size_t(stored));
    out.skipped = 0;
    if (H5Dread_chunk(f.dataset, H5P_DEFAULT, offset, &out.skipped, out.bytes.data()) < 0)
        fail(var, frame, ti, tj, "libhdf5 could not read the stored chunk");
    return true;
}

void TileDecoder::decode(std::size_t var, std::size_t frame, int ti, int tj, const StoredTile& stored, Inflater& inflater,
                         float* out) const {
    const Field& f = fields_.at(var);
    const std::size_t cells = std::size_t(tile_x_) * std::size_t(tile_y_), bytes = cells * sizeof(float);
    inflater.a_.resize(bytes);
    inflater.b_.resize(bytes);
    // Undo the filters last to first, each from one scratch tile into the other.
    const unsigned char* in = stored.bytes.data();
    std::size_t in_bytes = stored.bytes.size();
    for (std::size_t k = f.filters.size(); k-- > 0;) {
        if ((stored.skipped >> k) & 1u) continue;
        unsigned char* dest = in == inflater.a_.data() ? inflater.b_.data() : inflater.a_.data();
        if (f.filters[k] == H5Z_FILTER_DEFLATE) {
            std::size_t got = 0;
            const libdeflate_result r = libdeflate_zlib_decompress(inflater.d_, in, in_bytes, dest, bytes, &got);
            if (r != LIBDEFLATE_SUCCESS || got != bytes)
                fail(var, frame, ti, tj,
                     "the stored chunk does not inflate to " + std::to_string(bytes) +
                         " bytes (its data are corrupted; the file's structure reads)");
        } else {  // shuffle: byte 0 of every value, then byte 1, …
            if (in_bytes != bytes) fail(var, frame, ti, tj, "the shuffled chunk has " + std::to_string(in_bytes) + " bytes");
            for (std::size_t e = 0; e < cells; ++e) {
                const std::uint32_t word = std::uint32_t(in[e]) | std::uint32_t(in[cells + e]) << 8 |
                                           std::uint32_t(in[2 * cells + e]) << 16 | std::uint32_t(in[3 * cells + e]) << 24;
                std::memcpy(dest + e * sizeof(float), &word, sizeof word);
            }
        }
        in = dest;
        in_bytes = bytes;
    }
    if (in_bytes != bytes)
        fail(var, frame, ti, tj, "the stored chunk has " + std::to_string(in_bytes) + " bytes, not " + std::to_string(bytes));
    std::memcpy(out, in, bytes);
}

bool TileDecoder::read(std::size_t var, std::size_t frame, int ti, int tj, float* out) {
    if (!fetch(var, frame, ti, tj, stored_)) return false;
    decode(var, frame, ti, tj, stored_, inflater_, out);
    return true;
}

}  // namespace flotsam
