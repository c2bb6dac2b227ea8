// Terrain: the heights of a DEM together with the metric geometry the lighting kernels need.
// Built by demlight/geo/ from a georeferenced raster (or by tests from analytic surfaces); consumed by
// demlight/lighting/ without any knowledge of GDAL or CRSs.
#pragma once

#include "demlight/core/grid.h"

#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

namespace demlight {

/// WGS84 mean earth radius (metres); curvature uses R / (1 - k) with refraction coefficient k.
inline constexpr double kEarthRadiusM = 6371008.8;
/// Default refraction coefficient k of terrain sight lines (docs/design.md §3), for every product.
inline constexpr double kDefaultRefraction = 0.13;

/// Meridian convergence sampled on a coarse lattice: value (i, j) is gamma at cell
/// (min(i * stepCells, width-1), min(j * stepCells, height-1)). gamma (degrees) is the azimuth of
/// grid north measured clockwise from true north, so gridAzimuth = trueAzimuth - gamma.
/// An empty grid means gamma = 0 everywhere (geographic CRS, or tests).
struct ConvergenceField {
    Grid<float> gammaDeg;
    std::size_t stepCells = 1;
    /// Where cell (0, 0) of the terrain lies on the lattice's grid: a terrain cut from a larger
    /// one keeps that one's lattice, so gamma at a cell has the same bits in both.
    double colOffset = 0, rowOffset = 0;

    bool empty() const { return gammaDeg.empty(); }
    /// Gamma at a cell, bilinear between lattice nodes (degrees).
    double at(double col, double row) const;
    /// Smallest and largest sampled gamma (degrees); {0, 0} when empty.
    std::pair<double, double> range() const;
};

/// The full grid a terrain was cut from (a tile of a larger DEM): its size, per-row cell sizes
/// and convergence. Horizon sweeps lay their regions, scan lines and distances on this grid, so a
/// cut terrain's horizons are the same bits as the full one's on the cells they share
/// (docs/design.md §2: a tile computed with its halo gives the same bits as the whole DEM).
struct GridFrame {
    std::size_t width = 0, height = 0;
    std::vector<double> cellWidthM, cellHeightM;  ///< one entry per row of the full grid
    ConvergenceField convergence;                 ///< of the full grid (offsets 0)
    /// Lowest and highest valid height of the full grid (heightRangeM): the relief that search
    /// distances are sized from, the same for every tile.
    float lowM = 0, highM = 0;
    /// SteepSteps::share() of the full grid: how much of it is walls (surface models) rather
    /// than terrain; the scene plan sizes the horizon's near field from it.
    double steepStepShare = 0;
};

/// Steep steps between neighbours, counted over a grid's rows in order (whole, or in strips of
/// rows as a streaming pass reads them): pairs of edge-adjacent valid cells whose heights differ
/// by more than the distance between their centres (a slope over 45 degrees), per valid cell.
/// Measured: 0–1.6 % on the project's terrain DEMs (cliffs, volcano rims), 11–32 % on city and
/// dune-edge surface models (walls, roof edges, tree crowns).
struct SteepSteps {
    std::size_t steep = 0, valid = 0;
    /// Adds rows [row0, row0 + rows.height()) of the grid (row0 must follow the rows added
    /// before); cellWidthM/cellHeightM are the full grid's per-row sizes.
    void add(const Grid<float>& rows, std::size_t row0, const std::vector<double>& cellWidthM,
             const std::vector<double>& cellHeightM);
    double share() const { return valid ? static_cast<double>(steep) / static_cast<double>(valid) : 0.0; }

private:
    std::vector<float> lastRow_;  // the last row added, for the vertical pairs across strips
};

struct Terrain {
    /// Heights in metres; NaN marks nodata. Row 0 is the north edge.
    Grid<float> heightsM;
    /// East-west extent of a cell (metres), one entry per row (constant for projected CRSs).
    std::vector<double> cellWidthM;
    /// North-south extent of a cell (metres), one entry per row.
    std::vector<double> cellHeightM;
    /// Latitude of each row's centre (degrees), used for sun-position regions. May be empty.
    std::vector<double> rowLatitudeDeg;
    /// Grid vs true north (projected CRSs). Empty for geographic CRSs.
    ConvergenceField convergence;
    /// The full grid this terrain was cut from and the cut's corner on it; null when the
    /// terrain is a grid of its own.
    std::shared_ptr<const GridFrame> frame;
    std::size_t frameCol0 = 0, frameRow0 = 0;

    std::size_t width() const { return heightsM.width(); }
    std::size_t height() const { return heightsM.height(); }
    bool valid(std::size_t col, std::size_t row) const { return !std::isnan(heightsM(col, row)); }
};

/// Length of the DEM's diagonal (metres): the widest row's width (per-row cell widths) and the
/// summed cell heights. A search distance this long or longer is the whole DEM.
double diagonalM(const Terrain& terrain);

/// Lowest and highest valid height (metres); {+inf, -inf} when every cell is nodata.
std::pair<float, float> heightRangeM(const Grid<float>& heightsM);

/// The full grid of a terrain, by reference: its frame's, or the terrain's own; col0/row0 is
/// the terrain's cell (0, 0) on it.
struct FullGridRef {
    std::size_t width, height;
    const std::vector<double>& cellWidthM;
    const std::vector<double>& cellHeightM;
    const ConvergenceField& convergence;
    std::size_t col0, row0;
    const Terrain& terrain;  ///< the terrain it was taken from
    /// Lowest and highest valid height of the full grid; {+inf, -inf} when none.
    std::pair<float, float> heightRangeM() const;
    /// Smallest cell side of any row (metres).
    double minCellM() const;
    /// GridFrame::steepStepShare of the full grid (SteepSteps over the terrain when it has no frame).
    double steepStepShare() const;
};
FullGridRef fullGrid(const Terrain& terrain);

/// The terrain's own cells on its full grid (all of it when it has no frame).
inline CellWindow cellsOnFullGrid(const Terrain& t) {
    return {t.frameCol0, t.frameRow0, t.frameCol0 + t.width(), t.frameRow0 + t.height()};
}

/// diagonalM of the full grid.
double diagonalM(const FullGridRef& grid);

/// The window [col0, col0 + w) x [row0, row0 + h) of a terrain as a terrain of its own: heights,
/// per-row cell sizes and latitudes, and the convergence lattice re-sampled
/// every 16 cells of the window.
Terrain cropTerrain(const Terrain& t, std::size_t col0, std::size_t row0, std::size_t w, std::size_t h);

/// The window [col0, col0 + w) x [row0, row0 + h) of a terrain as a tile of it: heights, per-row
/// cell sizes and latitudes, the convergence lattice (the same nodes, offset), and the frame of
/// the full grid, so that kernels which anchor to the full grid give the tile the full terrain's
/// bits on the cells they share (truncation, too, is at the full grid's edges).
Terrain tileOf(const Terrain& t, const CellWindow& window);
/// tileOf with the frame of `t` (frameOf) made once by the caller, for one who cuts many tiles:
/// the frame's height range is a pass over every cell.
Terrain tileOf(const Terrain& t, const CellWindow& window, std::shared_ptr<const GridFrame> frame);
/// tileOf with the heights given: `geometry` supplies the per-row cell sizes, latitudes and
/// convergence of the grid the window is on (its heights are not read and may be empty), so a
/// source that reads windows from disk makes the tiles tileOf cuts from a terrain in memory.
Terrain tileOf(const Terrain& geometry, const CellWindow& window, std::shared_ptr<const GridFrame> frame,
               Grid<float> heightsM);
/// The frame a tile of `t` carries: t's own, or t as a full grid.
std::shared_ptr<const GridFrame> frameOf(const Terrain& t);

/// The centred window of at most w x h cells (sizes clamped to the terrain), as cropTerrain.
Terrain cropTerrainCentre(const Terrain& t, std::size_t w, std::size_t h);

/// A flat-earth, square-cell terrain for tests: every row has the same cell size.
Terrain makeUniformTerrain(Grid<float> heightsM, double cellSizeM);

}  // namespace demlight
