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

/// Memory a product needs per cell it computes (bytes), as a rule of thumb for sizing tiles:
/// the heights, normals and sweep planes every horizon product holds, plus each output band.
double productBytesPerCell(std::size_t outputBands);

/// The tile side for --tile-size auto: the whole extent when extent + halo fits `memoryBytes`
/// at `bytesPerCell` (one piece is fastest), else the largest side s with (s + 2 halo)^2 cells
/// within it, at least 256 cells (a smaller tile re-reads more halo than it computes).
std::size_t automaticTileCells(const CellWindow& extent, std::size_t haloCells, double bytesPerCell,
                               double memoryBytes);

/// GDAL's block cache a run allows itself out of a memory budget of `memoryBytes`: an eighth,
/// at most 256 MiB (the rest sizes the tiles).
double rasterCacheBytes(double memoryBytes);

/// Half of this machine's physical memory (bytes): --memory-limit's default.
double defaultMemoryLimitBytes();

}  // namespace demlight
