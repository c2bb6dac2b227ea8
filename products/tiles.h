// Running a raster product over a DEM in tiles: every product computes any window with its halo
// and gives it the whole DEM's bits (tests/tiling_test.cpp), so a DEM can be lit tile by tile
// with one tile of each output in memory, or window by window in separate processes.
#pragma once

#include "products/product.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace demlight {

/// Tiles of at most `tileCells` x `tileCells` covering `extent`, row by row from its north-west
/// corner (the last column and row of tiles may be narrower).
std::vector<CellWindow> tilesOf(const CellWindow& extent, std::size_t tileCells);

/// A tile's progress as its share of the whole job's: fraction f of tile `index` of `count`
/// reports (index + f) / count, the stage prefixed "tile i/n". Cancelling the job cancels the tile.
ProgressFn tileProgress(const ProgressFn& job, std::size_t index, std::size_t count);

/// Memory a product holds while it computes one tile (bytes), as a rule of thumb for sizing
/// tiles: so much per cell it reads (the tile with its halo) and so much per cell of the tile.
struct TileBytes {
    double perReadCell = 0;
    double perTileCell = 0;
};

/// A product that computes every cell it reads and crops the result to the tile (onWindow):
/// heights, normals, sweep planes and scratch for every read cell, and each output band.
TileBytes productTileBytes(std::size_t outputBands);

/// A product that computes the tile's cells only (onWindowCells: sky, aperture): heights and two
/// sweep planes for every read cell (onWindowCells drops the raw band values once the heights
/// are made); normals, the integral's sums (`sumBytesPerCell`) and the output bands that need
/// memory of their own (`newBands`: not made from the sums in place) for the tile's cells.
TileBytes windowProductTileBytes(std::size_t sumBytesPerCell, std::size_t newBands);

/// The tile side for --tile-size auto: the whole extent when extent + halo fits `memoryBytes`
/// at `bytes` (one piece is fastest), else the largest side s whose tile with its halo fits,
/// at least 256 cells (a smaller tile re-reads more halo than it computes); then evened out so
/// that the extent's longer side is cut into tiles of equal size (a thin last tile would read a
/// whole halo for a few cells).
std::size_t automaticTileCells(const CellWindow& extent, std::size_t haloCells, const TileBytes& bytes,
                               double memoryBytes);

/// GDAL's block cache a run allows itself out of a memory budget of `memoryBytes`: an eighth,
/// at most 256 MiB.
double rasterCacheBytes(double memoryBytes);

/// What a run holds besides its tile and GDAL's block cache: the program, its libraries and
/// GDAL's and PROJ's own state (a sky run on the bundled 152 x 187 sample peaks at 64 MB).
inline constexpr double kProcessBytes = 64.0 * (1 << 20);

/// The memory --tile-size auto sizes tiles for out of a budget of `memoryBytes`: the budget less
/// the block cache (rasterCacheBytes) and the process (kProcessBytes).
double tileMemoryBytes(double memoryBytes);

/// Half of this machine's physical memory (bytes): --memory-limit's default.
double defaultMemoryLimitBytes();

}  // namespace demlight
