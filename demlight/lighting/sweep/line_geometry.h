// Line geometry of a sweep region: which scan lines, their shear (slope) and offsets, the metric
// length of a step per row, distances from the full grid's far edge, and where lines leave the
// grid. Everything on the full grid, so a tile and its DEM share the bits.
#pragma once

#include "demlight/lighting/horizon.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace demlight::sweep {

/// How a region's lines map onto the full grid. Major index m steps one cell per line sample; a
/// line k sits at minor coordinate k + slope*m. farSign = +1 when the far end (toward the
/// azimuth) has the larger major index. Indices are the full grid's; the terrain's heights and
/// outputs cover [majorLo, majorHi) x [minorLo, minorHi) of it.
struct LineGeometry {
    bool xMajor;
    bool nearestLine;  // HorizonParams::nearestLine: one line serves each cell, into plane A
    long nearSteps = 0;  // HorizonParams::nearFieldSteps
    long delay = 0;    // cells are served this many steps behind the walk: nearSteps, 0 along a grid axis
    bool crossings = false;  // HorizonParams::farFieldCrossings (with delay > 0)
    int farSign;
    double slope;
    std::size_t majorSize, minorSize;
    long mFar, mNear;  // inclusive major range a region's lines may walk, far end first
    long extensionSteps;  // steps walked beyond the farthest served cell (covers maxDistanceM)
    long kFirst, kLast;
    std::size_t majorWin0, majorWin1, minorWin0, minorWin1;
    long majorLo, majorHi, minorLo, minorHi;
    long mEdge;  // the full grid's far edge: every line's distances count from there
    /// No two points of a line are this far apart (metres): a range limit at least this long
    /// removes nothing, and the sweep runs without the range limit's bookkeeping.
    double spanBoundM = 0;
    std::vector<double> stepLengthM;  // metric length of one line step, per grid row
    /// Distance of a line sample from the far edge (metres) per major index, when it is the same
    /// for every line (Y-major lines, or equal steps in every row); empty otherwise, and each
    /// line sums its own steps from the edge. Either way a sample's distance has the same bits
    /// wherever a walk starts, so tiles and the full grid build the same hulls.
    std::vector<double> sigmaAt;
    /// Without sigmaAt (X-major lines across rows of different step lengths: geographic grids):
    /// arc length along a line per unit of minor coordinate y is stepLengthM[row of y] / |slope|,
    /// so a sample's distance from the far edge is |A(y) - A(y_edge)| / |slope|, with A the
    /// integral of the step lengths over rows (rowArc[r]: up to row r's upper boundary, r - 0.5).
    /// A function of the sample's position alone, with no sum along the walk.
    std::vector<double> rowArc;
    double invAbsSlope = 0;
    std::vector<long> base;           // lineOffset() per major index
    std::vector<double> frac;
    /// Steps toward the far end before the line leaves the DEM (cell edges at -0.5 and
    /// size - 0.5) through the major / minor ends, per major / minor index.
    std::vector<double> edgeStepsMajor, edgeStepsMinor;
};

/// minor = base + frac for the line k = 0 at major index m. Shared by the sweep and the combine
/// pass (through LineGeometry::base/frac) so both see the same bits.
inline void lineOffset(double slope, long m, long& base, double& frac) {
    const double fm = slope * static_cast<double>(m);
    const double fl = std::floor(fm);
    base = static_cast<long>(fl);
    frac = fm - fl;
    if (frac >= 1.0) {  // fm a hair below an integer
        frac = 0.0;
        ++base;
    }
}

/// Grid-aligned and diagonal directions computed through sin/cos are off by ~1e-17; snap them
/// so their lines run exactly through cell centres.
constexpr double kSlopeSnap = 1e-12;
inline double snapSlope(double slope) {
    if (std::abs(slope) < kSlopeSnap) return 0.0;
    if (std::abs(std::abs(slope) - 1.0) < kSlopeSnap) return slope > 0 ? 1.0 : -1.0;
    return slope;
}

/// Height at which a line's hull is queried for a cell it serves (frac > 0: the line passes
/// between the cell and a neighbour). The line's own sample at the cell's major index, plus the
/// part of the cell's height that interpolating the two bracketing lines' samples would lose:
/// r = frac (1 - frac) (2 h_j - h_{j-1} - h_{j+1}). On a plane r = 0 and the query is exact; on a
/// ridge r > 0 keeps the cell from inheriting its lower neighbours' horizon. (Querying with the
/// cell's own height instead is wrong on slopes: the line lies off the cell by up to a cell, and
/// the cross-line height offset divided by a near distance gives a large error.)
/// [nLo, nHi) is the minor range the terrain holds: at its edges (the full grid's, or a tile's,
/// whose edge cells are halo) a neighbour is missing and the line's sample is used.
template <class Index>
inline double observerHeight(const float* H, const Index& index, long m, long j, long nLo, long nHi, double frac,
                             float cellHeight, float lineSample) {
    if (frac == 0.0) return cellHeight;  // the line runs through the cell centre
    if (std::isnan(lineSample)) return cellHeight;
    if (j <= nLo || j + 1 >= nHi) return lineSample;
    const float hm = H[index(m, j - 1)], hp = H[index(m, j + 1)];
    if (std::isnan(hm) || std::isnan(hp)) return lineSample;
    return lineSample + frac * (1.0 - frac) * (2.0 * cellHeight - hm - hp);
}

/// A(y) of LineGeometry::rowArc at minor coordinate y (rows clamped beyond the grid).
inline double arcAt(const LineGeometry& geo, double y) {
    const std::size_t rows = geo.stepLengthM.size();
    if (!(y >= -0.5)) return (y + 0.5) * geo.stepLengthM.front();
    const auto r = static_cast<std::size_t>(y + 0.5);
    if (r >= rows) return geo.rowArc[rows] + (y - (static_cast<double>(rows) - 0.5)) * geo.stepLengthM.back();
    return geo.rowArc[r] + (y - (static_cast<double>(r) - 0.5)) * geo.stepLengthM[r];
}

/// Distance (metres) from the far edge of the sample of a line at minor coordinate y and major
/// index m, the line's arc coordinate at the edge being edgeArc (LineGeometry::rowArc).
inline double lineDistance(const LineGeometry& geo, double edgeArc, double y, long m) {
    if (geo.invAbsSlope == 0.0) {  // along a row: that row's steps
        const std::size_t rows = geo.stepLengthM.size();
        const auto r = static_cast<std::size_t>(std::clamp(y + 0.5, 0.0, static_cast<double>(rows - 1)));
        return static_cast<double>(std::abs(m - geo.mEdge)) * geo.stepLengthM[r];
    }
    return std::abs(arcAt(geo, y) - edgeArc) * geo.invAbsSlope;
}

/// The geometry of `region`'s lines over a terrain holding `terrainCells` of the full grid.
LineGeometry makeGeometry(const FullGridRef& g, const CellWindow& terrainCells, const SweepRegion& region,
                          double maxDistanceM, bool nearestLine, int nearFieldSteps, bool farFieldCrossings);

}  // namespace demlight::sweep
