// Direct sun over a whole DEM at one instant: the driver `demlight sun`, time-lapse frames and
// sun-hour integrals share. Each cell uses its own sun position (interpolated from a SunField).
// Over a large DEM the sun's azimuth differs from cell to cell; the horizon is swept along a
// few azimuths spanning that range and each cell interpolates between the two that bracket its
// own sun azimuth.
#pragma once

#include "lighting/horizon.h"
#include "lighting/sun.h"
#include "lighting/surface.h"
#include "src/progress.h"
#include "src/sun_field.h"
#include "src/terrain.h"

#include <vector>

namespace demlight {

/// Largest spread of the sun's azimuth over the DEM served by one sweep (degrees). Horizons
/// change with azimuth by well under 1 deg per deg on real terrain, so a shared azimuth costs
/// < ~0.05 deg of horizon.
inline constexpr double kSunAzimuthToleranceDeg = 0.1;
/// Spacing of the sweep azimuths when the spread is larger (degrees). Linear interpolation of
/// the horizon in azimuth over 0.5 deg is exact wherever the horizon point does not jump, and
/// the 5.6 deg spacing of `timelapse --horizon-mode interpolated:64` already gives a sun
/// visibility MAE of 0.0016, so 0.5 deg is far inside the budget.
inline constexpr double kSunAzimuthSpacingDeg = 0.5;

struct SunFrameParams {
    double sunDiameterDeg = kSunDiameterDeg;
    /// Search distance (metres); <= 0 means sunSearchDistanceM() for the field's lowest sun.
    double maxDistanceM = 0;
    double refraction = 0.13;
    /// As HorizonParams::curvature and HorizonParams::directionToleranceDeg (the scene plan's).
    bool curvature = true;
    double directionToleranceDeg = 0;
    int threads = 0;
};

struct SunFrame {
    SunLight light;                       ///< visibility and irradiance; NaN at nodata
    std::vector<double> sweepAzimuthsDeg; ///< azimuths swept (empty when the sun is down everywhere)
    double maxDistanceM = 0;              ///< the search distance used
};

/// The azimuths to sweep (degrees, unwrapped like the field): the midpoint when the field's
/// azimuth spread is at most kSunAzimuthToleranceDeg, otherwise evenly spaced from the lowest to
/// the highest azimuth at most kSunAzimuthSpacingDeg apart.
std::vector<double> sunSweepAzimuthsDeg(const SunField& field, std::size_t width, std::size_t height);

/// Search distance that catches every shadow at this sun: relief / tan(lowest elevation minus
/// the disk radius, at least 0.25 deg), at least one cell; the DEM diagonal when that is
/// kWholeDemShareOfDiagonal of it or more.
double sunSearchDistanceM(const Terrain& terrain, double lowestSunElevationDeg,
                          double sunDiameterDeg);

/// Visibility and irradiance of the sun for every cell. When the sun's upper limb is below the
/// horizon everywhere, every valid cell gets 0 without any sweep.
SunFrame computeSunFrame(const Terrain& terrain, const Normals& normals, const SunField& field,
                         const SunFrameParams& params, ProgressCounter* progress = nullptr);

}  // namespace demlight
