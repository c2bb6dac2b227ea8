// The walk of a block of scan lines (demlight/lighting/sweep/walk.h).
#include "demlight/lighting/sweep/walk.h"

#include "demlight/lighting/sweep/axis_walk.h"
#include "demlight/lighting/sweep/hull.h"
#include "demlight/lighting/sweep/lanes_avx512.h"
#include "demlight/core/simd.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace demlight::sweep {
namespace {

/// How many line steps ahead a block prefetches its heights and output cells (BlockWalk): a
/// step of a block costs about one memory latency
/// (docs/measurements.md#demlightlightingsweepwalkcpp-kprefetchsteps).
constexpr long kPrefetchSteps = 4;
constexpr long kFloatsPerCacheLine = 16;

/// The walk of one block of lines from the far end toward the observer, one member per stage of a
/// step. Limited: maxDistanceM is finite (chunks, logs and the second pass); an instantiation
/// each so the whole-DEM walk, which sky integrals run once per direction, carries none of that
/// code. Lanes: the walk takes eight lines at once (walkEightLines; the AVX-512 path, the whole
/// DEM, cells served after the walk, no crossing points), in instantiations of its own so that
/// the others compile as they did without it. eightAtOnce (the AVX-512 path) serves eight lines
/// at once where it can; false serves one line at a time.
template <bool XMajor, bool Limited, bool Lanes>
class BlockWalk {
public:
    BlockWalk(const Terrain& t, const LineGeometry& geo, double invR, double maxDistanceM, long kBegin, long kEnd,
              float* planeA, float* planeB, std::vector<HullPoint>& scratch, RangeLog* logs, const ValidCells& valid,
              bool eightAtOnce)
        : geo_(geo), H_(t.heightsM.data()), W_(t.width()), invR_(invR), halfInvR_(0.5 * invR),
          maxDistanceM_(maxDistanceM), kBegin_(kBegin), kEnd_(kEnd), planeA_(planeA), planeB_(planeB),
          scratch_(scratch), logs_(logs), valid_(valid), bitmap_(valid.used()), eightAtOnce_(eightAtOnce),
          nLines_(static_cast<std::size_t>(kEnd - kBegin)),
          // With a near field a line also takes a point where it crosses a grid line between steps.
          lineCapacity_((geo.delay > 0 ? 2 : 1) * (static_cast<std::size_t>(std::abs(geo.mFar - geo.mNear)) + 1)),
          N_(static_cast<long>(geo.minorSize)), mStep_(-geo.farSign), minorWin0_(static_cast<long>(geo.minorWin0)),
          minorWin1_(static_cast<long>(geo.minorWin1)), mLo_(geo.majorLo), nLo_(geo.minorLo), nHi_(geo.minorHi),
          sigmaTable_(!geo.sigmaAt.empty()), delay_(geo.delay) {
        if (scratch_.size() < nLines_ * lineCapacity_) scratch_.resize(nLines_ * lineCapacity_);
    }

    void run() {
        if (!findServedSteps()) return;
        startLines();
        // The cells within `delay` steps of the walk's start have no sample that far beyond them
        // (the walk starts at the DEM's far edge, or beyond every cell this block serves).
        bool served = false;
        for (long i = 0; delay_ > 0 && i < delay_ && !served; ++i) {
            serveDelayed(mStart_ + i * mStep_);
            served = mStart_ + i * mStep_ == mServeNear_;
        }
        for (long m = mStart_; !served; m += mStep_) {
            prefetch(m);
            walkStep(m);
            if (delay_ == 0) {
                served = m == mServeNear_;
            } else {
                serveDelayed(m + delay_ * mStep_);
                served = m + delay_ * mStep_ == mServeNear_;
            }
        }
        if (limited) {
            for (std::size_t b = 0; b < nLines_; ++b) limitRangePass(logs_[b], maxDistanceM_, invR_, scratch_);
        }
    }

private:
    static constexpr bool limited = Limited;

    std::size_t index(long m, long j) const {
        return XMajor ? static_cast<std::size_t>(j - nLo_) * W_ + static_cast<std::size_t>(m - mLo_)
                      : static_cast<std::size_t>(m - mLo_) * W_ + static_cast<std::size_t>(j - nLo_);
    }
    /// Whether any of minor indices j0..j1 at step m (clipped to the terrain) holds a height:
    /// from the bitmap where it is kept, else reading the heights until one is found.
    bool heightsAt(long m, long j0, long j1) const {
        j0 = std::max(j0, nLo_);
        j1 = std::min(j1, nHi_ - 1);
        if (bitmap_) return j0 <= j1 && valid_.any(m - mLo_, j0 - nLo_, j1 - nLo_);
        for (long j = j0; j <= j1; ++j)
            if (!std::isnan(H_[index(m, j)])) return true;
        return false;
    }
    /// The same where a wrong "yes" only costs time (serving, prefetching): without the bitmap,
    /// yes.
    bool mayHaveHeights(long m, long j0, long j1) const { return !bitmap_ || heightsAt(m, j0, j1); }

    /// A block serves window cells only where one of its lines is within a cell of the window's
    /// minor range; off-axis, in a region narrower than the DEM, that is a fraction of the
    /// window's major range. The walk goes from extensionSteps beyond the farthest such step
    /// (enough for maxDistanceM) to the nearest one, not over the whole region. False when the
    /// block serves no cell.
    bool findServedSteps() {
        for (long m = static_cast<long>(geo_.majorWin0); m < static_cast<long>(geo_.majorWin1); ++m) {
            const long base = geo_.base[static_cast<std::size_t>(m)];
            if (kBegin_ + base <= minorWin1_ - 1 && kEnd_ - 1 + base >= minorWin0_ - 1) {
                if (mServeFar_ < 0 || (m - mServeFar_) * geo_.farSign > 0) mServeFar_ = m;
                if (mServeNear_ < 0 || (m - mServeNear_) * geo_.farSign < 0) mServeNear_ = m;
            }
        }
        if (mServeFar_ < 0) return false;
        mStart_ = std::clamp(mServeFar_ + geo_.farSign * geo_.extensionSteps, std::min(geo_.mFar, geo_.mNear),
                             std::max(geo_.mFar, geo_.mNear));
        return true;
    }

    void startLines() {
        const auto edge = static_cast<std::size_t>(geo_.mEdge);
        for (std::size_t b = 0; b < nLines_; ++b) {
            // Without a distance table, every sample's distance is taken from the line's arc
            // coordinate at the far edge.
            const long k = kBegin_ + static_cast<long>(b);
            const double edgeArc =
                sigmaTable_ ? 0.0 : arcAt(geo_, static_cast<double>(k + geo_.base[edge]) + geo_.frac[edge]);
            lines_[b] = {scratch_.data() + b * lineCapacity_, 0, 0, edgeArc, 0, maxDistanceM_,
                         limited ? &logs_[b] : nullptr, 0, 0, 0, 0, -std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()};
            if (limited) logs_[b].reset(lineCapacity_);
        }
    }

    /// Range limit, a cell whose chunk is its line's (value: from the current chunk's hull): the
    /// previous chunk's points within range may raise it; the rest are the exact pass's.
    void raiseFromPrevChunk(LineState& line, double sigmaC, double gCell, long chunkC, float* cell, float value) {
        if (line.prevLo >= line.prevHi || prevChunkCannotRaise(line, sigmaC, gCell, invR_, value)) return;
        const std::size_t v = tangentVertex(line.buf, line.prevLo, line.prevHi, line.prevHint, sigmaC, gCell);
        line.prevHint = v;
        const HullPoint& pv = line.buf[v];
        const float bound = rangeSlope(pv.g, pv.sigmaM, gCell, sigmaC, invR_);
        if (bound > value) {
            if (pv.sigmaM >= sigmaC - maxDistanceM_) {
                *cell = bound;
            } else {
                line.log->queries[line.log->nQueries++] = {sigmaC, gCell, chunkC, line.log->nPoints, cell, false};
            }
        }
    }

    /// With a near field (geo.delay steps), a cell is served `delay` steps after the walk passed
    /// it, from the hulls of the samples walked so far: its scan lines' terrain at least `delay`
    /// steps away, queried at the cell's own height (the near field is the combine pass's).
    void serveDelayed(long mc) {
        if (mc < static_cast<long>(geo_.majorWin0) || mc >= static_cast<long>(geo_.majorWin1)) return;
        const long baseC = geo_.base[static_cast<std::size_t>(mc)];
        // Nodata cells are not served: a step of only those has nothing to do.
        if (!mayHaveHeights(mc, kBegin_ + baseC, kEnd_ + baseC)) return;
        const double fracC = geo_.frac[static_cast<std::size_t>(mc)];
        std::size_t b = 0;
#ifdef DEMLIGHT_SWEEP_AVX512
        // Eight lines at once where both cells of every line are window cells; serveLine serves
        // the rest, and every line of range-limited sweeps. With one scan line per cell each line
        // serves the cell it is nearest to (the same side for every line of the step) into plane
        // A, at any fraction; with two, both cells where the line runs between them.
        if (eightAtOnce_ && (fracC > 0.0 || geo_.nearestLine)) {
            for (; b + kSimdLines <= nLines_; b += kSimdLines) serveEightDelayed(b, mc, baseC, fracC);
        }
#endif
        for (; b < nLines_; ++b) serveLineDelayed(b, mc, baseC, fracC);
    }

    /// A line's distance at step mc (metres from the far edge), for either serving path.
    double sigmaOfLine(std::size_t b, long n0, long mc, double fracC) const {
        return sigmaTable_ ? geo_.sigmaAt[static_cast<std::size_t>(mc)]
                           : lineDistance(geo_, lines_[b].edgeArcM, static_cast<double>(n0) + fracC, mc);
    }

    void serveLineDelayed(std::size_t b, long mc, long baseC, double fracC) {
        LineState& line = lines_[b];
        const long n0 = kBegin_ + static_cast<long>(b) + baseC;
        if (n0 < minorWin0_ - 1 || n0 >= minorWin1_) return;
        long servedCell[2] = {fracC > 0.0 ? n0 + 1 : n0, n0};
        int nServed = fracC > 0.0 ? 2 : 1;
        if (geo_.nearestLine) {
            servedCell[0] = fracC > 0.5 ? n0 + 1 : n0;
            nServed = 1;
        }
        const double sigmaC = sigmaOfLine(b, n0, mc, fracC);
        const double dropC = sigmaC * sigmaC * halfInvR_;
        // Range limit: the chunk of the cell against the walk's (line.chunk, whose points the
        // hull [lo, hi) holds; [prevLo, prevHi) holds the chunk before it).
        const long chunkC = limited ? static_cast<long>(std::floor(sigmaC / maxDistanceM_)) : 0;
        float* const servedPlane[2] = {planeA_, planeB_};
        for (int s = 0; s < nServed; ++s) {
            const long j = servedCell[s];
            if (j < minorWin0_ || j >= minorWin1_) continue;
            const std::size_t idx = index(mc, j);
            const float hc = H_[idx];
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
                    value = static_cast<float>((pv.g - gCell) / (sigmaC - pv.sigmaM) - sigmaC * invR_);
                } else if (pv.sigmaM >= sigmaC - maxDistanceM_) {
                    // The walk's chunk is the cell's previous one: its tangent is the answer
                    // when in range, else the cell is left to the exact pass.
                    value = rangeSlope(pv.g, pv.sigmaM, gCell, sigmaC, invR_);
                } else {
                    line.log->queries[line.log->nQueries++] = {sigmaC, gCell, chunkC, line.log->nPoints, cell, true};
                }
            }
            *cell = value;
            // The previous chunk, as for the undelayed walk (walkLine).
            if (Limited && hullInRange) raiseFromPrevChunk(line, sigmaC, gCell, chunkC, cell, value);
        }
    }

#ifdef DEMLIGHT_SWEEP_AVX512
    /// Lines b..b+7 served at step mc as serveLineDelayed does, eight at once where every cell
    /// they serve is a window cell (and, with a range limit, in its line's chunk), else one by one.
    void serveEightDelayed(std::size_t b, long mc, long baseC, double fracC) {
        const long n0 = kBegin_ + static_cast<long>(b) + baseC;
        if (n0 < minorWin0_ || n0 + static_cast<long>(kSimdLines) >= minorWin1_) {
            for (std::size_t l = 0; l < kSimdLines; ++l) serveLineDelayed(b + l, mc, baseC, fracC);
            return;
        }
        [[maybe_unused]] alignas(64) double sigmas[kSimdLines];
        [[maybe_unused]] long chunks[kSimdLines];
        if constexpr (Limited) {
            // Range limit: at once where every lane's cells lie in its line's chunk (the
            // hull in range); otherwise line by line.
            laneDistancesInto(geo_, lines_, b, mc, n0, fracC, sigmas);
            bool inChunk = true;
            for (std::size_t l = 0; l < kSimdLines; ++l) {
                chunks[l] = static_cast<long>(std::floor(sigmas[l] / maxDistanceM_));
                inChunk = inChunk && chunks[l] == lines_[b + l].chunk;
            }
            if (!inChunk) {
                for (std::size_t l = 0; l < kSimdLines; ++l) serveLineDelayed(b + l, mc, baseC, fracC);
                return;
            }
        }
        const long idxA = static_cast<long>(index(mc, n0 + 1)), idxB = static_cast<long>(index(mc, n0));
        const long served[2] = {geo_.nearestLine ? (fracC > 0.5 ? idxA : idxB) : idxA, idxB};
        float* const servedPlane[2] = {planeA_, planeB_};
        const int nServed = geo_.nearestLine ? 1 : 2;
        serveEightLines({lines_, scratch_.data(), lineCapacity_, b, &geo_, mc, n0, fracC}, H_, planeA_,
                        nServed == 2 ? planeB_ : nullptr, served[0], nServed == 2 ? served[1] : 0, idxA - idxB,
                        Limited ? sigmas : nullptr, halfInvR_, invR_);
        if constexpr (Limited) {
            // Then each cell's previous chunk, as serveLineDelayed does: a line's cells in its
            // order (each tangent search starts where the line's last ended).
            for (std::size_t l = 0; l < kSimdLines; ++l) {
                LineState& line = lines_[b + l];
                if (line.prevLo >= line.prevHi) continue;
                const double dropC = sigmas[l] * sigmas[l] * halfInvR_;
                for (int s = 0; s < nServed; ++s) {
                    const auto idx = static_cast<std::size_t>(served[s] + static_cast<long>(l) * (idxA - idxB));
                    const float hc = H_[idx];
                    if (std::isnan(hc)) continue;
                    float* cell = servedPlane[s] + idx;
                    raiseFromPrevChunk(line, sigmas[l], static_cast<double>(hc) - dropC, chunks[l], cell, *cell);
                }
            }
        }
    }
#endif

    /// Fetches the heights and output cells of the step kPrefetchSteps ahead of m, and of the
    /// cells delayed serving reaches then.
    void prefetch(long m) const {
        // Along rows (Y-major) each step lands on a new row, a page or more away, which the
        // hardware prefetchers do not follow: without this the sweep spends much of its time
        // waiting on that load (docs/measurements.md#demlightlightingsweepwalkcpp-kprefetchsteps).
        if (const long ahead = m + mStep_ * kPrefetchSteps; ahead >= mLo_ && ahead < geo_.majorHi) {
            const long aheadBase = geo_.base[static_cast<std::size_t>(ahead)];
            const long j0 = std::max(nLo_, kBegin_ + aheadBase - 1);
            const long j1 = std::min(nHi_ - 1, kEnd_ + aheadBase + 1);
            // (A step of only nodata cells reads and writes none of them.)
            if (j0 <= j1 && mayHaveHeights(ahead, j0, j1)) {
                if constexpr (XMajor) {
                    for (long j = j0; j <= j1; ++j) {
                        __builtin_prefetch(H_ + index(ahead, j));
                        __builtin_prefetch(planeA_ + index(ahead, j), 1);
                    }
                } else {
                    for (long j = j0; j <= j1; j += kFloatsPerCacheLine) {
                        __builtin_prefetch(H_ + index(ahead, j));
                        __builtin_prefetch(planeA_ + index(ahead, j), 1);
                    }
                    __builtin_prefetch(H_ + index(ahead, j1));
                    __builtin_prefetch(planeA_ + index(ahead, j1), 1);
                }
            }
        }
        // Delayed serving reads and writes the cells `delay` steps ahead of the walk: fetch
        // those kPrefetchSteps ahead of that (both planes: two lines serve each cell).
        if (const long servedAhead = m + mStep_ * (delay_ + kPrefetchSteps);
            delay_ > 0 && servedAhead >= mLo_ && servedAhead < geo_.majorHi) {
            const long servedBase = geo_.base[static_cast<std::size_t>(servedAhead)];
            const long j0 = std::max(nLo_, kBegin_ + servedBase - 1);
            const long j1 = std::min(nHi_ - 1, kEnd_ + servedBase + 1);
            const long stride = XMajor ? 1 : kFloatsPerCacheLine;
            const bool any = j0 <= j1 && mayHaveHeights(servedAhead, j0, j1);
            for (long j = j0; any && j <= j1; j += stride) {
                __builtin_prefetch(H_ + index(servedAhead, j));
                __builtin_prefetch(planeA_ + index(servedAhead, j), 1);
                if (!geo_.nearestLine) __builtin_prefetch(planeB_ + index(servedAhead, j), 1);
            }
            if (any) {
                __builtin_prefetch(H_ + index(servedAhead, j1));
                __builtin_prefetch(planeA_ + index(servedAhead, j1), 1);
                if (!geo_.nearestLine) __builtin_prefetch(planeB_ + index(servedAhead, j1), 1);
            }
        }
    }

    /// With a near field, the far field follows the bilinear surface between steps too: where
    /// the lines cross a grid line of the minor axis between the previous step and this one
    /// (the same crossing for every line, at fraction tc of the step), each takes a point
    /// there, linear between the two cells on that grid line; that is where a wall's top edge
    /// along the major axis lies. Pushed before this step's samples (it is farther).
    void pushCrossings(long m, long base, double frac) {
        const long prev = m - mStep_;
        const long basePrev = geo_.base[static_cast<std::size_t>(prev)];
        const double fracPrev = geo_.frac[static_cast<std::size_t>(prev)];
        if (!(frac > 0.0 && fracPrev > 0.0 && basePrev != base)) return;
        const long n = std::max(basePrev, base);
        const double yPrev = static_cast<double>(basePrev) + fracPrev, yNow = static_cast<double>(base) + frac;
        const double tc = (static_cast<double>(n) - yPrev) / (yNow - yPrev);
        // (Only nodata on both grid lines: no line takes a point.)
        const bool bothSteps = prev >= mLo_ && prev < geo_.majorHi &&
                               (mayHaveHeights(prev, kBegin_ + n, kEnd_ - 1 + n) ||
                                mayHaveHeights(m, kBegin_ + n, kEnd_ - 1 + n));
        for (std::size_t b = 0; bothSteps && b < nLines_; ++b) {
            LineState& line = lines_[b];
            const long j = kBegin_ + static_cast<long>(b) + n;
            if (j < nLo_ || j >= nHi_) continue;
            const float hPrev = H_[index(prev, j)], hNow = H_[index(m, j)];
            const float h = std::isnan(hPrev) ? hNow : std::isnan(hNow) ? hPrev
                          : static_cast<float>((1.0 - tc) * hPrev + tc * hNow);
            if (std::isnan(h)) continue;
            const double sigma =
                sigmaTable_ ? geo_.sigmaAt[static_cast<std::size_t>(prev)] +
                                  tc * (geo_.sigmaAt[static_cast<std::size_t>(m)] -
                                        geo_.sigmaAt[static_cast<std::size_t>(prev)])
                            : lineDistance(geo_, line.edgeArcM, static_cast<double>(j), m);
            if (limited && sigma >= line.nextChunkM) enterChunk(line, sigma, maxDistanceM_);
            const double g = static_cast<double>(h) - sigma * sigma * halfInvR_;
            const std::size_t top = hullTopAfterPops(line, sigma, g);
            if (limited) line.log->points[line.log->nPoints++] = {sigma, g, line.chunk};
            line.hi = top;
            line.buf[line.hi++] = {sigma, g};
            if (limited) line.maxG = std::max(line.maxG, g);
        }
    }

    /// One step m of the walk: crossing points, then each line's sample pushed (serving the
    /// cells it brackets first when cells are served as the walk reaches them).
    void walkStep(long m) {
        const long base = geo_.base[static_cast<std::size_t>(m)];
        const double frac = geo_.frac[static_cast<std::size_t>(m)];
        // Skip steps where every line of the block lies outside the grid.
        const long n0First = kBegin_ + base, n0Last = kEnd_ - 1 + base;
        const bool anyInside = n0Last >= nLo_ - 1 && n0First <= nHi_ - 1;
        const bool inWindow = m >= static_cast<long>(geo_.majorWin0) && m < static_cast<long>(geo_.majorWin1);
        // Where every cell the block's lines sample or serve at this step is nodata (sea, voids),
        // the lines only advance their distances: nothing is sampled, served or pushed. The
        // range limit's chunk bookkeeping catches up at the next valid sample, which is the same:
        // a chunk boundary crossed over nodata leaves an empty hull behind either way.
        const bool allNodata = anyInside && !heightsAt(m, n0First, n0Last + 1);
        if (geo_.crossings && m != mStart_) pushCrossings(m, base, frac);
        // Where every line is off the terrain's cells or every cell is nodata there is nothing
        // to sample or serve (distances need no walking: they are a function of position).
        if (!anyInside || allNodata) return;
        std::size_t b = 0;
#ifdef DEMLIGHT_SWEEP_AVX512
        // Eight lines at once where all eight and the cells after them lie inside the terrain;
        // walkLine walks the rest (and drops those lanes' cached top vertices).
        for (; Lanes && b + kSimdLines <= nLines_; b += kSimdLines) {
            TopVertices& cached = topVertices_[b / kSimdLines];
            const long n0 = kBegin_ + static_cast<long>(b) + base;
            if (n0 < nLo_ || n0 + static_cast<long>(kSimdLines) >= nHi_) {
                for (std::size_t l = 0; l < kSimdLines; ++l) walkLine(b + l, m, base, frac, inWindow);
                cached.valid = false;
                continue;
            }
            const long idx0 = static_cast<long>(index(m, n0));
            walkEightLines({lines_, scratch_.data(), lineCapacity_, b, &geo_, m, n0, frac}, H_, idx0,
                           static_cast<long>(index(m, n0 + 1)) - idx0, halfInvR_, cached);
        }
#endif
        for (; b < nLines_; ++b) walkLine(b, m, base, frac, inWindow);
    }

    /// Line b's sample at step m: pops, serving (undelayed), push.
    void walkLine(std::size_t b, long m, long base, double frac, bool inWindow) {
        LineState& line = lines_[b];
        const long n0 = kBegin_ + static_cast<long>(b) + base;
        const long n1 = n0 + 1;
        if (n0 < -1 || n0 > N_ - 1) return;
        const double sigma = sigmaTable_ ? geo_.sigmaAt[static_cast<std::size_t>(m)]
                                         : lineDistance(geo_, line.edgeArcM, static_cast<double>(n0) + frac, m);

        // Line sample: linear across the line between the two bracketing cells; heights
        // are known inside the hull of the cell centres only. Cells of the full grid
        // outside the terrain count as nodata: they lie beyond the search distance of
        // every cell served (the halo), so no chunk that serves a cell holds them.
        const bool inside = n0 >= nLo_ && (frac == 0.0 ? n0 < nHi_ : n1 < nHi_);
        const float h0 = inside ? H_[index(m, n0)] : std::numeric_limits<float>::quiet_NaN();
        float sample = h0;
        if (frac > 0.0 && inside) {
            const float h1 = H_[index(m, n1)];
            if (std::isnan(h0)) {
                sample = h1;
            } else if (!std::isnan(h1)) {
                sample = static_cast<float>((1.0 - frac) * h0 + frac * h1);
            }
        }

        // Range limit: a fresh hull per chunk of length maxDistanceM (see limitRangePass).
        // Chunks start at multiples of maxDistanceM from the far edge, so a chunk that
        // serves a cell starts within the halo and every walk builds the same hull.
        if (limited && sigma >= line.nextChunkM) enterChunk(line, sigma, maxDistanceM_);

        // The line sample's tangent vertex = the hull top after the pops it causes:
        // pop v1 while the slope to v2 (farther) is at least the slope to v1.
        const bool sampleValid = !std::isnan(sample);
        const double drop = sigma * sigma * halfInvR_;
        const double gSample = static_cast<double>(sample) - drop;
        const std::size_t top = sampleValid ? hullTopAfterPops(line, sigma, gSample) : line.hi;

        // (n0 in [minorWin0 - 1, minorWin1 - 1]: n1 or n0 is a window cell.)
        if (delay_ == 0 && inWindow && n0 >= minorWin0_ - 1 && n0 < minorWin1_)
            serveLine(line, m, n0, frac, sample, sigma, drop, top);

        if (sampleValid) {
            if (limited) line.log->points[line.log->nPoints++] = {sigma, gSample, line.chunk};
            line.hi = top;
            line.buf[line.hi++] = {sigma, gSample};
            if (limited) line.maxG = std::max(line.maxG, gSample);
        }
    }

    /// Serves the cells a line brackets at step m as the walk reaches them: cell n0 + 1 (line
    /// below it, weight frac) into plane A, cell n0 (line above it, weight 1 - frac) into plane
    /// B; on an exact hit (frac == 0) cell n0 into plane A. `top` is the hull's top after the
    /// pops of the line's sample.
    void serveLine(LineState& line, long m, long n0, double frac, float sample, double sigma, double drop,
                   std::size_t top) {
        const long n1 = n0 + 1;
        long servedCell[2] = {frac > 0.0 ? n1 : n0, n0};
        float* const servedPlane[2] = {planeA_, planeB_};
        int nServed = frac > 0.0 ? 2 : 1;
        if (geo_.nearestLine) {
            // Only the cell this line is nearest to (frac is the same for every line
            // at this step, so exactly one line serves each cell).
            servedCell[0] = frac > 0.5 ? n1 : n0;
            nServed = 1;
        }
        const auto cellIndex = [this](long mm, long j) { return index(mm, j); };
        for (int s = 0; s < nServed; ++s) {
            const long j = servedCell[s];
            if (j < minorWin0_ || j >= minorWin1_) continue;
            const std::size_t idx = index(m, j);
            const float hc = H_[idx];
            if (std::isnan(hc)) continue;
            const double hQuery = observerHeight(H_, cellIndex, m, j, nLo_, nHi_, frac, hc, sample);
            const double gCell = hQuery - drop;
            float value = -std::numeric_limits<float>::infinity();
            if (line.lo < line.hi) {
                const std::size_t start = top > line.lo ? top - 1 : line.lo;
                value = static_cast<float>(tangentSlope(line, start, sigma, gCell) - sigma * invR_);
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

    const LineGeometry& geo_;
    const float* H_;
    std::size_t W_;
    double invR_, halfInvR_, maxDistanceM_;
    long kBegin_, kEnd_;
    float* planeA_;
    float* planeB_;
    std::vector<HullPoint>& scratch_;
    RangeLog* logs_;
    const ValidCells& valid_;
    bool bitmap_;
    [[maybe_unused]] bool eightAtOnce_;
    std::size_t nLines_, lineCapacity_;
    long N_, mStep_, minorWin0_, minorWin1_, mLo_, nLo_, nHi_;
    bool sigmaTable_;
    long delay_;
    long mServeFar_ = -1, mServeNear_ = -1, mStart_ = 0;
    LineState lines_[kLinesPerBlock];
#ifdef DEMLIGHT_SWEEP_AVX512
    TopVertices topVertices_[Lanes ? kLinesPerBlock / kSimdLines : 1];
#endif
};

}  // namespace

void walkLineBlock(const Terrain& t, const LineGeometry& geo, double invR, double maxDistanceM, long kBegin,
                   long kEnd, float* planeA, float* planeB, const ValidCells& valid, bool eightAtOnce) {
    thread_local std::vector<HullPoint> scratch;
    thread_local RangeLog logs[kLinesPerBlock];
    // The walk eight lines at once where it only pushes: cells served after it (delay > 0), no
    // crossing points between steps (they push too); a range limit's chunks and logs keep
    // it line by line (tried: slower, docs/performance.md).
    const bool lanes = kLanesWalk && eightAtOnce && geo.delay > 0 && !geo.crossings;
    // A range limit longer than every line (the whole DEM searched) changes nothing.
    const bool limited = std::isfinite(maxDistanceM) && maxDistanceM <= geo.spanBoundM;
    // Along a grid axis over the whole DEM, the gather-free kernel serves the block; the walk
    // below serves every other block (sheared lines, delayed serving, range limits).
    if (axisKernelServes(geo, limited)) return walkAxisBlock(t, geo, invR, kBegin, kEnd, planeA);
    const auto run = [&]<bool XMajor, bool Limited, bool Lanes>() {
        BlockWalk<XMajor, Limited, Lanes>(t, geo, invR, maxDistanceM, kBegin, kEnd, planeA, planeB, scratch, logs, valid,
                                          eightAtOnce)
            .run();
    };
    if (limited) {
        geo.xMajor ? run.template operator()<true, true, false>() : run.template operator()<false, true, false>();
    } else if (lanes) {
        geo.xMajor ? run.template operator()<true, false, true>() : run.template operator()<false, false, true>();
    } else {
        geo.xMajor ? run.template operator()<true, false, false>() : run.template operator()<false, false, false>();
    }
}

}  // namespace demlight::sweep
