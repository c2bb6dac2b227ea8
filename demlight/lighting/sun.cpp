#include "demlight/lighting/sun.h"

#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/fast_math.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace demlight {

Enu directionEnu(double azimuthDeg, double elevationDeg) {
    // Reduce the azimuth first so that 0 and 360 give the same bits.
    const double az = wrapAzimuthDeg(azimuthDeg) * kDegToRad;
    const double el = elevationDeg * kDegToRad;
    const double c = std::cos(el);
    return {c * std::sin(az), c * std::cos(az), std::sin(el)};
}

double tangentPlaneElevationDeg(const Enu& n, double azimuthDeg) {
    // Direction v = (cos e sin A, cos e cos A, sin e) lies in the plane when N·v = 0.
    const double az = wrapAzimuthDeg(azimuthDeg) * kDegToRad;
    const double horizontal = n.east * std::sin(az) + n.north * std::cos(az);
    return std::atan2(-horizontal, n.up) * kRadToDeg;
}

double sunVisibility(double horizonDeg, double sunElevationDeg, double sunDiameterDeg) {
    if (std::isnan(horizonDeg)) return std::numeric_limits<double>::quiet_NaN();
    // Hoffman & Mitchell 2001b, Eq. 5, 6: the disk spans [θmin, θmax].
    const double thetaMin = sunElevationDeg - 0.5 * sunDiameterDeg;
    const double thetaMax = sunElevationDeg + 0.5 * sunDiameterDeg;
    if (!(thetaMax > thetaMin)) {
        return horizonDeg < sunElevationDeg ? 1.0 : horizonDeg > sunElevationDeg ? 0.0 : 0.5;
    }
    // Hoffman & Mitchell 2001b, Eq. 7, clamped to [0, 1].
    return std::clamp((thetaMax - horizonDeg) / (thetaMax - thetaMin), 0.0, 1.0);
}

double sunVisibilityClamped(const Enu& normal, double horizonDeg, double sunAzimuthDeg,
                            double sunElevationDeg, double sunDiameterDeg) {
    if (std::isnan(horizonDeg)) return std::numeric_limits<double>::quiet_NaN();
    const double effective = std::max(horizonDeg, tangentPlaneElevationDeg(normal, sunAzimuthDeg));
    return sunVisibility(effective, sunElevationDeg, sunDiameterDeg);
}

SunTerms sunTerms(const Enu& normal, double horizonDeg, double sunAzimuthDeg,
                  double sunElevationDeg, double sunDiameterDeg) {
    // Reduce the azimuth first so that 0 and 360 give the same bits (as directionEnu).
    const double az = wrapAzimuthDeg(sunAzimuthDeg) * kDegToRad;
    const double el = sunElevationDeg * kDegToRad;
    return sunTerms(normal, horizonDeg,
                    SunAngles{sunAzimuthDeg, sunElevationDeg, std::sin(az), std::cos(az), std::sin(el), std::cos(el)},
                    sunDiameterDeg);
}

SunTerms sunTerms(const Enu& normal, double horizonDeg, const SunAngles& sun, double sunDiameterDeg) {
    if (std::isnan(horizonDeg)) return {horizonDeg, horizonDeg};
    // Tangent-plane elevation in the sun's azimuth: atan2(-N_h·a, N_up) (as
    // tangentPlaneElevationDeg), with the polynomial arctangent.
    const double across = -(normal.east * sun.sinAzimuth + normal.north * sun.cosAzimuth);
    const double planeDeg = normal.up > 0.0   ? fastAtan(across / normal.up) * kRadToDeg
                            : normal.up < 0.0 ? std::atan2(across, normal.up) * kRadToDeg
                                              : (across > 0.0 ? 90.0 : across < 0.0 ? -90.0 : 0.0);
    const double o = sunVisibility(std::max(horizonDeg, planeDeg), sun.elevationDeg, sunDiameterDeg);
    const double cosine = (normal.east * sun.sinAzimuth + normal.north * sun.cosAzimuth) * sun.cosElevation +
                          normal.up * sun.sinElevation;
    // Hoffman & Mitchell 2001b, Eq. 3 with Li_sun = 1 (normalised irradiance, docs/design.md §3).
    return {o, o * std::max(0.0, cosine)};
}

double sunIrradiance(const Enu& normal, double horizonDeg, double sunAzimuthDeg,
                     double sunElevationDeg, double sunDiameterDeg) {
    return sunTerms(normal, horizonDeg, sunAzimuthDeg, sunElevationDeg, sunDiameterDeg).irradiance;
}

SunLight computeSunLight(const Terrain& terrain, const HorizonMap& horizon, const Normals& normals,
                         double sunAzimuthDeg, double sunElevationDeg, double sunDiameterDeg) {
    if (!horizon.angleDeg.sameShape(terrain.heightsM) || !normals.east.sameShape(terrain.heightsM) ||
        !normals.north.sameShape(terrain.heightsM) || !normals.up.sameShape(terrain.heightsM))
        throw Error("sun: horizon map and normals must have the terrain's size");
    if (!std::isfinite(sunAzimuthDeg))
        throw Error("sun: azimuth must be a finite number of degrees, got " + std::to_string(sunAzimuthDeg));
    if (!(sunElevationDeg >= -90.0 && sunElevationDeg <= 90.0))
        throw Error("sun: elevation must be in [-90, 90] degrees, got " + std::to_string(sunElevationDeg));
    if (!(sunDiameterDeg >= 0.0 && sunDiameterDeg < 90.0))
        throw Error("sun: disk diameter must be in [0, 90) degrees, got " + std::to_string(sunDiameterDeg));

    const std::size_t W = terrain.width(), H = terrain.height();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    SunLight out{Grid<float>(W, H, nan), Grid<float>(W, H, nan)};
    const double azimuth = wrapAzimuthDeg(sunAzimuthDeg);
    parallelFor(0, H, [&](std::size_t row) {
        for (std::size_t col = 0; col < W; ++col) {
            if (!terrain.valid(col, row)) continue;
            const Enu n = normals.at(col, row);
            const double h = horizon.angleDeg(col, row);
            const SunTerms terms = sunTerms(n, h, azimuth, sunElevationDeg, sunDiameterDeg);
            out.visibility(col, row) = static_cast<float>(terms.visibility);
            out.irradiance(col, row) = static_cast<float>(terms.irradiance);
        }
    }, 8);
    return out;
}

}  // namespace demlight
