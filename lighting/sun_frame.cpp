#include "lighting/sun_frame.h"

#include "src/angles.h"
#include "src/parallel.h"

#include <algorithm>
#include <cmath>

namespace demlight {
namespace {

/// Floor of the elevation used to size the search distance (degrees).
constexpr double kLowestShadowElevationDeg = 0.25;

}  // namespace

std::vector<double> sunSweepAzimuthsDeg(const SunField& field, std::size_t width, std::size_t height) {
    const auto [lo, hi] = field.azimuthRange(0, 0, width, height);
    if (hi - lo <= kSunAzimuthToleranceDeg) return {0.5 * (lo + hi)};
    const auto intervals = static_cast<std::size_t>(std::ceil((hi - lo) / kSunAzimuthSpacingDeg));
    std::vector<double> azimuths(intervals + 1);
    for (std::size_t i = 0; i <= intervals; ++i)
        azimuths[i] = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(intervals);
    return azimuths;
}

double sunSearchDistanceM(const Terrain& t, double lowestSunElevationDeg, double sunDiameterDeg) {
    const auto [lo, hi] = heightRangeM(t.heightsM);
    const double angle =
        std::max(lowestSunElevationDeg - sunDiameterDeg / 2, kLowestShadowElevationDeg);
    double heightM = 0;
    for (double h : t.cellHeightM) heightM += h;
    const double widthM = t.cellWidthM[t.height() / 2] * static_cast<double>(t.width());
    const double byRelief = static_cast<double>(hi - lo) / std::tan(angle * kDegToRad);
    return std::max(t.cellHeightM.front(), std::min(byRelief, std::hypot(widthM, heightM)));
}

SunFrame computeSunFrame(const Terrain& t, const Normals& normals, const SunField& field,
                         const SunFrameParams& params, ProgressCounter* progress) {
    SunFrame frame;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    frame.light.visibility = Grid<float>(t.width(), t.height(), nan);
    frame.light.irradiance = frame.light.visibility;
    const auto [lowestSun, highestSun] = field.elevationRange();
    frame.maxDistanceM = params.maxDistanceM > 0
                             ? params.maxDistanceM
                             : sunSearchDistanceM(t, lowestSun, params.sunDiameterDeg);

    if (highestSun <= -params.sunDiameterDeg / 2) {
        // The whole disk is below the horizon everywhere: night.
        for (std::size_t i = 0; i < t.heightsM.size(); ++i)
            if (!std::isnan(t.heightsM.data()[i]))
                frame.light.visibility.data()[i] = frame.light.irradiance.data()[i] = 0.0f;
        if (progress) progress->advance(t.heightsM.size());
        return frame;
    }

    HorizonParams hp;
    hp.refraction = params.refraction;
    hp.threads = params.threads;
    hp.maxDistanceM = frame.maxDistanceM;
    frame.sweepAzimuthsDeg = sunSweepAzimuthsDeg(field, t.width(), t.height());
    const std::vector<double>& azimuths = frame.sweepAzimuthsDeg;
    std::vector<HorizonMap> horizons;
    for (double az : azimuths) {
        hp.azimuthDeg = wrapAzimuthDeg(az);
        horizons.push_back(sweepHorizon(t, hp, progress));
    }
    const double spacing = azimuths.size() > 1 ? azimuths[1] - azimuths[0] : 1.0;
    parallelFor(0, t.height(), params.threads, [&](std::size_t row) {
        for (std::size_t col = 0; col < t.width(); ++col) {
            if (std::isnan(horizons[0].angleDeg(col, row))) continue;
            const auto [az, el] = field.at(static_cast<double>(col) + 0.5, static_cast<double>(row) + 0.5);
            // Horizon at this cell's own sun azimuth, linear between the bracketing sweeps.
            double h = horizons[0].angleDeg(col, row);
            if (azimuths.size() > 1) {
                const double u = std::clamp((az - azimuths[0]) / spacing, 0.0,
                                            static_cast<double>(azimuths.size() - 1));
                const auto i0 = std::min(static_cast<std::size_t>(u), azimuths.size() - 2);
                const double f = u - static_cast<double>(i0);
                h = (1 - f) * horizons[i0].angleDeg(col, row) + f * horizons[i0 + 1].angleDeg(col, row);
            }
            const Enu n = normals.at(col, row);
            const double azimuth = wrapAzimuthDeg(az);
            const SunTerms terms = sunTerms(n, h, azimuth, el, params.sunDiameterDeg);
            frame.light.visibility(col, row) = static_cast<float>(terms.visibility);
            frame.light.irradiance(col, row) = static_cast<float>(terms.irradiance);
        }
    });
    return frame;
}

}  // namespace demlight
