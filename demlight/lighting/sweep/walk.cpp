// The walk of a block of scan lines (demlight/lighting/sweep/walk.h).
#include "demlight/lighting/sweep/walk.h"

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

/// How many line steps ahead a block prefetches its heights and output cells (sweepBlock): a
/// step of a block costs about one memory latency
/// (docs/measurements.md#demlightlightingsweepwalkcpp-kprefetchsteps).
constexpr long kPrefetchSteps = 4;
constexpr long kFloatsPerCacheLine = 16;

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
        // (docs/measurements.md#demlightlightingsweepwalkcpp-kprefetchsteps).
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
    const auto run = [&]<bool XMajor, bool Limited, bool Lanes>() {
        sweepBlock<XMajor, Limited, Lanes>(t, geo, invR, maxDistanceM, kBegin, kEnd, planeA, planeB, scratch, logs,
                                           valid, eightAtOnce);
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
