#include "demlight/lighting/sun_frame.h"

#include "demlight/lighting/quality.h"
#include "demlight/core/angles.h"
#include "demlight/core/fast_math.h"
#include "demlight/core/parallel.h"
#include "demlight/core/simd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace demlight {
namespace {

/// Floor of the elevation used to size the search distance (degrees).
constexpr double kLowestShadowElevationDeg = 0.25;

/// sunTerms() along one row, branch-free so the compiler vectorises it: the horizon clamped to
/// the tangent plane in the sun's azimuth, the visible fraction of the disk (Hoffman & Mitchell
/// 2001b, Eq. 5-7; a point sun when !Disk) and the Lambert term. Normals of a height field have
/// N_up > 0 (computeNormals), where sunTerms() takes the same arctangent; NaN horizons (nodata)
/// give NaN. The pointers do not alias (restrict). Inlined into shadeSunRow for each SimdPath.
template <bool Disk>
DEMLIGHT_INLINE inline void shadeRow(const float* __restrict horizonDeg, const float* __restrict east, const float* __restrict north,
              const float* __restrict up, const detail::SunRowAngles sun, float* __restrict visibility,
              float* __restrict irradiance, std::size_t cols, double diameterDeg) {
    const double* __restrict sinAz = sun.sinAzimuth;
    const double* __restrict cosAz = sun.cosAzimuth;
    const double* __restrict sinEl = sun.sinElevation;
    const double* __restrict cosEl = sun.cosElevation;
    const double* __restrict elDeg = sun.elevationDeg;
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t col = 0; col < cols; ++col) {
        const double h = horizonDeg[col], ne = east[col], nn = north[col], nu = up[col];
        const double toward = ne * sinAz[col] + nn * cosAz[col];  // N_h . (sun's azimuth)
        const double planeDeg = fastAtan(-toward / nu) * kRadToDeg;
        const double effective = std::max(h, planeDeg);  // NaN horizon stays NaN
        double o;
        if constexpr (Disk) {  // as sunVisibility()
            const double thetaMin = elDeg[col] - 0.5 * diameterDeg, thetaMax = elDeg[col] + 0.5 * diameterDeg;
            o = std::clamp((thetaMax - effective) / (thetaMax - thetaMin), 0.0, 1.0);
        } else {
            o = effective < elDeg[col] ? 1.0 : effective > elDeg[col] ? 0.0 : effective == elDeg[col] ? 0.5 : kNaN;
        }
        const double cosine = toward * cosEl[col] + nu * sinEl[col];
        visibility[col] = static_cast<float>(o);
        irradiance[col] = static_cast<float>(o * std::max(0.0, cosine));
    }
}

/// Interpolating strategy: largest spread of the sun's azimuth served by one sweep, and the
/// spacing of the sweep azimuths when the spread is larger (degrees). Linear interpolation of the
/// horizon in azimuth over 0.5 deg is exact wherever the horizon point does not jump, and the
/// far coarser 5.6 deg spacing of `timelapse --horizon-mode interpolated:64` is already accurate
/// (docs/measurements.md#lightingsun_framecpp-ksunazimuthspacingdeg).
constexpr double kSunAzimuthToleranceDeg = 0.1;
constexpr double kSunAzimuthSpacingDeg = 0.5;

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

/// The azimuths of the interpolating strategy (degrees, unwrapped like the field): the midpoint
/// when the field's spread is at most kSunAzimuthToleranceDeg, otherwise evenly spaced from the
/// lowest to the highest azimuth at most kSunAzimuthSpacingDeg apart.
std::vector<double> sunSweepAzimuthsDeg(const SunField& field, std::size_t width, std::size_t height) {
    const auto [lo, hi] = field.azimuthRange(0, 0, width, height);
    if (hi - lo <= kSunAzimuthToleranceDeg) return {0.5 * (lo + hi)};
    const auto intervals = static_cast<std::size_t>(std::ceil((hi - lo) / kSunAzimuthSpacingDeg));
    std::vector<double> azimuths(intervals + 1);
    for (std::size_t i = 0; i <= intervals; ++i)
        azimuths[i] = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(intervals);
    return azimuths;
}

}  // namespace

namespace detail {

void shadeSunRow(const float* horizonDeg, const float* east, const float* north, const float* up,
                 const SunRowAngles& sun, float* visibility, float* irradiance, std::size_t cols,
                 double sunDiameterDeg) {
    onWidestPath([&]() DEMLIGHT_INLINE {
        if (sunDiameterDeg > 0.0) {
            shadeRow<true>(horizonDeg, east, north, up, sun, visibility, irradiance, cols, sunDiameterDeg);
        } else {
            shadeRow<false>(horizonDeg, east, north, up, sun, visibility, irradiance, cols, sunDiameterDeg);
        }
    });
}

}  // namespace detail

double sunSearchDistanceM(const Terrain& t, double lowestSunElevationDeg, double sunDiameterDeg) {
    return reliefSearch(t, std::max(lowestSunElevationDeg - sunDiameterDeg / 2, kLowestShadowElevationDeg)).distanceM;
}

const char* sunSweepStrategyName(SunSweepStrategy s) {
    switch (s) {
        case SunSweepStrategy::Following: return "following";
        case SunSweepStrategy::Interpolating: return "interpolating";
        case SunSweepStrategy::Cheapest: break;
    }
    return "cheapest";
}

namespace {

/// One sweep of the interpolating strategy: at azimuths[azimuthIndex], over params.window.
struct FixedSweep {
    std::size_t azimuthIndex;
    HorizonParams params;
};

/// The sweeps of a frame: the following strategy's one sweep (its params), or the
/// interpolating strategy's sweeps (fixedSweeps, non-empty) at their azimuths.
struct SunSweepPlan {
    HorizonParams following;
    std::vector<double> azimuths;
    std::vector<FixedSweep> fixedSweeps;
};

/// Chooses the frame's sweeps (and sets frame.maxDistanceM to the whole DEM's diagonal where the
/// whole DEM is searched).
SunSweepPlan planSunSweeps(const Terrain& t, const SunField& field, const SunFrameParams& params, SunFrame& frame) {
    SunSweepPlan plan;
    // The following strategy's sweep; the interpolating one's sweeps copy it.
    HorizonParams& hp = plan.following;
    hp.refraction = params.refraction;
    hp.curvature = params.curvature;
    hp.truncationFlags = false;
    hp.nearestLine = params.nearestLine;
    hp.nearFieldSteps = params.nearFieldSteps;
    hp.farFieldCrossings = params.farFieldCrossings;
    hp.maxDistanceM = frame.maxDistanceM;
    hp.azimuthDeg = field.centreAzimuthDeg;
    hp.azimuthAtDeg = [&field](double col, double row) { return field.atFull(col + 0.5, row + 0.5).first; };
    hp.directionToleranceFloorDeg = params.directionToleranceFloorDeg;
    // Automatic tolerance: one cell of sideways drift at the sun's own search distance, the
    // farthest a shadow can be cast from; with or without the range limit below.
    hp.directionToleranceDeg = params.directionToleranceDeg > 0 ? params.directionToleranceDeg
                                                                : effectiveDirectionToleranceDeg(t, hp);
    if (!params.maxDistanceM && !rangeLimitPays(t, hp)) {
        // The sun's own distance finds every shadow; farther terrain cannot rise above this sun,
        // so the whole DEM gives the same visibility, and costs less unless the limit cuts the
        // line walks (regions) by more than its own overhead.
        hp.maxDistanceM = std::numeric_limits<double>::infinity();
        frame.maxDistanceM = diagonalM(fullGrid(t));
    }
    // Two exact strategies; the one with fewer estimated line steps runs.
    //  - Following: one sweep whose regions follow the sun's azimuth. Cheapest while the
    //    tolerance is loose (sun well up); near sunrise the tolerance tightens to ~0.01 deg at
    //    the whole DEM's distance and thousands of narrow regions would each walk the DEM.
    //  - Interpolating: sweeps at azimuths kSunAzimuthSpacingDeg apart spanning the field, each
    //    over the cells whose own azimuth it brackets (its regions split for the convergence
    //    only), and each cell's horizon linear in azimuth between the two bracketing sweeps.
    // Chosen on the DEM's full grid (windows in its coordinates), so every tile chooses alike.
    const FullGridRef full = fullGrid(t);
    plan.azimuths = sunSweepAzimuthsDeg(field, full.width, full.height);
    const std::vector<double>& azimuths = plan.azimuths;
    const std::vector<CellWindow> windows = sweepWindows(field, azimuths, full.width, full.height);
    std::vector<FixedSweep>& fixedSweeps = plan.fixedSweeps;
    if (azimuths.size() > 1 && params.strategy != SunSweepStrategy::Following) {
        double interpolatingSteps = 0;
        for (std::size_t i = 0; i < azimuths.size(); ++i) {
            if (windows[i].col0 == windows[i].col1) continue;
            HorizonParams p = hp;
            p.azimuthAtDeg = nullptr;
            p.azimuthDeg = wrapAzimuthDeg(azimuths[i]);
            p.window = windows[i];
            interpolatingSteps += estimateSweepSteps(t, p);
            // The sweep covers the window's cells of this terrain, in its coordinates.
            const CellWindow& w = windows[i];
            const CellWindow local{std::max(w.col0, full.col0) - full.col0, std::max(w.row0, full.row0) - full.row0,
                                   std::min(w.col1, full.col0 + t.width()), std::min(w.row1, full.row0 + t.height())};
            if (local.col1 <= full.col0 + local.col0 || local.row1 <= full.row0 + local.row0) {
                p.window.reset();  // no cell of this terrain: skipped below
            } else {
                p.window = CellWindow{local.col0, local.row0, local.col1 - full.col0, local.row1 - full.row0};
            }
            fixedSweeps.push_back({i, p});
        }
        if (params.strategy == SunSweepStrategy::Cheapest && interpolatingSteps >= estimateSweepSteps(t, hp))
            fixedSweeps.clear();
    }
    return plan;
}

}  // namespace

double sunFrameSearchDistanceM(const Terrain& terrain, const SunField& field, const SunFrameParams& params) {
    if (params.maxDistanceM) return *params.maxDistanceM;
    return sunSearchDistanceM(terrain, field.elevationRange().first, params.sunDiameterDeg);
}

SunFrame computeSunFrame(const Terrain& t, const Normals& normals, const SunField& field,
                         const SunFrameParams& params, ProgressCounter* progress, SweepBuffers* sharedBuffers) {
    SunFrame frame;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    frame.light.visibility = Grid<float>(t.width(), t.height(), nan);
    frame.light.irradiance = frame.light.visibility;
    const double highestSun = field.elevationRange().second;
    frame.maxDistanceM = sunFrameSearchDistanceM(t, field, params);

    if (highestSun <= -params.sunDiameterDeg / 2) {
        // The whole disk is below the horizon everywhere: night (rows on every thread).
        const std::size_t w = t.width();
        parallelFor(0, t.height(), [&](std::size_t row) {
            const float* h = t.heightsM.rowPtr(row);
            float* vis = frame.light.visibility.rowPtr(row);
            float* irr = frame.light.irradiance.rowPtr(row);
            for (std::size_t c = 0; c < w; ++c)
                if (!std::isnan(h[c])) vis[c] = irr[c] = 0.0f;
        }, 16);
        if (progress) progress->advance(t.heightsM.size());
        return frame;
    }

    SunSweepPlan plan = planSunSweeps(t, field, params, frame);
    const HorizonParams& hp = plan.following;
    const std::vector<double>& azimuths = plan.azimuths;
    std::vector<FixedSweep>& fixedSweeps = plan.fixedSweeps;
    frame.strategy = fixedSweeps.empty() ? SunSweepStrategy::Following : SunSweepStrategy::Interpolating;
    std::vector<HorizonMap> horizons(fixedSweeps.empty() ? 1 : azimuths.size());
    SweepBuffers ownBuffers;
    SweepBuffers& buffers = sharedBuffers ? *sharedBuffers : ownBuffers;
    std::erase_if(fixedSweeps, [](const FixedSweep& sweep) { return !sweep.params.window; });
    if (frame.strategy == SunSweepStrategy::Following) {
        frame.sweepRegions = sweepHorizonInto(t, hp, horizons[0], buffers, progress);
    } else {
        // Progress: the frame counts as one pass over the cells, shared by window areas.
        const auto area = [](const CellWindow& w) { return (w.col1 - w.col0) * (w.row1 - w.row0); };
        std::size_t totalArea = 0, areaDone = 0, reported = 0;
        for (const FixedSweep& sweep : fixedSweeps) totalArea += area(*sweep.params.window);
        totalArea = std::max<std::size_t>(totalArea, 1);
        for (const FixedSweep& sweep : fixedSweeps) {
            frame.sweepRegions += sweepHorizonInto(t, sweep.params, horizons[sweep.azimuthIndex], buffers);
            if (progress) {
                areaDone += area(*sweep.params.window);
                const std::size_t target = t.heightsM.size() * areaDone / totalArea;
                progress->advance(target - reported);
                reported = target;
                progress->throwIfCancelled();
            }
        }
    }
    const double spacing = azimuths.size() > 1 ? azimuths[1] - azimuths[0] : 1.0;
    const auto horizonAt = [&](std::size_t col, std::size_t row, double azimuthDeg) -> double {
        if (horizons.size() == 1) return horizons[0].angleDeg(col, row);
        // Linear between the bracketing sweeps, whose windows both contain this cell.
        const double u = std::clamp((azimuthDeg - azimuths[0]) / spacing, 0.0,
                                    static_cast<double>(azimuths.size() - 1));
        const auto i0 = std::min(static_cast<std::size_t>(u), azimuths.size() - 2);
        const double f = u - static_cast<double>(i0);
        return (1 - f) * horizons[i0].angleDeg(col, row) + f * horizons[i0 + 1].angleDeg(col, row);
    };
    if (horizons.size() == 1) {
        // One sweep: the sun's angles of a row into buffers, then the vectorised shading pass.
        const std::size_t width = t.width();
        parallelFor(0, t.height(), [&](std::size_t row) {
            thread_local std::vector<double> buffer;
            buffer.resize(5 * width);
            detail::SunRowAngles angles{buffer.data(), buffer.data() + width, buffer.data() + 2 * width,
                                buffer.data() + 3 * width, buffer.data() + 4 * width};
            forEachSunInRow(field, row, width, [&](std::size_t col, const SunAngles& sun) {
                angles.sinAzimuth[col] = sun.sinAzimuth;
                angles.cosAzimuth[col] = sun.cosAzimuth;
                angles.sinElevation[col] = sun.sinElevation;
                angles.cosElevation[col] = sun.cosElevation;
                angles.elevationDeg[col] = sun.elevationDeg;
            });
            const float* h = horizons[0].angleDeg.rowPtr(row);
            float* visibility = frame.light.visibility.rowPtr(row);
            float* irradiance = frame.light.irradiance.rowPtr(row);
            detail::shadeSunRow(h, normals.east.rowPtr(row), normals.north.rowPtr(row), normals.up.rowPtr(row),
                                angles, visibility, irradiance, width, params.sunDiameterDeg);
        });
        return frame;
    }
    parallelFor(0, t.height(), [&](std::size_t row) {
        forEachSunInRow(field, row, t.width(), [&](std::size_t col, const SunAngles& sun) {
            if (std::isnan(t.heightsM(col, row))) return;
            const SunTerms terms = sunTerms(normals.at(col, row), horizonAt(col, row, sun.azimuthDeg), sun,
                                            params.sunDiameterDeg);
            frame.light.visibility(col, row) = static_cast<float>(terms.visibility);
            frame.light.irradiance(col, row) = static_cast<float>(terms.irradiance);
        });
    });
    return frame;
}

}  // namespace demlight
