// The sun's position across a DEM at one instant, sampled on a coarse lattice of cells (filled
// by demlight/geo/ with SPA; read by demlight/lighting/). Over a large DEM the sun's azimuth and elevation differ
// from place to place by about the longitude span in hour angle.
#pragma once

#include "demlight/core/grid.h"

#include <cstddef>
#include <utility>

namespace demlight {

/// Node (i, j) holds the sun at cell (min(i * stepCells, width-1), min(j * stepCells, height-1)).
/// Azimuths are unwrapped around the centre azimuth so interpolation never crosses 0/360.
struct SunField {
    Grid<float> azimuthDeg;    ///< true azimuth, unwrapped (may lie outside [0, 360))
    Grid<float> elevationDeg;  ///< apparent topocentric elevation
    std::size_t stepCells = 64;
    double centreAzimuthDeg = 0;    ///< at the DEM centre, in [0, 360)
    double centreElevationDeg = 0;  ///< at the DEM centre
    /// A field of a whole DEM read by a tile of it (onTile): the tile's cell (0, 0) on the
    /// DEM's grid, and that grid's width (0 = the width callers pass). Lattice intervals stay
    /// anchored to the DEM, so a tile's cells get the DEM's bits.
    double colOffset = 0, rowOffset = 0;
    std::size_t fullWidth = 0;

    /// A field with the same sun everywhere (tests, or a sun given by the user).
    static SunField uniform(double azimuthDeg, double elevationDeg);
    /// This field as read by a tile whose cell (0, 0) is (col0, row0) of a DEM `fullWidth` wide.
    SunField onTile(std::size_t col0, std::size_t row0, std::size_t fullWidth) const;
    /// Azimuth (degrees, unwrapped) and elevation (degrees) at a cell, bilinear between nodes.
    std::pair<double, double> at(double col, double row) const;
    /// As at(), for a point on the DEM's grid (offsets not applied).
    std::pair<double, double> atFull(double col, double row) const;
    /// Smallest and largest azimuth over a window of cells of the DEM's grid (degrees, unwrapped).
    std::pair<double, double> azimuthRange(std::size_t col0, std::size_t row0, std::size_t col1,
                                           std::size_t row1) const;
    /// Smallest and largest elevation over the whole field (degrees).
    std::pair<double, double> elevationRange() const;
};

}  // namespace demlight
