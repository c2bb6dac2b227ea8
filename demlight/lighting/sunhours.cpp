// Sun-hour integrals; see sunhours.h.
#include "demlight/lighting/sunhours.h"

#include "demlight/lighting/canopy.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace demlight {
namespace {

/// Share of [0, 1] on which the linear function from e0 to e1 exceeds `threshold`.
double fractionAbove(double e0, double e1, double threshold) {
    const bool up0 = e0 > threshold, up1 = e1 > threshold;
    if (up0 == up1) return up0 ? 1.0 : 0.0;
    const double crossing = (threshold - e0) / (e1 - e0);  // in [0, 1]: the ends straddle it
    return up0 ? crossing : 1.0 - crossing;
}

void checkInstants(std::span<const SunInstant> instants, const char* what) {
    if (instants.size() < 2) throw Error(std::string(what) + ": need at least two instants");
    for (std::size_t i = 1; i < instants.size(); ++i)
        if (!(instants[i].hours > instants[i - 1].hours))
            throw Error(std::string(what) + ": instants must be strictly increasing");
}

}  // namespace

HorizonStack computeHorizonStack(const Terrain& t, std::size_t directions,
                                 const HorizonParams& params, ProgressCounter* progress) {
    if (directions < 2) throw Error("horizon stack: need at least 2 directions");
    HorizonStack stack;
    stack.maxDistanceM = params.maxDistanceM;
    HorizonParams hp = params;
    for (std::size_t i = 0; i < directions; ++i) {
        hp.azimuthDeg = 360.0 * static_cast<double>(i) / static_cast<double>(directions);
        stack.angleDeg.push_back(sweepHorizon(t, hp, progress).angleDeg);
    }
    return stack;
}

SunLight sunLightFromStack(const Terrain& t, const Normals& normals, const HorizonStack& stack,
                           const SunField& field, double sunDiameterDeg) {
    const std::size_t w = t.width(), h = t.height(), n = stack.angleDeg.size();
    if (n < 2) throw Error("horizon stack: need at least 2 directions");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    SunLight light{Grid<float>(w, h, nan), Grid<float>(w, h, nan)};
    if (field.elevationRange().second <= -sunDiameterDeg / 2) {
        // Night everywhere: no sun to place.
        for (std::size_t i = 0; i < t.heightsM.size(); ++i)
            if (!std::isnan(t.heightsM.data()[i])) light.visibility.data()[i] = light.irradiance.data()[i] = 0.0f;
        return light;
    }
    const double nD = static_cast<double>(n), sectorDeg = 360.0 / nD;
    // Per row: the sun's angles and each cell's horizon interpolated at its own sun azimuth into
    // buffers, then the vectorised shading pass of exact sun frames (NaN horizons at nodata give
    // NaN light).
    parallelFor(0, h, [&](std::size_t row) {
        thread_local std::vector<double> buffer;
        thread_local std::vector<float> horizonRow;
        thread_local std::vector<const float*> stackRow;
        buffer.resize(5 * w);
        horizonRow.resize(w);
        stackRow.resize(n);
        for (std::size_t i = 0; i < n; ++i) stackRow[i] = stack.angleDeg[i].rowPtr(row);
        detail::SunRowAngles angles{buffer.data(), buffer.data() + w, buffer.data() + 2 * w, buffer.data() + 3 * w,
                                    buffer.data() + 4 * w};
        forEachSunInRow(field, row, w, [&](std::size_t col, const SunAngles& sun) {
            angles.sinAzimuth[col] = sun.sinAzimuth;
            angles.cosAzimuth[col] = sun.cosAzimuth;
            angles.sinElevation[col] = sun.sinElevation;
            angles.cosElevation[col] = sun.cosElevation;
            angles.elevationDeg[col] = sun.elevationDeg;
            // Directions from the azimuth in [0, 360): the field's is unwrapped, within a turn of it.
            double u = sun.azimuthDeg / sectorDeg;
            while (u < 0.0) u += nD;
            while (u >= nD) u -= nD;
            const std::size_t i0 = std::min(static_cast<std::size_t>(u), n - 1), i1 = i0 + 1 == n ? 0 : i0 + 1;
            const double f = u - static_cast<double>(i0);
            horizonRow[col] = static_cast<float>((1 - f) * stackRow[i0][col] + f * stackRow[i1][col]);
        });
        detail::shadeSunRow(horizonRow.data(), normals.east.rowPtr(row), normals.north.rowPtr(row),
                            normals.up.rowPtr(row), angles, light.visibility.rowPtr(row), light.irradiance.rowPtr(row),
                            w, sunDiameterDeg);
    });
    return light;
}

SunHoursMaps integrateSunHours(const Terrain& t, const Normals& normals,
                               std::span<const SunInstant> instants, const SunFieldAt& fieldAt,
                               const SunHoursParams& params, ProgressCounter* progress) {
    checkInstants(instants, "sun hours");

    const std::size_t w = t.width(), h = t.height();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Grid<double> sumVis(w, h, 0.0), sumIrr(w, h, 0.0);
    Grid<float> prevVis(w, h, 0.0f);
    SunHoursMaps out;
    out.firstLitClock = Grid<float>(w, h, nan);
    out.lastLitClock = Grid<float>(w, h, nan);

    SweepBuffers buffers;  // the instants' sweeps' scratch and valid-cell bitmap
    SweepBuffers groundBuffers;  // the same for the ground under a canopy
    if (params.canopyGround && (params.stack || !params.underCrown))
        throw Error("integrateSunHours: a canopy needs exact sweeps and its cells under a crown");
    for (std::size_t i = 0; i < instants.size(); ++i) {
        // Trapezoid weights (hours): half the neighbouring intervals.
        const double before = i > 0 ? instants[i].hours - instants[i - 1].hours : 0.0;
        const double after = i + 1 < instants.size() ? instants[i + 1].hours - instants[i].hours : 0.0;
        const double weight = 0.5 * (before + after);
        const SunField field = fieldAt(i);
        const bool dark = field.elevationRange().second < kSunDownElevationDeg;
        SunFrame frame;
        if (!dark) {
            if (params.stack)
                frame.light = sunLightFromStack(t, normals, *params.stack, field, params.frame.sunDiameterDeg);
            else
                frame = computeSunFrame(t, normals, field, params.frame, nullptr, &buffers);
            if (params.canopyGround)
                blendCanopySun(frame,
                               computeSunFrame(*params.canopyGround, normals, field, params.frame, nullptr,
                                               &groundBuffers),
                               *params.underCrown, params.transmissivity);
            ++out.instantsSwept;
        }
        const double clock = instants[i].clockHours;
        const double prevClock = i > 0 ? instants[i - 1].clockHours : clock;
        const bool last = i + 1 == instants.size();
        parallelFor(0, h, [&](std::size_t row) {
            for (std::size_t col = 0; col < w; ++col) {
                if (!t.valid(col, row)) continue;
                const float v = dark ? 0.0f : frame.light.visibility(col, row);
                const float e = dark ? 0.0f : frame.light.irradiance(col, row);
                if (std::isnan(v)) continue;
                sumVis(col, row) += weight * v;
                sumIrr(col, row) += weight * e;
                const float p = prevVis(col, row);
                if (i == 0) {
                    if (v >= kLitVisibility) out.firstLitClock(col, row) = static_cast<float>(clock);
                } else {
                    // Linear interpolation of the crossing between the two samples.
                    const double f = (kLitVisibility - p) / (static_cast<double>(v) - p);
                    const double crossing = prevClock + f * (clock - prevClock);
                    if (p < kLitVisibility && v >= kLitVisibility &&
                        std::isnan(out.firstLitClock(col, row)))
                        out.firstLitClock(col, row) = static_cast<float>(crossing);
                    if (p >= kLitVisibility && v < kLitVisibility)
                        out.lastLitClock(col, row) = static_cast<float>(crossing);
                }
                if (last && v >= kLitVisibility) out.lastLitClock(col, row) = static_cast<float>(clock);
                prevVis(col, row) = v;
            }
        });
        if (progress) {
            progress->advance(1);
            progress->throwIfCancelled();
        }
    }

    out.sunHours = Grid<float>(w, h, nan);
    out.sunIrradiation = Grid<float>(w, h, nan);
    for (std::size_t k = 0; k < t.heightsM.size(); ++k) {
        if (std::isnan(t.heightsM.data()[k])) continue;
        out.sunHours.data()[k] = static_cast<float>(sumVis.data()[k]);
        out.sunIrradiation.data()[k] = static_cast<float>(sumIrr.data()[k]);
    }
    return out;
}

Grid<float> integrateDaylight(const Terrain& t, std::span<const SunInstant> instants,
                              const SunFieldAt& geometricFieldAt) {
    checkInstants(instants, "daylight");
    const std::size_t w = t.width(), h = t.height();
    Grid<double> sum(w, h, 0.0);
    SunField prev = geometricFieldAt(0);
    for (std::size_t i = 1; i < instants.size(); ++i) {
        SunField cur = geometricFieldAt(i);
        const double interval = instants[i].hours - instants[i - 1].hours;
        // The whole interval when the sun is up at both ends everywhere, none when it is down at
        // both ends everywhere (bilinear interpolation stays inside the lattice's range); else
        // per cell.
        const auto [lo0, hi0] = prev.elevationRange();
        const auto [lo1, hi1] = cur.elevationRange();
        const bool allUp = std::min(lo0, lo1) > kSunriseGeometricElevationDeg;
        const bool allDown = std::max(hi0, hi1) <= kSunriseGeometricElevationDeg;
        parallelFor(0, h, [&](std::size_t row) {
            const double y = static_cast<double>(row) + 0.5;
            for (std::size_t col = 0; col < w; ++col) {
                if (!t.valid(col, row) || allDown) continue;
                if (allUp) {
                    sum(col, row) += interval;
                    continue;
                }
                const double x = static_cast<double>(col) + 0.5;
                sum(col, row) += interval * fractionAbove(prev.at(x, y).second, cur.at(x, y).second,
                                                          kSunriseGeometricElevationDeg);
            }
        });
        prev = std::move(cur);
    }
    Grid<float> out(w, h, std::numeric_limits<float>::quiet_NaN());
    for (std::size_t k = 0; k < out.size(); ++k)
        if (!std::isnan(t.heightsM.data()[k])) out.data()[k] = static_cast<float>(sum.data()[k]);
    return out;
}

Grid<float> skyIrradiation(const Grid<float>& skyTerm, const Grid<float>& daylightHours) {
    if (skyTerm.width() != daylightHours.width() || skyTerm.height() != daylightHours.height())
        throw Error("sky irradiation: the sky term and the daylight hours differ in size");
    Grid<float> out(skyTerm.width(), skyTerm.height());
    for (std::size_t k = 0; k < out.size(); ++k)
        out.data()[k] = skyTerm.data()[k] * daylightHours.data()[k];  // NaN propagates
    return out;
}

}  // namespace demlight
