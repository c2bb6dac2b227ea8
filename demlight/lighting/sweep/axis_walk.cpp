// The walk of a block of lines along a grid axis (demlight/lighting/sweep/axis_walk.h).
#include "demlight/lighting/sweep/axis_walk.h"

#include "demlight/lighting/hull_lanes.h"
#include "demlight/lighting/sweep/walk.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace demlight::sweep {
namespace {

/// The block's walk on the major axis: from the far end of the terrain (no range limit, so every
/// line starts there, in a tile as in its DEM) to the nearest window step; window steps start
/// firstServed steps in.
struct AxisSteps {
    long mStart, mStep;
    std::size_t n, firstServed;
};

AxisSteps axisSteps(const LineGeometry& geo) {
    const long win0 = static_cast<long>(geo.majorWin0), win1 = static_cast<long>(geo.majorWin1);
    const long serveFar = geo.farSign > 0 ? win1 - 1 : win0;
    const long serveNear = geo.farSign > 0 ? win0 : win1 - 1;
    const long mStart = geo.mFar;
    return {mStart, -geo.farSign, static_cast<std::size_t>(std::abs(serveNear - mStart)) + 1,
            static_cast<std::size_t>(std::abs(serveFar - mStart))};
}

struct AxisScratch {
    HullGeometry geometry;
    HullScratch hull;
    std::vector<float> heights, slopes;  // a transposed block: sample i of line b at [i * 16 + b]
};

}  // namespace

bool axisKernelServes(const LineGeometry& geo, bool limited) {
    // The kernel counts rows in exact floats.
    return geo.slope == 0.0 && geo.delay == 0 && !limited && geo.majorSize < (std::size_t{1} << 24);
}

void walkAxisBlock(const Terrain& t, const LineGeometry& geo, double invR, long kBegin, long kEnd, float* planeA) {
    // On an axis line k runs through the cells of minor index k and serves only those.
    const long j0 = std::max({kBegin, static_cast<long>(geo.minorWin0), geo.minorLo});
    const long j1 = std::min({kEnd, static_cast<long>(geo.minorWin1), geo.minorHi});
    if (j0 >= j1) return;
    thread_local AxisScratch s;
    const AxisSteps steps = axisSteps(geo);
    const auto lines = static_cast<std::size_t>(j1 - j0);
    const std::ptrdiff_t W = static_cast<std::ptrdiff_t>(t.width());
    const float* H = t.heightsM.data();
    HullGeometry& g = s.geometry;
    g.invRadius = invR;
    g.sigmaM.resize(steps.n);
    if (!geo.xMajor) {
        // Lines along columns: the rows' distances from the far edge (the same for every line),
        // counted from the walk's first row; heights and slopes in place, a row apart.
        g.lineScale.clear();
        // Counted in the full grid's mean step, whatever part of it this walk covers.
        g.spacingM = (geo.sigmaAt[static_cast<std::size_t>(geo.mEdge == 0 ? geo.majorSize - 1 : 0)] -
                      geo.sigmaAt[static_cast<std::size_t>(geo.mEdge)]) /
                     static_cast<double>(std::max<std::size_t>(geo.majorSize - 1, 1));
        const double sigma0 = geo.sigmaAt[static_cast<std::size_t>(steps.mStart)];
        for (std::size_t i = 0; i < steps.n; ++i)
            g.sigmaM[i] = geo.sigmaAt[static_cast<std::size_t>(steps.mStart + static_cast<long>(i) * steps.mStep)] - sigma0;
        const std::ptrdiff_t first = (steps.mStart - geo.majorLo) * W + (j0 - geo.minorLo);
        HullBlock block{H + first, planeA + first, 0, lines};
        block.heightsRowStep = block.outRowStep = steps.mStep * W;
        block.firstOutRow = steps.firstServed;
        hullSlopes(g, block, s.hull);
        return;
    }
    // Lines along rows: each row its own step (a geographic grid's cell width), through a copy of
    // the block with the lines side by side.
    g.lineScale.resize(lines);
    g.spacingM = 0.0;
    for (std::size_t i = 0; i < steps.n; ++i) g.sigmaM[i] = static_cast<double>(i);
    for (std::size_t b = 0; b < lines; ++b) g.lineScale[b] = geo.stepLengthM[static_cast<std::size_t>(j0) + b];
    s.heights.resize(steps.n * kLinesPerBlock);
    s.slopes.resize(steps.n * kLinesPerBlock);
    const std::ptrdiff_t startCol = steps.mStart - geo.majorLo;
    const float* rows[kLinesPerBlock];
    for (std::size_t b = 0; b < lines; ++b) rows[b] = H + (j0 - geo.minorLo + static_cast<long>(b)) * W + startCol;
    // A sample of every line at a time: one cache line written whole, the rows read in step.
    for (std::size_t i = 0; i < steps.n; ++i) {
        const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(i) * steps.mStep;
        for (std::size_t b = 0; b < lines; ++b) s.heights[i * kLinesPerBlock + b] = rows[b][at];
    }
    HullBlock block{s.heights.data(), s.slopes.data(), kLinesPerBlock, lines};
    block.firstOutRow = steps.firstServed;
    hullSlopes(g, block, s.hull);
    float* outRows[kLinesPerBlock];
    for (std::size_t b = 0; b < lines; ++b) outRows[b] = planeA + (rows[b] - H);
    for (std::size_t i = steps.firstServed; i < steps.n; ++i) {
        const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(i) * steps.mStep;
        // Nodata cells keep what they hold (NaN), as the walk of lines one by one leaves them.
        for (std::size_t b = 0; b < lines; ++b)
            if (rows[b][at] == rows[b][at]) outRows[b][at] = s.slopes[i * kLinesPerBlock + b];
    }
}

}  // namespace demlight::sweep
