// Direct sun: visibility of the sun's disk over the horizon and the lit irradiance
// (Hoffman & Mitchell 2001b, Eq. 3 and 5–7; docs/design.md §6.2).
#pragma once

#include "demlight/lighting/horizon.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/grid.h"
#include "demlight/core/terrain.h"

namespace demlight {

/// Mean apparent angular diameter of the sun (degrees).
inline constexpr double kSunDiameterDeg = 0.533;

/// Unit vector toward a direction given by true azimuth and elevation (degrees), in ENU.
Enu directionEnu(double azimuthDeg, double elevationDeg);

/// Elevation (degrees) of the plane tangent to the surface with unit normal `normal`, in true
/// azimuth `azimuthDeg`: directions below it are behind the surface.
double tangentPlaneElevationDeg(const Enu& normal, double azimuthDeg);

/// Fraction of the sun's disk above a horizon (Hoffman & Mitchell 2001b, Eq. 5–7): with θmin/max =
/// θsun ∓ α/2, O = clamp((θmax - θh) / (θmax - θmin), 0, 1). A disk of zero diameter is a step (0.5
/// exactly on the horizon). Angles in degrees; NaN horizon gives NaN.
double sunVisibility(double horizonDeg, double sunElevationDeg, double sunDiameterDeg);

/// Visibility with the horizon clamped to the hemisphere of the normal (Hoffman & Mitchell's
/// "effective horizon"): θh' = max(θh, tangent-plane elevation in the sun's azimuth).
double sunVisibilityClamped(const Enu& normal, double horizonDeg, double sunAzimuthDeg,
                            double sunElevationDeg, double sunDiameterDeg);

/// Normalised direct-sun irradiance for a unit-radiance sun (Hoffman & Mitchell 2001b, Eq. 3;
/// docs/design.md §3: a flat, unshadowed cell under a zenith sun gets 1): O · max(0, N·s) with O
/// from sunVisibilityClamped.
double sunIrradiance(const Enu& normal, double horizonDeg, double sunAzimuthDeg,
                     double sunElevationDeg, double sunDiameterDeg);

/// Both terms of one cell at once (the grid drivers need both; the visibility is computed once).
struct SunTerms {
    double visibility;  ///< as sunVisibilityClamped
    double irradiance;  ///< as sunIrradiance
};
SunTerms sunTerms(const Enu& normal, double horizonDeg, double sunAzimuthDeg,
                  double sunElevationDeg, double sunDiameterDeg);

/// The sun seen from one cell: its elevation and the sines and cosines of its azimuth and
/// elevation, for grid drivers that evaluate thousands of cells under nearly the same sun.
struct SunAngles {
    double azimuthDeg, elevationDeg;
    double sinAzimuth, cosAzimuth, sinElevation, cosElevation;
};

/// sunTerms() from precomputed angles (the one implementation; the overload above fills the
/// angles with <cmath>). The tangent-plane elevation goes through the polynomial arctangent,
/// within 2e-7 degrees of tangentPlaneElevationDeg(), the <cmath> form the references and
/// sunVisibilityClamped() keep.
SunTerms sunTerms(const Enu& normal, double horizonDeg, const SunAngles& sun, double sunDiameterDeg);

struct SunLight {
    /// Clamped visibility of the sun's disk in [0, 1]; NaN at nodata.
    Grid<float> visibility;
    /// Normalised irradiance O · max(0, N·s); NaN at nodata.
    Grid<float> irradiance;
};

/// Sun visibility and irradiance for every cell, from the horizon map computed in the sun's
/// azimuth and the surface normals. Throws Error on mismatched grids or out-of-range angles
/// (elevation in [-90, 90], diameter in [0, 90)). Parallel over rows (0 = all cores).
SunLight computeSunLight(const Terrain& terrain, const HorizonMap& horizonAtSunAzimuth,
                         const Normals& normals, double sunAzimuthDeg, double sunElevationDeg,
                         double sunDiameterDeg = kSunDiameterDeg);

}  // namespace demlight
