// makeGeometry (demlight/lighting/sweep/line_geometry.h).
#include "demlight/lighting/sweep/line_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demlight::sweep {

LineGeometry makeGeometry(const FullGridRef& g, const CellWindow& terrainCells, const SweepRegion& region,
                          double maxDistanceM, bool nearestLine, int nearFieldSteps, bool farFieldCrossings) {
    LineGeometry geo;
    geo.nearestLine = nearestLine;
    geo.xMajor = std::abs(region.dirCol) >= std::abs(region.dirRow);
    const double major = geo.xMajor ? region.dirCol : region.dirRow;
    const double minor = geo.xMajor ? region.dirRow : region.dirCol;
    geo.farSign = major >= 0 ? 1 : -1;
    geo.slope = snapSlope(minor / major);
    // Along a grid axis each cell's scan line is its own ray through the cell centres: the line's
    // hull holds the near field's points on centres, and cells are served as the walk reaches
    // them, without delay. The stencil keeps only the points between centres (nearStencil): the
    // bilinear surface is linear there, but the curvature drop favours the nearest point of a
    // level stretch, and next to a void the reference's rule reweights the taps.
    geo.nearSteps = nearFieldSteps;
    geo.delay = geo.slope == 0.0 ? 0 : nearFieldSteps;
    geo.crossings = geo.delay > 0 && farFieldCrossings;
    geo.majorSize = geo.xMajor ? g.width : g.height;
    geo.minorSize = geo.xMajor ? g.height : g.width;
    const CellWindow& w = region.window;
    geo.majorWin0 = geo.xMajor ? w.col0 : w.row0;
    geo.majorWin1 = geo.xMajor ? w.col1 : w.row1;
    geo.minorWin0 = geo.xMajor ? w.row0 : w.col0;
    geo.minorWin1 = geo.xMajor ? w.row1 : w.col1;
    const CellWindow& tc = terrainCells;
    geo.majorLo = static_cast<long>(geo.xMajor ? tc.col0 : tc.row0);
    geo.majorHi = static_cast<long>(geo.xMajor ? tc.col1 : tc.row1);
    geo.minorLo = static_cast<long>(geo.xMajor ? tc.row0 : tc.col0);
    geo.minorHi = static_cast<long>(geo.xMajor ? tc.row1 : tc.col1);

    geo.stepLengthM.resize(g.height);
    double minStep = std::numeric_limits<double>::infinity(), maxStep = 0;
    bool equalSteps = true;
    for (std::size_t r = 0; r < g.height; ++r) {
        const double dc = geo.xMajor ? 1.0 : geo.slope;
        const double dr = geo.xMajor ? geo.slope : 1.0;
        geo.stepLengthM[r] = std::hypot(dc * g.cellWidthM[r], dr * g.cellHeightM[r]);
        minStep = std::min(minStep, geo.stepLengthM[r]);
        maxStep = std::max(maxStep, geo.stepLengthM[r]);
        equalSteps = equalSteps && geo.stepLengthM[r] == geo.stepLengthM[0];
    }

    // Far end: the terrain's edge, or far enough beyond the window to cover maxDistanceM.
    const long M = static_cast<long>(geo.majorSize);
    // Two points of a line are at most M - 1 steps apart, and at most (N - 1) / |slope|: off the
    // axes a line crosses the grid's minor extent in fewer steps than its major one (37 deg on a
    // 327 x 468 grid: 436 of 468). Each step is at most maxStep long (rows beyond the grid count
    // with its outer rows' steps); one step more of margin against rounding. Of the full grid, so
    // that a tile and the whole DEM take the same path.
    const double minorSteps = geo.slope == 0.0 ? static_cast<double>(M)
                                               : static_cast<double>(geo.minorSize) / std::abs(geo.slope);
    geo.spanBoundM = (std::min(static_cast<double>(M), minorSteps) + 1.0) * maxStep;
    long extension = M;
    if (std::isfinite(maxDistanceM)) {
        // In double first: a huge finite distance would overflow the conversion to long.
        extension = static_cast<long>(std::min(static_cast<double>(M), std::ceil(maxDistanceM / minStep) + 1));
    }
    geo.extensionSteps = extension;
    if (geo.farSign > 0) {
        geo.mNear = static_cast<long>(geo.majorWin0);
        geo.mFar = std::min(geo.majorHi - 1, static_cast<long>(geo.majorWin1) - 1 + extension);
        geo.mEdge = M - 1;
    } else {
        geo.mNear = static_cast<long>(geo.majorWin1) - 1;
        geo.mFar = std::max(geo.majorLo, static_cast<long>(geo.majorWin0) - extension);
        geo.mEdge = 0;
    }

    geo.base.resize(geo.majorSize);
    geo.frac.resize(geo.majorSize);
    for (std::size_t m = 0; m < geo.majorSize; ++m) lineOffset(geo.slope, static_cast<long>(m), geo.base[m], geo.frac[m]);

    // Distances from the far edge, summed in walking order (each sample's σ is the sum of the
    // steps walked before it).
    if (geo.xMajor && !equalSteps) {
        geo.rowArc.assign(g.height + 1, 0.0);
        for (std::size_t r = 0; r < g.height; ++r) geo.rowArc[r + 1] = geo.rowArc[r] + geo.stepLengthM[r];
        geo.invAbsSlope = geo.slope != 0.0 ? 1.0 / std::abs(geo.slope) : 0.0;
    } else {
        geo.sigmaAt.assign(geo.majorSize, 0.0);
        const long near = -geo.farSign;
        for (long m = geo.mEdge + near; m >= 0 && m < M; m += near) {
            const auto prev = static_cast<std::size_t>(m - near);
            geo.sigmaAt[static_cast<std::size_t>(m)] =
                geo.sigmaAt[prev] + geo.stepLengthM[geo.xMajor ? 0 : prev];
        }
    }

    const double majorD = static_cast<double>(geo.majorSize), minorD = static_cast<double>(geo.minorSize);
    const double minorPerFarStep = geo.slope * geo.farSign;
    geo.edgeStepsMajor.resize(geo.majorSize);
    for (std::size_t m = 0; m < geo.majorSize; ++m) {
        const double md = static_cast<double>(m);
        geo.edgeStepsMajor[m] = geo.farSign > 0 ? majorD - 0.5 - md : md + 0.5;
    }
    geo.edgeStepsMinor.resize(geo.minorSize);
    for (std::size_t j = 0; j < geo.minorSize; ++j) {
        const double jd = static_cast<double>(j);
        geo.edgeStepsMinor[j] = minorPerFarStep > 0   ? (minorD - 0.5 - jd) / minorPerFarStep
                                : minorPerFarStep < 0 ? (jd + 0.5) / -minorPerFarStep
                                                      : std::numeric_limits<double>::infinity();
    }

    // Lines serving window cells: k = j - base or j - base - 1 at the window's major ends.
    long baseA, baseB;
    double fracUnused;
    lineOffset(geo.slope, static_cast<long>(geo.majorWin0), baseA, fracUnused);
    lineOffset(geo.slope, static_cast<long>(geo.majorWin1) - 1, baseB, fracUnused);
    geo.kFirst = static_cast<long>(geo.minorWin0) - std::max(baseA, baseB) - 1;
    geo.kLast = static_cast<long>(geo.minorWin1) - 1 - std::min(baseA, baseB);
    return geo;
}

}  // namespace demlight::sweep
