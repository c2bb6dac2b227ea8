// The AVX-512 hull kernel: eight lines at once, one per lane, each lane making the scalar
// walk's (hull.h) comparisons in the same order. Included by walk.cpp only (its functions have
// internal linkage there, as the walk's own).
#pragma once

#include "demlight/lighting/sweep/hull.h"
#include "demlight/lighting/sweep/line_geometry.h"
#include "demlight/core/avx512.h"
#include "demlight/core/simd.h"

#include <cstddef>
#include <cstdint>

namespace demlight::sweep {
namespace {

#ifdef DEMLIGHT_HAS_AVX512_KERNELS
#define DEMLIGHT_SWEEP_AVX512 1
/// Eight lines' delayed serving at once (BlockWalk::serveDelayed), one line per AVX-512 lane,
/// where simdPath() is SimdPath::Avx512 (functions marked DEMLIGHT_AVX512, called from the
/// portable BlockWalk with plain arrays).
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

/// laneDistances into out[0, 8), for the portable BlockWalk.
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
/// serving: BlockWalk's Lanes), one line per AVX-512 lane: the line sample between cells n0
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

}  // namespace
}  // namespace demlight::sweep
