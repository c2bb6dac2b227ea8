// Direct sun over a whole DEM at one instant: the driver `demlight sun`, time-lapse frames and
// sun-hour integrals share. Each cell uses its own sun position (interpolated from a SunField);
// horizons are swept per tile along the tile's own sun azimuth.
#pragma once

#include "lighting/horizon.h"
#include "lighting/sun.h"
#include "lighting/surface.h"
#include "src/progress.h"
#include "src/sun_field.h"
#include "src/terrain.h"

#include <vector>

namespace demlight {

/// Largest spread of the sun's azimuth inside one swept tile (degrees). Horizons change with
/// azimuth by well under 1 deg per deg on real terrain, so a shared azimuth costs < ~0.05 deg.
inline constexpr double kSunAzimuthToleranceDeg = 0.1;
/// Tiles are not split below this many cells on a side.
inline constexpr std::size_t kMinSunTileCells = 64;

struct SunFrameParams {
    double sunDiameterDeg = kSunDiameterDeg;
    /// Search distance (metres); <= 0 means sunSearchDistanceM() for the field's lowest sun.
    double maxDistanceM = 0;
    double refraction = 0.13;
    int threads = 0;
};

struct SunFrame {
    SunLight light;                ///< visibility and irradiance; NaN at nodata
    std::vector<CellWindow> tiles; ///< the regions swept (empty when the sun is down everywhere)
    double maxDistanceM = 0;       ///< the search distance used
};

/// Splits the DEM into tiles (halving the longer side) until the sun's azimuth varies by at
/// most kSunAzimuthToleranceDeg within each, or a tile is below 2 * kMinSunTileCells a side.
std::vector<CellWindow> sunTiles(const SunField& field, std::size_t width, std::size_t height);

/// Search distance that catches every shadow at this sun: relief / tan(lowest elevation minus
/// the disk radius, at least 0.25 deg), capped by the DEM diagonal, at least one cell.
double sunSearchDistanceM(const Terrain& terrain, double lowestSunElevationDeg,
                          double sunDiameterDeg);

/// Visibility and irradiance of the sun for every cell. When the sun's upper limb is below the
/// horizon everywhere, every valid cell gets 0 without any sweep.
SunFrame computeSunFrame(const Terrain& terrain, const Normals& normals, const SunField& field,
                         const SunFrameParams& params, ProgressCounter* progress = nullptr);

}  // namespace demlight
