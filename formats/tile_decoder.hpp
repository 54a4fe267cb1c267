// A flow field's stored tiles, decoded here instead of through netCDF's data path.
//
// The flow file keeps h, u and v as float32 (time, y, x) in (1, tile_y, tile_x) chunks
// with HDF5's shuffle and deflate filters (flow_file.hpp). Replaying a 1 cm flow, most of
// the processor time went to reading them: zlib's inflate (43 % of `sweep_bench`'s
// samples) and libhdf5's filter pipeline and copies around it (12 %). This reads a
// chunk's stored bytes as they are (HDF5's H5Dread_chunk), inflates them with libdeflate
// and undoes the shuffle: the same bytes nc_get_vara gives, in about half the time
// (docs/sweep.md, "Reading the tiles without netCDF").
//
// Only the layout the flow writer makes is decoded: float32 little-endian, chunked one
// frame deep, no filters but shuffle and deflate (either, both or none, in any order the
// pipeline lists them). For anything else open() returns nullptr and the caller reads
// through netCDF, which handles every layout.
//
// Reading the stored bytes goes through libhdf5, which is not thread-safe: one caller at a
// time, as for the netCDF handle the same process holds on the file. Decoding them is
// pure: several threads may decode the tiles of one frame at once.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

struct libdeflate_decompressor;

namespace flotsam {

class TileDecoder {
public:
    // Opens `path` read-only for the (time, y, x) variables `names`; nullptr where one of
    // them is not stored as described above, or the file cannot be opened through HDF5.
    static std::unique_ptr<TileDecoder> open(const std::string& path, const std::vector<std::string>& names);
    ~TileDecoder();
    TileDecoder(const TileDecoder&) = delete;
    TileDecoder& operator=(const TileDecoder&) = delete;

    int tile_x() const { return tile_x_; }  // chunk edge along x [cells]
    int tile_y() const { return tile_y_; }  // chunk edge along y [cells]

    // A tile's stored bytes, as fetch() reads them.
    struct StoredTile {
        std::vector<unsigned char> bytes;
        std::uint32_t skipped = 0;  // bit k: filter k of the pipeline was not applied
    };
    // What decode() works with: a libdeflate decompressor and two tiles of scratch. One
    // per thread; decode() is thread-safe with separate Inflaters.
    class Inflater {
    public:
        Inflater();
        ~Inflater();
        Inflater(const Inflater&) = delete;
        Inflater& operator=(const Inflater&) = delete;

    private:
        friend class TileDecoder;
        libdeflate_decompressor* d_ = nullptr;
        std::vector<unsigned char> a_, b_;
    };

    // Reads the stored bytes of tile (ti, tj) (cells [ti tile_x, (ti + 1) tile_x) ×
    // [tj tile_y, …)) of frame `frame` of variable `var` (an index into open()'s names)
    // through libhdf5: not thread-safe. Returns false where the chunk was never written
    // (read it through netCDF: it holds the fill value).
    bool fetch(std::size_t var, std::size_t frame, int ti, int tj, StoredTile& out);
    // Decodes a fetched tile into out: tile_y × tile_x floats, row-major, x fastest; a
    // tile at the grid's east or north edge is stored whole, its cells past the edge hold
    // the writer's fill. Throws Error naming the file, variable, frame and tile where the
    // stored bytes do not decode.
    void decode(std::size_t var, std::size_t frame, int ti, int tj, const StoredTile& in, Inflater& inflater,
                float* out) const;
    // fetch() and decode() in one, with the decoder's own Inflater: false as fetch().
    bool read(std::size_t var, std::size_t frame, int ti, int tj, float* out);

private:
    struct Field;  // one variable (tile_decoder.cpp)
    TileDecoder() = default;
    [[noreturn]] void fail(std::size_t var, std::size_t frame, int ti, int tj, const std::string& what) const;

    std::string path_;
    long long file_ = -1;  // hid_t
    std::vector<Field> fields_;
    int tile_x_ = 0, tile_y_ = 0;
    StoredTile stored_;  // read()'s
    Inflater inflater_;  // read()'s
};

}  // namespace flotsam
