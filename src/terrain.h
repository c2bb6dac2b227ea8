// Terrain: the heights of a DEM together with the metric geometry the lighting kernels need.
// Built by geo/ from a georeferenced raster (or by tests from analytic surfaces); consumed by
// lighting/ without any knowledge of GDAL or CRSs.
#pragma once

#include "src/grid.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace demlight {

/// WGS84 mean earth radius (metres); curvature uses R / (1 - k) with refraction coefficient k.
inline constexpr double kEarthRadiusM = 6371008.8;
/// Default refraction coefficient k of terrain sight lines (DESIGN §1), for every product.
inline constexpr double kDefaultRefraction = 0.13;

/// Meridian convergence sampled on a coarse lattice: value (i, j) is gamma at cell
/// (min(i * stepCells, width-1), min(j * stepCells, height-1)). gamma (degrees) is the azimuth of
/// grid north measured clockwise from true north, so gridAzimuth = trueAzimuth - gamma.
/// An empty grid means gamma = 0 everywhere (geographic CRS, or tests).
struct ConvergenceField {
    Grid<float> gammaDeg;
    std::size_t stepCells = 1;

    bool empty() const { return gammaDeg.empty(); }
    /// Gamma at a cell, bilinear between lattice nodes (degrees).
    double at(double col, double row) const;
    /// Smallest and largest sampled gamma (degrees); {0, 0} when empty.
    std::pair<double, double> range() const;
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

    std::size_t width() const { return heightsM.width(); }
    std::size_t height() const { return heightsM.height(); }
    bool valid(std::size_t col, std::size_t row) const { return !std::isnan(heightsM(col, row)); }
};

/// Length of the DEM's diagonal (metres): the widest row's width (per-row cell widths) and the
/// summed cell heights. A search distance this long or longer is the whole DEM.
double diagonalM(const Terrain& terrain);

/// Lowest and highest valid height (metres); {+inf, -inf} when every cell is nodata.
std::pair<float, float> heightRangeM(const Grid<float>& heightsM);

/// The window [col0, col0 + w) x [row0, row0 + h) of a terrain as a terrain of its own: heights,
/// per-row cell sizes and latitudes, and the convergence lattice re-sampled
/// every 16 cells of the window.
Terrain cropTerrain(const Terrain& t, std::size_t col0, std::size_t row0, std::size_t w, std::size_t h);

/// The centred window of at most w x h cells (sizes clamped to the terrain), as cropTerrain.
Terrain cropTerrainCentre(const Terrain& t, std::size_t w, std::size_t h);

/// A flat-earth, square-cell terrain for tests: every row has the same cell size.
Terrain makeUniformTerrain(Grid<float> heightsM, double cellSizeM);

}  // namespace demlight
