// What demlight sees in a DEM before lighting it: size, CRS, extent, metric cell sizes, heights
// as read (scale, offset, unit), nodata, convergence, and the longest shadow of a low sun.
#pragma once

#include "demlight/geo/dem.h"
#include "demlight/geo/dem_source.h"

#include <array>
#include <limits>
#include <optional>
#include <string>

namespace demlight {

/// Sun elevation of DemInfo::longestShadowM (degrees).
inline constexpr double kInfoLowSunDeg = 5.0;

struct DemInfo {
    /// One row's geometry (geographic DEMs: south, centre and north rows differ).
    struct Row {
        const char* name = "";  ///< "south", "centre", "north"
        std::size_t row = 0;
        double latitudeDeg = 0, cellWidthM = 0, cellHeightM = 0;
    };
    std::size_t width = 0, height = 0;
    /// Along the outline; a latitude/longitude DEM's longitudes as its grid has them (359.9 .. 360.1).
    double latMinDeg = std::numeric_limits<double>::infinity(), latMaxDeg = -std::numeric_limits<double>::infinity();
    double lonMinDeg = std::numeric_limits<double>::infinity(), lonMaxDeg = -std::numeric_limits<double>::infinity();
    std::array<Row, 3> rows;
    double elevationMinM = 0, elevationMaxM = 0, reliefM = 0;
    double nodataFraction = 0;
    /// Smallest and largest meridian convergence (degrees); projected DEMs only.
    std::optional<std::pair<double, double>> convergenceDeg;
    double longestShadowM = 0;  ///< relief / tan(kInfoLowSunDeg)
};

/// Describes a DEM (latitude/longitude extent from points along its outline: a projected grid's
/// edges are curves in latitude/longitude).
DemInfo describeDem(const Dem& dem);
/// describeDem of a source's whole DEM, from its geometry and opening pass (no heights read).
DemInfo describeDem(const DemSource& source);

}  // namespace demlight
