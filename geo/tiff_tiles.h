// Float32 GeoTIFF tiles encoded by demlight instead of libtiff: the floating-point predictor
// (TIFF Technical Note 3) and ZSTD, tiles in parallel, written raw into the file GDAL created.
// libtiff 4.5's predictor moves one byte at a time and took a fifth of a time-lapse frame's CPU
// (docs/performance.md, "Float32 tiles encoded by demlight"); the file is the same GeoTIFF, every
// reader decodes it as before.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demlight::detail {

/// How the GTiff stores Float32 bands when its creation options are demlight's defaults (tiled,
/// ZSTD, PREDICTOR=3, band-interleaved), which FloatTileWriter encodes itself.
struct FloatTileEncoding {
    int zstdLevel = 1;
    int threads = 0;  // NUM_THREADS: 0 = all cores
};

/// The encoding FloatTileWriter uses for a GTiff created with `creationOptions` (defaults and the
/// user's, KEY=VALUE), or nothing when an option asks for anything else (another codec or
/// predictor, pixel interleave, strips, a lossy or custom option): GDAL writes those itself.
std::optional<FloatTileEncoding> floatTileEncoding(const std::vector<std::string>& creationOptions);

/// Tests turn the writer off to compare its files with GDAL's (writeRaster then always writes
/// through GDAL).
extern std::atomic<bool> encodeFloatTiles;
/// Tiles FloatTileWriter has written in this process (tests check that it wrote theirs).
extern std::atomic<std::size_t> floatTilesWritten;

/// The floating-point predictor of one row of `n` floats, as libtiff's fpDiff on a little-endian
/// machine: the row's bytes regrouped most significant first (all first bytes, then all second
/// bytes, ...), then each byte minus the one before it. `out` holds 4 * n bytes.
void predictFloatRow(const float* row, std::size_t n, std::uint8_t* out);

/// Fills the Float32 bands of a tiled, band-interleaved GeoTIFF that GDAL created with
/// SPARSE_OK=TRUE and closed before writing any cell (so it holds the directory, georeference
/// and metadata, and no tile): each tile is predicted and compressed here, tiles of a strip in
/// parallel, and appended to the file with libtiff's TIFFWriteRawTile; close() rewrites the tile
/// offsets in place. The file's own tags (tile size, predictor, codec) are checked at opening.
class FloatTileWriter {
public:
    FloatTileWriter(const std::string& path, std::size_t width, std::size_t height, std::size_t bands,
                    FloatTileEncoding encoding);
    FloatTileWriter(const FloatTileWriter&) = delete;
    FloatTileWriter& operator=(const FloatTileWriter&) = delete;
    ~FloatTileWriter();
    /// The file's tile height: writeRows takes whole rows of tiles.
    std::size_t tileHeight() const;
    /// Writes rows [row0, row0 + rows) of band `band` (0-based) from `values` (row-major, the
    /// raster's width per row). row0 is a multiple of tileHeight(); rows is too, or reaches the
    /// last row. Throws Error (libtiff's reason) when the file cannot take them.
    void writeRows(std::size_t band, std::size_t row0, std::size_t rows, const float* values);
    /// Writes the tile offsets and closes the file; throws Error when that fails.
    void close();

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace demlight::detail
