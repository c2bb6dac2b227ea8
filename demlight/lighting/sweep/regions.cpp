// Regions of a sweep and the automatic direction tolerance (demlight/lighting/horizon.h:
// sweepRegions, effectiveDirectionToleranceDeg).
#include "demlight/lighting/sweep/regions.h"

#include "demlight/core/angles.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace demlight {

namespace {

/// Regions are not split below this many cells per side (the direction error of a region that
/// small is bounded by the local geometry, not by the split).
constexpr std::size_t kMinRegionCells = 8;

/// Automatic direction tolerance: the swept line may drift this many cells sideways from the
/// true line at the search distance; clamped to these bounds (degrees).
constexpr double kLateralBudgetCells = 1.0;
constexpr double kMinAutoToleranceDeg = 0.01;
constexpr double kMaxAutoToleranceDeg = 0.5;

std::size_t clampRow(double row, std::size_t height) {
    if (!(row > 0.0)) return 0;
    const auto r = static_cast<std::size_t>(row + 0.5);
    return std::min(r, height - 1);
}

// Regions, scan lines, distances and edges are laid on the full grid a terrain was cut from
// (FullGridRef, in its coordinates), so a tile with its halo gets the full grid's bits.

/// Grid direction (cells per metre; +col east, +row south) of true azimuth `azimuthDeg` at a
/// point of the full grid, from the convergence and the cell sizes of the nearest row.
void localGridDirection(const FullGridRef& g, double azimuthDeg, double col, double row,
                        double& dirCol, double& dirRow) {
    const std::size_t r = clampRow(row, g.height);
    const double gridAzRad = (azimuthDeg - g.convergence.at(col, row)) * kDegToRad;
    dirCol = std::sin(gridAzRad) / g.cellWidthM[r];
    dirRow = -std::cos(gridAzRad) / g.cellHeightM[r];
}

/// The true azimuth (degrees) that a grid direction represents at a point of the full grid.
double trueAzimuthOfDirection(const FullGridRef& g, double dirCol, double dirRow, double col,
                              double row) {
    const std::size_t r = clampRow(row, g.height);
    const double east = dirCol * g.cellWidthM[r];
    const double north = -dirRow * g.cellHeightM[r];
    return std::atan2(east, north) * kRadToDeg + g.convergence.at(col, row);
}

/// a - b wrapped to (-180, 180] degrees.
double signedAzimuthDifferenceDeg(double a, double b) {
    double d = std::fmod(a - b, 360.0);
    if (d > 180.0) d -= 360.0;
    if (d <= -180.0) d += 360.0;
    return d;
}

/// The azimuth wanted at (col, row): the params' field, or the one azimuth.
struct AzimuthTarget {
    double azimuthDeg;
    const std::function<double(double, double)>& field;
    double operator()(double col, double row) const { return field ? field(col, row) : azimuthDeg; }
};

/// Splits w (see sweepRegions) and appends the regions that meet `wanted`; parts of w outside
/// it are not split further (a region's split depends on the region alone, so the regions that
/// meet `wanted` are those of splitting the whole of w).
void splitRegion(const FullGridRef& t, const AzimuthTarget& target, double toleranceDeg, const CellWindow& w,
                 const CellWindow& wanted, std::vector<SweepRegion>& out, std::size_t& examined) {
    if (w.col1 <= wanted.col0 || wanted.col1 <= w.col0 || w.row1 <= wanted.row0 || wanted.row1 <= w.row0) return;
    ++examined;
    const double c0 = static_cast<double>(w.col0), c1 = static_cast<double>(w.col1 - 1);
    const double r0 = static_cast<double>(w.row0), r1 = static_cast<double>(w.row1 - 1);
    const double cm = 0.5 * (c0 + c1), rm = 0.5 * (r0 + r1);
    SweepRegion region{w, 0.0, 0.0};
    localGridDirection(t, target(cm, rm), cm, rm, region.dirCol, region.dirRow);
    // Signed error of the region's direction at (c, r); zero at the centre by construction.
    auto err = [&](double c, double r) {
        return signedAzimuthDifferenceDeg(trueAzimuthOfDirection(t, region.dirCol, region.dirRow, c, r),
                                          target(c, r));
    };
    // Nine samples: corners, edge midpoints, centre.
    const double rows[3] = {r0, rm, r1}, cols[3] = {c0, cm, c1};
    double e[3][3];  // e[i][k] at (cols[k], rows[i])
    double worst = 0;
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) {
            e[i][k] = err(cols[k], rows[i]);
            worst = std::max(worst, std::abs(e[i][k]));
        }
    }
    const std::size_t w_ = w.col1 - w.col0, h_ = w.row1 - w.row0;
    const bool canSplitCols = w_ >= 2 * kMinRegionCells;
    const bool canSplitRows = h_ >= 2 * kMinRegionCells;
    if (worst <= toleranceDeg || (!canSplitCols && !canSplitRows)) {
        out.push_back(region);
        return;
    }
    // Halve across the axis along which the error changes most (its largest change between
    // opposite edges), so the halves' errors shrink. (Unsigned errors cannot tell: a corner's
    // error carries the other axis's change too, and a wrong pick halves the same way forever.)
    double colVariation = 0, rowVariation = 0;
    for (int i = 0; i < 3; ++i) {
        colVariation = std::max(colVariation, std::abs(e[i][2] - e[i][0]));
        rowVariation = std::max(rowVariation, std::abs(e[2][i] - e[0][i]));
    }
    const bool splitCols = canSplitCols && (!canSplitRows || colVariation > rowVariation ||
                                            (colVariation == rowVariation && w_ >= h_));
    CellWindow a = w, b = w;
    if (splitCols) {
        a.col1 = b.col0 = w.col0 + w_ / 2;
    } else {
        a.row1 = b.row0 = w.row0 + h_ / 2;
    }
    splitRegion(t, target, toleranceDeg, a, wanted, out, examined);
    splitRegion(t, target, toleranceDeg, b, wanted, out, examined);
}

/// The output window on the full grid.
CellWindow outputWindow(const Terrain& t, const HorizonParams& p) {
    const CellWindow w = p.window ? *p.window : CellWindow{0, 0, t.width(), t.height()};
    const FullGridRef g = fullGrid(t);
    return {w.col0 + g.col0, w.row0 + g.row0, w.col1 + g.col0, w.row1 + g.row0};
}

}  // namespace

namespace sweep {

std::vector<SweepRegion> fullGridRegions(const Terrain& terrain, const HorizonParams& params) {
    validateHorizonParams(terrain, params);
    return sweepRegionsOnFullGrid(terrain, params, outputWindow(terrain, params));
}

}  // namespace sweep

std::vector<SweepRegion> sweepRegionsOnFullGrid(const Terrain& terrain, const HorizonParams& params,
                                                const CellWindow& out, std::size_t* examined) {
    const FullGridRef g = fullGrid(terrain);
    std::vector<SweepRegion> all;
    std::size_t count = 0;
    splitRegion(g, AzimuthTarget{wrapAzimuthDeg(params.azimuthDeg), params.azimuthAtDeg},
                effectiveDirectionToleranceDeg(terrain, params), CellWindow{0, 0, g.width, g.height}, out, all, count);
    if (examined) *examined = count;
    std::vector<SweepRegion> clipped;
    for (SweepRegion r : all) {
        r.window = {std::max(r.window.col0, out.col0), std::max(r.window.row0, out.row0),
                    std::min(r.window.col1, out.col1), std::min(r.window.row1, out.row1)};
        if (r.window.col0 < r.window.col1 && r.window.row0 < r.window.row1) clipped.push_back(r);
    }
    return clipped;
}

double effectiveDirectionToleranceDeg(const Terrain& terrain, const HorizonParams& params) {
    if (params.directionToleranceDeg > 0.0) return params.directionToleranceDeg;
    const FullGridRef g = fullGrid(terrain);
    double minCellM = std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < g.height; ++r) minCellM = std::min({minCellM, g.cellWidthM[r], g.cellHeightM[r]});
    const double reachM = std::min(params.maxDistanceM, diagonalM(g));
    const double deg = std::atan(kLateralBudgetCells * minCellM / reachM) * kRadToDeg;
    return std::max(std::clamp(deg, kMinAutoToleranceDeg, kMaxAutoToleranceDeg), params.directionToleranceFloorDeg);
}

std::vector<SweepRegion> sweepRegions(const Terrain& terrain, const HorizonParams& params) {
    std::vector<SweepRegion> regions = sweep::fullGridRegions(terrain, params);
    const FullGridRef g = fullGrid(terrain);
    for (SweepRegion& r : regions)
        r.window = {r.window.col0 - g.col0, r.window.row0 - g.row0, r.window.col1 - g.col0, r.window.row1 - g.row0};
    return regions;
}

}  // namespace demlight
