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

/// Side of the blocks (cells) in which sweepWindows() bounds the cells of each sweep.
constexpr std::size_t kWindowBlockCells = 64;

/// For each sweep azimuth a_i, the bounding window of the cells whose own sun azimuth lies in
/// [a_(i-1), a_(i+1)], the only cells that interpolate with sweep i; empty (col0 == col1) when
/// no cell needs it. Taken over blocks of kWindowBlockCells with the field's exact range in each.
std::vector<CellWindow> sweepWindows(const SunField& field, const std::vector<double>& azimuths,
                                     std::size_t width, std::size_t height) {
    const std::size_t n = azimuths.size();
    std::vector<CellWindow> windows(n);
    if (n == 1) {
        windows[0] = {0, 0, width, height};
        return windows;
    }
    for (std::size_t r0 = 0; r0 < height; r0 += kWindowBlockCells) {
        const std::size_t r1 = std::min(r0 + kWindowBlockCells, height);
        for (std::size_t c0 = 0; c0 < width; c0 += kWindowBlockCells) {
            const std::size_t c1 = std::min(c0 + kWindowBlockCells, width);
            const auto [lo, hi] = field.azimuthRange(c0, r0, c1, r1);
            for (std::size_t i = 0; i < n; ++i) {
                const double below = i == 0 ? -1e300 : azimuths[i - 1];
                const double above = i + 1 == n ? 1e300 : azimuths[i + 1];
                if (hi < below || lo > above) continue;
                CellWindow& w = windows[i];
                if (w.col0 == w.col1) {
                    w = {c0, r0, c1, r1};
                } else {
                    w = {std::min(w.col0, c0), std::min(w.row0, r0), std::max(w.col1, c1),
                         std::max(w.row1, r1)};
                }
            }
        }
    }
    return windows;
}

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

    HorizonParams hp;
    hp.refraction = params.refraction;
    hp.curvature = params.curvature;
    hp.directionToleranceDeg = params.directionToleranceDeg;
    hp.threads = params.threads;
    hp.maxDistanceM = frame.maxDistanceM;
    frame.sweepAzimuthsDeg = sunSweepAzimuthsDeg(field, t.width(), t.height());
    const std::vector<double>& azimuths = frame.sweepAzimuthsDeg;
    if (params.maxDistanceM <= 0) {
        // The sun's own distance finds every shadow; farther terrain cannot rise above this sun,
        // so the whole DEM gives the same visibility, and costs less unless the limit cuts the
        // line walks (regions, small windows) by more than its own overhead.
        hp.azimuthDeg = wrapAzimuthDeg(azimuths[azimuths.size() / 2]);
        if (!rangeLimitPays(t, hp)) {
            hp.maxDistanceM = std::numeric_limits<double>::infinity();
            frame.maxDistanceM = diagonalM(t);
        }
    }
    // Each sweep covers only the cells that interpolate with it, so a frame costs about two
    // DEM-wide sweeps however many azimuths it spans. Progress: the frame counts as one pass
    // over the cells, shared among the sweeps by their window areas.
    const std::vector<CellWindow> windows = sweepWindows(field, azimuths, t.width(), t.height());
    const auto area = [](const CellWindow& w) { return (w.col1 - w.col0) * (w.row1 - w.row0); };
    std::size_t totalArea = 0;
    for (const CellWindow& w : windows) totalArea += area(w);
    std::vector<HorizonMap> horizons(azimuths.size());
    SweepBuffers buffers;
    std::size_t areaDone = 0, reported = 0;
    for (std::size_t i = 0; i < azimuths.size(); ++i) {
        if (area(windows[i]) == 0) continue;
        hp.azimuthDeg = wrapAzimuthDeg(azimuths[i]);
        hp.window = windows[i];
        sweepHorizonInto(t, hp, horizons[i], buffers);
        if (progress) {
            areaDone += area(windows[i]);
            const std::size_t target = t.heightsM.size() * areaDone / totalArea;
            progress->advance(target - reported);
            reported = target;
            progress->throwIfCancelled();
        }
    }
    const double spacing = azimuths.size() > 1 ? azimuths[1] - azimuths[0] : 1.0;
    // Each cell's sun from the middle sweep azimuth plus a small offset: no library
    // trigonometry per cell.
    const SunAnglesNear sunAngles(azimuths[azimuths.size() / 2]);
    parallelFor(0, t.height(), params.threads, [&](std::size_t row) {
        for (std::size_t col = 0; col < t.width(); ++col) {
            if (std::isnan(t.heightsM(col, row))) continue;
            const auto [az, el] = field.at(static_cast<double>(col) + 0.5, static_cast<double>(row) + 0.5);
            // Horizon at this cell's own sun azimuth, linear between the bracketing sweeps.
            // Both bracketing sweeps' windows contain this cell (sweepWindows).
            double h = 0;
            if (azimuths.size() == 1) {
                h = horizons[0].angleDeg(col, row);
            } else {
                const double u = std::clamp((az - azimuths[0]) / spacing, 0.0,
                                            static_cast<double>(azimuths.size() - 1));
                const auto i0 = std::min(static_cast<std::size_t>(u), azimuths.size() - 2);
                const double f = u - static_cast<double>(i0);
                h = (1 - f) * horizons[i0].angleDeg(col, row) + f * horizons[i0 + 1].angleDeg(col, row);
            }
            const Enu n = normals.at(col, row);
            const SunTerms terms =
                sunTerms(n, h, sunAngles(az, el), params.sunDiameterDeg);
            frame.light.visibility(col, row) = static_cast<float>(terms.visibility);
            frame.light.irradiance(col, row) = static_cast<float>(terms.irradiance);
        }
    });
    return frame;
}

}  // namespace demlight
