#include "demlight/products/tiles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unistd.h>

namespace demlight {

std::vector<CellWindow> tilesOf(const CellWindow& extent, TileShape shape) {
    const std::size_t cols = std::max<std::size_t>(shape.cols, 1), rows = std::max<std::size_t>(shape.rows, 1);
    std::vector<CellWindow> tiles;
    for (std::size_t r0 = extent.row0; r0 < extent.row1; r0 += rows)
        for (std::size_t c0 = extent.col0; c0 < extent.col1; c0 += cols)
            tiles.push_back({c0, r0, std::min(extent.col1, c0 + cols), std::min(extent.row1, r0 + rows)});
    return tiles;
}

std::vector<CellWindow> tilesOf(const CellWindow& extent, std::size_t tileCells) {
    return tilesOf(extent, TileShape{tileCells, tileCells});
}

ProgressFn tileProgress(const ProgressFn& job, std::size_t index, std::size_t count) {
    if (!job) return {};
    if (count <= 1) return job;
    const std::string prefix = "tile " + std::to_string(index + 1) + "/" + std::to_string(count) + ": ";
    return [job, index, count, prefix](double fraction, const std::string& stage) {
        return job((static_cast<double>(index) + std::clamp(fraction, 0.0, 1.0)) / static_cast<double>(count),
                   prefix + stage);
    };
}

TileBytes productTileBytes(std::size_t outputBands) {
    // Heights (4) and the DEM band (4), normals (12), two sweep planes (8), per-direction
    // accumulators and scratch (~24), each output band (4), and a margin (8), all for every
    // cell read (docs/performance.md, "A DEM larger than memory").
    return {60.0 + 4.0 * static_cast<double>(outputBands), 0.0};
}

TileBytes windowProductTileBytes(std::size_t sumBytesPerCell, std::size_t newBands) {
    // Read cells: heights (4), the sweep's horizon plane and second plane (8), a margin (4).
    // Tile cells: normals (12), the sums, each new output band (4), a margin (8).
    return {16.0, 20.0 + static_cast<double>(sumBytesPerCell) + 4.0 * static_cast<double>(newBands)};
}

double tileBytes(TileShape shape, std::size_t haloCells, std::size_t gridCols, std::size_t gridRows,
                 const TileBytes& bytes) {
    const auto read = [&](std::size_t cells, std::size_t grid) {
        return static_cast<double>(std::min(cells + 2 * std::min(haloCells, grid), grid));
    };
    return read(shape.cols, gridCols) * read(shape.rows, gridRows) * bytes.perReadCell +
           static_cast<double>(shape.cols) * static_cast<double>(shape.rows) * bytes.perTileCell;
}

namespace {

/// Below this a tile re-reads more halo than it computes.
constexpr std::size_t kSmallestTile = 256;

std::size_t tileCount(std::size_t cells, std::size_t tile) { return (cells + tile - 1) / tile; }

/// Cells read along one axis by tiles of `tile` cells over [first, last) of a grid of `grid`
/// cells, each with its halo clipped to the grid.
double cellsRead(std::size_t first, std::size_t last, std::size_t tile, std::size_t halo, std::size_t grid) {
    double sum = 0;
    for (std::size_t a = first; a < last; a += tile) {
        const std::size_t b = std::min(last, a + tile);
        sum += static_cast<double>(std::min(grid, b + std::min(halo, grid)) - (a - std::min(a, halo)));
    }
    return sum;
}

}  // namespace

TilePlan automaticTiles(const CellWindow& extent, std::size_t gridCols, std::size_t gridRows, std::size_t haloCells,
                        const TileBytes& bytes, double memoryBytes) {
    const std::size_t cols = extent.col1 - extent.col0, rows = extent.row1 - extent.row0;
    const auto memory = [&](TileShape s) { return tileBytes(s, haloCells, gridCols, gridRows, bytes); };
    TilePlan plan;
    if (memory({cols, rows}) <= memoryBytes) {
        plan.shape = {cols, rows};
        plan.smallestTileBytes = memory(plan.shape);
        return plan;
    }
    // A kind of tile: its shape for a side s (the cut axis's cells), and the cells it cuts.
    struct Kind {
        std::size_t cut;  // cells of the axis the side s cuts
        TileShape (*shape)(std::size_t s, std::size_t cols, std::size_t rows);
    };
    const Kind kinds[] = {
        {std::max(cols, rows), [](std::size_t s, std::size_t c, std::size_t r) { return TileShape{std::min(s, c), std::min(s, r)}; }},
        {rows, [](std::size_t s, std::size_t c, std::size_t) { return TileShape{c, s}; }},
        {cols, [](std::size_t s, std::size_t, std::size_t r) { return TileShape{s, r}; }},
    };
    double bestRead = 0;
    std::size_t bestCount = 0;
    plan.smallestTileBytes = std::numeric_limits<double>::infinity();
    for (const Kind& kind : kinds) {
        const auto shapeOf = [&](std::size_t s) { return kind.shape(s, cols, rows); };
        std::size_t lo = std::min(kSmallestTile, kind.cut), hi = kind.cut;
        plan.smallestTileBytes = std::min(plan.smallestTileBytes, memory(shapeOf(lo)));
        if (memory(shapeOf(lo)) > memoryBytes) continue;
        // The largest side that fits (memory grows with the side).
        while (lo < hi) {
            const std::size_t mid = lo + (hi - lo + 1) / 2;
            if (memory(shapeOf(mid)) <= memoryBytes) lo = mid;
            else hi = mid - 1;
        }
        const std::size_t count = tileCount(kind.cut, lo);
        const TileShape shape = shapeOf(tileCount(kind.cut, count));
        const double read = cellsRead(extent.col0, extent.col1, shape.cols, haloCells, gridCols) *
                            cellsRead(extent.row0, extent.row1, shape.rows, haloCells, gridRows);
        const std::size_t tiles = tileCount(cols, shape.cols) * tileCount(rows, shape.rows);
        if (bestCount == 0 || read < bestRead || (read == bestRead && tiles < bestCount)) {
            plan.shape = shape;
            bestRead = read;
            bestCount = tiles;
        }
    }
    return plan;
}

double rasterCacheBytes(double memoryBytes) { return std::min(memoryBytes / 8, 256.0 * (1 << 20)); }

double tileMemoryBytes(double memoryBytes) {
    return std::max(memoryBytes - rasterCacheBytes(memoryBytes) - kProcessBytes, 0.0);
}

double memoryBudgetFor(double tileBytes) {
    // tileMemoryBytes(m) = m - min(m / 8, cap) - process: increasing in m, so invert each branch.
    const double cap = rasterCacheBytes(std::numeric_limits<double>::infinity());
    const double belowCap = (tileBytes + kProcessBytes) * 8.0 / 7.0;
    return belowCap / 8 <= cap ? belowCap : tileBytes + kProcessBytes + cap;
}

double defaultMemoryLimitBytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return 4e9;
    return 0.5 * static_cast<double>(pages) * static_cast<double>(pageSize);
}

}  // namespace demlight
