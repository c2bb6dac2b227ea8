// The exact near field of a sweep (demlight/lighting/sweep/near_field.h).
#include "demlight/lighting/sweep/near_field.h"

#include "demlight/core/simd.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace demlight::sweep {
namespace {

/// The near field's first steps are sampled at the reference's quarter cells (walls and roof
/// edges next to the cell); beyond them only where the ray crosses grid lines.
constexpr long kDenseNearSteps = 2;

}  // namespace

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

namespace {

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

/// A row's taps of the near field: the cell heights h0 of the window's columns and the rows of
/// each point's taps, with the point's tap count as a constant (on a grid line the taps with
/// weight are the first two).
struct RowTaps {
    const float* h0;
    long width;
    void of(const NearPoint& p, const float** tap) const {
        for (int k = 0; k < 4; ++k) tap[k] = h0 + p.tapRow[k] * width + p.tapCol[k];
    }
    template <class Pass>
    void pass(const NearPoint& p, Pass&& run) const {
        const float* tap[4];
        of(p, tap);
        if (p.taps == 2) {
            run(std::integral_constant<int, 2>{}, tap);
        } else {
            run(std::integral_constant<int, 4>{}, tap);
        }
    }
};

/// Consecutive points with the same taps (and so the same range) go in one pass, up to four.
bool sameTaps(const NearPoint& a, const NearPoint& b) {
    if (a.taps != b.taps) return false;
    for (int k = 0; k < a.taps; ++k) {
        if (a.tapCol[k] != b.tapCol[k] || a.tapRow[k] != b.tapRow[k]) return false;
    }
    return true;
}

/// Every point of the stencil over the window columns of its range (ranges[q]) whose taps are
/// all valid: the vectorised loops, points with the same taps grouped, a lone point paired
/// with the next lone one where both ranges hold the cell. Cells with a void among a point's
/// taps are flagged.
void pointPasses(const RowTaps& taps, const std::vector<NearPoint>& stencil,
                 const std::vector<std::pair<long, long>>& ranges, float* __restrict best,
                 std::uint8_t* __restrict flag) {
    const float* h0 = taps.h0;
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
                taps.pass(pt, [&](auto n, const float* const* tap) {
                    nearPointRow<decltype(n)::value>(h0, tap[0], tap[1], tap[2], tap[3], &pt, best, flag, b0, b1);
                });
            };
            // Cells before the shared range, then the shared range, then after it: a cell's
            // points still come a then b.
            single(p, begin, std::min(end, both0));
            single(pb, beginB, std::min(endB, both0));
            if (both0 < both1) {
                const float* ta[4];
                const float* tb[4];
                taps.of(p, ta);
                taps.of(pb, tb);
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
        taps.pass(p, [&](auto n, const float* const* tap) {
            constexpr int kTaps = decltype(n)::value;
            switch (group) {
            case 1: nearPointRow<kTaps>(h0, tap[0], tap[1], tap[2], tap[3], &p, best, flag, begin, end); break;
            case 2: nearPointRow<kTaps, 2>(h0, tap[0], tap[1], tap[2], tap[3], &p, best, flag, begin, end); break;
            case 3: nearPointRow<kTaps, 3>(h0, tap[0], tap[1], tap[2], tap[3], &p, best, flag, begin, end); break;
            default: nearPointRow<kTaps, 4>(h0, tap[0], tap[1], tap[2], tap[3], &p, best, flag, begin, end); break;
            }
        });
    }
}

/// Cells of [fastBegin, fastEnd) (inside every point's range) with a void among their taps:
/// every point again by the reference's rule, vectorised over runs of such cells (a run bridges
/// up to kRunGap unflagged cells, whose values it does not use). A nodata cell is flagged by its
/// own height; it has no horizon, so it is no part of a run.
void reweightVoidRuns(const RowTaps& taps, const std::vector<NearPoint>& stencil, long fastBegin, long fastEnd,
                      std::size_t cols, std::uint8_t* __restrict flag, std::vector<float>& out) {
    const float* h0 = taps.h0;
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
            taps.pass(p, [&](auto n, const float* const* tap) {
                nearPointRowReweighted<decltype(n)::value>(h0, tap[0], tap[1], tap[2], tap[3], p, rwBest, i, runEnd);
            });
        }
        for (long c = i; c < runEnd; ++c) {
            if (flag[c]) out[static_cast<std::size_t>(c)] = rwBest[c];
        }
        i = last;
    }
}

}  // namespace

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
    const RowTaps taps{h0, static_cast<long>(W)};
    std::uint8_t* flag = bad.data();
    pointPasses(taps, stencil, ranges, out.data(), flag);
    reweightVoidRuns(taps, stencil, fastBegin, fastEnd, cols, flag, out);
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

}  // namespace demlight::sweep
