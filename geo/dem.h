// A DEM opened for lighting: the raster band, its CRS facts, and the Terrain (heights plus
// per-row metric cell sizes and meridian convergence) the lighting kernels consume.
#pragma once

#include "geo/raster.h"
#include "src/terrain.h"

#include <memory>
#include <optional>
#include <string>

namespace demlight {

/// What demlight needs to know about a CRS.
struct CrsInfo {
    std::string name;
    std::optional<int> epsg;
    bool geographic = false;
    /// Projected CRSs: metres per linear unit of the CRS (1 for metre grids).
    double linearUnitM = 1.0;
    /// Ellipsoid of the CRS (metres, and inverse flattening; 0 for a sphere).
    double semiMajorM = 6378137.0;
    double inverseFlattening = 298.257223563;
};

/// Converts grid coordinates of a projected DEM to latitude/longitude (opaque; GDAL inside).
class LatLonTransform;

struct Dem {
    RasterBand band;
    CrsInfo crs;
    /// Heights (the band's values) plus per-row cell sizes and convergence.
    Terrain terrain;
    /// Set for projected DEMs; shared so Dem stays cheap to copy.
    std::shared_ptr<const LatLonTransform> toLatLon;
};

/// Opens a DEM: reads band 1, checks the georeferencing, computes per-row metric cell sizes
/// (GeographicLib on the CRS's ellipsoid for geographic CRSs) and the meridian convergence
/// lattice for projected CRSs. Throws Error on all bad input listed in DESIGN §6.
Dem loadDem(const std::string& path);

/// Latitude and longitude (degrees, on the CRS's own datum) of a cell centre.
std::pair<double, double> cellLatLon(const Dem& dem, double col, double row);

}  // namespace demlight
