#include "products/tiles.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unistd.h>

namespace demlight {

std::vector<CellWindow> tilesOf(const CellWindow& extent, std::size_t tileCells) {
    tileCells = std::max<std::size_t>(tileCells, 1);
    std::vector<CellWindow> tiles;
    for (std::size_t r0 = extent.row0; r0 < extent.row1; r0 += tileCells)
        for (std::size_t c0 = extent.col0; c0 < extent.col1; c0 += tileCells)
            tiles.push_back({c0, r0, std::min(extent.col1, c0 + tileCells), std::min(extent.row1, r0 + tileCells)});
    return tiles;
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

std::size_t automaticTileCells(const CellWindow& extent, std::size_t haloCells, const TileBytes& bytes,
                               double memoryBytes) {
    const double cols = static_cast<double>(extent.col1 - extent.col0);
    const double rows = static_cast<double>(extent.row1 - extent.row0);
    const double halo = static_cast<double>(haloCells);
    const std::size_t whole = std::max(extent.col1 - extent.col0, extent.row1 - extent.row0);
    if ((cols + 2 * halo) * (rows + 2 * halo) * bytes.perReadCell + cols * rows * bytes.perTileCell <= memoryBytes)
        return whole;
    // The largest s with a (s + 2h)^2 + b s^2 <= M: the positive root of
    // (a + b) s^2 + 4 a h s + 4 a h^2 - M = 0.
    const double a = bytes.perReadCell, b = bytes.perTileCell;
    const double discriminant = 16 * a * a * halo * halo - 4 * (a + b) * (4 * a * halo * halo - memoryBytes);
    const double side = discriminant > 0 ? (-4 * a * halo + std::sqrt(discriminant)) / (2 * (a + b)) : 0.0;
    constexpr std::size_t kSmallestTile = 256;
    const std::size_t largest = std::min(whole, std::max(kSmallestTile, static_cast<std::size_t>(std::max(side, 0.0))));
    const std::size_t count = (whole + largest - 1) / largest;
    return (whole + count - 1) / count;
}

double rasterCacheBytes(double memoryBytes) { return std::min(memoryBytes / 8, 256.0 * (1 << 20)); }

double tileMemoryBytes(double memoryBytes) {
    return std::max(memoryBytes - rasterCacheBytes(memoryBytes) - kProcessBytes, 0.0);
}

double defaultMemoryLimitBytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return 4e9;
    return 0.5 * static_cast<double>(pages) * static_cast<double>(pageSize);
}

}  // namespace demlight
