// Direct sun over a whole DEM at one instant: the driver `demlight sun`, time-lapse frames and
// sun-hour integrals share. Each cell uses its own sun position (interpolated from a SunField).
// Over a large DEM the sun's azimuth differs from cell to cell; the sweeps follow it (see
// computeSunFrame).
#pragma once

#include "demlight/lighting/horizon.h"
#include "demlight/lighting/sun.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/progress.h"
#include "demlight/core/angles.h"
#include "demlight/core/sun_field.h"
#include "demlight/core/terrain.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace demlight {

/// How computeSunFrame sweeps a sun whose azimuth varies over the DEM (see there).
enum class SunSweepStrategy { Cheapest, Following, Interpolating };

/// "following" or "interpolating" ("cheapest" for Cheapest).
const char* sunSweepStrategyName(SunSweepStrategy s);

struct SunFrameParams {
    double sunDiameterDeg = kSunDiameterDeg;
    /// Search distance; none: each sun's own (sunFrameSearchDistanceM).
    SearchDistanceM maxDistanceM;
    double refraction = kDefaultRefraction;
    /// As HorizonParams::curvature and HorizonParams::directionToleranceDeg (the scene plan's).
    bool curvature = true;
    double directionToleranceDeg = 0;
    double directionToleranceFloorDeg = 0;  ///< as HorizonParams::directionToleranceFloorDeg
    /// HorizonParams::nearestLine for the sun's sweeps (one scan line per cell). No scene plan
    /// sets it: it is cheaper than two lines but far less accurate on ridges (the bench's
    /// docs/bench/auto_vs_full.csv, sun rows' notes;
    /// docs/measurements.md#lightingsun_frameh-sunframeparamsnearestline).
    bool nearestLine = false;
    /// As HorizonParams::nearFieldSteps (the scene plan's).
    int nearFieldSteps = 0;
    /// As HorizonParams::farFieldCrossings (the scene plan's).
    bool farFieldCrossings = true;
    /// Cheapest (estimated line steps) unless a test forces one.
    SunSweepStrategy strategy = SunSweepStrategy::Cheapest;
};

struct SunFrame {
    SunLight light;                       ///< visibility and irradiance; NaN at nodata
    std::size_t sweepRegions = 0;         ///< regions of the frame's sweeps (0 when the sun is down everywhere)
    /// The strategy that ran: Following or Interpolating (Cheapest never; the sun down: Following).
    SunSweepStrategy strategy = SunSweepStrategy::Following;
    double maxDistanceM = 0;              ///< the search distance used
};

namespace detail {

/// The sun's angles along one row (forEachSunInRow), one array per quantity.
struct SunRowAngles {
    double* sinAzimuth;
    double* cosAzimuth;
    double* sinElevation;
    double* cosElevation;
    double* elevationDeg;
};

/// computeSunFrame's shading of one row from one horizon grid: sunTerms() for every cell
/// (tests/sun_frame_test.cpp holds it to that), branch-free so it vectorises. Normals must have
/// N_up > 0, as computeNormals gives; NaN horizons give NaN. No array may overlap another.
void shadeSunRow(const float* horizonDeg, const float* east, const float* north, const float* up,
                 const SunRowAngles& sun, float* visibility, float* irradiance, std::size_t cols,
                 double sunDiameterDeg);

}  // namespace detail

/// Calls fn(col, sun) for every column of `row` with the field's sun at the cell's centre
/// (SunField::at; the azimuth unwrapped like the field). Along a row the field is linear within each lattice interval, so each
/// interval's cells take azimuth and elevation linearly between its end cells, and their sines
/// and cosines by one angle-addition step per cell from the first cell's <cmath> values: no
/// trigonometry per cell, within ~1e-14 of <cmath> (tests/sun_frame_test.cpp). Intervals are the
/// DEM's (SunField::onTile): a tile starting inside one steps from the interval's first cell.
template <class Fn>
void forEachSunInRow(const SunField& field, std::size_t row, std::size_t width, Fn&& fn) {
    const double y = static_cast<double>(row) + 0.5 + field.rowOffset;
    const std::size_t step = std::max<std::size_t>(field.stepCells, 1);
    const auto offset = static_cast<std::size_t>(field.colOffset);  // cells of the DEM left of the tile
    const std::size_t fullWidth = field.fullWidth ? field.fullWidth : width;
    const std::size_t end = offset + width;  // in the DEM's columns from here on
    for (std::size_t c0 = offset / step * step; c0 < end;) {
        const std::size_t c1 = std::min(fullWidth, (c0 / step + 1) * step);  // one lattice interval
        const auto [az0, el0] = field.atFull(static_cast<double>(c0) + 0.5, y);
        const auto [az1, el1] = field.atFull(static_cast<double>(c1) - 0.5, y);
        const double last = static_cast<double>(c1 - c0 - 1);
        const double dAz = last > 0 ? (az1 - az0) / last : 0.0, dEl = last > 0 ? (el1 - el0) / last : 0.0;
        const double sinDAz = std::sin(dAz * kDegToRad), cosDAz = std::cos(dAz * kDegToRad);
        const double sinDEl = std::sin(dEl * kDegToRad), cosDEl = std::cos(dEl * kDegToRad);
        SunAngles sun{az0, el0, std::sin(az0 * kDegToRad), std::cos(az0 * kDegToRad), std::sin(el0 * kDegToRad),
                      std::cos(el0 * kDegToRad)};
        for (std::size_t col = c0; col < std::min(c1, end); ++col) {
            if (col >= offset) fn(col - offset, static_cast<const SunAngles&>(sun));
            sun.azimuthDeg = az0 + dAz * static_cast<double>(col + 1 - c0);
            sun.elevationDeg = el0 + dEl * static_cast<double>(col + 1 - c0);
            const double sa = sun.sinAzimuth * cosDAz + sun.cosAzimuth * sinDAz;
            sun.cosAzimuth = sun.cosAzimuth * cosDAz - sun.sinAzimuth * sinDAz;
            sun.sinAzimuth = sa;
            const double se = sun.sinElevation * cosDEl + sun.cosElevation * sinDEl;
            sun.cosElevation = sun.cosElevation * cosDEl - sun.sinElevation * sinDEl;
            sun.sinElevation = se;
        }
        c0 = c1;
    }
}

/// Search distance that catches every shadow at this sun: relief / tan(lowest elevation minus
/// the disk radius, at least 0.25 deg), at least one cell; the DEM diagonal when that is
/// kWholeDemShareOfDiagonal of it or more.
double sunSearchDistanceM(const Terrain& terrain, double lowestSunElevationDeg,
                          double sunDiameterDeg);

/// The search distance of a sun frame: params.maxDistanceM when given, else sunSearchDistanceM
/// for the field's lowest sun (the halo a window's sun terms read).
double sunFrameSearchDistanceM(const Terrain& terrain, const SunField& field, const SunFrameParams& params);

/// Visibility and irradiance of the sun for every cell, each cell's horizon taken along its own
/// sun azimuth (within the direction tolerance): either one sweep whose regions follow the sun's
/// azimuth (HorizonParams::azimuthAtDeg), or, when that costs more line steps
/// (estimateSweepSteps; near sunrise and sunset on large DEMs), sweeps at azimuths 0.5 deg apart
/// over the cells they bracket, interpolated linearly in azimuth per cell. The tolerance is
/// params.directionToleranceDeg, or when that is 0, one cell of sideways drift at the sun's search
/// distance (sunSearchDistanceM: no shadow is cast from farther). When the sun's upper limb is
/// below the horizon everywhere, every valid cell gets 0 without any sweep. `buffers`: the
/// sweeps' scratch, kept by callers that compute many frames of one terrain (see SweepBuffers);
/// null: the frame's own.
SunFrame computeSunFrame(const Terrain& terrain, const Normals& normals, const SunField& field,
                         const SunFrameParams& params, ProgressCounter* progress = nullptr,
                         SweepBuffers* buffers = nullptr);

}  // namespace demlight
