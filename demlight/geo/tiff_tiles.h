// GeoTIFF tiles encoded by demlight instead of libtiff: the floating-point predictor (TIFF
// Technical Note 3) of Float32 bands or the horizontal one of Int16 bands, and ZSTD, tiles in
// parallel, written raw into the file GDAL created. libtiff 4.5's predictors move one byte or
// sample at a time; its floating-point one took a fifth of a time-lapse frame's CPU
// (docs/performance.md, "Float32 tiles encoded by demlight"). The file is the same GeoTIFF,
// every reader decodes it as before.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demlight::detail {

/// The bands TileWriter encodes: Float32 with the floating-point predictor (3), or Int16 (the
/// fixed-point horizons) with the horizontal one (2).
enum class TileSamples { Float32, Int16 };

/// How the GTiff stores its bands when its creation options are demlight's defaults (tiled,
/// ZSTD, the samples' predictor, band-interleaved), which TileWriter encodes itself.
struct TileEncoding {
    TileSamples samples = TileSamples::Float32;
    int zstdLevel = 9;  // libtiff's level when ZSTD_LEVEL is not given (tif_zstd.c)
    int threads = 0;  // NUM_THREADS: 0 = all cores
};

/// The encoding TileWriter uses for `samples` in a GTiff created with `creationOptions`
/// (defaults and the user's, KEY=VALUE), or nothing when an option asks for anything else
/// (another codec or predictor, pixel interleave, strips, a lossy or custom option): GDAL writes
/// those itself.
std::optional<TileEncoding> tileEncoding(const std::vector<std::string>& creationOptions,
                                         TileSamples samples = TileSamples::Float32);

/// Tests turn the writer off to compare its files with GDAL's (writeRaster then always writes
/// through GDAL).
extern std::atomic<bool> encodeTiles;
/// Tiles TileWriter has written in this process (tests check that it wrote theirs).
extern std::atomic<std::size_t> tilesWritten;

/// The floating-point predictor of one row of `n` floats, as libtiff's fpDiff on a little-endian
/// machine: the row's bytes regrouped most significant first (all first bytes, then all second
/// bytes, ...), then each byte minus the one before it. `out` holds 4 * n bytes.
void predictFloatRow(const float* row, std::size_t n, std::uint8_t* out);
/// The horizontal predictor of one row of `n` 16-bit samples, as libtiff's horDiff16 with one
/// sample per pixel: each sample minus the one before it (mod 2^16), little-endian in `out`
/// (2 * n bytes; the GeoTIFFs GDAL creates here are little-endian).
void predictInt16Row(const std::int16_t* row, std::size_t n, std::uint8_t* out);

/// Fills the bands (Float32 or Int16) of a tiled, band-interleaved GeoTIFF that GDAL created with
/// SPARSE_OK=TRUE and closed before writing any cell (so it holds the directory, georeference
/// and metadata, and no tile): each tile is predicted and compressed here, tiles of a strip in
/// parallel, and appended to the file with libtiff's TIFFWriteRawTile; close() rewrites the tile
/// offsets in place. The file's own tags (tile size, predictor, codec) are checked at opening.
class TileWriter {
public:
    TileWriter(const std::string& path, std::size_t width, std::size_t height, std::size_t bands,
                    TileEncoding encoding);
    TileWriter(const TileWriter&) = delete;
    TileWriter& operator=(const TileWriter&) = delete;
    ~TileWriter();
    /// The file's tile height: writeRows takes whole rows of tiles.
    std::size_t tileHeight() const;
    /// Writes rows [row0, row0 + rows) of band `band` (0-based) from `values` (row-major, the
    /// raster's width per row; float or std::int16_t as the encoding's samples). row0 is a
    /// multiple of tileHeight(); rows is too, or reaches the last row. Throws Error (libtiff's
    /// reason) when the file cannot take them.
    void writeRows(std::size_t band, std::size_t row0, std::size_t rows, const void* values);
    /// Writes the tile offsets and closes the file; throws Error when that fails.
    void close();

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace demlight::detail
