// The hull sweep's floor on this machine: what the bare upper-hull kernel costs per cell and
// direction, beside the library's sweep on the same lines, in one run.
//
// Usage: demlight_sweep_floor_bench DEM [runs] [ratios]   (default 5 runs, medians printed; "ratios":
// only the alternating rounds of the vector kernels, one thread)
//
// The lines are the DEM's columns walked from the north edge (azimuth 0, the sweep's cheapest
// case: every line runs through cell centres, one region, no range limit, no near field). Each
// step does what no hull sweep can skip: read a height, drop it by the earth's curvature, pop
// the vertices the new point hides (Dozier 1981; Timonen & Westerholm 2010), take the tangent of
// the cell's own sample (the vertex below the new top, one division) and push the point. It
// skips everything else the library does: serving a cell from two lines between centres, other
// azimuths (regions, distances per line), range limits, nodata bitmaps, the near field, the
// combine pass, the angle, allocating the map. The vector kernels step over a vector of nodata
// only (sea), as the library steps over void blocks; the scalar one tests each cell. So no sweep
// of the library can be faster than this kernel (docs/performance.md, "The floor of a hull
// sweep").
//
// Kernels: scalar, 64 lines in lock-step with the heights prefetched a few rows ahead (the
// library's layout); where AVX-512 is compiled in, eight lines a vector with each line's two top
// vertices kept in registers (the farther ones gathered, the pushed point scattered), the same
// bits as scalar; and that kernel in single precision, sixteen lines a vector (not the same bits:
// the bench prints how far its angles are from the double kernels'). On a geographic DEM
// (columns are meridians) the kernels are checked against the library's sweep at azimuth 0: the
// angles agree to float rounding, or the bench says how many cells differ by more than 1e-3 deg.
#include "bench/bench_timing.h"
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/hull_lanes.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#if defined(__AVX512F__) && defined(__AVX512DQ__) && defined(__AVX512VL__)
// As in demlight/core/avx512.h: GCC 12 reports its intrinsics' deliberately undefined start
// values as maybe uninitialized where they are inlined.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <immintrin.h>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#define FLOOR_AVX512 1
#endif

namespace {

constexpr long kBlock = 64;        // lines per block (the library's kLinesPerBlock)
constexpr long kPrefetchRows = 8;  // rows ahead

struct Lines {
    const float* heights;  // row-major, NaN = nodata
    long width, height;
    std::vector<double> sigma;  // distance of each row from the north edge (metres)
    double invR;
    demlight::HullGeometry geometry;  // the same distances for the library's hull kernel
    demlight::HullGeometry uniform;   // the mean spacing on every row (timing only: not the DEM's distances)
};

void prefetchRow(const Lines& l, float* out, long row, long c0, long n) {
    if (row >= l.height) return;
    for (long k = 0; k < n; k += 16) {
        __builtin_prefetch(l.heights + row * l.width + c0 + k);
        __builtin_prefetch(out + row * l.width + c0 + k, 1);
    }
}

/// Slopes (tangent of the horizon, curvature included) of columns [c0, c0 + n), n <= kBlock;
/// -inf where no farther point exists, NaN at nodata. hull: kBlock * height points of scratch.
void scalarBlock(const Lines& l, float* out, long c0, long n, std::vector<double>& hull) {
    long top[kBlock] = {};
    const double halfInvR = 0.5 * l.invR;
    for (long r = 0; r < l.height; ++r) {
        prefetchRow(l, out, r + kPrefetchRows, c0, n);
        const double s = l.sigma[static_cast<std::size_t>(r)];
        const double drop = s * s * halfInvR;
        for (long b = 0; b < n; ++b) {
            const float h = l.heights[r * l.width + c0 + b];
            float* o = out + r * l.width + c0 + b;
            if (std::isnan(h)) {
                *o = h;
                continue;
            }
            double* v = hull.data() + 2 * b * l.height;  // (sigma, g) pairs
            long t = top[b];
            const double g = static_cast<double>(h) - drop;
            // Pop v1 unless the slope to v2 (farther) is below the slope to v1.
            while (t >= 2 && !((v[2 * t - 3] - g) * (s - v[2 * t - 2]) < (v[2 * t - 1] - g) * (s - v[2 * t - 4]))) --t;
            *o = t >= 1 ? static_cast<float>((v[2 * t - 1] - g) / (s - v[2 * t - 2]) - s * l.invR)
                        : -std::numeric_limits<float>::infinity();
            v[2 * t] = s;
            v[2 * t + 1] = g;
            top[b] = t + 1;
        }
    }
}

#ifdef FLOOR_AVX512
/// scalarBlock for n == kBlock, eight lines per vector. Vertex v of lane l is at [v * 8 + l] of
/// the lane group's sigma and g arrays.
void simdBlock(const Lines& l, float* out, long c0, std::vector<double>& hull) {
    constexpr long kGroups = kBlock / 8;
    struct Group {
        __m512i top;
        __m512d s1, g1, s2, g2;  // the top vertex and the one below it
    };
    Group st[kGroups];
    const __m512d zero = _mm512_setzero_pd();
    for (Group& q : st) q = {_mm512_setzero_si512(), zero, zero, zero, zero};
    const __m512i lane = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
    const __m512i one = _mm512_set1_epi64(1), two = _mm512_set1_epi64(2);
    const __m512d invR = _mm512_set1_pd(l.invR);
    const __m256 none = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
    const double halfInvR = 0.5 * l.invR;
    for (long r = 0; r < l.height; ++r) {
        prefetchRow(l, out, r + kPrefetchRows, c0, kBlock);
        const double sd = l.sigma[static_cast<std::size_t>(r)];
        const __m512d s = _mm512_set1_pd(sd);
        const __m512d drop = _mm512_set1_pd(sd * sd * halfInvR);
        for (long q = 0; q < kGroups; ++q) {
            double* S = hull.data() + 2 * q * 8 * l.height;
            double* G = S + 8 * l.height;
            const __m256 h = _mm256_loadu_ps(l.heights + r * l.width + c0 + q * 8);
            const __m512d hd = _mm512_cvtps_pd(h);
            const __mmask8 valid = _mm512_cmp_pd_mask(hd, hd, _CMP_ORD_Q);
            if (!valid) {  // nodata only (sea): the hull stays as it is, as the library's void blocks
                _mm256_storeu_ps(out + r * l.width + c0 + q * 8, h);
                continue;
            }
            const __m512d g = hd - drop;
            Group& L = st[q];
            __m512i top = L.top;
            __m512d s1 = L.s1, g1 = L.g1, s2 = L.s2, g2 = L.g2;
            const __mmask8 hasTop = valid & _mm512_cmpge_epi64_mask(top, one);
            __mmask8 active = valid & _mm512_cmpge_epi64_mask(top, two);
            for (;;) {
                const __mmask8 keep = _mm512_cmp_pd_mask((g2 - g) * (s - s1), (g1 - g) * (s - s2), _CMP_LT_OQ);
                const __mmask8 pop = active & ~keep;
                if (!pop) break;
                top = _mm512_mask_sub_epi64(top, pop, top, one);
                s1 = _mm512_mask_mov_pd(s1, pop, s2);
                g1 = _mm512_mask_mov_pd(g1, pop, g2);
                active = pop & _mm512_cmpge_epi64_mask(top, two);
                const __m512i below = _mm512_add_epi64(_mm512_slli_epi64(_mm512_sub_epi64(top, two), 3), lane);
                s2 = _mm512_mask_i64gather_pd(s2, active, below, S, 8);
                g2 = _mm512_mask_i64gather_pd(g2, active, below, G, 8);
            }
            const __m512d slope = (g1 - g) / (s - s1) - s * invR;
            __m256 value = _mm256_mask_blend_ps(hasTop, none, _mm512_cvtpd_ps(slope));
            value = _mm256_mask_blend_ps(valid, h, value);  // NaN stays
            _mm256_storeu_ps(out + r * l.width + c0 + q * 8, value);
            const __m512i at = _mm512_add_epi64(_mm512_slli_epi64(top, 3), lane);
            _mm512_mask_i64scatter_pd(S, valid, at, s, 8);
            _mm512_mask_i64scatter_pd(G, valid, at, g, 8);
            L.top = _mm512_mask_add_epi64(top, valid, top, one);
            L.s2 = _mm512_mask_mov_pd(s2, valid, s1);
            L.g2 = _mm512_mask_mov_pd(g2, valid, g1);
            L.s1 = _mm512_mask_mov_pd(s1, valid, s);
            L.g1 = _mm512_mask_mov_pd(g1, valid, g);
        }
    }
}

/// simdBlock in single precision, sixteen lines per vector: not the same bits (distances of
/// 1e5 m keep 8 mm in a float), so the bench reports how far its angles are from the double
/// kernels'. Vertex v of lane l is at [v * 16 + l].
void floatBlock(const Lines& l, float* out, long c0, std::vector<double>& hullD) {
    constexpr long kGroups = kBlock / 16;
    struct Group {
        __m512i top;
        __m512 s1, g1, s2, g2;
    };
    Group st[kGroups];
    const __m512 zero = _mm512_setzero_ps();
    for (Group& q : st) q = {_mm512_setzero_si512(), zero, zero, zero, zero};
    auto* hull = reinterpret_cast<float*>(hullD.data());  // 2 * kBlock * height floats of the doubles' room
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i one = _mm512_set1_epi32(1), two = _mm512_set1_epi32(2);
    const __m512 invR = _mm512_set1_ps(static_cast<float>(l.invR));
    const __m512 none = _mm512_set1_ps(-std::numeric_limits<float>::infinity());
    const double halfInvR = 0.5 * l.invR;
    for (long r = 0; r < l.height; ++r) {
        prefetchRow(l, out, r + kPrefetchRows, c0, kBlock);
        const double sd = l.sigma[static_cast<std::size_t>(r)];
        const __m512 s = _mm512_set1_ps(static_cast<float>(sd));
        const __m512 drop = _mm512_set1_ps(static_cast<float>(sd * sd * halfInvR));
        for (long q = 0; q < kGroups; ++q) {
            float* S = hull + 2 * q * 16 * l.height;
            float* G = S + 16 * l.height;
            const __m512 h = _mm512_loadu_ps(l.heights + r * l.width + c0 + q * 16);
            const __mmask16 valid = _mm512_cmp_ps_mask(h, h, _CMP_ORD_Q);
            if (!valid) {
                _mm512_storeu_ps(out + r * l.width + c0 + q * 16, h);
                continue;
            }
            const __m512 g = h - drop;
            Group& L = st[q];
            __m512i top = L.top;
            __m512 s1 = L.s1, g1 = L.g1, s2 = L.s2, g2 = L.g2;
            const __mmask16 hasTop = valid & _mm512_cmpge_epi32_mask(top, one);
            __mmask16 active = valid & _mm512_cmpge_epi32_mask(top, two);
            for (;;) {
                const __mmask16 keep = _mm512_cmp_ps_mask((g2 - g) * (s - s1), (g1 - g) * (s - s2), _CMP_LT_OQ);
                const __mmask16 pop = active & ~keep;
                if (!pop) break;
                top = _mm512_mask_sub_epi32(top, pop, top, one);
                s1 = _mm512_mask_mov_ps(s1, pop, s2);
                g1 = _mm512_mask_mov_ps(g1, pop, g2);
                active = pop & _mm512_cmpge_epi32_mask(top, two);
                const __m512i below = _mm512_add_epi32(_mm512_slli_epi32(_mm512_sub_epi32(top, two), 4), lane);
                s2 = _mm512_mask_i32gather_ps(s2, active, below, S, 4);
                g2 = _mm512_mask_i32gather_ps(g2, active, below, G, 4);
            }
            __m512 value = _mm512_mask_blend_ps(hasTop, none, (g1 - g) / (s - s1) - s * invR);
            value = _mm512_mask_blend_ps(valid, h, value);
            _mm512_storeu_ps(out + r * l.width + c0 + q * 16, value);
            const __m512i at = _mm512_add_epi32(_mm512_slli_epi32(top, 4), lane);
            _mm512_mask_i32scatter_ps(S, valid, at, s, 4);
            _mm512_mask_i32scatter_ps(G, valid, at, g, 4);
            L.top = _mm512_mask_add_epi32(top, valid, top, one);
            L.s2 = _mm512_mask_mov_ps(s2, valid, s1);
            L.g2 = _mm512_mask_mov_ps(g2, valid, g1);
            L.s1 = _mm512_mask_mov_ps(s1, valid, s);
            L.g1 = _mm512_mask_mov_ps(g1, valid, g);
        }
    }
}
#endif

enum class Kernel { scalar, doubleLanes, floatLanes, hullLanes, hullLanesUniform, copyOnly };

/// Every column, blocks spread over `threads`; the vector kernels take the full blocks, the
/// scalar one the rest.
void sweepColumns(const Lines& l, float* out, int threads, Kernel kernel) {
    const auto blocks = static_cast<std::size_t>((l.width + kBlock - 1) / kBlock);
    demlight::withThreads(threads, [&] { demlight::parallelFor(0, blocks, [&](std::size_t blk) {
        thread_local std::vector<double> hull;
        hull.resize(static_cast<std::size_t>(2 * kBlock * l.height));
        const long c0 = static_cast<long>(blk) * kBlock, n = std::min(kBlock, l.width - c0);
        if (kernel == Kernel::hullLanes || kernel == Kernel::hullLanesUniform) {  // hull_lanes.h, ragged blocks too
            thread_local demlight::HullScratch scratch;
            return demlight::hullSlopesVector(
                kernel == Kernel::hullLanes ? l.geometry : l.uniform,
                {l.heights + c0, out + c0, static_cast<std::size_t>(l.width), static_cast<std::size_t>(n)}, scratch);
        }
        if (kernel == Kernel::copyOnly) {  // what every kernel does besides the hull: read, write
            for (long r = 0; r < l.height; ++r) {
                prefetchRow(l, out, r + kPrefetchRows, c0, n);
                std::copy_n(l.heights + r * l.width + c0, n, out + r * l.width + c0);
            }
            return;
        }
#ifdef FLOOR_AVX512
        if (kernel == Kernel::doubleLanes && n == kBlock) return simdBlock(l, out, c0, hull);
        if (kernel == Kernel::floatLanes && n == kBlock) return floatBlock(l, out, c0, hull);
#endif
        (void)kernel;
        scalarBlock(l, out, c0, n, hull);
    }); });
}

/// Cells where the kernel's angle and the library's differ by more than 1e-3 deg (either NaN
/// alone counts; cells the kernel finds no farther point for are skipped, the library gives
/// them its no-horizon value), and the largest difference.
void compare(const std::vector<float>& slopes, const demlight::HorizonMap& ref, long& differing, double& maxDiff) {
    differing = 0;
    maxDiff = 0;
    const float* a = ref.angleDeg.data();
    for (std::size_t i = 0; i < slopes.size(); ++i) {
        const float s = slopes[i];
        if (std::isnan(s) || std::isnan(a[i])) {
            differing += std::isnan(s) != std::isnan(a[i]);
            continue;
        }
        if (std::isinf(s)) continue;
        const double d = std::abs(std::atan(static_cast<double>(s)) * 180.0 / M_PI - a[i]);
        maxDiff = std::max(maxDiff, d);
        differing += d > 1e-3;
    }
}

#ifdef FLOOR_AVX512
/// Angle differences of `slopes` from the double kernels' `exact` (degrees), printed.
void reportAgainst(const std::vector<float>& slopes, const std::vector<float>& exact, const char* name) {
    std::vector<double> diffs;
    for (std::size_t i = 0; i < slopes.size(); ++i) {
        if (!std::isfinite(slopes[i]) || !std::isfinite(exact[i])) continue;
        diffs.push_back(std::abs(std::atan(static_cast<double>(slopes[i])) - std::atan(static_cast<double>(exact[i]))) *
                        180.0 / M_PI);
    }
    if (diffs.empty()) return;
    std::sort(diffs.begin(), diffs.end());
    std::printf("%s against the double kernels: median %.1e, p99 %.1e, p99.9 %.1e, max %.1e deg over %zu cells\n", name,
                diffs[diffs.size() / 2], diffs[diffs.size() * 99 / 100], diffs[diffs.size() * 999 / 1000],
                diffs.back(), diffs.size());
}

/// CPU time of the calling thread spent in f (seconds): time the scheduler gives to other
/// processes of a busy machine is not counted.
template <class F>
double threadSeconds(F&& f) {
    timespec a{}, b{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
    f();
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
    return static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec);
}

struct Timed {
    const char* name;
    std::function<void()> run;
};

/// One thread, the kernels timed in turn within each round (the order rotating between rounds),
/// each round's times divided by the first kernel's: medians and ranges of those ratios, so that
/// a machine busy with other work moves every kernel of a round alike.
void ratioRounds(const std::vector<Timed>& kernels, double cells, int runs) {
    const std::size_t count = kernels.size();
    const int rounds = std::max(3, 2 * runs + 1);
    std::vector<std::vector<double>> seconds(count), ratios(count);
    std::vector<double> t(count);
    for (int round = 0; round < rounds; ++round) {
        for (std::size_t j = 0; j < count; ++j) {
            const std::size_t k = (j + static_cast<std::size_t>(round)) % count;
            t[k] = threadSeconds(kernels[k].run);
        }
        for (std::size_t k = 0; k < count; ++k) {
            seconds[k].push_back(t[k]);
            ratios[k].push_back(t[k] / t[0]);
        }
    }
    std::printf("one thread, %d alternating rounds, thread CPU time: ratio to the first, median [min, max]; "
                "ns/cell median\n",
                rounds);
    for (std::size_t k = 0; k < count; ++k) {
        std::sort(ratios[k].begin(), ratios[k].end());
        std::sort(seconds[k].begin(), seconds[k].end());
        std::printf("  %-48s %6.3f [%.3f, %.3f] %8.2f\n", kernels[k].name, ratios[k][ratios[k].size() / 2],
                    ratios[k].front(), ratios[k].back(), seconds[k][seconds[k].size() / 2] / cells * 1e9);
    }
}

/// The floor kernels and hull_lanes.h's on every column.
void columnRatios(const Lines& l, float* out, int runs) {
    const auto on = [&](Kernel k) { return [&l, out, k] { sweepColumns(l, out, 1, k); }; };
    ratioRounds({{"float kernel (16 lines, gathers)", on(Kernel::floatLanes)},
                 {"double kernel (8 lines, gathers)", on(Kernel::doubleLanes)},
                 {"hull_lanes.h kernel (16 lines, no gathers)", on(Kernel::hullLanes)},
                 {"  the same, uniform spacing (timing only)", on(Kernel::hullLanesUniform)},
                 {"only reading heights, writing the output", on(Kernel::copyOnly)}},
                static_cast<double>(l.width * l.height), runs);
}

/// A strip of `kStripColumns` columns from the middle of the DEM, on its own: the float kernel
/// and hull_lanes.h on its columns, and hull_lanes.h's sheared lines at `azimuthDeg` (in grid
/// terms: tan(azimuth) columns a row, the distance along a line a row's height over its cosine),
/// every cell served from the two lines beside it. The sheared kernel's largest angle difference
/// from its reference is printed.
void stripRatios(const Lines& l, double azimuthDeg, int runs) {
    constexpr long kStripColumns = 256;
    if (l.width < kStripColumns) return;
    const long c0 = (l.width - kStripColumns) / 2;
    std::vector<float> heights(static_cast<std::size_t>(kStripColumns * l.height));
    for (long r = 0; r < l.height; ++r)
        std::copy_n(l.heights + r * l.width + c0, kStripColumns, heights.begin() + r * kStripColumns);
    Lines strip = l;
    strip.heights = heights.data();
    strip.width = kStripColumns;
    const double shear = std::tan(azimuthDeg * M_PI / 180.0);
    demlight::HullGeometry along = l.geometry;
    for (double& s : along.sigmaM) s /= std::cos(azimuthDeg * M_PI / 180.0);
    std::vector<float> out(heights.size()), exact(heights.size());
    const demlight::HullShear grid{heights.data(), out.data(), static_cast<std::size_t>(kStripColumns),
                                   static_cast<std::size_t>(l.height), shear};
    demlight::HullScratch scratch;
    demlight::hullShearVector(along, grid, scratch);
    demlight::hullShearReference(along, {heights.data(), exact.data(), grid.width, grid.height, shear}, scratch);
    double maxDeg = 0;
    for (std::size_t i = 0; i < out.size(); ++i)
        if (std::isfinite(out[i]) && std::isfinite(exact[i]))
            maxDeg = std::max(maxDeg, std::abs(std::atan(static_cast<double>(out[i])) -
                                               std::atan(static_cast<double>(exact[i]))) * 180.0 / M_PI);
    std::printf("a %ld-column strip from column %ld; sheared lines at %.1f deg: max %.1e deg from their reference\n",
                kStripColumns, c0, azimuthDeg, maxDeg);
    const auto on = [&](Kernel k) { return [&strip, &out, k] { sweepColumns(strip, out.data(), 1, k); }; };
    const std::string sheared = "hull_lanes.h sheared lines at " + std::to_string(azimuthDeg).substr(0, 4) + " deg";
    ratioRounds({{"float kernel on the strip's columns", on(Kernel::floatLanes)},
                 {"hull_lanes.h kernel on the strip's columns", on(Kernel::hullLanes)},
                 {sheared.c_str(), [&] { demlight::hullShearVector(along, grid, scratch); }}},
                static_cast<double>(heights.size()), runs);
}
#endif

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s DEM [runs] [ratios]\n", argv[0]);
        return 2;
    }
    try {
        const demlight::Dem dem = demlight::loadDem(argv[1]);
        const demlight::Terrain& t = dem.terrain;
        const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
        demlight::HorizonParams p;  // azimuth 0, whole DEM, no near field
        p.azimuthDeg = 0.0;
        Lines lines{t.heightsM.data(), static_cast<long>(t.width()), static_cast<long>(t.height()), {}, 0.0, {}, {}};
        // The library's distances along a column: the sum of the row heights walked (its sigmaAt).
        lines.sigma.assign(t.height(), 0.0);
        for (std::size_t r = 1; r < t.height(); ++r) lines.sigma[r] = lines.sigma[r - 1] + t.cellHeightM[r - 1];
        lines.invR = demlight::inverseEffectiveRadius(p);
        lines.geometry = {lines.sigma, lines.invR, {}};
        lines.uniform = lines.geometry;
        for (std::size_t r = 0; r < t.height(); ++r)
            lines.uniform.sigmaM[r] = lines.sigma.back() * static_cast<double>(r) / static_cast<double>(t.height() - 1);
        // "ratios" as a third argument: only the alternating rounds (and the kernel's error).
        const bool ratiosOnly = argc > 3 && std::string(argv[3]) == "ratios";
        const int all = demlight::resolveThreadCount(0);
        const double cells = static_cast<double>(t.width() * t.height());
        std::vector<float> slopes(t.width() * t.height());
        demlight::HorizonMap ref;
#ifdef FLOOR_AVX512
        if (ratiosOnly && demlight::hullVectorKernelAvailable()) {
            std::printf("%s: %zu x %zu cells, azimuth 0, whole DEM\n", argv[1], t.width(), t.height());
            sweepColumns(lines, slopes.data(), 1, Kernel::doubleLanes);
            const std::vector<float> doubleSlopes = slopes;
            sweepColumns(lines, slopes.data(), 1, Kernel::hullLanes);
            reportAgainst(slopes, doubleSlopes, "hull_lanes.h kernel");
            columnRatios(lines, slopes.data(), runs);
            stripRatios(lines, 37.0, runs);
            return 0;
        }
#endif

        // On a projected grid true north turns against the columns (meridian convergence): the
        // library's lines at azimuth 0 are not the columns, and the angles are not compared.
        const bool comparable = t.convergence.empty();
        std::printf("%s: %zu x %zu cells, azimuth 0, whole DEM, median of %d runs\n", argv[1], t.width(),
                    t.height(), runs);
        if (!comparable)
            std::printf("(projected grid: its columns are not true north, so the kernels' angles are not compared)\n");
        std::printf("%-44s %14s %16s %10s %12s\n", "kernel", "ns/cell 1 thr", "ns/cell all thr", "ratio", "cells off");
        const auto row = [&](const char* name, const std::function<void(int)>& run, bool check) {
            const double one = demlight::bench::medianSeconds(runs, [&] { run(1); });
            const double many = demlight::bench::medianSeconds(runs, [&] { run(all); });
            long differing = 0;
            double maxDiff = 0;
            char off[64] = "-";
            if (check && comparable) {
                compare(slopes, ref, differing, maxDiff);
                std::snprintf(off, sizeof off, "%ld (max %.1e deg)", differing, maxDiff);
            }
            std::printf("%-44s %14.2f %16.2f %10.2f %12s\n", name, one / cells * 1e9, many / cells * 1e9, one / many,
                        off);
        };
        row("library sweep (sweepHorizon, all passes)", [&](int threads) {
            demlight::withThreads(threads, [&] { ref = demlight::sweepHorizon(t, p); });
        }, false);
        const auto kernel = [&](Kernel k) {
            return [&, k](int threads) { sweepColumns(lines, slopes.data(), threads, k); };
        };
        row("bare hull kernel, scalar", kernel(Kernel::scalar), true);
#ifdef FLOOR_AVX512
        row("bare hull kernel, AVX-512 (8 lines a vector)", kernel(Kernel::doubleLanes), true);
        const std::vector<float> doubleSlopes = slopes;
        row("bare hull kernel, AVX-512 float (16 lines)", kernel(Kernel::floatLanes), true);
        double maxDeg = 0;
        std::vector<double> diffs;
        for (std::size_t i = 0; i < slopes.size(); ++i) {
            if (!std::isfinite(slopes[i]) || !std::isfinite(doubleSlopes[i])) continue;
            const double a = std::atan(static_cast<double>(slopes[i]));
            const double b = std::atan(static_cast<double>(doubleSlopes[i]));
            diffs.push_back(std::abs(a - b) * 180.0 / M_PI);
            maxDeg = std::max(maxDeg, diffs.back());
        }
        std::sort(diffs.begin(), diffs.end());
        if (!diffs.empty())
            std::printf("float kernel against the double kernels: median %.1e, p99 %.1e, max %.1e deg over %zu cells\n",
                        diffs[diffs.size() / 2], diffs[diffs.size() * 99 / 100], maxDeg, diffs.size());
        if (demlight::hullVectorKernelAvailable()) {
            row("hull_lanes.h kernel (16 lines, no gathers)", kernel(Kernel::hullLanes), true);
            reportAgainst(slopes, doubleSlopes, "hull_lanes.h kernel");
            columnRatios(lines, slopes.data(), runs);
        }
#else
        std::printf("(AVX-512 not compiled in: no vector kernel)\n");
#endif
    } catch (const demlight::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
