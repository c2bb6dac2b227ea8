// The combine of a sweep (demlight/lighting/sweep/combine.h).
#include "demlight/lighting/sweep/combine.h"

#include "demlight/lighting/sweep/near_field.h"
#include "demlight/core/angles.h"
#include "demlight/core/fast_math.h"
#include "demlight/core/simd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace demlight::sweep {
namespace {

/// combineRow's two-line case without flags, branch-free so the compiler vectorises it: the
/// tangents of the two lines bracketing each cell (plane A weighted frac, plane B 1 - frac;
/// either one alone where the other met no terrain; plane A alone where frac = 0, plane B then
/// holding nothing of this region) into a horizon angle. frac is per cell along X-major lines
/// (fracs[col]) and one value per row along Y-major ones. Plane A is NaN where the sweep served
/// nothing (nodata cells: reset to NaN, never served), and the angle stays NaN there. Inlined
/// into combineTwoLines.
template <bool XMajor, bool Near>
DEMLIGHT_INLINE inline void combineTwoLinesLoop(float* __restrict planeA, const float* __restrict planeB,
                                                const double* __restrict fracs, double rowFrac,
                                                const float* __restrict near, std::size_t cols) {
    const float none = -std::numeric_limits<float>::infinity();
    for (std::size_t col = 0; col < cols; ++col) {
        const double frac = XMajor ? fracs[col] : rowFrac;
        const float a = planeA[col], b = planeB[col];
        const auto mixed = static_cast<float>(frac * a + (1.0 - frac) * b);
        const float both = a == none ? b : b != none ? mixed : a;
        float slope = frac > 0.0 ? both : a;
        if constexpr (Near) slope = near[col] > slope ? near[col] : slope;  // NaN (nodata) stays
        const auto angle = static_cast<float>(fastAtan(static_cast<double>(slope)) * kRadToDeg);
        planeA[col] = slope == none ? static_cast<float>(kNoHorizonDeg) : angle;
    }
}

/// combineTwoLinesLoop on the widest SimdPath.
template <bool XMajor, bool Near>
void combineTwoLines(float* planeA, const float* planeB, const double* fracs, double rowFrac, const float* near,
                     std::size_t cols) {
    onWidestPath([&]() DEMLIGHT_INLINE { combineTwoLinesLoop<XMajor, Near>(planeA, planeB, fracs, rowFrac, near, cols); });
}

/// combineRow's one-line case (plane A holds the tangents), on the widest SimdPath; near is null
/// without a near field.
void combineOneLine(float* planeA, const float* near, std::size_t cols) {
    onWidestPath([&]() DEMLIGHT_INLINE {
        const float none = -std::numeric_limits<float>::infinity();
        for (std::size_t i = 0; i < cols; ++i) {
            float slope = planeA[i];
            if (near) slope = near[i] > slope ? near[i] : slope;
            const float angle = static_cast<float>(fastAtan(static_cast<double>(slope)) * kRadToDeg);
            planeA[i] = slope == none ? static_cast<float>(kNoHorizonDeg) : angle;
        }
    });
}

}  // namespace

/// Turns the two planes of tangents into angles for the region's window, and sets the
/// truncation flag from the distance to the DEM edge along the region's direction. Plane A is
/// NaN at nodata cells (never served), so their angle stays NaN. Both loops are branch-free.
/// `row` and `w` are on the full grid; the planes and flags cover the terrain's cells.
void combineRow(const LineGeometry& geo, const Terrain& terrain, const FullGridRef& g, double maxDistanceM,
                double invR, std::size_t row, const CellWindow& w, const CellWindow& terrainCells, float* planeA,
                const float* planeB, std::uint8_t* truncated) {
    const std::size_t W = terrain.width();
    const std::size_t offset = (row - terrainCells.row0) * W + (w.col0 - terrainCells.col0), cols = w.col1 - w.col0;
    if (truncated) {
        // Truncated where the DEM edge along the region direction is nearer than maxDistanceM.
        const double stepM = geo.stepLengthM[row];
        std::uint8_t* flags = truncated + offset;
        if (geo.xMajor) {
            const double minor = geo.edgeStepsMinor[row];
            const double* major = geo.edgeStepsMajor.data() + w.col0;
            for (std::size_t i = 0; i < cols; ++i) flags[i] = std::min(major[i], minor) * stepM < maxDistanceM;
        } else {
            const double major = geo.edgeStepsMajor[row];
            const double* minor = geo.edgeStepsMinor.data() + w.col0;
            for (std::size_t i = 0; i < cols; ++i) flags[i] = std::min(major, minor[i]) * stepM < maxDistanceM;
        }
    }
    // Plane A stays NaN at nodata cells (never served): the runs of them at the row's ends are
    // left so, here and in the near field (a coastal DEM's sea).
    const RowSpan span = nonNanSpan(terrain.heightsM.data() + offset, cols);
    const float* near = nullptr;
    if (geo.nearSteps > 0) {
        thread_local std::vector<NearPoint> stencil;
        thread_local std::vector<float> nearSlopes;
        thread_local std::vector<std::uint8_t> bad;
        nearStencil(geo, g, row, maxDistanceM, invR, stencil);
        nearFieldRow(terrain, g, terrainCells, row, w, span, stencil, nearSlopes, bad);
        near = nearSlopes.data();
    }
    const std::size_t first = span.first, n = span.end - span.first;
    const std::size_t at = offset + first;  // (plane B is empty, null, with one line per cell)
    if (near) near += first;
    if (geo.nearestLine) {
        combineOneLine(planeA + at, near, n);
    } else if (geo.xMajor) {
        const double* fracs = geo.frac.data() + w.col0 + first;
        if (near) {
            combineTwoLines<true, true>(planeA + at, planeB + at, fracs, 0.0, near, n);
        } else {
            combineTwoLines<true, false>(planeA + at, planeB + at, fracs, 0.0, near, n);
        }
    } else if (near) {
        combineTwoLines<false, true>(planeA + at, planeB + at, nullptr, geo.frac[row], near, n);
    } else {
        combineTwoLines<false, false>(planeA + at, planeB + at, nullptr, geo.frac[row], near, n);
    }
}

}  // namespace demlight::sweep
