#include "lighting/sun_frame.h"

#include "lighting/quality.h"
#include "src/angles.h"
#include "src/parallel.h"

#include <algorithm>
#include <cmath>

namespace demlight {
namespace {

/// Floor of the elevation used to size the search distance (degrees).
constexpr double kLowestShadowElevationDeg = 0.25;

/// Diagonal of the DEM (metres), from the middle row's cell width and the summed cell heights.
double diagonalM(const Terrain& t) {
    double heightM = 0;
    for (double h : t.cellHeightM) heightM += h;
    const double widthM = t.cellWidthM[t.height() / 2] * static_cast<double>(t.width());
    return std::hypot(widthM, heightM);
}

}  // namespace

double sunSearchDistanceM(const Terrain& t, double lowestSunElevationDeg, double sunDiameterDeg) {
    const auto [lo, hi] = heightRangeM(t.heightsM);
    const double angle =
        std::max(lowestSunElevationDeg - sunDiameterDeg / 2, kLowestShadowElevationDeg);
    const double byRelief = static_cast<double>(hi - lo) / std::tan(angle * kDegToRad);
    const double diagonal = diagonalM(t);
    return std::max(t.cellHeightM.front(), byRelief >= kWholeDemShareOfDiagonal * diagonal ? diagonal : byRelief);
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

    // One sweep serves every cell at its own sun azimuth: its regions split wherever the sun's
    // azimuth (and the grid convergence) drift more than the direction tolerance.
    HorizonParams hp;
    hp.refraction = params.refraction;
    hp.curvature = params.curvature;
    hp.threads = params.threads;
    hp.maxDistanceM = frame.maxDistanceM;
    hp.azimuthDeg = field.centreAzimuthDeg;
    hp.azimuthAtDeg = [&field](double col, double row) { return field.at(col + 0.5, row + 0.5).first; };
    // Automatic tolerance: one cell of sideways drift at the sun's own search distance, the
    // farthest a shadow can be cast from; with or without the range limit below.
    hp.directionToleranceDeg = params.directionToleranceDeg > 0 ? params.directionToleranceDeg
                                                                : effectiveDirectionToleranceDeg(t, hp);
    if (params.maxDistanceM <= 0 && !rangeLimitPays(t, hp)) {
        // The sun's own distance finds every shadow; farther terrain cannot rise above this sun,
        // so the whole DEM gives the same visibility, and costs less unless the limit cuts the
        // line walks (regions) by more than its own overhead.
        hp.maxDistanceM = std::numeric_limits<double>::infinity();
        frame.maxDistanceM = diagonalM(t);
    }
    frame.sweepRegions = sweepRegions(t, hp).size();
    HorizonMap horizon;
    SweepBuffers buffers;
    sweepHorizonInto(t, hp, horizon, buffers, progress);
    parallelFor(0, t.height(), params.threads, [&](std::size_t row) {
        forEachSunInRow(field, row, t.width(), [&](std::size_t col, const SunAngles& sun) {
            if (std::isnan(t.heightsM(col, row))) return;
            const SunTerms terms =
                sunTerms(normals.at(col, row), horizon.angleDeg(col, row), sun, params.sunDiameterDeg);
            frame.light.visibility(col, row) = static_cast<float>(terms.visibility);
            frame.light.irradiance(col, row) = static_cast<float>(terms.irradiance);
        });
    });
    return frame;
}

}  // namespace demlight
