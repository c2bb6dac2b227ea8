// Horizon sweep: upper convex hulls along lines parallel to the azimuth (Dozier 1981; Timonen &
// Westerholm 2010), with the curvature trick of docs/design.md §4. See demlight/lighting/horizon.h.
#include "demlight/lighting/horizon.h"

#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/fast_math.h"
#include "demlight/core/parallel.h"
#include "demlight/core/simd.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <numbers>
#include <string>
#include <type_traits>

#include "demlight/core/avx512.h"

namespace demlight {

namespace {

/// Lines processed in lock-step by one task: adjacent lines touch adjacent cells at each step,
/// so a block reads and writes a few cache lines per step whatever the direction.
constexpr std::size_t kLinesPerBlock = 16;

/// How many line steps ahead a block prefetches its heights and output cells (sweepBlock): a
/// step of a block costs about one memory latency
/// (docs/measurements.md#lightinghorizon_sweepcpp-kprefetchsteps).
constexpr long kPrefetchSteps = 4;
constexpr long kFloatsPerCacheLine = 16;

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

std::vector<SweepRegion> fullGridRegions(const Terrain& terrain, const HorizonParams& params) {
    validateHorizonParams(terrain, params);
    return sweepRegionsOnFullGrid(terrain, params, outputWindow(terrain, params));
}

}  // namespace

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

namespace {

/// One upper-hull vertex: distance from the line's far end (metres) and g = h - σ²/(2 R_eff).
struct HullPoint {
    double sigmaM;
    double g;
};

/// Range-limited sweeps only: what the second pass (limitRangePass) needs of one line.
struct RangeLog {
    /// A valid line sample, far to near, with the chunk (floor(σ / maxDistanceM)) it fell in.
    struct Point {
        double sigmaM;
        double g;
        long chunk;
    };
    /// A served cell in chunk >= 1, whose first-pass value saw only its own chunk.
    struct Query {
        double sigmaM;
        double gCell;
        long chunk;
        std::size_t pointsBefore;  // points.size() when the cell was served: the farther points
        float* cell;
        /// Delayed serving: the cell's chunk is one past the walk's (it lies within nearFieldSteps
        /// after a chunk boundary), so the farther points it may see end before the chunk's
        /// nearest ones; resolved one by one (limitRangePass).
        bool straddles;
    };
    /// points[0, nPoints) and queries[0, nQueries) are in use; sized once per block (at most
    /// two points and two queries per line step) so the walk appends without capacity checks.
    std::vector<Point> points;
    std::vector<Query> queries;
    std::size_t nPoints = 0, nQueries = 0;
    void reset(std::size_t capacity) {
        if (points.size() < capacity) points.resize(capacity);
        if (queries.size() < 2 * capacity) queries.resize(2 * capacity);
        nPoints = nQueries = 0;
    }
};

/// Per-line state of the far-to-near walk: the hull is buf[lo, hi) with the farthest point at lo.
struct LineState {
    HullPoint* buf;
    std::size_t lo;
    std::size_t hi;
    double edgeArcM;  // arcAt() of the line at the far edge; unused with LineGeometry::sigmaAt
    long chunk;
    double nextChunkM;  // σ at which the chunk changes
    RangeLog* log;      // range-limited sweeps only
    /// Range-limited sweeps: the previous chunk's final hull is kept at buf[prevLo, prevHi) (the
    /// current one starts after it), and the vertex its last tangent touched.
    std::size_t prevLo, prevHi, prevHint;
    /// Delayed serving (nearFieldSteps > 0): the current hull's vertex the line's last tangent touched.
    std::size_t hint;
    /// Range-limited sweeps: the highest g pushed in the current chunk and in the previous one
    /// (-inf when empty), for prevChunkCannotRaise.
    double maxG, prevMaxG;
};

/// Range-limited sweeps: true when no point of the previous chunk's hull can give a cell at
/// (sigmaQ, gQ) a slope above `value` (the current chunk's answer), so that its tangent need not
/// be searched. The bound is rangeSlope() to the highest g of that chunk at the distance that
/// makes it steepest: its nearest point (the chunk's last, always a vertex) when that g is above
/// the cell, else its farthest (its first, never popped). rangeSlope() rises with g and falls
/// with the distance, operation by operation, so it bounds every vertex's; the comparison is
/// strict because this copy of the expression may be contracted differently by the compiler.
inline bool prevChunkCannotRaise(const LineState& line, double sigmaQ, double gQ, double invR, float value) {
    const double rise = line.prevMaxG - gQ;
    const double sigmaP = rise >= 0.0 ? line.buf[line.prevHi - 1].sigmaM : line.buf[line.prevLo].sigmaM;
    return static_cast<float>(rise / (sigmaQ - sigmaP) - sigmaQ * invR) < value;
}

/// A line's walk reaches sigma (metres from the far edge) in a later chunk of maxDistanceM: the
/// hull so far becomes the previous chunk's when the chunks are consecutive, else both empty.
inline void enterChunk(LineState& line, double sigma, double maxDistanceM) {
    const long chunk = static_cast<long>(std::floor(sigma / maxDistanceM));
    if (chunk == line.chunk + 1) {
        line.prevLo = line.lo;
        line.prevHi = line.hi;
        line.prevHint = line.hi > 0 ? line.hi - 1 : 0;
        line.lo = line.hi;
        line.prevMaxG = line.maxG;
    } else {
        line.prevLo = line.prevHi = line.lo = line.hi = 0;
        line.prevMaxG = -std::numeric_limits<double>::infinity();
    }
    line.maxG = -std::numeric_limits<double>::infinity();
    line.chunk = chunk;
    line.nextChunkM = static_cast<double>(line.chunk + 1) * maxDistanceM;
}

/// One past the hull's new top when the point (sigma, g), nearer than every vertex, is pushed:
/// vertex v1 is popped while the slope to v2 (farther) is at least the slope to v1. The vertex
/// below it is the point's tangent vertex.
/// The first two tests are made without branches: a push pops one vertex about two times in
/// three and none or two nearly all the other times, so a loop's exit branch would be
/// mispredicted on about a third of the pushes (measured on Mount St. Helens and the dune edge);
/// the loop runs only from a third pop on. The tests and their order are the loop's, so is the result.
/// Always inlined: it runs once per line and step, and GCC stopped inlining it into the
/// range-limited walk once that sweep also served eight lines at once (the horizon job then took
/// 1.009x the time of this inlined one, 8 pairs: at the noise).
[[gnu::always_inline]] inline std::size_t hullTopAfterPops(const LineState& line, double sigma, double g) {
    const std::size_t lo = line.lo, hi = line.hi;
    const HullPoint* const buf = line.buf;
    // Pop v1 unless the slope to v2 (farther) is below the slope to v1.
    const auto pops = [&](const HullPoint& v1, const HullPoint& v2) {
        return !((v2.g - g) * (sigma - v1.sigmaM) < (v1.g - g) * (sigma - v2.sigmaM));
    };
    if (hi - lo < 2) return hi;
    // The second test reads a vertex that exists only when three do; otherwise it reads the
    // first one again and its answer is masked.
    const bool first = pops(buf[hi - 1], buf[hi - 2]);
    const bool three = hi - lo >= 3;
    const bool second = pops(buf[hi - 2], buf[three ? hi - 3 : hi - 2]) & three;
    std::size_t top = hi - static_cast<std::size_t>(first) - static_cast<std::size_t>(first & second);
    if (first & second) {
        while (top - lo >= 2 && pops(buf[top - 1], buf[top - 2])) --top;
    }
    return top;
}

/// The curved-earth tangent (slope of the sight line) from a cell at (sigmaQ, gQ) to a line
/// point (sigmaP, gP), as both passes evaluate it. Not inlined, so that both get the same bits
/// whatever the compiler contracts at each call: a tile's first pass may find a point its
/// DEM's walk leaves to the exact pass (its previous chunk started later), and the two must agree.
[[gnu::noinline]] float rangeSlope(double gP, double sigmaP, double gQ, double sigmaQ, double invR) {
    return static_cast<float>((gP - gQ) / (sigmaQ - sigmaP) - sigmaQ * invR);
}



/// slope(a) > slope(b) from a cell at (sigmaQ, gQ) nearer than both points, by cross
/// multiplication (both distances are positive): no division.
inline bool steeperFrom(const HullPoint& a, const HullPoint& b, double sigmaQ, double gQ) {
    return (a.g - gQ) * (sigmaQ - b.sigmaM) > (b.g - gQ) * (sigmaQ - a.sigmaM);
}

/// Largest g-space slope from (sigmaQ, gQ) to the hull, walking from vertex i (the slope from a
/// point nearer than every vertex is unimodal along an upper hull). Slopes are compared by cross
/// multiplication (all distances are positive), so only the answer costs a division.
inline std::size_t tangentVertex(const HullPoint* h, std::size_t lo, std::size_t hi, std::size_t i, double sigmaQ,
                                 double gQ) {
    auto steeper = [&](std::size_t a, std::size_t b) { return steeperFrom(h[a], h[b], sigmaQ, gQ); };
    bool moved = false;
    while (i > lo && steeper(i - 1, i)) {
        --i;
        moved = true;
    }
    if (!moved) {
        while (i + 1 < hi && !steeper(i, i + 1)) ++i;
    }
    return i;
}

inline double tangentSlope(const LineState& line, std::size_t i, double sigmaQ, double gQ) {
    const HullPoint* h = line.buf;
    i = tangentVertex(h, line.lo, line.hi, i, sigmaQ, gQ);
    return (h[i].g - gQ) / (sigmaQ - h[i].sigmaM);
}


/// Second pass of a range-limited line (maxDistanceM = L). The first pass reset its hull whenever
/// floor(σ/L) changed, so each cell saw exactly the points of its own chunk farther than itself,
/// all within L. The points within L that it missed lie in the previous (farther) chunk with
/// σ ≥ σ_cell - L. Walking the cells of a chunk from near to far, that set grows at its far end,
/// so an upper hull built by adding points in order of distance answers every cell (binary search
/// for the tangent); the result is max-ed into the planes. Exact: O(n log n) per line. A cell is
/// skipped when no point of the hull could beat its first-pass value (highest g over the nearest
/// distance), which is most cells.
void limitRangePass(const RangeLog& log, double maxDistanceM, double invR, std::vector<HullPoint>& hull) {
    const auto& pts = log.points;
    if (log.nQueries == 0) return;
    if (hull.size() < log.nPoints) hull.resize(log.nPoints);
    long chunk = std::numeric_limits<long>::min();
    std::size_t next = 0;  // candidate points are pts[0, next), the farthest first
    std::size_t top = 0;   // hull = hull[0, top), nearest first
    double maxG = -std::numeric_limits<double>::infinity();
    for (std::size_t qi = log.nQueries; qi-- > 0;) {
        const RangeLog::Query* q = &log.queries[qi];
        if (q->straddles) {
            // Its points are the walk's chunk's from q->sigmaM - L up to pointsBefore; a nearer
            // cell of its chunk may have put nearer ones into the hull, so scan them directly
            // (at most nearFieldSteps cells per line and chunk get here).
            float& cell = *q->cell;
            const double limit = q->sigmaM - maxDistanceM;
            for (std::size_t i = q->pointsBefore; i-- > 0 && pts[i].sigmaM >= limit;)
                cell = std::max(cell, rangeSlope(pts[i].g, pts[i].sigmaM, q->gCell, q->sigmaM, invR));
            continue;
        }
        if (q->chunk != chunk) {
            chunk = q->chunk;
            top = 0;
            maxG = -std::numeric_limits<double>::infinity();
            next = q->pointsBefore;
            while (next > 0 && pts[next - 1].chunk >= chunk) --next;
        }
        // Grow the hull with previous-chunk points within range of this cell.
        const double limit = q->sigmaM - maxDistanceM;
        while (next > 0 && pts[next - 1].sigmaM >= limit && pts[next - 1].chunk == chunk - 1) {
            const RangeLog::Point& pt = pts[--next];
            const HullPoint p{pt.sigmaM, pt.g};
            maxG = std::max(maxG, p.g);
            // Points arrive farther each time (x = -σ increasing): keep right turns only.
            while (top >= 2) {
                const HullPoint& o = hull[top - 2];
                const HullPoint& a = hull[top - 1];
                const double cross = (o.sigmaM - a.sigmaM) * (p.g - o.g) - (a.g - o.g) * (o.sigmaM - p.sigmaM);
                if (cross < 0.0) break;
                --top;
            }
            hull[top++] = p;
        }
        if (top == 0) continue;
        // Upper bound of the slope to any hull point: the highest g at the distance that makes
        // it steepest (the nearest point if above the cell, else the farthest).
        const double rise = maxG - q->gCell;
        const double boundDistM = q->sigmaM - (rise >= 0.0 ? hull[0].sigmaM : hull[top - 1].sigmaM);
        float& cell = *q->cell;
        if (static_cast<float>(rise / boundDistM - q->sigmaM * invR) <= cell) continue;
        // Slopes compared without divisions: two a step made the search a chain of divisions
        // (docs/performance.md, "The range pass without divisions").
        std::size_t lo = 0, hi = top - 1;
        while (lo < hi) {
            const std::size_t mid = (lo + hi) / 2;
            if (steeperFrom(hull[mid + 1], hull[mid], q->sigmaM, q->gCell)) lo = mid + 1; else hi = mid;
        }
        cell = std::max(cell, rangeSlope(hull[lo].g, hull[lo].sigmaM, q->gCell, q->sigmaM, invR));
    }
}

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
double snapSlope(double slope) {
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

/// A word with its n lowest bits set (all 64 for n >= 64).
std::uint64_t lowBits(std::size_t n) { return n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1; }

/// Bit j % 64 of out[m] for the cells m of a row (X-major lines: minor index j is the row).
void setRowBits(std::uint64_t* __restrict out, const float* __restrict row, std::size_t width, unsigned bit) {
    for (std::size_t m = 0; m < width; ++m) out[m] |= static_cast<std::uint64_t>(row[m] == row[m]) << bit;
}

/// Bits 0..n-1 for cells 0..n-1 of a run along a row (Y-major lines: minor index j is the column).
std::uint64_t rowRunBits(const float* __restrict row, std::size_t n) {
    std::uint64_t w = 0;
    for (std::size_t j = 0; j < n; ++j) w |= static_cast<std::uint64_t>(row[j] == row[j]) << j;
    return w;
}

/// Which of a terrain's cells hold a height, one bit each, laid out along one scan orientation:
/// the cells a block of lines meets at one step (one major index, consecutive minor indices) are
/// one or two words, where the heights are a cell a row apart (X-major lines: a column). Half
/// of a coastal tile is sea: its steps are told by this test, without reading their heights.
/// Bit (m, j) is at words[(j / 64) * majorSize + m] (a step's words next to the next step's);
/// no words where few cells are nodata (kBitmapVoidShare). Indices are the terrain's (major -
/// majorLo, minor - minorLo).
class ValidCells {
public:
    /// The bitmap of `bits`, built first unless it is this terrain's heights grid's.
    ValidCells(const Terrain& t, bool xMajor, int threads, SweepBuffers::ValidBits& bits)
        : majorSize_(xMajor ? t.width() : t.height()) {
        if (bits.heights != t.heightsM.data() || bits.width != t.width() || bits.height != t.height()) {
            build(t, xMajor, threads, bits.words);
            bits.heights = t.heightsM.data();
            bits.width = t.width();
            bits.height = t.height();
        }
        words_ = bits.words.empty() ? nullptr : bits.words.data();
    }
    /// Whether the bitmap is kept: see kBitmapVoidShare.
    bool used() const { return words_ != nullptr; }
    /// Whether any of cells j0..j1 (inclusive, 0 <= j0 <= j1) at major index m holds a height;
    /// only when used().
    bool any(long m, long j0, long j1) const {
        const auto at = [&](long j) {
            return words_[static_cast<std::size_t>(j) / 64 * majorSize_ + static_cast<std::size_t>(m)];
        };
        const long w0 = j0 / 64, w1 = j1 / 64;
        if (w0 == w1) return (at(j0) >> (j0 % 64)) & lowBits(static_cast<std::size_t>(j1 - j0 + 1));
        if (at(j0) >> (j0 % 64)) return true;
        for (long w = w0 + 1; w < w1; ++w)
            if (at(w * 64)) return true;
        return at(j1) & lowBits(static_cast<std::size_t>(j1 % 64 + 1));
    }

private:
    /// The bitmap is kept where at least this share of the cells is nodata: where voids are few
    /// and scattered, few steps of a block meet only nodata, and its extra tests (serving,
    /// prefetching) cost more than they skip (measured: docs/performance.md, "Sea and other
    /// large voids skipped"). Below it the sweep reads a step's heights until it finds one.
    static constexpr double kBitmapVoidShare = 0.1;

    void build(const Terrain& t, bool xMajor, int threads, std::vector<std::uint64_t>& words) const {
        const std::size_t W = t.width(), H = t.height();
        const std::size_t minorSize = xMajor ? H : W, groups = (minorSize + 63) / 64;
        words.assign(groups * majorSize_, 0);
        std::atomic<std::size_t> validCells{0};
        parallelFor(0, groups, threads, [&](std::size_t g) {
            std::uint64_t* out = words.data() + g * majorSize_;
            const std::size_t j0 = g * 64, n = std::min<std::size_t>(64, minorSize - j0);
            if (xMajor) {
                for (std::size_t j = j0; j < j0 + n; ++j) setRowBits(out, t.heightsM.rowPtr(j), W, static_cast<unsigned>(j % 64));
            } else {
                for (std::size_t m = 0; m < H; ++m) out[m] = rowRunBits(t.heightsM.rowPtr(m) + j0, n);
            }
            std::size_t count = 0;
            for (std::size_t m = 0; m < majorSize_; ++m) count += static_cast<std::size_t>(std::popcount(out[m]));
            validCells += count;
        });
        const double voids = static_cast<double>(W * H - validCells.load());
        if (voids < kBitmapVoidShare * static_cast<double>(W * H)) words.clear();
    }

    std::size_t majorSize_;
    const std::uint64_t* words_ = nullptr;
};


#ifdef DEMLIGHT_HAS_AVX512_KERNELS
#define DEMLIGHT_SWEEP_AVX512 1
/// Eight lines' delayed serving at once (sweepBlock's serveDelayed), one line per AVX-512 lane,
/// where simdPath() is SimdPath::Avx512 (functions marked DEMLIGHT_AVX512, called from the
/// portable sweepBlock with plain arrays).
/// Each lane makes the scalar loop's comparisons and arithmetic in the same order, written as the
/// same expressions on vectors (so the compiler contracts them alike), and the same
/// hull walk from the line's hint: the same bits. The branches of the scalar tangent search
/// become masks, and its divisions one vector division per served plane.
/// __m512d and __m512i are the compilers' vector types: + - * / act per lane.
constexpr std::size_t kSimdLines = 8;

DEMLIGHT_AVX512 inline __mmask8 steeperLanes(__m512d ga, __m512d sa, __m512d gb, __m512d sb, __m512d gQ, __m512d sQ) {
    // slope(a) > slope(b), as steeperFrom()
    const __m512d lhs = (ga - gQ) * (sQ - sb);
    const __m512d rhs = (gb - gQ) * (sQ - sa);
    return _mm512_cmp_pd_mask(lhs, rhs, _CMP_GT_OQ);
}

/// What serveEightLines and walkEightLines need of a block: its line states and hull buffers, its
/// first lane's line, and the step.
struct EightLines {
    LineState* lines;  // the block's lines[b0, b0 + 8)
    HullPoint* hulls;  // the block's scratch: line b's hull starts at b * lineCapacity
    std::size_t lineCapacity;
    std::size_t b0;
    const LineGeometry* geo;
    long m, n0;   // the step's major index, and lane 0's minor index at it
    double frac;  // the lines' minor offset from n0 at step m
};

/// The distances from the far edge (metres) of lines b0..b0+7 at major index m, the first at
/// minor coordinate n0 + frac and each next one a cell further, every one inside the full grid's
/// rows: with a distance table the step's, a broadcast (eight stores and a vector load of them
/// cost 2-3 % of the sweep at 37 deg on Mount St. Helens and both surface models: the load waits
/// for the stores); otherwise lineDistance()'s expressions on vectors, arcAt's clamps never
/// applying (lines across rows, invAbsSlope > 0).
DEMLIGHT_AVX512 inline __m512d laneDistances(const LineGeometry& geo, const LineState* lines, std::size_t b0, long m,
                                              long n0, double frac) {
    if (!geo.sigmaAt.empty()) return _mm512_set1_pd(geo.sigmaAt[static_cast<std::size_t>(m)]);
    alignas(64) double arcs[kSimdLines];
    for (std::size_t l = 0; l < kSimdLines; ++l) arcs[l] = lines[b0 + l].edgeArcM;
    const __m512d edgeArc = _mm512_load_pd(arcs);
    // n0 + lane + frac, as static_cast<double>(n0 + lane) + frac.
    const __m512d y = _mm512_set1_pd(static_cast<double>(n0)) + _mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7) +
                      _mm512_set1_pd(frac);
    const __m512i r = _mm512_cvttpd_epi64(y + _mm512_set1_pd(0.5));
    const __m512d rowArc = _mm512_i64gather_pd(r, geo.rowArc.data(), 8);
    const __m512d step = _mm512_i64gather_pd(r, geo.stepLengthM.data(), 8);
    const __m512d arc = rowArc + (y - (_mm512_cvtepi64_pd(r) - _mm512_set1_pd(0.5))) * step;
    return _mm512_abs_pd(arc - edgeArc) * _mm512_set1_pd(geo.invAbsSlope);
}

/// laneDistances into out[0, 8), for the portable sweepBlock.
DEMLIGHT_AVX512 void laneDistancesInto(const LineGeometry& geo, const LineState* lines, std::size_t b0, long m, long n0,
                                       double frac, double* out) {
    _mm512_store_pd(out, laneDistances(geo, lines, b0, m, n0, frac));
}

/// Serves, for lines b0..b0+7 at one major index, the cell after each line (cell index
/// idxA + lane * idxStride) into planeA and the cell before it (idxB + lane * idxStride) into
/// planeB, every one of them inside the window; sigmaC is each lane's distance of the step.
/// With planeB null (one scan line per cell) only planeA's cells are served. The lanes' distances
/// are sigmas[0, 8), or laneDistances(e.geo, ..., e.m, e.n0, e.frac) where sigmas is null.
DEMLIGHT_AVX512 void serveEightLines(const EightLines& e, const float* H, float* planeA, float* planeB, long idxA,
                                     long idxB, long idxStride, const double* sigmas, double halfInvR, double invR) {
    const __m512d sigmaC = sigmas ? _mm512_load_pd(sigmas) : laneDistances(*e.geo, e.lines, e.b0, e.m, e.n0, e.frac);
    constexpr long long kStateWords = sizeof(LineState) / sizeof(long long);
    static_assert(sizeof(LineState) % sizeof(long long) == 0 && sizeof(std::size_t) == sizeof(long long));
    const __m512i lane = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
    const __m512i stateIdx = _mm512_mullo_epi64(lane, _mm512_set1_epi64(kStateWords));
    const auto* state = reinterpret_cast<const long long*>(e.lines + e.b0);
    const __m512i lo = _mm512_i64gather_epi64(stateIdx, state + offsetof(LineState, lo) / 8, 8);
    const __m512i hi = _mm512_i64gather_epi64(stateIdx, state + offsetof(LineState, hi) / 8, 8);
    __m512i hint = _mm512_i64gather_epi64(stateIdx, state + offsetof(LineState, hint) / 8, 8);
    const __m512i one = _mm512_set1_epi64(1);
    // Hull vertex v of lane l: doubles 2 (hullStart_l + v) (σ) and that + 1 (g).
    const __m512i hullStart = _mm512_mullo_epi64(
        _mm512_add_epi64(lane, _mm512_set1_epi64(static_cast<long long>(e.b0))),
        _mm512_set1_epi64(static_cast<long long>(e.lineCapacity)));
    const auto* hullSigma = reinterpret_cast<const double*>(e.hulls);
    const double* hullG = hullSigma + 1;
    const __mmask8 hullNonEmpty = _mm512_cmplt_epi64_mask(lo, hi);
    const __m512i hiLess1 = _mm512_sub_epi64(hi, one);
    const __m512i cellStep = _mm512_mullo_epi64(lane, _mm512_set1_epi64(idxStride));
    const __m512d dropC = sigmaC * sigmaC * _mm512_set1_pd(halfInvR);
    const __m512d invRv = _mm512_set1_pd(invR);
    float* const planes[2] = {planeA, planeB};
    const long idx0[2] = {idxA, idxB};
    for (int s = 0; s < (planeB ? 2 : 1); ++s) {
        // The lanes' cells: consecutive along rows (Y-major lines), a row apart otherwise.
        const __m512i cell = _mm512_add_epi64(_mm512_set1_epi64(idx0[s]), cellStep);
        const __m256 h = idxStride == 1 ? _mm256_loadu_ps(H + idx0[s]) : _mm512_i64gather_ps(cell, H, 4);
        const __m512d hc = _mm512_cvtps_pd(h);
        const __mmask8 valid = _mm512_cmp_pd_mask(hc, hc, _CMP_ORD_Q);  // not nodata
        const __mmask8 query = valid & hullNonEmpty;
        const __m512d gCell = hc - dropC;
        // tangentVertex from clamp(hint, lo, hi - 1): one step down or up, then on while it
        // rises; (si, gi) follow vertex i.
        __m512i i = _mm512_min_epi64(_mm512_max_epi64(hint, lo), hiLess1);
        const auto vertex = [&](__mmask8 m, __m512i v, __m512d& sig, __m512d& g) DEMLIGHT_AVX512 {
            const __m512i at = _mm512_slli_epi64(_mm512_add_epi64(hullStart, v), 1);
            sig = _mm512_mask_i64gather_pd(_mm512_setzero_pd(), m, at, hullSigma, 8);
            g = _mm512_mask_i64gather_pd(_mm512_setzero_pd(), m, at, hullG, 8);
        };
        __m512d si, gi;
        vertex(query, i, si, gi);
        __mmask8 down, up;
        {
            const __mmask8 hasFarther = query & _mm512_cmpgt_epi64_mask(i, lo);
            __m512d sf, gf;
            vertex(hasFarther, _mm512_sub_epi64(i, one), sf, gf);
            down = hasFarther & steeperLanes(gf, sf, gi, si, gCell, sigmaC);
            const __mmask8 hasNearer = query & ~down & _mm512_cmplt_epi64_mask(i, hiLess1);
            __m512d sn, gn;
            vertex(hasNearer, _mm512_add_epi64(i, one), sn, gn);
            up = hasNearer & ~steeperLanes(gi, si, gn, sn, gCell, sigmaC);
            i = _mm512_mask_sub_epi64(i, down, i, one);
            i = _mm512_mask_add_epi64(i, up, i, one);
            si = _mm512_mask_blend_pd(down, _mm512_mask_blend_pd(up, si, sn), sf);
            gi = _mm512_mask_blend_pd(down, _mm512_mask_blend_pd(up, gi, gn), gf);
        }
        // Lanes that moved go on in the same direction while the next vertex is steeper (down)
        // or not less steep (up).
        for (;;) {
            down &= _mm512_cmpgt_epi64_mask(i, lo);
            up &= _mm512_cmplt_epi64_mask(i, hiLess1);
            if (!(down | up)) break;
            __m512d sNext, gNext;  // vertex i - 1 (down) or i + 1 (up)
            vertex(down | up, _mm512_mask_add_epi64(_mm512_sub_epi64(i, one), up, i, one), sNext, gNext);
            // down: steeper(i - 1, i); up: steeper(i, i + 1)
            const __mmask8 st = steeperLanes(_mm512_mask_blend_pd(up, gNext, gi), _mm512_mask_blend_pd(up, sNext, si),
                                             _mm512_mask_blend_pd(up, gi, gNext), _mm512_mask_blend_pd(up, si, sNext),
                                             gCell, sigmaC);
            down &= st;
            up &= ~st;
            i = _mm512_mask_sub_epi64(i, down, i, one);
            i = _mm512_mask_add_epi64(i, up, i, one);
            si = _mm512_mask_blend_pd(down | up, si, sNext);
            gi = _mm512_mask_blend_pd(down | up, gi, gNext);
        }
        const __m512d slope = (gi - gCell) / (sigmaC - si) - sigmaC * invRv;
        const __m256 none = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
        const __m256 value = _mm256_mask_blend_ps(query, none, _mm512_cvtpd_ps(slope));
        if (idxStride == 1) {
            _mm256_mask_storeu_ps(planes[s] + idx0[s], valid, value);
        } else {
            _mm512_mask_i64scatter_ps(planes[s], valid, cell, value, 4);
        }
        hint = _mm512_mask_blend_epi64(query, hint, i);
    }
    _mm512_i64scatter_epi64(const_cast<long long*>(state) + offsetof(LineState, hint) / 8, stateIdx, hint, 8);
}

/// The two nearest vertices of eight lines' hulls (buf[hi - 1] and buf[hi - 2] of each lane),
/// kept between steps by walkEightLines so that a push's first pop test reads no hull memory;
/// `valid` is false until it has walked these lanes, and after anything else pushed to them.
struct TopVertices {
    alignas(64) double s1[kSimdLines], g1[kSimdLines], s2[kSimdLines], g2[kSimdLines];
    bool valid = false;
};

/// One step of the far-to-near walk for lines b0..b0+7 where it serves nothing (the delayed
/// serving: sweepBlock's Lanes), one line per AVX-512 lane: the line sample between cells n0
/// (index idx0 + lane * idxStride) and n0 + 1, every one of them inside the terrain, the pops it
/// causes and its push. The scalar walk's comparisons and arithmetic are written as the same
/// expressions on vectors (so the compiler contracts them alike), and its pop loop becomes a
/// masked loop over the lanes that still pop: the same bits, the same hulls.
DEMLIGHT_AVX512 void walkEightLines(const EightLines& e, const float* H, long idx0, long idxStride, double halfInvR,
                                    TopVertices& top) {
    const double frac = e.frac;
    const __m512d sigma = laneDistances(*e.geo, e.lines, e.b0, e.m, e.n0, frac);
    constexpr long long kStateWords = sizeof(LineState) / sizeof(long long);
    const __m512i lane = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
    const __m512i stateIdx = _mm512_mullo_epi64(lane, _mm512_set1_epi64(kStateWords));
    auto* state = reinterpret_cast<long long*>(e.lines + e.b0);
    const __m512i lo = _mm512_i64gather_epi64(stateIdx, state + offsetof(LineState, lo) / 8, 8);
    const __m512i hi = _mm512_i64gather_epi64(stateIdx, state + offsetof(LineState, hi) / 8, 8);
    const __m512i one = _mm512_set1_epi64(1), two = _mm512_set1_epi64(2);
    // Hull vertex v of lane l: doubles 2 (hullStart_l + v) (σ) and that + 1 (g).
    const __m512i hullStart = _mm512_mullo_epi64(
        _mm512_add_epi64(lane, _mm512_set1_epi64(static_cast<long long>(e.b0))),
        _mm512_set1_epi64(static_cast<long long>(e.lineCapacity)));
    auto* hullSigma = reinterpret_cast<double*>(e.hulls);
    double* hullG = hullSigma + 1;
    const auto at = [&](__m512i v) DEMLIGHT_AVX512 { return _mm512_slli_epi64(_mm512_add_epi64(hullStart, v), 1); };

    // The line sample: linear between the two cells, or the one with a height.
    const __m512i step = _mm512_set1_epi64(idxStride);
    const __m512i cell = _mm512_add_epi64(_mm512_set1_epi64(idx0), _mm512_mullo_epi64(lane, step));
    const __m256 h0 = idxStride == 1 ? _mm256_loadu_ps(H + idx0) : _mm512_i64gather_ps(cell, H, 4);
    __m256 sample = h0;
    if (frac > 0.0) {
        const __m256 h1 = idxStride == 1 ? _mm256_loadu_ps(H + idx0 + 1)
                                         : _mm512_i64gather_ps(_mm512_add_epi64(cell, step), H, 4);
        const __m512d h0d = _mm512_cvtps_pd(h0), h1d = _mm512_cvtps_pd(h1);
        const __m256 mixed = _mm512_cvtpd_ps(_mm512_set1_pd(1.0 - frac) * h0d + _mm512_set1_pd(frac) * h1d);
        const __mmask8 nan0 = _mm512_cmp_pd_mask(h0d, h0d, _CMP_UNORD_Q);
        const __mmask8 nan1 = _mm512_cmp_pd_mask(h1d, h1d, _CMP_UNORD_Q);
        sample = _mm256_mask_blend_ps(nan0, _mm256_mask_blend_ps(nan1, mixed, h0), h1);
    }
    const __m512d sampleD = _mm512_cvtps_pd(sample);
    const __mmask8 valid = _mm512_cmp_pd_mask(sampleD, sampleD, _CMP_ORD_Q);
    const __m512d drop = sigma * sigma * _mm512_set1_pd(halfInvR);
    const __m512d g = sampleD - drop;

    // hullTopAfterPops: pop v1 while the hull keeps two vertices and the slope to v2 (farther)
    // is at least the slope to v1.
    const __m512i count = _mm512_sub_epi64(hi, lo);
    __m512d topS1, topG1, topS2, topG2;
    if (top.valid) {
        topS1 = _mm512_load_pd(top.s1);
        topG1 = _mm512_load_pd(top.g1);
        topS2 = _mm512_load_pd(top.s2);
        topG2 = _mm512_load_pd(top.g2);
    } else {
        const __mmask8 has1 = _mm512_cmpge_epi64_mask(count, one), has2 = _mm512_cmpge_epi64_mask(count, two);
        topS1 = _mm512_mask_i64gather_pd(_mm512_setzero_pd(), has1, at(_mm512_sub_epi64(hi, one)), hullSigma, 8);
        topG1 = _mm512_mask_i64gather_pd(_mm512_setzero_pd(), has1, at(_mm512_sub_epi64(hi, one)), hullG, 8);
        topS2 = _mm512_mask_i64gather_pd(_mm512_setzero_pd(), has2, at(_mm512_sub_epi64(hi, two)), hullSigma, 8);
        topG2 = _mm512_mask_i64gather_pd(_mm512_setzero_pd(), has2, at(_mm512_sub_epi64(hi, two)), hullG, 8);
        top.valid = true;
    }
    __m512d s1 = topS1, g1 = topG1, s2 = topS2, g2 = topG2;
    __m512i t = hi;
    __mmask8 active = valid & _mm512_cmpge_epi64_mask(count, two);
    while (active) {
        const __mmask8 keep = _mm512_cmp_pd_mask((g2 - g) * (sigma - s1), (g1 - g) * (sigma - s2), _CMP_LT_OQ);
        const __mmask8 pop = active & ~keep;
        if (!pop) break;
        t = _mm512_mask_sub_epi64(t, pop, t, one);
        s1 = _mm512_mask_mov_pd(s1, pop, s2);
        g1 = _mm512_mask_mov_pd(g1, pop, g2);
        active = pop & _mm512_cmpge_epi64_mask(_mm512_sub_epi64(t, lo), two);
        const __m512i below = at(_mm512_sub_epi64(t, two));
        s2 = _mm512_mask_i64gather_pd(s2, active, below, hullSigma, 8);
        g2 = _mm512_mask_i64gather_pd(g2, active, below, hullG, 8);
    }
    // The push: buf[t] = (σ, g) and hi = t + 1 where the sample holds a height.
    _mm512_mask_i64scatter_pd(hullSigma, valid, at(t), sigma, 8);
    _mm512_mask_i64scatter_pd(hullG, valid, at(t), g, 8);
    _mm512_mask_i64scatter_epi64(state + offsetof(LineState, hi) / 8, valid, stateIdx, _mm512_add_epi64(t, one), 8);
    _mm512_store_pd(top.s2, _mm512_mask_mov_pd(topS2, valid, s1));
    _mm512_store_pd(top.g2, _mm512_mask_mov_pd(topG2, valid, g1));
    _mm512_store_pd(top.s1, _mm512_mask_mov_pd(topS1, valid, sigma));
    _mm512_store_pd(top.g1, _mm512_mask_mov_pd(topG1, valid, g));
}
#endif

#ifdef DEMLIGHT_SWEEP_AVX512
constexpr bool kLanesWalk = true;
#else
constexpr bool kLanesWalk = false;
#endif

/// Limited: maxDistanceM is finite (chunks, logs and the second pass); an instantiation each so
/// the whole-DEM walk, which sky integrals run once per direction, carries none of that code.
/// Lanes: the walk takes eight lines at once (walkEightLines; the AVX-512 path, the whole DEM,
/// cells served after the walk, no crossing points), in instantiations of its own so that the
/// others compile as they did without it. eightAtOnce (the AVX-512 path) serves eight lines at
/// once where it can; false serves one line at a time.
template <bool XMajor, bool Limited, bool Lanes>
void sweepBlock(const Terrain& t, const LineGeometry& geo, double invR, double maxDistanceM,
                long kBegin, long kEnd, float* planeA, float* planeB, std::vector<HullPoint>& scratch,
                RangeLog* logs, const ValidCells& valid, [[maybe_unused]] bool eightAtOnce) {
    const std::size_t W = t.width();
    const float* H = t.heightsM.data();
    // With a near field a line also takes a point where it crosses a grid line between steps.
    const std::size_t lineCapacity =
        (geo.delay > 0 ? 2 : 1) * (static_cast<std::size_t>(std::abs(geo.mFar - geo.mNear)) + 1);
    const std::size_t nLines = static_cast<std::size_t>(kEnd - kBegin);
    if (scratch.size() < nLines * lineCapacity) scratch.resize(nLines * lineCapacity);
    constexpr bool limited = Limited;

    const long N = static_cast<long>(geo.minorSize);
    const long mStep = -geo.farSign;
    const long minorWin0 = static_cast<long>(geo.minorWin0), minorWin1 = static_cast<long>(geo.minorWin1);
    const long mLo = geo.majorLo, nLo = geo.minorLo, nHi = geo.minorHi;
    const bool sigmaTable = !geo.sigmaAt.empty();
    const double halfInvR = 0.5 * invR;
    auto index = [W, mLo, nLo](long m, long j) {
        return XMajor ? static_cast<std::size_t>(j - nLo) * W + static_cast<std::size_t>(m - mLo)
                      : static_cast<std::size_t>(m - mLo) * W + static_cast<std::size_t>(j - nLo);
    };
    // Whether any of minor indices j0..j1 at step m (clipped to the terrain) holds a height:
    // from the bitmap where it is kept, else reading the heights until one is found.
    const bool bitmap = valid.used();
    auto heightsAt = [&](long m, long j0, long j1) {
        j0 = std::max(j0, nLo);
        j1 = std::min(j1, nHi - 1);
        if (bitmap) return j0 <= j1 && valid.any(m - mLo, j0 - nLo, j1 - nLo);
        for (long j = j0; j <= j1; ++j)
            if (!std::isnan(H[index(m, j)])) return true;
        return false;
    };
    // The same where a wrong "yes" only costs time (serving, prefetching): without the bitmap,
    // yes.
    auto mayHaveHeights = [&](long m, long j0, long j1) { return !bitmap || heightsAt(m, j0, j1); };

    // A block serves window cells only where one of its lines is within a cell of the window's
    // minor range; off-axis, in a region narrower than the DEM, that is a fraction of the
    // window's major range. Walk from extensionSteps beyond the farthest such step (enough for
    // maxDistanceM) to the nearest one, not over the whole region.
    long mServeFar = -1, mServeNear = -1;
    for (long m = static_cast<long>(geo.majorWin0); m < static_cast<long>(geo.majorWin1); ++m) {
        const long base = geo.base[static_cast<std::size_t>(m)];
        if (kBegin + base <= minorWin1 - 1 && kEnd - 1 + base >= minorWin0 - 1) {
            if (mServeFar < 0 || (m - mServeFar) * geo.farSign > 0) mServeFar = m;
            if (mServeNear < 0 || (m - mServeNear) * geo.farSign < 0) mServeNear = m;
        }
    }
    if (mServeFar < 0) return;
    const long mStart = std::clamp(mServeFar + geo.farSign * geo.extensionSteps, std::min(geo.mFar, geo.mNear),
                                   std::max(geo.mFar, geo.mNear));
    LineState lines[kLinesPerBlock];
    const auto edge = static_cast<std::size_t>(geo.mEdge);
    for (std::size_t b = 0; b < nLines; ++b) {
        // Without a distance table, every sample's distance is taken from the line's arc
        // coordinate at the far edge.
        const long k = kBegin + static_cast<long>(b);
        const double edgeArc = sigmaTable ? 0.0 : arcAt(geo, static_cast<double>(k + geo.base[edge]) + geo.frac[edge]);
        lines[b] = {scratch.data() + b * lineCapacity, 0, 0, edgeArc, 0, maxDistanceM, limited ? &logs[b] : nullptr,
                    0, 0, 0, 0, -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
        if (limited) logs[b].reset(lineCapacity);
    }
    // Range limit, a cell whose chunk is its line's (value: from the current chunk's hull): the
    // previous chunk's points within range may raise it; the rest are the exact pass's.
    [[maybe_unused]] const auto raiseFromPrevChunk = [&](LineState& line, double sigmaC, double gCell, long chunkC,
                                                         float* cell, float value) {
        if (line.prevLo >= line.prevHi || prevChunkCannotRaise(line, sigmaC, gCell, invR, value)) return;
        const std::size_t v = tangentVertex(line.buf, line.prevLo, line.prevHi, line.prevHint, sigmaC, gCell);
        line.prevHint = v;
        const HullPoint& pv = line.buf[v];
        const float bound = rangeSlope(pv.g, pv.sigmaM, gCell, sigmaC, invR);
        if (bound > value) {
            if (pv.sigmaM >= sigmaC - maxDistanceM) {
                *cell = bound;
            } else {
                line.log->queries[line.log->nQueries++] = {sigmaC, gCell, chunkC, line.log->nPoints, cell, false};
            }
        }
    };
    // With a near field (geo.delay steps), a cell is served `delay` steps after the walk passed
    // it, from the hulls of the samples walked so far: its scan lines' terrain at least `delay`
    // steps away, queried at the cell's own height (the near field is the combine pass's).
    const long delay = geo.delay;
    auto serveDelayed = [&](long mc) {
        if (mc < static_cast<long>(geo.majorWin0) || mc >= static_cast<long>(geo.majorWin1)) return;
        const long baseC = geo.base[static_cast<std::size_t>(mc)];
        // Nodata cells are not served: a step of only those has nothing to do.
        if (!mayHaveHeights(mc, kBegin + baseC, kEnd + baseC)) return;
        const double fracC = geo.frac[static_cast<std::size_t>(mc)];
        // A line's distance at this step (metres from the far edge), for either serving path.
        const auto sigmaOfLine = [&](std::size_t b, long n0) {
            return sigmaTable ? geo.sigmaAt[static_cast<std::size_t>(mc)]
                              : lineDistance(geo, lines[b].edgeArcM, static_cast<double>(n0) + fracC, mc);
        };
        const auto serveLine = [&](std::size_t b) {
            LineState& line = lines[b];
            const long n0 = kBegin + static_cast<long>(b) + baseC;
            if (n0 < minorWin0 - 1 || n0 >= minorWin1) return;
            long servedCell[2] = {fracC > 0.0 ? n0 + 1 : n0, n0};
            int nServed = fracC > 0.0 ? 2 : 1;
            if (geo.nearestLine) {
                servedCell[0] = fracC > 0.5 ? n0 + 1 : n0;
                nServed = 1;
            }
            const double sigmaC = sigmaOfLine(b, n0);
            const double dropC = sigmaC * sigmaC * halfInvR;
            // Range limit: the chunk of the cell against the walk's (line.chunk, whose points the
            // hull [lo, hi) holds; [prevLo, prevHi) holds the chunk before it).
            const long chunkC = limited ? static_cast<long>(std::floor(sigmaC / maxDistanceM)) : 0;
            float* const servedPlane[2] = {planeA, planeB};
            for (int s = 0; s < nServed; ++s) {
                const long j = servedCell[s];
                if (j < minorWin0 || j >= minorWin1) continue;
                const std::size_t idx = index(mc, j);
                const float hc = H[idx];
                if (std::isnan(hc)) continue;
                const double gCell = static_cast<double>(hc) - dropC;
                float value = -std::numeric_limits<float>::infinity();
                float* cell = servedPlane[s] + idx;
                const bool hullInRange = !limited || chunkC == line.chunk;
                if (line.lo < line.hi && (hullInRange || chunkC == line.chunk + 1)) {
                    const std::size_t v = tangentVertex(line.buf, line.lo, line.hi,
                                                        std::clamp(line.hint, line.lo, line.hi - 1), sigmaC, gCell);
                    line.hint = v;
                    const HullPoint& pv = line.buf[v];
                    if (hullInRange) {
                        value = static_cast<float>((pv.g - gCell) / (sigmaC - pv.sigmaM) - sigmaC * invR);
                    } else if (pv.sigmaM >= sigmaC - maxDistanceM) {
                        // The walk's chunk is the cell's previous one: its tangent is the answer
                        // when in range, else the cell is left to the exact pass.
                        value = rangeSlope(pv.g, pv.sigmaM, gCell, sigmaC, invR);
                    } else {
                        line.log->queries[line.log->nQueries++] = {sigmaC, gCell, chunkC, line.log->nPoints, cell,
                                                                   true};
                    }
                }
                *cell = value;
                // The previous chunk, as for the undelayed walk below.
                if (Limited && hullInRange) raiseFromPrevChunk(line, sigmaC, gCell, chunkC, cell, value);
            }
        };
        std::size_t b = 0;
#ifdef DEMLIGHT_SWEEP_AVX512
        // Eight lines at once where both cells of every line are window cells; serveLine serves
        // the rest, and every line of range-limited sweeps. With one scan line per cell each line
        // serves the cell it is nearest to (the same side for every line of the step) into plane
        // A, at any fraction; with two, both cells where the line runs between them.
        if (eightAtOnce && (fracC > 0.0 || geo.nearestLine)) {
            for (; b + kSimdLines <= nLines; b += kSimdLines) {
                const long n0 = kBegin + static_cast<long>(b) + baseC;
                if (n0 < minorWin0 || n0 + static_cast<long>(kSimdLines) >= minorWin1) {
                    for (std::size_t l = 0; l < kSimdLines; ++l) serveLine(b + l);
                    continue;
                }
                [[maybe_unused]] alignas(64) double sigmas[kSimdLines];
                [[maybe_unused]] long chunks[kSimdLines];
                if constexpr (Limited) {
                    // Range limit: at once where every lane's cells lie in its line's chunk (the
                    // hull in range); otherwise line by line.
                    laneDistancesInto(geo, lines, b, mc, n0, fracC, sigmas);
                    bool inChunk = true;
                    for (std::size_t l = 0; l < kSimdLines; ++l) {
                        chunks[l] = static_cast<long>(std::floor(sigmas[l] / maxDistanceM));
                        inChunk = inChunk && chunks[l] == lines[b + l].chunk;
                    }
                    if (!inChunk) {
                        for (std::size_t l = 0; l < kSimdLines; ++l) serveLine(b + l);
                        continue;
                    }
                }
                const long idxA = static_cast<long>(index(mc, n0 + 1)), idxB = static_cast<long>(index(mc, n0));
                const long served[2] = {geo.nearestLine ? (fracC > 0.5 ? idxA : idxB) : idxA, idxB};
                float* const servedPlane[2] = {planeA, planeB};
                const int nServed = geo.nearestLine ? 1 : 2;
                serveEightLines({lines, scratch.data(), lineCapacity, b, &geo, mc, n0, fracC}, H, planeA,
                                nServed == 2 ? planeB : nullptr, served[0], nServed == 2 ? served[1] : 0, idxA - idxB,
                                Limited ? sigmas : nullptr, halfInvR, invR);
                if constexpr (Limited) {
                    // Then each cell's previous chunk, as serveLine does: a line's cells in
                    // serveLine's order (each tangent search starts where the line's last ended).
                    for (std::size_t l = 0; l < kSimdLines; ++l) {
                        LineState& line = lines[b + l];
                        if (line.prevLo >= line.prevHi) continue;
                        const double dropC = sigmas[l] * sigmas[l] * halfInvR;
                        for (int s = 0; s < nServed; ++s) {
                            const auto idx = static_cast<std::size_t>(served[s] + static_cast<long>(l) * (idxA - idxB));
                            const float hc = H[idx];
                            if (std::isnan(hc)) continue;
                            float* cell = servedPlane[s] + idx;
                            raiseFromPrevChunk(line, sigmas[l], static_cast<double>(hc) - dropC, chunks[l], cell, *cell);
                        }
                    }
                }
            }
        }
#endif
        for (; b < nLines; ++b) serveLine(b);
    };
#ifdef DEMLIGHT_SWEEP_AVX512
    [[maybe_unused]] TopVertices topVertices[Lanes ? kLinesPerBlock / kSimdLines : 1];
#endif
    // The cells within `delay` steps of the walk's start have no sample that far beyond them
    // (the walk starts at the DEM's far edge, or beyond every cell this block serves).
    bool served = false;
    for (long i = 0; delay > 0 && i < delay && !served; ++i) {
        serveDelayed(mStart + i * mStep);
        served = mStart + i * mStep == mServeNear;
    }
    for (long m = mStart; !served; m += mStep) {
        const long base = geo.base[static_cast<std::size_t>(m)];
        const double frac = geo.frac[static_cast<std::size_t>(m)];
        // Fetch the heights and output cells of a step kPrefetchSteps ahead. Along rows (Y-major)
        // each step lands on a new row, a page or more away, which the hardware prefetchers do
        // not follow: without this the sweep spends much of its time waiting on that load
        // (docs/measurements.md#lightinghorizon_sweepcpp-kprefetchsteps).
        if (const long ahead = m + mStep * kPrefetchSteps; ahead >= mLo && ahead < geo.majorHi) {
            const long aheadBase = geo.base[static_cast<std::size_t>(ahead)];
            const long j0 = std::max(nLo, kBegin + aheadBase - 1);
            const long j1 = std::min(nHi - 1, kEnd + aheadBase + 1);
            // (A step of only nodata cells reads and writes none of them.)
            if (j0 <= j1 && mayHaveHeights(ahead, j0, j1)) {
                if constexpr (XMajor) {
                    for (long j = j0; j <= j1; ++j) {
                        __builtin_prefetch(H + index(ahead, j));
                        __builtin_prefetch(planeA + index(ahead, j), 1);
                    }
                } else {
                    for (long j = j0; j <= j1; j += kFloatsPerCacheLine) {
                        __builtin_prefetch(H + index(ahead, j));
                        __builtin_prefetch(planeA + index(ahead, j), 1);
                    }
                    __builtin_prefetch(H + index(ahead, j1));
                    __builtin_prefetch(planeA + index(ahead, j1), 1);
                }
            }
        }
        // Delayed serving reads and writes the cells `delay` steps ahead of the walk: fetch
        // those kPrefetchSteps ahead of that (both planes: two lines serve each cell).
        if (const long servedAhead = m + mStep * (delay + kPrefetchSteps);
            delay > 0 && servedAhead >= mLo && servedAhead < geo.majorHi) {
            const long servedBase = geo.base[static_cast<std::size_t>(servedAhead)];
            const long j0 = std::max(nLo, kBegin + servedBase - 1);
            const long j1 = std::min(nHi - 1, kEnd + servedBase + 1);
            const long stride = XMajor ? 1 : kFloatsPerCacheLine;
            const bool any = j0 <= j1 && mayHaveHeights(servedAhead, j0, j1);
            for (long j = j0; any && j <= j1; j += stride) {
                __builtin_prefetch(H + index(servedAhead, j));
                __builtin_prefetch(planeA + index(servedAhead, j), 1);
                if (!geo.nearestLine) __builtin_prefetch(planeB + index(servedAhead, j), 1);
            }
            if (any) {
                __builtin_prefetch(H + index(servedAhead, j1));
                __builtin_prefetch(planeA + index(servedAhead, j1), 1);
                if (!geo.nearestLine) __builtin_prefetch(planeB + index(servedAhead, j1), 1);
            }
        }
        // Skip steps where every line of the block lies outside the grid.
        const long n0First = kBegin + base, n0Last = kEnd - 1 + base;
        const bool anyInside = n0Last >= nLo - 1 && n0First <= nHi - 1;
        const bool inWindow = m >= static_cast<long>(geo.majorWin0) &&
                              m < static_cast<long>(geo.majorWin1);
        // Where every cell the block's lines sample or serve at this step is nodata (sea, voids),
        // the lines only advance their distances: nothing is sampled, served or pushed. The
        // range limit's chunk bookkeeping catches up at the next valid sample, which is the same:
        // a chunk boundary crossed over nodata leaves an empty hull behind either way.
        const bool allNodata = anyInside && !heightsAt(m, n0First, n0Last + 1);
        // With a near field, the far field follows the bilinear surface between steps too: where
        // the lines cross a grid line of the minor axis between the previous step and this one
        // (the same crossing for every line, at fraction tc of the step), each takes a point
        // there, linear between the two cells on that grid line; that is where a wall's top edge
        // along the major axis lies. Pushed before this step's samples (it is farther).
        if (geo.crossings && m != mStart) {
            const long prev = m - mStep;
            const long basePrev = geo.base[static_cast<std::size_t>(prev)];
            const double fracPrev = geo.frac[static_cast<std::size_t>(prev)];
            if (frac > 0.0 && fracPrev > 0.0 && basePrev != base) {
                const long n = std::max(basePrev, base);
                const double yPrev = static_cast<double>(basePrev) + fracPrev, yNow = static_cast<double>(base) + frac;
                const double tc = (static_cast<double>(n) - yPrev) / (yNow - yPrev);
                // (Only nodata on both grid lines: no line takes a point.)
                const bool bothSteps = prev >= mLo && prev < geo.majorHi &&
                                       (mayHaveHeights(prev, kBegin + n, kEnd - 1 + n) ||
                                        mayHaveHeights(m, kBegin + n, kEnd - 1 + n));
                for (std::size_t b = 0; bothSteps && b < nLines; ++b) {
                    LineState& line = lines[b];
                    const long j = kBegin + static_cast<long>(b) + n;
                    if (j < nLo || j >= nHi) continue;
                    const float hPrev = H[index(prev, j)], hNow = H[index(m, j)];
                    const float h = std::isnan(hPrev) ? hNow : std::isnan(hNow) ? hPrev
                                  : static_cast<float>((1.0 - tc) * hPrev + tc * hNow);
                    if (std::isnan(h)) continue;
                    const double sigma =
                        sigmaTable ? geo.sigmaAt[static_cast<std::size_t>(prev)] +
                                         tc * (geo.sigmaAt[static_cast<std::size_t>(m)] -
                                               geo.sigmaAt[static_cast<std::size_t>(prev)])
                                   : lineDistance(geo, line.edgeArcM, static_cast<double>(j), m);
                    if (limited && sigma >= line.nextChunkM) enterChunk(line, sigma, maxDistanceM);
                    const double g = static_cast<double>(h) - sigma * sigma * halfInvR;
                    const std::size_t top = hullTopAfterPops(line, sigma, g);
                    if (limited) line.log->points[line.log->nPoints++] = {sigma, g, line.chunk};
                    line.hi = top;
                    line.buf[line.hi++] = {sigma, g};
                    if (limited) line.maxG = std::max(line.maxG, g);
                }
            }
        }
        // Where every line is off the terrain's cells or every cell is nodata there is nothing
        // to sample or serve (distances need no walking: they are a function of position).
        if (anyInside && !allNodata) {
            const auto walkLine = [&](std::size_t b) {
                LineState& line = lines[b];
                const long n0 = kBegin + static_cast<long>(b) + base;
                const long n1 = n0 + 1;
                if (n0 < -1 || n0 > N - 1) return;
                const double sigma = sigmaTable ? geo.sigmaAt[static_cast<std::size_t>(m)]
                                                : lineDistance(geo, line.edgeArcM, static_cast<double>(n0) + frac, m);

                // Line sample: linear across the line between the two bracketing cells; heights
                // are known inside the hull of the cell centres only. Cells of the full grid
                // outside the terrain count as nodata: they lie beyond the search distance of
                // every cell served (the halo), so no chunk that serves a cell holds them.
                const bool inside = n0 >= nLo && (frac == 0.0 ? n0 < nHi : n1 < nHi);
                const float h0 = inside ? H[index(m, n0)] : std::numeric_limits<float>::quiet_NaN();
                float sample = h0;
                if (frac > 0.0 && inside) {
                    const float h1 = H[index(m, n1)];
                    if (std::isnan(h0)) {
                        sample = h1;
                    } else if (!std::isnan(h1)) {
                        sample = static_cast<float>((1.0 - frac) * h0 + frac * h1);
                    }
                }

                // Range limit: a fresh hull per chunk of length maxDistanceM (see limitRangePass).
                // Chunks start at multiples of maxDistanceM from the far edge, so a chunk that
                // serves a cell starts within the halo and every walk builds the same hull.
                if (limited && sigma >= line.nextChunkM) enterChunk(line, sigma, maxDistanceM);

                // The line sample's tangent vertex = the hull top after the pops it causes:
                // pop v1 while the slope to v2 (farther) is at least the slope to v1.
                const bool sampleValid = !std::isnan(sample);
                const double drop = sigma * sigma * halfInvR;
                const double gSample = static_cast<double>(sample) - drop;
                const std::size_t top = sampleValid ? hullTopAfterPops(line, sigma, gSample) : line.hi;

                // Serve the cells this line brackets at this step: cell n1 (line below it, weight
                // frac) into plane A, cell n0 (line above it, weight 1-frac) into plane B; on an
                // exact hit (frac == 0) cell n0 into plane A.
                // (n0 in [minorWin0 - 1, minorWin1 - 1]: n1 or n0 is a window cell.)
                if (delay == 0 && inWindow && n0 >= minorWin0 - 1 && n0 < minorWin1) {
                    long servedCell[2] = {frac > 0.0 ? n1 : n0, n0};
                    float* const servedPlane[2] = {planeA, planeB};
                    int nServed = frac > 0.0 ? 2 : 1;
                    if (geo.nearestLine) {
                        // Only the cell this line is nearest to (frac is the same for every line
                        // at this step, so exactly one line serves each cell).
                        servedCell[0] = frac > 0.5 ? n1 : n0;
                        nServed = 1;
                    }
                    for (int s = 0; s < nServed; ++s) {
                        const long j = servedCell[s];
                        if (j < minorWin0 || j >= minorWin1) continue;
                        const std::size_t idx = index(m, j);
                        const float hc = H[idx];
                        if (std::isnan(hc)) continue;
                        const double hQuery = observerHeight(H, index, m, j, nLo, nHi, frac, hc, sample);
                        const double gCell = hQuery - drop;
                        float value = -std::numeric_limits<float>::infinity();
                        if (line.lo < line.hi) {
                            const std::size_t start = top > line.lo ? top - 1 : line.lo;
                            value = static_cast<float>(tangentSlope(line, start, sigma, gCell) - sigma * invR);
                        }
                        float* cell = servedPlane[s] + idx;
                        *cell = value;
                        // The previous chunk: the tangent to its hull bounds what its points within
                        // range can add, and is that answer when its vertex is in range; otherwise
                        // the cell is left to the exact pass. (A walk that starts inside that chunk
                        // has a hull of fewer points; every point within range is in both, so both
                        // find the same answer, the exact pass by the same rangeSlope.)
                        if (Limited) raiseFromPrevChunk(line, sigma, gCell, line.chunk, cell, value);
                    }
                }

                if (sampleValid) {
                    if (limited) line.log->points[line.log->nPoints++] = {sigma, gSample, line.chunk};
                    line.hi = top;
                    line.buf[line.hi++] = {sigma, gSample};
                    if (limited) line.maxG = std::max(line.maxG, gSample);
                }
            };
            std::size_t b = 0;
#ifdef DEMLIGHT_SWEEP_AVX512
            // Eight lines at once where all eight and the cells after them lie inside the terrain;
            // walkLine walks the rest (and drops those lanes' cached top vertices).
            for (; Lanes && b + kSimdLines <= nLines; b += kSimdLines) {
                TopVertices& cached = topVertices[b / kSimdLines];
                const long n0 = kBegin + static_cast<long>(b) + base;
                if (n0 < nLo || n0 + static_cast<long>(kSimdLines) >= nHi) {
                    for (std::size_t l = 0; l < kSimdLines; ++l) walkLine(b + l);
                    cached.valid = false;
                    continue;
                }
                const long idx0 = static_cast<long>(index(m, n0));
                walkEightLines({lines, scratch.data(), lineCapacity, b, &geo, m, n0, frac}, H, idx0,
                               static_cast<long>(index(m, n0 + 1)) - idx0, halfInvR, cached);
            }
#endif
            for (; b < nLines; ++b) walkLine(b);
        }
        if (delay == 0) {
            if (m == mServeNear) break;
        } else {
            serveDelayed(m + delay * mStep);
            if (m + delay * mStep == mServeNear) break;
        }
    }
    if (limited) {
        for (std::size_t b = 0; b < nLines; ++b) limitRangePass(logs[b], maxDistanceM, invR, scratch);
    }
}

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

/// The near field's first steps are sampled at the reference's quarter cells (walls and roof
/// edges next to the cell); beyond them only where the ray crosses grid lines.
constexpr long kDenseNearSteps = 2;

/// One point of the near field's stencil: the ray from a cell centre, `dc` columns and `dr` rows
/// away, at distance d; its bilinear taps (offsets from the cell, weights > 0, padded to four
/// with zero-weight copies of the first so every point costs the same).
struct NearPoint {
    double dc, dr;
    float invDistance, drop;  // 1/d (1/metres) and d/(2 R_eff): slope = (h - h0)/d - d/(2 R_eff)
    long tapCol[4], tapRow[4];
    float weight[4];
    int taps;  // 2 when the point lies on a grid line (weights 2 and 3 zero), else 4
};

/// The near field's points for cells of full-grid row `row`: the reference's quarter-cell steps
/// along the region's direction up to nearSteps line steps (or maxDistanceM), the same offsets for
/// every cell of the row.
void nearStencil(const LineGeometry& geo, const FullGridRef& g, std::size_t row, double maxDistanceM, double invR,
                 std::vector<NearPoint>& out) {
    out.clear();
    const double stepM = kReferenceStepOfCell * std::min(g.cellWidthM[row], g.cellHeightM[row]);
    const double lineStepM = geo.stepLengthM[row];
    const double reachM = std::min(static_cast<double>(geo.nearSteps) * lineStepM, maxDistanceM);
    const double denseM = std::min(static_cast<double>(std::min<long>(geo.nearSteps, kDenseNearSteps)) * lineStepM, reachM);
    // Distances (metres) of the points: quarter cells up to denseM, and where the ray crosses a
    // grid line of either axis (the bilinear surface is linear along those lines).
    thread_local std::vector<double> ds;
    ds.clear();
    for (long k = 1;; ++k) {
        const double d = static_cast<double>(k) * stepM;
        if (d > denseM) break;
        ds.push_back(d);
    }
    // The crossings are taken in the dense part too: a wall's top edge (a line of cell centres)
    // is then sampled exactly wherever the ray meets it.
    const double absSlope = std::abs(geo.slope);
    for (long m = 1; static_cast<double>(m) * lineStepM <= reachM; ++m) ds.push_back(static_cast<double>(m) * lineStepM);
    if (absSlope > 0.0) {
        for (long n = 1; static_cast<double>(n) / absSlope * lineStepM <= reachM; ++n)
            ds.push_back(static_cast<double>(n) / absSlope * lineStepM);
    }
    std::sort(ds.begin(), ds.end());
    ds.erase(std::unique(ds.begin(), ds.end()), ds.end());
    for (const double d : ds) {
        const double major = geo.farSign * d / lineStepM, minor = geo.slope * major;
        NearPoint p;
        // A crossing lands on its grid line up to rounding: put it there, so that it takes the
        // two taps of that line and not a third of weight 1e-16 (which a void beside it would
        // reweight to the whole height).
        const auto snap = [](double v) { return std::abs(v - std::round(v)) < 1e-9 ? std::round(v) : v; };
        p.dc = snap(geo.xMajor ? major : minor);
        p.dr = snap(geo.xMajor ? minor : major);
        // Along a grid axis the sweep serves each cell from the hull of its own row's or column's
        // cell centres (no delay, see makeGeometry), which answers every point on a centre.
        if (geo.delay == 0 && p.dc == std::round(p.dc) && p.dr == std::round(p.dr)) continue;
        p.invDistance = static_cast<float>(1.0 / d);
        p.drop = static_cast<float>(0.5 * d * invR);
        const double c0 = std::floor(p.dc), r0 = std::floor(p.dr);
        const double fx = p.dc - c0, fy = p.dr - r0;
        const double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        int n = 0;
        for (int t = 0; t < 4; ++t) {
            if (!(w[t] > 0.0)) continue;
            p.tapCol[n] = static_cast<long>(c0) + (t & 1);
            p.tapRow[n] = static_cast<long>(r0) + (t >> 1);
            p.weight[n] = static_cast<float>(w[t]);
            ++n;
        }
        for (int t = n; t < 4; ++t) {
            p.tapCol[t] = p.tapCol[0];
            p.tapRow[t] = p.tapRow[0];
            p.weight[t] = 0.0f;
        }
        p.taps = n <= 2 ? 2 : 4;
        out.push_back(p);
    }
}

/// The near-field slope of one cell whose stencil reaches beyond the terrain (the DEM's edge):
/// the reference's rule at each point, heights clamped to the full grid's
/// outer cell centres, nodata taps dropped and the rest reweighted, the march ending where the
/// ray leaves the full grid. (col, row) are on the full grid; taps beyond the terrain count as
/// nodata (a served cell's halo holds every point within its search distance).
/// Points for which skip(q) holds are left out (the caller has them, see nearFieldRow).
template <class Skip>
float nearFieldAt(const Terrain& t, const FullGridRef& g, const CellWindow& cells, std::size_t col, std::size_t row,
                  const std::vector<NearPoint>& stencil, const Skip& skip) {
    const float h0 = t.heightsM(col - cells.col0, row - cells.row0);
    const double maxX = static_cast<double>(g.width) - 1, maxY = static_cast<double>(g.height) - 1;
    float best = -std::numeric_limits<float>::infinity();
    for (std::size_t q = 0; q < stencil.size(); ++q) {
        if (skip(q)) continue;
        const NearPoint& p = stencil[q];
        double x = static_cast<double>(col) + p.dc, y = static_cast<double>(row) + p.dr;
        if (x < -0.5 || x > maxX + 0.5 || y < -0.5 || y > maxY + 0.5) break;
        x = std::clamp(x, 0.0, maxX);
        y = std::clamp(y, 0.0, maxY);
        const auto c0 = static_cast<std::size_t>(x), r0 = static_cast<std::size_t>(y);
        const std::size_t c1 = std::min(c0 + 1, g.width - 1), r1 = std::min(r0 + 1, g.height - 1);
        const double fx = x - static_cast<double>(c0), fy = y - static_cast<double>(r0);
        const double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        const std::size_t tc[4] = {c0, c1, c0, c1}, tr[4] = {r0, r0, r1, r1};
        double sum = 0, weight = 0;
        for (int k = 0; k < 4; ++k) {
            if (!(w[k] > 0.0) || tc[k] < cells.col0 || tc[k] >= cells.col1 || tr[k] < cells.row0 ||
                tr[k] >= cells.row1)
                continue;
            const float v = t.heightsM(tc[k] - cells.col0, tr[k] - cells.row0);
            if (std::isnan(v)) continue;
            sum += w[k] * (static_cast<double>(v) - h0);
            weight += w[k];
        }
        if (!(weight > 0.0)) continue;
        best = std::max(best, static_cast<float>(sum / weight * p.invDistance - p.drop));
    }
    return best;
}

/// A stencil point's bilinear height relative to the cell's own, from the differences d of its
/// taps' heights to the cell's (fused multiply-adds in a fixed order; NaN where a tap is nodata).
/// Taps = 2 skips the zero-weight taps 2 and 3. Every fast pass below evaluates it thus.
template <int Taps>
DEMLIGHT_INLINE inline float nearPointRise(const float* w, float d0, float d1, float d2, float d3) {
    float v = w[0] * d0;
    v = std::fma(w[1], d1, v);
    if constexpr (Taps == 4) {
        v = std::fma(w[2], d2, v);
        v = std::fma(w[3], d3, v);
    }
    return v;
}

/// G consecutive stencil points p[0, G) with the same taps for cells [begin, end) of a row: each
/// point's slope max-ed into `best` in order, `flag` set where a tap is nodata (NaN). With G > 1
/// the taps' differences are taken once and `best` and `flag` read and written once for the G
/// (the quarter-cell points of a near field's first steps share a cell's four corners three or
/// four at a time); each point's operations are those of G = 1, so the bits are too. Inlined into
/// nearPointRow, which compiles it for each SimdPath.
template <int Taps, int G>
DEMLIGHT_INLINE inline void nearPointRowLoop(const float* __restrict h0, const float* __restrict t0,
                                             const float* __restrict t1, const float* __restrict t2,
                                             const float* __restrict t3, const NearPoint* p, float* __restrict best,
                                             std::uint8_t* __restrict flag, long begin, long end) {
    float w[G][4], invD[G], drop[G];
    for (int g = 0; g < G; ++g) {
        for (int k = 0; k < 4; ++k) w[g][k] = p[g].weight[k];
        invD[g] = p[g].invDistance;
        drop[g] = p[g].drop;
    }
    for (long i = begin; i < end; ++i) {
        const float h = h0[i];
        const float d0 = t0[i] - h, d1 = t1[i] - h;
        const float d2 = Taps == 4 ? t2[i] - h : 0.0f, d3 = Taps == 4 ? t3[i] - h : 0.0f;
        float b = best[i];
        bool nan = false;
        for (int g = 0; g < G; ++g) {
            const float v = nearPointRise<Taps>(w[g], d0, d1, d2, d3);
            const float slope = std::fma(v, invD[g], -drop[g]);
            nan |= v != v;
            b = slope > b ? slope : b;
        }
        flag[i] |= static_cast<std::uint8_t>(nan);
        best[i] = b;
    }
}

/// nearPointRowLoop on the widest SimdPath.
template <int Taps, int G = 1>
void nearPointRow(const float* h0, const float* t0, const float* t1, const float* t2, const float* t3,
                  const NearPoint* p, float* best, std::uint8_t* flag, long begin, long end) {
    onWidestPath([&]() DEMLIGHT_INLINE { nearPointRowLoop<Taps, G>(h0, t0, t1, t2, t3, p, best, flag, begin, end); });
}

/// Two consecutive stencil points with taps of their own (ta, tb) for cells [begin, end) of a
/// row: each as nearPointRow makes it, pa then pb (the same bits), the cell's height, `best` and
/// `flag` read and written once for the two. Most of a surface model's points are grid-line
/// crossings of two taps each, none sharing them. Inlined into nearPointPairRow.
template <int Taps>
DEMLIGHT_INLINE inline void nearPointPairRowLoop(const float* __restrict h0, const float* const* ta,
                                                 const float* const* tb, const NearPoint& pa, const NearPoint& pb,
                                                 float* __restrict best, std::uint8_t* __restrict flag, long begin,
                                                 long end) {
    const float* __restrict a0 = ta[0];
    const float* __restrict a1 = ta[1];
    const float* __restrict a2 = ta[2];
    const float* __restrict a3 = ta[3];
    const float* __restrict b0 = tb[0];
    const float* __restrict b1 = tb[1];
    const float* __restrict b2 = tb[2];
    const float* __restrict b3 = tb[3];
    const float* wa = pa.weight;
    const float* wb = pb.weight;
    for (long i = begin; i < end; ++i) {
        const float h = h0[i];
        const float va = nearPointRise<Taps>(wa, a0[i] - h, a1[i] - h, Taps == 4 ? a2[i] - h : 0.0f,
                                             Taps == 4 ? a3[i] - h : 0.0f);
        const float vb = nearPointRise<Taps>(wb, b0[i] - h, b1[i] - h, Taps == 4 ? b2[i] - h : 0.0f,
                                             Taps == 4 ? b3[i] - h : 0.0f);
        const float slopeA = std::fma(va, pa.invDistance, -pa.drop);
        const float slopeB = std::fma(vb, pb.invDistance, -pb.drop);
        float b = best[i];
        b = slopeA > b ? slopeA : b;
        b = slopeB > b ? slopeB : b;
        flag[i] |= static_cast<std::uint8_t>((va != va) | (vb != vb));
        best[i] = b;
    }
}

/// nearPointPairRowLoop on the widest SimdPath.
template <int Taps>
void nearPointPairRow(const float* h0, const float* const* ta, const float* const* tb, const NearPoint& pa,
                      const NearPoint& pb, float* best, std::uint8_t* flag, long begin, long end) {
    onWidestPath([&]() DEMLIGHT_INLINE { nearPointPairRowLoop<Taps>(h0, ta, tb, pa, pb, best, flag, begin, end); });
}

/// One stencil point for cells [begin, end) of a row by the reference's rule next to voids: the
/// taps that are valid heights, reweighted by their weights' sum (the same fused multiply-adds,
/// in the same order, as the scalar rule of nearFieldAt on taps inside the terrain), its slope
/// max-ed into `best` where any tap is valid. Branch-free, so it vectorises like nearPointRow;
/// inlined into nearPointRowReweighted.
template <int Taps>
DEMLIGHT_INLINE inline void nearPointRowReweightedLoop(const float* __restrict h0, const float* __restrict t0,
                                                       const float* __restrict t1, const float* __restrict t2,
                                                       const float* __restrict t3, const NearPoint& p,
                                                       float* __restrict best, long begin, long end) {
    const float w[4] = {p.weight[0], p.weight[1], p.weight[2], p.weight[3]};
    // A zero-weight tap (the padding of a point on a cell centre or a grid line) never counts.
    const bool used[4] = {w[0] > 0.0f, w[1] > 0.0f, w[2] > 0.0f, w[3] > 0.0f};
    const float invD = p.invDistance, drop = p.drop;
    for (long i = begin; i < end; ++i) {
        const float h = h0[i];
        const float d[4] = {t0[i] - h, t1[i] - h, Taps == 4 ? t2[i] - h : 0.0f, Taps == 4 ? t3[i] - h : 0.0f};
        float sum = 0.0f, weight = 0.0f;
        for (int k = 0; k < Taps; ++k) {
            const bool ok = used[k] && d[k] == d[k];  // a NaN tap (void) drops out
            sum = ok ? std::fma(w[k], d[k], sum) : sum;
            weight = ok ? weight + w[k] : weight;
        }
        const float slope = std::fma(sum / weight, invD, -drop);  // NaN where no tap counted
        best[i] = weight > 0.0f && slope > best[i] ? slope : best[i];
    }
}

/// nearPointRowReweightedLoop on the widest SimdPath.
template <int Taps>
void nearPointRowReweighted(const float* h0, const float* t0, const float* t1, const float* t2, const float* t3,
                            const NearPoint& p, float* best, long begin, long end) {
    onWidestPath([&]() DEMLIGHT_INLINE { nearPointRowReweightedLoop<Taps>(h0, t0, t1, t2, t3, p, best, begin, end); });
}

/// Near-field slopes of the window cells [w.col0, w.col1) of full-grid row `row` into `out`
/// (-inf where the near field holds no terrain). Each stencil point takes the vectorised loop
/// over the cells whose taps for it are valid heights inside the terrain (heights relative to
/// the cell's own, fused multiply-adds in a fixed order, so a cell gets the same bits whichever
/// tile it is in); cells next to voids take the reference's rule on the same taps, and the points
/// of cells near the DEM's edge whose taps leave it take nearFieldAt's.
void nearFieldRow(const Terrain& t, const FullGridRef& g, const CellWindow& cells, std::size_t row,
                  const CellWindow& w, RowSpan heights, const std::vector<NearPoint>& stencil,
                  std::vector<float>& out, std::vector<std::uint8_t>& bad) {
    const std::size_t cols = w.col1 - w.col0, W = t.width();
    const long colsL = static_cast<long>(cols);
    out.assign(cols, -std::numeric_limits<float>::infinity());
    bad.assign(cols, 0);
    // Per point, the window columns [begin, end) whose taps all lie inside the terrain (terrain
    // coordinates: col - cells.col0); the cells inside every point's range are [fastBegin, fastEnd).
    thread_local std::vector<std::pair<long, long>> ranges;
    ranges.resize(stencil.size());
    const long r = static_cast<long>(row - cells.row0);
    const long c0 = static_cast<long>(w.col0 - cells.col0);
    const float* H = t.heightsM.data();
    const float* h0 = H + static_cast<std::size_t>(r) * W + static_cast<std::size_t>(c0);
    // Nodata cells have no horizon (the combine keeps their NaN whatever the near field is): the
    // ranges leave out the row's runs of them at both ends, `heights` (window columns). The
    // valid cells keep their ranges, and so their points and edge rules.
    const auto valid0 = static_cast<long>(heights.first), valid1 = static_cast<long>(heights.end);
    long fastBegin = 0, fastEnd = colsL;
    for (std::size_t q = 0; q < stencil.size(); ++q) {
        const NearPoint& p = stencil[q];
        const long dcMin = *std::min_element(p.tapCol, p.tapCol + 4), dcMax = *std::max_element(p.tapCol, p.tapCol + 4);
        const long drMin = *std::min_element(p.tapRow, p.tapRow + 4), drMax = *std::max_element(p.tapRow, p.tapRow + 4);
        const bool rowsInside = r + drMin >= 0 && r + drMax < static_cast<long>(t.height());
        const long begin = rowsInside ? std::clamp(-dcMin - c0, valid0, valid1) : valid1;
        const long end = rowsInside ? std::clamp(static_cast<long>(W) - dcMax - c0, begin, valid1) : begin;
        ranges[q] = {begin, end};
        fastBegin = std::max(fastBegin, begin);
        fastEnd = std::min(fastEnd, end);
    }
    fastEnd = std::max(fastEnd, fastBegin);
    float* __restrict best = out.data();
    std::uint8_t* __restrict flag = bad.data();
    // Runs `pass` for point p with its taps' rows and its tap count as a constant (on a grid line
    // the taps with weight are the first two).
    const auto tapsOf = [&](const NearPoint& p, const float** tap) {
        for (int k = 0; k < 4; ++k) tap[k] = h0 + p.tapRow[k] * static_cast<long>(W) + p.tapCol[k];
    };
    const auto pointPass = [&](const NearPoint& p, auto&& pass) {
        const float* tap[4];
        tapsOf(p, tap);
        if (p.taps == 2) {
            pass(std::integral_constant<int, 2>{}, tap);
        } else {
            pass(std::integral_constant<int, 4>{}, tap);
        }
    };
    // Consecutive points with the same taps (and so the same range) in one pass, up to four.
    const auto sameTaps = [](const NearPoint& a, const NearPoint& b) {
        if (a.taps != b.taps) return false;
        for (int k = 0; k < a.taps; ++k) {
            if (a.tapCol[k] != b.tapCol[k] || a.tapRow[k] != b.tapRow[k]) return false;
        }
        return true;
    };
    const auto groupEnd = [&](std::size_t q) {
        std::size_t next = q + 1;
        while (next < stencil.size() && next - q < 4 && sameTaps(stencil[q], stencil[next])) ++next;
        return next;
    };
    for (std::size_t q = 0, next = 0; q < stencil.size(); q = next) {
        next = groupEnd(q);
        // Plain names, not a structured binding: clang 14 (the sanitizer build) cannot capture one.
        const long begin = ranges[q].first;
        const long end = ranges[q].second;
        const NearPoint& p = stencil[q];
        const std::size_t group = next - q;
        // A point alone, followed by another alone with as many taps: the two in one pass where
        // both ranges hold the cell, each alone on the rest of its range (in the same order).
        if (group == 1 && next < stencil.size() && groupEnd(next) == next + 1 && stencil[next].taps == p.taps) {
            const NearPoint& pb = stencil[next];
            const long beginB = ranges[next].first, endB = ranges[next].second;
            const long both0 = std::max(begin, beginB), both1 = std::max(both0, std::min(end, endB));
            // One point alone on [b0, b1).
            const auto single = [&](const NearPoint& pt, long b0, long b1) {
                if (b0 >= b1) return;
                pointPass(pt, [&](auto taps, const float* const* tap) {
                    nearPointRow<decltype(taps)::value>(h0, tap[0], tap[1], tap[2], tap[3], &pt, best, flag, b0, b1);
                });
            };
            // Cells before the shared range, then the shared range, then after it: a cell's
            // points still come a then b.
            single(p, begin, std::min(end, both0));
            single(pb, beginB, std::min(endB, both0));
            if (both0 < both1) {
                const float* ta[4];
                const float* tb[4];
                tapsOf(p, ta);
                tapsOf(pb, tb);
                if (p.taps == 2) {
                    nearPointPairRow<2>(h0, ta, tb, p, pb, best, flag, both0, both1);
                } else {
                    nearPointPairRow<4>(h0, ta, tb, p, pb, best, flag, both0, both1);
                }
            }
            single(p, std::max(begin, both1), end);
            single(pb, std::max(beginB, both1), endB);
            next = next + 1;
            continue;
        }
        if (begin >= end) continue;
        pointPass(p, [&](auto taps, const float* const* tap) {
            constexpr int kTaps = decltype(taps)::value;
            switch (group) {
            case 1: nearPointRow<kTaps>(h0, tap[0], tap[1], tap[2], tap[3], &p, best, flag, begin, end); break;
            case 2: nearPointRow<kTaps, 2>(h0, tap[0], tap[1], tap[2], tap[3], &p, best, flag, begin, end); break;
            case 3: nearPointRow<kTaps, 3>(h0, tap[0], tap[1], tap[2], tap[3], &p, best, flag, begin, end); break;
            default: nearPointRow<kTaps, 4>(h0, tap[0], tap[1], tap[2], tap[3], &p, best, flag, begin, end); break;
            }
        });
    }
    // Cells inside every point's range with a void among their taps: every point again by the
    // reference's rule, vectorised over runs of such cells (a run bridges up to kRunGap unflagged
    // cells, whose values it does not use). A nodata cell is flagged by its own height; it has
    // no horizon, so it is no part of a run.
    for (long i = fastBegin; i < fastEnd; ++i) flag[i] = flag[i] && h0[i] == h0[i];
    thread_local std::vector<float> reweighted;
    reweighted.resize(cols);
    float* __restrict rwBest = reweighted.data();
    constexpr long kRunGap = 16;
    for (long i = fastBegin; i < fastEnd; ++i) {
        // Most cells have no void among their taps: skip their flags eight at a time (a flag at a
        // time cost the dune-edge surface model's near field 1.48 -> 1.57x at 37 deg, measured).
        for (std::uint64_t eight; i + 8 <= fastEnd && (std::memcpy(&eight, flag + i, 8), eight == 0);) i += 8;
        if (i == fastEnd) break;  // flag[fastEnd] is an edge cell's (or past the row)
        if (!flag[i]) continue;
        long last = i;
        for (long c = i + 1; c < fastEnd && c - last <= kRunGap; ++c) {
            if (flag[c]) last = c;
        }
        const long runEnd = last + 1;
        std::fill(rwBest + i, rwBest + runEnd, -std::numeric_limits<float>::infinity());
        for (const NearPoint& p : stencil) {
            pointPass(p, [&](auto taps, const float* const* tap) {
                nearPointRowReweighted<decltype(taps)::value>(h0, tap[0], tap[1], tap[2], tap[3], p, rwBest, i, runEnd);
            });
        }
        for (long c = i; c < runEnd; ++c) {
            if (flag[c]) out[static_cast<std::size_t>(c)] = rwBest[c];
        }
        i = last;
    }
    // The cells outside [fastBegin, fastEnd), near the DEM's edge: the points whose taps leave
    // the terrain by the reference's rule (clamped, ending where the ray leaves the grid), the
    // others as taken above; next to a void, every point by that rule.
    const auto edgeCell = [&](long i) {
        if (std::isnan(h0[i])) return;  // nodata: no horizon
        const std::size_t col = w.col0 + static_cast<std::size_t>(i);
        const std::size_t at = static_cast<std::size_t>(i);
        if (flag[i]) {
            out[at] = nearFieldAt(t, g, cells, col, row, stencil, [](std::size_t) { return false; });
        } else {
            const float edge = nearFieldAt(t, g, cells, col, row, stencil, [&](std::size_t q) {
                return i >= ranges[q].first && i < ranges[q].second;
            });
            out[at] = edge > out[at] ? edge : out[at];
        }
    };
    for (long i = 0; i < fastBegin; ++i) edgeCell(i);
    for (long i = fastEnd; i < colsL; ++i) edgeCell(i);
}

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

}  // namespace

double inverseEffectiveRadius(const HorizonParams& params) {
    return params.curvature ? (1.0 - params.refraction) / kEarthRadiusM : 0.0;
}

void validateHorizonParams(const Terrain& terrain, const HorizonParams& p) {
    if (terrain.heightsM.empty()) throw Error("horizon: the terrain has no cells");
    if (terrain.cellWidthM.size() != terrain.height() || terrain.cellHeightM.size() != terrain.height())
        throw Error("horizon: terrain cell sizes must have one entry per row");
    for (std::size_t r = 0; r < terrain.height(); ++r) {
        if (!(terrain.cellWidthM[r] > 0.0) || !(terrain.cellHeightM[r] > 0.0) ||
            !std::isfinite(terrain.cellWidthM[r]) || !std::isfinite(terrain.cellHeightM[r]))
            throw Error("horizon: terrain cell sizes must be positive and finite (row " +
                        std::to_string(r) + ")");
    }
    if (!std::isfinite(p.azimuthDeg))
        throw Error("horizon: azimuth must be a finite number of degrees, got " + std::to_string(p.azimuthDeg));
    if (!(p.maxDistanceM > 0.0))
        throw Error("horizon: max distance must be > 0 metres, got " + std::to_string(p.maxDistanceM));
    if (!(p.refraction >= 0.0 && p.refraction < 1.0))
        throw Error("horizon: refraction coefficient must be in [0, 1), got " + std::to_string(p.refraction));
    if (!(p.directionToleranceFloorDeg >= 0.0))
        throw Error("horizon: direction tolerance floor must be >= 0 degrees, got " +
                    std::to_string(p.directionToleranceFloorDeg));
    if (!(p.directionToleranceDeg >= 0.0))
        throw Error("horizon: direction tolerance must be >= 0 degrees (0 = automatic), got " +
                    std::to_string(p.directionToleranceDeg));
    if (p.nearFieldSteps < 0 || p.nearFieldSteps > kMaxNearFieldSteps)
        throw Error("horizon: near field must be 0 to " + std::to_string(kMaxNearFieldSteps) + " steps, got " +
                    std::to_string(p.nearFieldSteps));
    if (p.window) {
        const CellWindow& w = *p.window;
        if (w.col0 >= w.col1 || w.row0 >= w.row1 || w.col1 > terrain.width() || w.row1 > terrain.height())
            throw Error("horizon: window must be a non-empty part of the " + std::to_string(terrain.width()) +
                        " x " + std::to_string(terrain.height()) + " grid");
    }
}

ReliefSearch reliefSearch(const Terrain& terrain, double elevationDeg) {
    const FullGridRef g = fullGrid(terrain);  // a tile's search is its DEM's
    const auto [lo, hi] = g.heightRangeM();
    ReliefSearch s;
    s.reliefM = lo <= hi ? static_cast<double>(hi - lo) : 0.0;  // no valid height: nothing occludes
    s.byReliefM = s.reliefM / std::tan(elevationDeg * kDegToRad);
    const double diagonal = diagonalM(g);
    s.wholeDem = s.byReliefM >= kWholeDemShareOfDiagonal * diagonal;
    s.distanceM = std::max(g.minCellM(), s.wholeDem ? diagonal : s.byReliefM);
    return s;
}

double defaultMaxDistanceM(const Terrain& terrain) {
    const auto [lo, hi] = fullGrid(terrain).heightRangeM();
    if (lo > hi) throw Error("horizon: the DEM has no valid heights");
    return reliefSearch(terrain, kDefaultLowestElevationDeg).distanceM;
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
    std::vector<SweepRegion> regions = fullGridRegions(terrain, params);
    const FullGridRef g = fullGrid(terrain);
    for (SweepRegion& r : regions)
        r.window = {r.window.col0 - g.col0, r.window.row0 - g.row0, r.window.col1 - g.col0, r.window.row1 - g.row0};
    return regions;
}

HorizonMap sweepHorizon(const Terrain& terrain, const HorizonParams& params, ProgressCounter* progress) {
    HorizonMap out;
    SweepBuffers buffers;
    sweepHorizonInto(terrain, params, out, buffers, progress);
    return out;
}

std::size_t sweepHorizonInto(const Terrain& terrain, const HorizonParams& params, HorizonMap& out,
                             SweepBuffers& buffers, ProgressCounter* progress) {
    const std::vector<SweepRegion> regions = fullGridRegions(terrain, params);
    const FullGridRef full = fullGrid(terrain);
    const CellWindow cells = cellsOnFullGrid(terrain);
    const double invR = inverseEffectiveRadius(params);
    const int threads = resolveThreadCount(params.threads);
    // Eight lines at once on the AVX-512 path (the portable one serves one line at a time).
    const bool eightAtOnce = simdPath() == SimdPath::Avx512;

    // Reused grids are refilled in place, by rows in parallel (no fresh pages to fault in).
    const auto reset = [&](auto& grid, auto fill) {
        if (grid.width() == terrain.width() && grid.height() == terrain.height()) {
            parallelFor(0, grid.height(), threads, [&](std::size_t row) {
                std::fill_n(grid.rowPtr(row), grid.width(), fill);
            }, 64);
        } else {
            grid = std::remove_reference_t<decltype(grid)>(terrain.width(), terrain.height(), fill);
        }
    };
    reset(out.angleDeg, std::numeric_limits<float>::quiet_NaN());
    if (params.truncationFlags) {
        reset(out.truncated, std::uint8_t{0});
    } else {
        out.truncated = Grid<std::uint8_t>();
    }
    // NaN until written, so a cell no line served would show up as NaN in the tests. Plane B is
    // read only where two lines serve a cell.
    Grid<float>& planeB = buffers.planeB;
    if (!params.nearestLine) reset(planeB, std::numeric_limits<float>::quiet_NaN());

    for (const SweepRegion& region : regions) {
        const LineGeometry geo = makeGeometry(full, cells, region, params.maxDistanceM, params.nearestLine,
                                              params.nearFieldSteps, params.farFieldCrossings);
        const long nLines = geo.kLast - geo.kFirst + 1;
        const std::size_t nBlocks = static_cast<std::size_t>((nLines + static_cast<long>(kLinesPerBlock) - 1) /
                                                             static_cast<long>(kLinesPerBlock));
        const CellWindow& w = region.window;
        const ValidCells valid(terrain, geo.xMajor, threads, buffers.validBits[geo.xMajor ? 0 : 1]);
        // The walk eight lines at once where it only pushes: cells served after it (delay > 0), no
        // crossing points between steps (they push too); a range limit's chunks and logs keep
        // it line by line (tried: slower, docs/performance.md).
        const bool lanes = kLanesWalk && eightAtOnce && geo.delay > 0 && !geo.crossings;
        // Every served cell of plane A is written; plane B only where frac > 0, read only there.
        parallelFor(0, nBlocks, threads, [&](std::size_t blockIndex) {
            if (progress && progress->cancelled()) return;
            thread_local std::vector<HullPoint> scratch;
            thread_local RangeLog logs[kLinesPerBlock];
            const long kBegin = geo.kFirst + static_cast<long>(blockIndex * kLinesPerBlock);
            const long kEnd = std::min(kBegin + static_cast<long>(kLinesPerBlock), geo.kLast + 1);
            const auto run = [&]<bool XMajor, bool Limited, bool Lanes>() {
                sweepBlock<XMajor, Limited, Lanes>(terrain, geo, invR, params.maxDistanceM, kBegin, kEnd,
                                                   out.angleDeg.data(), planeB.data(), scratch, logs, valid,
                                                   eightAtOnce);
            };
            // A range limit longer than every line (the whole DEM searched) changes nothing.
            const bool limited = std::isfinite(params.maxDistanceM) && params.maxDistanceM <= geo.spanBoundM;
            if (limited) {
                geo.xMajor ? run.template operator()<true, true, false>() : run.template operator()<false, true, false>();
            } else if (lanes) {
                geo.xMajor ? run.template operator()<true, false, true>() : run.template operator()<false, false, true>();
            } else {
                geo.xMajor ? run.template operator()<true, false, false>()
                           : run.template operator()<false, false, false>();
            }
        });
        if (progress) progress->throwIfCancelled();
        parallelFor(w.row0, w.row1, threads, [&](std::size_t row) {
            combineRow(geo, terrain, full, params.maxDistanceM, invR, row, w, cells, out.angleDeg.data(), planeB.data(),
                       params.truncationFlags ? out.truncated.data() : nullptr);
        }, 16);
        if (progress) {
            progress->advance((w.col1 - w.col0) * (w.row1 - w.row0));
            progress->throwIfCancelled();
        }
    }
    return regions.size();
}

}  // namespace demlight
