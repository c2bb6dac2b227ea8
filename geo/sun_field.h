// The sun's position across a DEM at one instant. Over a large DEM the sun's azimuth and
// elevation differ from place to place (by about the longitude span in hour angle); demlight
// evaluates SPA on a coarse lattice of cells and interpolates between the nodes.
#pragma once

#include "geo/dem.h"
#include "geo/solar_position.h"
#include "src/grid.h"

namespace demlight {

/// Sun position sampled every `stepCells` cells (clamped to the last row/column), as
/// ConvergenceField. Azimuths are stored unwrapped around the centre azimuth so interpolation
/// never crosses the 0/360 seam.
struct SunField {
    Grid<float> azimuthDeg;    ///< true azimuth, unwrapped (may lie outside [0, 360))
    Grid<float> elevationDeg;  ///< apparent topocentric elevation
    std::size_t stepCells = 64;
    SolarPosition centre;      ///< the full SPA result at the DEM centre

    /// Azimuth (degrees, unwrapped) and elevation (degrees) at a cell, bilinear between nodes.
    std::pair<double, double> at(double col, double row) const;
    /// Smallest and largest azimuth over a window of cells (degrees, unwrapped).
    std::pair<double, double> azimuthRange(std::size_t col0, std::size_t row0, std::size_t col1,
                                           std::size_t row1) const;
};

/// Evaluates SPA at lattice nodes of the DEM at instant t. `site` supplies pressure and
/// temperature; latitude, longitude and elevation come from each node (elevation from the DEM,
/// the DEM's mean where a node is nodata).
SunField computeSunField(const Dem& dem, UtcInstant t, const SolarSite& site,
                         const SpaOptions& options, std::size_t stepCells = 64);

}  // namespace demlight
