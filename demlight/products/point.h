// Point queries: the horizon profile, irradiance or insolation of one cell, for users who want
// the values at a site (a PV system, a weather station) rather than a raster. Every horizon is
// the reference ray march (demlight/lighting/horizon.h referenceHorizonAt) from that cell, and only the
// window of the DEM within the search distance of the cell is read, so the cost does not grow
// with the DEM.
//
// Against the raster products at the same cell: the horizon profile is the reference method's
// (horizon --method reference), up to float rounding of the ray's position; irradiance takes the
// sun computed by SPA at the cell (the raster interpolates a lattice of SPA positions) and the
// horizons of the ray march (the raster's sweep); insolation integrates every instant of the
// period exactly (the raster bins sun positions, demlight/lighting/insolation.h). tests/point_test.cpp
// measures each difference.
#pragma once

#include "demlight/geo/dem_source.h"
#include "demlight/products/insolation.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/product.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace demlight {

/// Where a point query looks: WGS84 latitude and longitude, or x and y in the DEM's CRS.
struct PointSpec {
    double first = 0, second = 0;  ///< latitude, longitude (degrees) or x, y (CRS units)
    bool wgs84 = true;
};

/// The cell a point falls in.
struct PointCell {
    double x = 0, y = 0;  ///< the point in the DEM's CRS
    CellIndex cell;       ///< the cell holding it (its west and north edges belong to it)
    double centreX = 0, centreY = 0;  ///< the cell centre in the DEM's CRS
    double latitudeDeg = 0, longitudeDeg = 0;  ///< of the cell centre, on the CRS's datum
    double heightM = 0;
};

/// The cell of `point` with its height. Throws Error naming the point and the DEM when the point
/// is outside the DEM or on a nodata cell.
PointCell locatePoint(const DemSource& source, const PointSpec& point);

/// The search of a point query: the scene plan's distance (--max-distance when given) and
/// curvature, as the raster products plan them for the whole DEM.
struct PointSearch {
    HorizonParams params;  ///< of the ray marches (azimuthDeg set per ray)
    std::size_t haloCells = 0;
    ScenePlan plan;
};
PointSearch pointSearch(const DemSource& source, const SearchRequest& search);

/// Horizon angles (degrees) from one cell in the given true azimuths, with truncation flags.
struct PointHorizon {
    PointCell point;
    std::vector<double> azimuthsDeg;
    std::vector<HorizonSample> samples;  ///< one per azimuth
    double maxDistanceM = 0;
};
PointHorizon pointHorizon(const DemSource& source, const PointCell& point, const std::vector<double>& azimuthsDeg,
                          const SearchRequest& search);

/// Irradiance (W m-2) at one cell and instant, with what it came from.
struct PointIrradiance {
    PointCell point;
    double sunAzimuthDeg = 0, sunElevationDeg = 0;  ///< SPA at the cell (apparent)
    double extraterrestrialWm2 = 0, linke = 0;
    double horizonAtSunDeg = 0;  ///< horizon in the sun's azimuth
    double sunVisibility = 0;    ///< O, the visible fraction of the disk
    std::optional<double> skyK0;  ///< visible-sky model: K of the horizons raised to the horizontal
    std::size_t skyDirections = 0;  ///< directions of skyK0 (0 with the rsun model)
    CellIrradiance irradiance;
    double maxDistanceM = 0;
};
PointIrradiance pointIrradiance(const DemSource& source, const PointCell& point, const IrradianceRequest& request);

/// Irradiation (kWh m-2) and hours of direct sun at one cell over a period, integrated per
/// instant (trapezoid weights over the request's step), each instant with its own sun and
/// horizon; request.elevationBandDeg is not used.
struct PointInsolation {
    PointCell point;
    UtcInstant start, end;
    std::size_t instants = 0, sunUpInstants = 0;
    CellIrradiance irradiation;  ///< kWh m-2
    double sunHours = 0;
    std::optional<double> skyK0;
    std::size_t skyDirections = 0;
    double maxDistanceM = 0;
};
PointInsolation pointInsolation(const DemSource& source, const PointCell& point, const InsolationRequest& request);

}  // namespace demlight
