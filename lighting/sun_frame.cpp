#include "lighting/sun_frame.h"

#include "src/angles.h"
#include "src/parallel.h"

#include <algorithm>
#include <cmath>

namespace demlight {
namespace {

/// Floor of the elevation used to size the search distance (degrees).
constexpr double kLowestShadowElevationDeg = 0.25;

void splitTiles(const SunField& field, CellWindow w, std::vector<CellWindow>& tiles) {
    const auto [lo, hi] = field.azimuthRange(w.col0, w.row0, w.col1, w.row1);
    const std::size_t cols = w.col1 - w.col0, rows = w.row1 - w.row0;
    if (hi - lo <= kSunAzimuthToleranceDeg || std::max(cols, rows) < 2 * kMinSunTileCells) {
        tiles.push_back(w);
        return;
    }
    CellWindow a = w, b = w;
    if (cols >= rows) {
        a.col1 = b.col0 = w.col0 + cols / 2;
    } else {
        a.row1 = b.row0 = w.row0 + rows / 2;
    }
    splitTiles(field, a, tiles);
    splitTiles(field, b, tiles);
}

}  // namespace

std::vector<CellWindow> sunTiles(const SunField& field, std::size_t width, std::size_t height) {
    std::vector<CellWindow> tiles;
    splitTiles(field, {0, 0, width, height}, tiles);
    return tiles;
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
    frame.tiles = sunTiles(field, t.width(), t.height());
    for (const CellWindow& tile : frame.tiles) {
        const auto [azLo, azHi] = field.azimuthRange(tile.col0, tile.row0, tile.col1, tile.row1);
        hp.azimuthDeg = wrapAzimuthDeg(0.5 * (azLo + azHi));
        hp.window = tile;
        const HorizonMap horizon = sweepHorizon(t, hp, progress);
        parallelFor(tile.row0, tile.row1, params.threads, [&](std::size_t row) {
            for (std::size_t col = tile.col0; col < tile.col1; ++col) {
                const float h = horizon.angleDeg(col, row);
                if (std::isnan(h)) continue;
                const auto [az, el] =
                    field.at(static_cast<double>(col) + 0.5, static_cast<double>(row) + 0.5);
                const Enu n = normals.at(col, row);
                const double azimuth = wrapAzimuthDeg(az);
                frame.light.visibility(col, row) = static_cast<float>(
                    sunVisibilityClamped(n, h, azimuth, el, params.sunDiameterDeg));
                frame.light.irradiance(col, row) =
                    static_cast<float>(sunIrradiance(n, h, azimuth, el, params.sunDiameterDeg));
            }
        });
    }
    return frame;
}

}  // namespace demlight
