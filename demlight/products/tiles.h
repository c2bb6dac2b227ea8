// Running a raster product over a DEM in tiles: every product computes any window with its halo
// and gives it the whole DEM's bits (tests/tiling_test.cpp), so a DEM can be lit tile by tile
// with one tile of each output in memory, or window by window in separate processes.
#pragma once

#include "demlight/products/product.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace demlight {

/// The size of a run's tiles (cells): cols x rows.
struct TileShape {
    std::size_t cols = 0, rows = 0;
    bool operator==(const TileShape&) const = default;
};

/// Tiles of at most shape.cols x shape.rows covering `extent`, row by row from its north-west
/// corner (the last column and row of tiles may be narrower).
std::vector<CellWindow> tilesOf(const CellWindow& extent, TileShape shape);
/// Square tiles of at most `tileCells` x `tileCells`.
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

/// Memory (bytes, at `bytes`) of a tile of `shape` on a grid of gridCols x gridRows cells: the
/// tile and what it reads, the tile grown by haloCells on every side and clipped to the grid (a
/// halo cannot read past the DEM's edges, so a halo longer than the DEM reads the DEM once).
double tileBytes(TileShape shape, std::size_t haloCells, std::size_t gridCols, std::size_t gridRows,
                 const TileBytes& bytes);

/// The tiles --tile-size auto cuts an extent into.
struct TilePlan {
    /// The tile size; {0, 0} when not even the smallest tile fits the memory given.
    TileShape shape;
    /// Memory (bytes) of the smallest tile the planner would use: what the budget must be at
    /// least.
    double smallestTileBytes = 0;
};

/// Plans --tile-size auto for `extent` (cells of a gridCols x gridRows DEM): one piece when the
/// extent with its halo fits `memoryBytes` at `bytes` (one piece is fastest); else the tiles
/// that fit and read the fewest cells in all, halos included, of three kinds: squares, strips
/// the extent's full width, and strips its full height (a halo that spans the DEM's short side
/// makes strips along the long side cheaper than squares). Each kind takes the largest tile
/// that fits, at least 256 cells a side (a smaller tile re-reads more halo than it computes),
/// evened out so that the extent is cut into tiles of equal size (a thin last tile would read a
/// whole halo for a few cells). Squares are evened on the extent's longer side.
TilePlan automaticTiles(const CellWindow& extent, std::size_t gridCols, std::size_t gridRows, std::size_t haloCells,
                        const TileBytes& bytes, double memoryBytes);

/// GDAL's block cache a run allows itself out of a memory budget of `memoryBytes`: an eighth,
/// at most 256 MiB.
double rasterCacheBytes(double memoryBytes);

/// What a run holds besides its tile and GDAL's block cache: the program, its libraries and
/// GDAL's and PROJ's own state (a sky run on the bundled 152 x 187 sample peaks at 64 MB).
inline constexpr double kProcessBytes = 64.0 * (1 << 20);

/// The memory --tile-size auto sizes tiles for out of a budget of `memoryBytes`: the budget less
/// the block cache (rasterCacheBytes) and the process (kProcessBytes).
double tileMemoryBytes(double memoryBytes);

/// The smallest budget (bytes) whose tileMemoryBytes is at least `tileBytes`.
double memoryBudgetFor(double tileBytes);

/// Half of this machine's physical memory (bytes): --memory-limit's default.
double defaultMemoryLimitBytes();

}  // namespace demlight
