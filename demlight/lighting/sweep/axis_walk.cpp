// The walk of a block of lines along a grid axis (demlight/lighting/sweep/axis_walk.h).
#include "demlight/lighting/sweep/axis_walk.h"

#include "demlight/lighting/hull_lanes.h"
#include "demlight/lighting/sweep/hull.h"
#include "demlight/lighting/sweep/walk.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace demlight::sweep {
namespace {

/// The block's walk on the major axis to the nearest window step; window steps start firstServed
/// steps in. Without a range limit from the far end of the terrain (every line starts there, in
/// a tile as in its DEM); with one from extensionSteps beyond the farthest window step (which
/// covers maxDistanceM), as the walk of lines one by one starts.
struct AxisSteps {
    long mStart, mStep;
    std::size_t n, firstServed;
};

AxisSteps axisSteps(const LineGeometry& geo, bool limited) {
    const long win0 = static_cast<long>(geo.majorWin0), win1 = static_cast<long>(geo.majorWin1);
    const long serveFar = geo.farSign > 0 ? win1 - 1 : win0;
    const long serveNear = geo.farSign > 0 ? win0 : win1 - 1;
    const long mStart = limited ? std::clamp(serveFar + geo.farSign * geo.extensionSteps, std::min(geo.mFar, geo.mNear),
                                             std::max(geo.mFar, geo.mNear))
                                : geo.mFar;
    return {mStart, -geo.farSign, static_cast<std::size_t>(std::abs(serveNear - mStart)) + 1,
            static_cast<std::size_t>(std::abs(serveFar - mStart))};
}

struct AxisScratch {
    HullGeometry geometry;
    HullScratch hull;
    std::vector<float> heights, slopes;  // a transposed block: sample i of line b at [i * 16 + b]
    std::vector<std::size_t> starts[kLinesPerBlock];  // each line's chunk starts (walk steps)
    std::vector<long> chunks[kLinesPerBlock];         // and their chunks
    std::vector<HullPoint> prevHull[kLinesPerBlock];
    std::vector<double> stepSigma;
};

/// The block's samples: sample i of line b (window minor index j0 + b) at heights[i * step + b],
/// its slope at out[i * step + b]; lines along columns in place, along rows a transposed copy.
struct AxisLanes {
    const float* heights;
    float* out;
    std::ptrdiff_t step;
    long j0;
};

/// Distance from the full grid's far edge of line j's sample at major index m, with the bits the
/// walk of lines one by one gives it (line_geometry.h: sigmaAt, else a row's own steps).
double sampleSigma(const LineGeometry& geo, long m, long j) {
    if (!geo.sigmaAt.empty()) return geo.sigmaAt[static_cast<std::size_t>(m)];
    return static_cast<double>(std::abs(m - geo.mEdge)) * geo.stepLengthM[static_cast<std::size_t>(j)];
}

/// Line j's range-limit chunks over the walk (floor(sigma / L), anchored to the full grid's far
/// edge as the walk of lines one by one cuts them): the walk steps where each starts, and its
/// chunk. Found by bisection (sigma grows along the walk).
void chunkStarts(const LineGeometry& geo, const AxisSteps& steps, long j, double maxDistanceM,
                 std::vector<std::size_t>& starts, std::vector<long>& chunks) {
    const auto chunkAt = [&](std::size_t i) {
        return static_cast<long>(std::floor(
            sampleSigma(geo, steps.mStart + static_cast<long>(i) * steps.mStep, j) / maxDistanceM));
    };
    starts.assign(1, 0);
    chunks.assign(1, chunkAt(0));
    const long last = chunkAt(steps.n - 1);
    while (chunks.back() < last) {
        std::size_t lo = starts.back() + 1, hi = steps.n - 1;  // first step of a later chunk in [lo, hi]
        while (lo < hi) {
            const std::size_t mid = (lo + hi) / 2;
            if (chunkAt(mid) > chunks.back()) hi = mid; else lo = mid + 1;
        }
        starts.push_back(lo);
        chunks.push_back(chunkAt(lo));
    }
}

/// The kernel over lines [b0, b1) of the block from walk step `start` (a chunk's first) to `end`:
/// each sample's slope to the hull of its chunk's samples before it.
void kernelSegment(const LineGeometry& geo, const AxisSteps& steps, const AxisLanes& lanes,
                   std::size_t b0, std::size_t b1, std::size_t start, std::size_t end, AxisScratch& s) {
    HullGeometry& g = s.geometry;
    const std::size_t n = end - start;
    g.sigmaM.resize(n);
    if (!geo.xMajor) {
        g.lineScale.clear();
        g.spacingM = (geo.sigmaAt[static_cast<std::size_t>(geo.mEdge == 0 ? geo.majorSize - 1 : 0)] -
                      geo.sigmaAt[static_cast<std::size_t>(geo.mEdge)]) /
                     static_cast<double>(std::max<std::size_t>(geo.majorSize - 1, 1));
        const long m0 = steps.mStart + static_cast<long>(start) * steps.mStep;
        const double sigma0 = geo.sigmaAt[static_cast<std::size_t>(m0)];
        for (std::size_t i = 0; i < n; ++i)
            g.sigmaM[i] = geo.sigmaAt[static_cast<std::size_t>(m0 + static_cast<long>(i) * steps.mStep)] - sigma0;
    } else {
        g.spacingM = 0.0;
        for (std::size_t i = 0; i < n; ++i) g.sigmaM[i] = static_cast<double>(i);
        g.lineScale.resize(b1 - b0);
        for (std::size_t b = b0; b < b1; ++b)
            g.lineScale[b - b0] = geo.stepLengthM[static_cast<std::size_t>(lanes.j0) + b];
    }
    const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(start) * lanes.step + static_cast<std::ptrdiff_t>(b0);
    HullBlock block{lanes.heights + at, lanes.out + at, kLinesPerBlock, b1 - b0};
    block.heightsRowStep = block.outRowStep = lanes.step;
    block.firstOutRow = steps.firstServed > start ? steps.firstServed - start : 0;
    hullSlopes(g, block, s.hull);
}

/// The previous chunk's part of the range limit for lines [b0, b1) and the cells of the chunk
/// from walk step `start` to `end`, whose previous chunk starts at `prevStart`: each cell's slope
/// is raised to the steepest to a previous-chunk sample within maxDistanceM. As limitRangePass
/// does it: walking the cells near to far, the samples in range grow at their far end, so an
/// upper hull grown in that order holds exactly them, whatever step the walk started at (a
/// tile's and its DEM's agree), and a binary search finds the tangent. A cell is skipped where
/// the highest sample of the chunk (as far as walked) at the distance that makes it steepest
/// cannot beat its slope, before the hull is grown to it (most cells: the hull grows only as far
/// as the cells that need it); then the same test with the samples in range.
void prevChunkPart(const LineGeometry& geo, const AxisSteps& steps, const AxisLanes& lanes, std::size_t b0,
                   std::size_t b1, std::size_t prevStart, std::size_t start, std::size_t end, double maxDistanceM,
                   double invR, AxisScratch& s) {
    const double halfInvR = 0.5 * invR;
    const std::size_t first = std::max(start, steps.firstServed);
    // Distances of the steps [prevStart, end): one table for lines along columns, else each
    // line's own step times the steps from the edge (sampleSigma's bits either way).
    const bool shared = !geo.sigmaAt.empty();
    s.stepSigma.resize(end);
    for (std::size_t i = prevStart; i < end; ++i) {
        const long m = steps.mStart + static_cast<long>(i) * steps.mStep;
        s.stepSigma[i] = shared ? geo.sigmaAt[static_cast<std::size_t>(m)] : static_cast<double>(std::abs(m - geo.mEdge));
    }
    const double* stepSigma = s.stepSigma.data();
    struct Grown {
        std::size_t next, top;
        double maxG;
    };
    Grown grown[kLinesPerBlock];
    // Per line: its step factor, the highest g of the chunk's walked samples, and the distances
    // of its nearest and farthest walked samples' steps.
    alignas(64) double scale[kLinesPerBlock], maxGChunk[kLinesPerBlock], sNear[kLinesPerBlock], sFar[kLinesPerBlock];
    const std::size_t nb = b1 - b0;
    for (std::size_t b = 0; b < nb; ++b) {
        scale[b] = shared ? 1.0 : geo.stepLengthM[static_cast<std::size_t>(lanes.j0) + b0 + b];
        maxGChunk[b] = -std::numeric_limits<double>::infinity();
        sNear[b] = stepSigma[start - 1] * scale[b];
        sFar[b] = stepSigma[prevStart] * scale[b];
        grown[b] = {start, 0, -std::numeric_limits<double>::infinity()};
        if (s.prevHull[b].size() < start - prevStart) s.prevHull[b].resize(start - prevStart);
    }
    for (std::size_t p = prevStart; p < start; ++p) {
        const float* hp = lanes.heights + static_cast<std::ptrdiff_t>(p) * lanes.step + static_cast<std::ptrdiff_t>(b0);
        for (std::size_t b = 0; b < nb; ++b) {
            const double sigmaP = stepSigma[p] * scale[b];
            // (NaN at nodata: the comparison keeps the maximum.)
            maxGChunk[b] = std::max(maxGChunk[b], static_cast<double>(hp[b]) - sigmaP * sigmaP * halfInvR);
        }
    }
    bool anyPoint = false;
    for (std::size_t b = 0; b < nb; ++b) anyPoint = anyPoint || maxGChunk[b] > -std::numeric_limits<double>::infinity();
    if (!anyPoint) return;
    for (std::size_t i = end; i-- > first;) {
        const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(i) * lanes.step + static_cast<std::ptrdiff_t>(b0);
        const float* hc = lanes.heights + row;
        float* out = lanes.out + row;
        // The bound of the chunk's samples for every line at once: the highest g at the
        // distance that makes it steepest bounds every sample's slope; with a relative margin of
        // 1e-9 (far above the rounding of any order of these operations) below the cell's slope,
        // no sample can raise it (rangeSlope rounds to float, monotonically). Nodata cells and
        // lines without a sample in the chunk need nothing.
        alignas(64) unsigned char need[kLinesPerBlock];
        for (std::size_t b = 0; b < nb; ++b) {
            const double sigmaC = stepSigma[i] * scale[b];
            const double gCell = static_cast<double>(hc[b]) - sigmaC * sigmaC * halfInvR;
            const double rise = maxGChunk[b] - gCell;
            const double dist = sigmaC - (rise >= 0.0 ? sNear[b] : sFar[b]);
            const double bound = rise / dist - sigmaC * invR;
            const bool cannotRaise = bound + 1e-9 * std::abs(bound) < static_cast<double>(out[b]);
            need[b] = !cannotRaise && hc[b] == hc[b] && maxGChunk[b] > -std::numeric_limits<double>::infinity();
        }
        for (std::size_t b = 0; b < nb; ++b) {
            if (!need[b]) continue;
            Grown& gr = grown[b];
            const double sigmaC = stepSigma[i] * scale[b];
            const double gCell = static_cast<double>(hc[b]) - sigmaC * sigmaC * halfInvR;
            float& cell = out[b];
            const double limit = sigmaC - maxDistanceM;
            HullPoint* hull = s.prevHull[b].data();
            while (gr.next > prevStart) {
                const std::size_t p = gr.next - 1;
                const double sigmaP = stepSigma[p] * scale[b];
                if (sigmaP < limit) break;
                gr.next = p;
                const float hp = lanes.heights[static_cast<std::ptrdiff_t>(p) * lanes.step + static_cast<std::ptrdiff_t>(b0 + b)];
                if (std::isnan(hp)) continue;
                const HullPoint pt{sigmaP, static_cast<double>(hp) - sigmaP * sigmaP * halfInvR};
                gr.maxG = std::max(gr.maxG, pt.g);
                // Points arrive farther each time: keep right turns only.
                while (gr.top >= 2) {
                    const HullPoint& o = hull[gr.top - 2];
                    const HullPoint& a = hull[gr.top - 1];
                    if ((o.sigmaM - a.sigmaM) * (pt.g - o.g) - (a.g - o.g) * (o.sigmaM - pt.sigmaM) < 0.0) break;
                    --gr.top;
                }
                hull[gr.top++] = pt;
            }
            if (gr.top == 0) continue;
            const double rise = gr.maxG - gCell;
            const double boundDistM = sigmaC - (rise >= 0.0 ? hull[0].sigmaM : hull[gr.top - 1].sigmaM);
            if (static_cast<float>(rise / boundDistM - sigmaC * invR) <= cell) continue;
            std::size_t lo = 0, hi = gr.top - 1;
            while (lo < hi) {
                const std::size_t mid = (lo + hi) / 2;
                if (steeperFrom(hull[mid + 1], hull[mid], sigmaC, gCell)) lo = mid + 1; else hi = mid;
            }
            cell = std::max(cell, rangeSlope(hull[lo].g, hull[lo].sigmaM, gCell, sigmaC, invR));
        }
    }
}

/// The range-limited walk of lines [0, lines) of the block, chunk by chunk: each chunk through
/// the kernel, then its previous chunk's part. Lines along columns share their distances, so
/// their chunks; along rows of a geographic grid each line has its own, and the lines whose
/// chunk starts and ends at the same steps (most neighbours) go together.
void limitedLanes(const LineGeometry& geo, const AxisSteps& steps, const AxisLanes& lanes, std::size_t lines,
                  double maxDistanceM, double invR, AxisScratch& s) {
    const std::size_t own = geo.sigmaAt.empty() ? lines : 1;  // sets of chunks
    std::size_t cursor[kLinesPerBlock];
    for (std::size_t b = 0; b < own; ++b) {
        chunkStarts(geo, steps, lanes.j0 + static_cast<long>(b), maxDistanceM, s.starts[b], s.chunks[b]);
        cursor[b] = 0;
    }
    struct Segment {
        std::size_t start = 0, end = 0, prevStart = 0;
        bool present = false, previous = false;
        bool operator==(const Segment&) const = default;
    };
    for (;;) {
        // The nearest chunk not yet walked by some line.
        long chunk = std::numeric_limits<long>::max();
        for (std::size_t b = 0; b < own; ++b)
            if (cursor[b] < s.chunks[b].size()) chunk = std::min(chunk, s.chunks[b][cursor[b]]);
        if (chunk == std::numeric_limits<long>::max()) return;
        Segment seg[kLinesPerBlock];
        for (std::size_t b = 0; b < own; ++b) {
            const std::size_t k = cursor[b];
            if (k >= s.chunks[b].size() || s.chunks[b][k] != chunk) continue;
            seg[b].present = true;
            seg[b].start = s.starts[b][k];
            seg[b].end = k + 1 < s.starts[b].size() ? s.starts[b][k + 1] : steps.n;
            seg[b].previous = k > 0 && s.chunks[b][k - 1] == chunk - 1;
            seg[b].prevStart = k > 0 ? s.starts[b][k - 1] : 0;
            ++cursor[b];
        }
        for (std::size_t b0 = 0, b1; b0 < own; b0 = b1) {
            for (b1 = b0 + 1; b1 < own && seg[b1] == seg[b0];) ++b1;
            const Segment& g = seg[b0];
            if (!g.present || g.end <= steps.firstServed) continue;
            const std::size_t l0 = own == 1 ? 0 : b0, l1 = own == 1 ? lines : b1;
            kernelSegment(geo, steps, lanes, l0, l1, g.start, g.end, s);
            if (g.previous) prevChunkPart(geo, steps, lanes, l0, l1, g.prevStart, g.start, g.end, maxDistanceM, invR, s);
        }
    }
}

}  // namespace

bool axisKernelServes(const LineGeometry& geo) {
    // The kernel counts rows in exact floats.
    return geo.slope == 0.0 && geo.delay == 0 && geo.majorSize < (std::size_t{1} << 24);
}

void walkAxisBlock(const Terrain& t, const LineGeometry& geo, double invR, double maxDistanceM, bool limited,
                   long kBegin, long kEnd, float* planeA) {
    // On an axis line k runs through the cells of minor index k and serves only those.
    const long j0 = std::max({kBegin, static_cast<long>(geo.minorWin0), geo.minorLo});
    const long j1 = std::min({kEnd, static_cast<long>(geo.minorWin1), geo.minorHi});
    if (j0 >= j1) return;
    thread_local AxisScratch s;
    const AxisSteps steps = axisSteps(geo, limited);
    const auto lines = static_cast<std::size_t>(j1 - j0);
    const std::ptrdiff_t W = static_cast<std::ptrdiff_t>(t.width());
    const float* H = t.heightsM.data();
    HullGeometry& g = s.geometry;
    g.invRadius = invR;
    if (!geo.xMajor) {
        // Lines along columns: heights and slopes in place, a row apart.
        const std::ptrdiff_t first = (steps.mStart - geo.majorLo) * W + (j0 - geo.minorLo);
        const AxisLanes lanes{H + first, planeA + first, steps.mStep * W, j0};
        if (limited) return limitedLanes(geo, steps, lanes, lines, maxDistanceM, invR, s);
        // The rows' distances from the far edge (the same for every line), counted from the
        // walk's first row in the full grid's mean step, whatever part of it this walk covers.
        kernelSegment(geo, steps, lanes, 0, lines, 0, steps.n, s);
        return;
    }
    // Lines along rows: each row its own step (a geographic grid's cell width), through a copy of
    // the block with the lines side by side.
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
    const AxisLanes lanes{s.heights.data(), s.slopes.data(), kLinesPerBlock, j0};
    if (limited)
        limitedLanes(geo, steps, lanes, lines, maxDistanceM, invR, s);
    else
        kernelSegment(geo, steps, lanes, 0, lines, 0, steps.n, s);
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
