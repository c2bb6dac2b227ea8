#include "demlight/lighting/hull_lanes.h"

#include "demlight/core/avx512.h"
#include "demlight/core/error.h"
#include "demlight/core/simd.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace demlight {

namespace {

constexpr float kNoHorizon = -std::numeric_limits<float>::infinity();

void checkBlock(const HullGeometry& geometry, const HullBlock& block) {
    if (block.heightsRowStep == 0 && block.outRowStep == 0 && block.lines > block.stride)
        throw Error("hull kernel: a block of " + std::to_string(block.lines) + " lines in rows of " +
                    std::to_string(block.stride) + " samples");
    if (!geometry.sigmaM.empty() && geometry.sigmaM.front() != 0.0)
        throw Error("hull kernel: sigmaM[0] must be 0, not " + std::to_string(geometry.sigmaM.front()));
    if (!geometry.lineScale.empty() && geometry.lineScale.size() < block.lines)
        throw Error("hull kernel: " + std::to_string(geometry.lineScale.size()) + " line factors for " +
                    std::to_string(block.lines) + " lines");
}

/// The steps between a block's samples in its heights and its output (floats).
std::ptrdiff_t heightsStep(const HullBlock& block) {
    return block.heightsRowStep != 0 ? block.heightsRowStep : static_cast<std::ptrdiff_t>(block.stride);
}
std::ptrdiff_t outStep(const HullBlock& block) {
    return block.outRowStep != 0 ? block.outRowStep : static_cast<std::ptrdiff_t>(block.stride);
}

/// The spacing the float kernels count distances in (HullGeometry::spacingM).
double uniformSpacing(const HullGeometry& geometry) {
    const std::size_t n = geometry.sigmaM.size();
    if (geometry.spacingM > 0.0) return geometry.spacingM;
    return n > 1 ? geometry.sigmaM.back() / static_cast<double>(n - 1) : 1.0;
}

/// Line b's factor on sigmaM (HullGeometry::lineScale).
double lineFactor(const HullGeometry& geometry, std::size_t b) {
    return geometry.lineScale.empty() ? 1.0 : geometry.lineScale[b];
}

void checkShear(const HullGeometry& geometry, const HullShear& grid) {
    if (!geometry.lineScale.empty()) throw Error("hull kernel: sheared lines take no line factors");
    if (!(grid.shearCols >= 0.0 && grid.shearCols <= 1.0))
        throw Error("hull kernel: shearCols " + std::to_string(grid.shearCols) + " outside [0, 1]");
    if (geometry.sigmaM.size() != grid.height)
        throw Error("hull kernel: " + std::to_string(geometry.sigmaM.size()) + " distances for " +
                    std::to_string(grid.height) + " rows");
}

/// The lines of a shear, m from shearFirstLine to width - 1: enough that the last row's first
/// cell has a line on its left.
long shearFirstLine(const HullShear& grid) {
    return grid.height == 0 ? 0
                            : -static_cast<long>(std::floor(static_cast<double>(grid.height - 1) * grid.shearCols)) - 1;
}

/// Where the lines of a shear cross row r: whole columns (the same for every line, added to m) and
/// the fraction across to the next cell.
struct ShearRow {
    long whole;
    float fraction;
};
ShearRow shearRow(const HullShear& grid, std::size_t r) {
    const double x = static_cast<double>(r) * grid.shearCols;
    const double whole = std::floor(x);
    return {static_cast<long>(whole), static_cast<float>(x - whole)};
}

/// A cell's slope from the lines on its left (a) and right (b): the cell lies 1 - fraction across
/// from a, fraction from b, so f a + (1 - f) b, one rounding; b alone where the fraction is 0 (b
/// passes through the cell), the other where one has no data (the grid's right edge, a void),
/// -inf where one has no earlier sample.
float serveCell(float a, float b, float fraction) {
    if (fraction == 0.0f || std::isnan(a)) return b;
    if (std::isnan(b)) return a;
    if (a == kNoHorizon || b == kNoHorizon) return kNoHorizon;
    return __builtin_fmaf(fraction, a - b, b);
}

/// A line's height at row r between the cells a (left) and b: a where the fraction is 0.
float lineHeight(float a, float b, float fraction) { return fraction == 0.0f ? a : __builtin_fmaf(fraction, b - a, a); }

}  // namespace

void hullSlopesReference(const HullGeometry& geometry, const HullBlock& block, HullScratch& scratch) {
    checkBlock(geometry, block);
    const std::size_t n = geometry.sigmaM.size();
    // Line b's hull: (sigma, g) pairs from its bottom vertex up, at hullD[2 * b * n].
    scratch.hullD.resize(2 * n * block.lines);
    std::vector<std::size_t> top(block.lines, 0);
    const double invR = geometry.invRadius;
    const std::ptrdiff_t hStep = heightsStep(block), oStep = outStep(block);
    for (std::size_t i = 0; i < n; ++i) {
        const float* h = block.heightsM + static_cast<std::ptrdiff_t>(i) * hStep;
        float* out = block.out + static_cast<std::ptrdiff_t>(i) * oStep;
        const bool written = i >= block.firstOutRow;
        for (std::size_t b = 0; b < block.lines; ++b) {
            if (std::isnan(h[b])) {
                if (written) out[b] = h[b];
                continue;
            }
            const double s = geometry.sigmaM[i] * lineFactor(geometry, b);
            const double drop = 0.5 * s * s * invR;
            double* v = scratch.hullD.data() + 2 * b * n;
            std::size_t t = top[b];
            const double g = static_cast<double>(h[b]) - drop;
            // Pop the top vertex v1 unless the slope to v2 (below it, farther) is under the slope
            // to v1: then v1 stands above the sight line to v2 and stays on the hull.
            while (t >= 2 && !((v[2 * t - 3] - g) * (s - v[2 * t - 2]) < (v[2 * t - 1] - g) * (s - v[2 * t - 4]))) --t;
            if (written)
                out[b] = t >= 1 ? static_cast<float>((v[2 * t - 1] - g) / (s - v[2 * t - 2]) - s * invR) : kNoHorizon;
            v[2 * t] = s;
            v[2 * t + 1] = g;
            top[b] = t + 1;
        }
    }
}

void hullShearReference(const HullGeometry& geometry, const HullShear& grid, HullScratch& scratch) {
    checkShear(geometry, grid);
    const long w = static_cast<long>(grid.width), first = shearFirstLine(grid);
    const std::size_t lines = static_cast<std::size_t>(w - first), n = grid.height;
    // Line m's heights and slopes at [(m - first) + r * lines]: one block, a column a line.
    std::vector<float> heights(lines * n), slopes(lines * n);
    const auto cell = [&](std::size_t r, long c) {
        return c >= 0 && c < w ? grid.heightsM[r * grid.width + static_cast<std::size_t>(c)]
                               : std::numeric_limits<float>::quiet_NaN();
    };
    for (std::size_t r = 0; r < n; ++r) {
        const ShearRow row = shearRow(grid, r);
        for (long m = first; m < w; ++m) {
            heights[r * lines + static_cast<std::size_t>(m - first)] =
                lineHeight(cell(r, m + row.whole), cell(r, m + row.whole + 1), row.fraction);
        }
    }
    hullSlopesReference(geometry, {heights.data(), slopes.data(), lines, lines}, scratch);
    for (std::size_t r = 0; r < n; ++r) {
        const ShearRow row = shearRow(grid, r);
        for (long c = 0; c < w; ++c) {
            // The lines on the cell's left and right: m + whole + fraction = c - 1 + fraction, c + fraction.
            const std::size_t left = static_cast<std::size_t>(c - row.whole - 1 - first);
            float& o = grid.out[r * grid.width + static_cast<std::size_t>(c)];
            o = std::isnan(cell(r, c)) ? cell(r, c)
                                       : serveCell(slopes[r * lines + left], slopes[r * lines + left + 1], row.fraction);
        }
    }
}

HullSlopeBound hullSlopeErrorBound(const HullGeometry& geometry, double maxAbsGM) {
    const std::size_t n = geometry.sigmaM.size();
    if (n < 2) return {};
    const auto ulp = [](double x) { return x > 0.0 ? std::ldexp(1.0, std::ilogb(x) - 23) : 0.0; };
    double dMin = std::numeric_limits<double>::infinity(), offMax = 0.0;
    const double spacing = uniformSpacing(geometry);
    for (std::size_t i = 1; i < n; ++i) {
        dMin = std::min(dMin, geometry.sigmaM[i] - geometry.sigmaM[i - 1]);
        offMax = std::max(offMax, std::abs(geometry.sigmaM[i] - static_cast<double>(i) * spacing));
    }
    // Line factors scale every distance of a line: the shortest step and the longest line matter.
    double scaleMin = 1.0, scaleMax = 1.0;
    if (!geometry.lineScale.empty()) {
        const auto [lo, hi] = std::minmax_element(geometry.lineScale.begin(), geometry.lineScale.end());
        scaleMin = *lo;
        scaleMax = *hi;
    }
    dMin *= scaleMin;
    const double gRoundings = geometry.lineScale.empty() ? 3.0 : 4.0;
    const double relative = std::ldexp(1.0, -20) + 2.0 * ulp(offMax * scaleMax) / dMin;
    const double curve = geometry.sigmaM.back() * scaleMax * geometry.invRadius;
    return {2.0 * (2.0 * gRoundings * ulp(maxAbsGM) / dMin + relative * 2.0 * curve), 2.0 * relative};
}

namespace {

/// Per-sample floats shared by every line: the drop sigma^2 / (2 R), the curvature term sigma / R,
/// and the offset of sigma from a uniform spacing (sigma - i * spacing).
struct RowTables {
    const float* drop;
    const float* curve;
    const float* offset;
    float spacing;
    double spacingM;  // the same in double, for the line factors
};

/// The per-sample tables of the float kernels in scratch.rowTables; whether the offsets are not all 0.
bool makeRowTables(const HullGeometry& geometry, HullScratch& scratch, RowTables& t) {
    const std::size_t n = geometry.sigmaM.size();
    if (n >= (std::size_t{1} << 24))
        throw Error("hull kernel: lines of " + std::to_string(n) + " samples (rows are exact floats below 2^24)");
    // The uniform spacing the row differences are scaled by, and each sample's offset from it.
    const double spacing = uniformSpacing(geometry);
    scratch.rowTables.resize(3 * n);
    float* drop = scratch.rowTables.data();
    float* curve = drop + n;
    float* offset = curve + n;
    bool varying = false;
    for (std::size_t i = 0; i < n; ++i) {
        const double s = geometry.sigmaM[i];
        drop[i] = static_cast<float>(0.5 * s * s * geometry.invRadius);
        curve[i] = static_cast<float>(s * geometry.invRadius);
        const double off = s - static_cast<double>(i) * spacing;
        // Offsets below float's rounding of a distance are none: the row differences are exact.
        offset[i] = std::abs(off) > std::ldexp(spacing, -24) ? static_cast<float>(off) : 0.0f;
        varying = varying || offset[i] != 0.0f;
    }
    t = {drop, curve, offset, static_cast<float>(spacing), spacing};
    return varying;
}

/// A line's spacing and the factors of its drop r^2 s^2 / (2 R) and curvature term r s / R in
/// float, where lines have factors (HullGeometry::lineScale; the tables serve the others).
struct LineFloats {
    float spacing, dropScale, curveScale;
};
LineFloats lineFloats(const HullGeometry& geometry, const RowTables& t, std::size_t b) {
    const double s = t.spacingM * lineFactor(geometry, b);
    return {static_cast<float>(s), static_cast<float>(0.5 * s * s * geometry.invRadius),
            static_cast<float>(s * geometry.invRadius)};
}

/// The pop tests' distance from a vertex at `row` (with `offset`) to the sample at rf (with
/// offR): in samples where the spacing is uniform (it cancels from the tests), metres otherwise.
/// The integer difference is exact; the offsets are small, so the sum keeps float's relative
/// precision.
template <bool kVarying>
inline float testDistance1(float rf, float row, float offR, float offset, float spacing) {
    const float k = rf - row;
    if constexpr (kVarying) return __builtin_fmaf(k, spacing, offR - offset);
    return k;
}

/// One line of a block through the vector kernel's arithmetic (groupLines), a lane at a time: the
/// pops a loop over its test, the tangent one division. hull: 3 n floats (g, row, offset of each
/// vertex, bottom first).
template <bool kVarying, bool kPerLine>
void portableLine(const RowTables& t, const LineFloats& lf, const float* heights, std::ptrdiff_t hStep, float* out,
                  std::ptrdiff_t oStep, std::size_t firstOut, std::size_t n, float* hull) {
    float* const hg = hull;
    float* const hr = hull + n;
    float* const ho = hull + 2 * n;
    const float spacing = kPerLine ? lf.spacing : t.spacing;
    std::size_t top = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const float h = heights[static_cast<std::ptrdiff_t>(i) * hStep];
        float* const o = out + static_cast<std::ptrdiff_t>(i) * oStep;
        if (std::isnan(h)) {
            if (i >= firstOut) *o = h;
            continue;
        }
        const float rf = static_cast<float>(i), offR = t.offset[i];
        const float g = h - (kPerLine ? (rf * rf) * lf.dropScale : t.drop[i]);
        // Pop the top vertex c unless the slope to b (below it) is under the slope to c.
        while (top >= 2) {
            const std::size_t c = top - 1, b = top - 2;
            const float dc = testDistance1<kVarying>(rf, hr[c], offR, ho[c], spacing);
            const float db = testDistance1<kVarying>(rf, hr[b], offR, ho[b], spacing);
            if (!((hg[b] - g) * dc >= (hg[c] - g) * db)) break;
            --top;
        }
        if (i >= firstOut) {
            float slope = kNoHorizon;
            if (top >= 1) {
                const float k1 = rf - hr[top - 1];
                const float d1 = kVarying ? __builtin_fmaf(k1, spacing, offR - ho[top - 1]) : k1 * spacing;
                slope = (hg[top - 1] - g) / d1 - (kPerLine ? rf * lf.curveScale : t.curve[i]);
            }
            *o = slope;
        }
        hg[top] = g;
        hr[top] = rf;
        ho[top] = offR;
        ++top;
    }
}

/// Throws where a block has line factors over a varying spacing (the kernels keep one spacing
/// a line); returns whether it has factors.
bool perLine(const HullGeometry& geometry, bool varying) {
    if (geometry.lineScale.empty()) return false;
    if (varying) throw Error("hull kernel: line factors need a uniform spacing along the lines");
    return true;
}

}  // namespace

void hullSlopesPortable(const HullGeometry& geometry, const HullBlock& block, HullScratch& scratch) {
    checkBlock(geometry, block);
    const std::size_t n = geometry.sigmaM.size();
    if (n == 0 || block.lines == 0) return;
    RowTables t{};
    const bool varying = makeRowTables(geometry, scratch, t);
    const bool lines = perLine(geometry, varying);
    scratch.lineHull.resize(3 * n);
    const std::ptrdiff_t hStep = heightsStep(block), oStep = outStep(block);
    for (std::size_t b = 0; b < block.lines; ++b) {
        const LineFloats lf = lineFloats(geometry, t, b);
        const auto run = [&]<bool kVarying, bool kPerLine>() {
            portableLine<kVarying, kPerLine>(t, lf, block.heightsM + b, hStep, block.out + b, oStep, block.firstOutRow,
                                             n, scratch.lineHull.data());
        };
        if (lines)
            run.template operator()<false, true>();
        else if (varying)
            run.template operator()<true, false>();
        else
            run.template operator()<false, false>();
    }
}

#ifdef DEMLIGHT_HAS_AVX512_KERNELS

namespace {

constexpr int kLanes = 16;
/// Hull vertices kept in registers per lane.
constexpr int kWindow = 5;
/// Window slots that hold over the push (the bottom one falls off).
constexpr int kSlots = kWindow - 1;
/// When a lane walks, the lanes whose windows keep this many vertices or fewer after their pops
/// refill them in the same call.
constexpr int kRefillKept = 2;
static_assert(kSlots > kRefillKept);
/// How far ahead the heights and the output are prefetched (rows of one group).
constexpr std::size_t kPrefetchRows = 12;


/// A group's scratch: each point's dropped height and the row of the hull vertex below it when it
/// was pushed (-1: none), at [row * kLanes + lane].
struct GroupPoints {
    float* g;
    float* link;
};

/// Distance from a vertex at `row` (with `offset`) to the sample at rf (with offR), in the units the
/// pop tests compare: samples where the spacing is uniform (it cancels from the tests), metres
/// otherwise. The integer difference is exact; the offsets are small, so the sum keeps float's
/// relative precision.
template <bool kVarying>
DEMLIGHT_AVX512 inline __m512 testDistance(__m512 rf, __m512 row, __m512 offR, __m512 offset, __m512 spacing) {
    const __m512 k = _mm512_sub_ps(rf, row);
    if constexpr (kVarying) return _mm512_fmadd_ps(k, spacing, _mm512_sub_ps(offR, offset));
    return k;
}


/// A group's registers in memory for walkLanes: the new points' g, the rows under the windows,
/// and slots 1..4 of the windows after the vector pops (g, row, offset).
struct alignas(64) WalkLanes {
    float g[kLanes], u[kLanes];
    float s[kSlots][kLanes], q[kSlots][kLanes], o[kSlots][kLanes];
};

/// The lanes of `walk` popped down to the window's last vertex while the hull goes on below it:
/// each continues popping along the links (the same test as the vector code). Those lanes, and
/// the lanes of `refill` (windows of two vertices or fewer over more hull), then take the top four
/// vertices of their hull into slots 1..4 from the links, so that they walk again later or not at
/// all. w holds slots 1 and 2 on entry, all four (and u) of these lanes on return. Kept out of line:
/// the vector loop keeps its registers.
template <bool kVarying>
DEMLIGHT_AVX512 __attribute__((noinline)) void walkLanes(unsigned walk, unsigned refill, std::size_t r,
                                                        const RowTables& t, const GroupPoints& points,
                                                        WalkLanes& w) {
    auto& gs = w.g;
    auto& u = w.u;
    auto& s = w.s;
    auto& q = w.q;
    auto& o = w.o;
    const float rf = static_cast<float>(r), offR = t.offset[r];
    for (unsigned m = refill; m; m &= m - 1) {
        const int l = __builtin_ctz(m);
        // The vertices the window keeps (one where the lane walks, one or two otherwise), then the
        // ones below through the links.
        int kept = 1;
        while (kept < kRefillKept && !std::isnan(s[kept][l])) ++kept;
        float below = u[l];
        if (walk & (1u << l)) {
            float gc = s[0][l], rowC = q[0][l];
            while (below >= 0.0f) {
                const auto b = static_cast<std::size_t>(below);
                const float gb = points.g[b * kLanes + l];
                const float dc = testDistance1<kVarying>(rf, rowC, offR, t.offset[static_cast<std::size_t>(rowC)], t.spacing);
                const float db = testDistance1<kVarying>(rf, below, offR, t.offset[b], t.spacing);
                if (!((gb - gs[l]) * dc >= (gc - gs[l]) * db)) break;
                gc = gb;
                rowC = below;
                below = points.link[b * kLanes + l];
            }
            s[0][l] = gc;
            q[0][l] = rowC;
        }
        for (int j = kept; j < kSlots; ++j) {
            if (below >= 0.0f) {
                const auto b = static_cast<std::size_t>(below);
                s[j][l] = points.g[b * kLanes + l];
                q[j][l] = below;
                below = points.link[b * kLanes + l];
            } else {
                s[j][l] = std::numeric_limits<float>::quiet_NaN();
                q[j][l] = -1.0f;
            }
        }
        u[l] = below;
        for (int j = 0; j < kSlots; ++j) o[j][l] = q[j][l] < 0.0f ? 0.0f : t.offset[static_cast<std::size_t>(q[j][l])];
    }
}

/// Sixteen lines of a block, one a column: their samples are the block's cells, hStep / oStep
/// floats apart in the heights / the output; samples before firstOut are not written.
struct ColumnLines {
    const float* heights;
    float* out;
    std::ptrdiff_t hStep, oStep;
    std::size_t col0, n, firstOut;
    __mmask16 lanes;  // the lines that exist

    // Inlined by force: out of line, a function of prefetches alone counts as having no effect,
    // and its calls are dropped.
    DEMLIGHT_AVX512 DEMLIGHT_INLINE void prefetch(std::size_t r) const {
        if (r + kPrefetchRows >= n) return;
        const auto ahead = static_cast<std::ptrdiff_t>(r + kPrefetchRows);
        const float* h = heights + ahead * hStep + static_cast<std::ptrdiff_t>(col0);
        float* o = out + ahead * oStep + static_cast<std::ptrdiff_t>(col0);
        _mm_prefetch(reinterpret_cast<const char*>(h), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(h + kLanes - 1), _MM_HINT_T0);
        __builtin_prefetch(o, 1);
        __builtin_prefetch(o + kLanes - 1, 1);
    }
    DEMLIGHT_AVX512 __m512 load(std::size_t r, __m512 nan) const {
        return _mm512_mask_loadu_ps(nan, lanes,
                                    heights + static_cast<std::ptrdiff_t>(r) * hStep + static_cast<std::ptrdiff_t>(col0));
    }
    /// value: the slopes, NaN where the sample has no data.
    DEMLIGHT_AVX512 void store(std::size_t r, __m512 value) const {
        if (r < firstOut) return;
        _mm512_mask_storeu_ps(out + static_cast<std::ptrdiff_t>(r) * oStep + static_cast<std::ptrdiff_t>(col0), lanes,
                              value);
    }
};

/// A group's lines' spacing and the factors of their drop and curvature term (LineFloats), one a
/// lane; unused without line factors.
struct alignas(64) LaneFloats {
    float spacing[kLanes], dropScale[kLanes], curveScale[kLanes];
};

/// The lanes whose columns i + lane lie in [0, width).
inline __mmask16 columnsInside(long i, long width) {
    const long lo = std::clamp(-i, 0L, 16L), hi = std::clamp(width - i, 0L, 16L);
    return lo < hi ? static_cast<__mmask16>(((1u << hi) - 1u) & ~((1u << lo) - 1u)) : 0;
}

/// Sixteen adjacent lines of a shear (lane b is line first + b): at each row the lines share the
/// fraction across, so their heights are two unaligned loads and a multiply-add, and the fifteen
/// cells between them are served by the slopes shifted one lane and a multiply-add.
struct ShearedLines {
    const HullShear& grid;
    long first;
    // Of the row load() read last, for store():
    long column = 0;  // the cell under lane 0
    __m512 fraction{}, cells{};

    template <class T>
    DEMLIGHT_AVX512 T* at(T* base, std::size_t r, long c) const {
        return base + static_cast<std::ptrdiff_t>(r * grid.width) + c;
    }
    // Inlined by force: out of line, a function of prefetches alone counts as having no effect,
    // and its calls are dropped.
    DEMLIGHT_AVX512 DEMLIGHT_INLINE void prefetch(std::size_t r) const {
        if (r + kPrefetchRows >= grid.height) return;
        const std::size_t ahead = r + kPrefetchRows;
        const long c = std::clamp(first + shearRow(grid, ahead).whole, 0L, static_cast<long>(grid.width) - 1);
        _mm_prefetch(reinterpret_cast<const char*>(at(grid.heightsM, ahead, c)), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(at(grid.heightsM, ahead, c) + kLanes), _MM_HINT_T0);
        __builtin_prefetch(at(grid.out, ahead, c), 1);
        __builtin_prefetch(at(grid.out, ahead, c) + kLanes, 1);
    }
    DEMLIGHT_AVX512 __m512 load(std::size_t r, __m512 nan) {
        const ShearRow row = shearRow(grid, r);
        const long w = static_cast<long>(grid.width);
        column = first + row.whole;
        fraction = _mm512_set1_ps(row.fraction);
        cells = _mm512_mask_loadu_ps(nan, columnsInside(column, w), at(grid.heightsM, r, column));
        if (row.fraction == 0.0f) return cells;  // lineHeight
        const __m512 right = _mm512_mask_loadu_ps(nan, columnsInside(column + 1, w), at(grid.heightsM, r, column + 1));
        return _mm512_fmadd_ps(fraction, _mm512_sub_ps(right, cells), cells);
    }
    /// value: the lines' slopes, NaN where their samples have no data. Serves the cells under
    /// lanes 1..15 (hullShearReference's serveCell).
    DEMLIGHT_AVX512 void store(std::size_t r, __m512 value) const {
        const __m512 left = _mm512_castsi512_ps(
            _mm512_alignr_epi32(_mm512_castps_si512(value), _mm512_castps_si512(value), 15));
        __m512 served = value;  // serveCell
        if (_mm512_cvtss_f32(fraction) != 0.0f) {
            const __m512 noHorizon = _mm512_set1_ps(kNoHorizon);
            served = _mm512_fmadd_ps(fraction, _mm512_sub_ps(left, value), value);
            served = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(left, noHorizon, _CMP_EQ_OQ) |
                                              _mm512_cmp_ps_mask(value, noHorizon, _CMP_EQ_OQ),
                                          served, noHorizon);
            served = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(value, value, _CMP_UNORD_Q), served, left);
            served = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(left, left, _CMP_UNORD_Q), served, value);
        }
        served = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(cells, cells, _CMP_UNORD_Q), served, cells);
        const __mmask16 lanes = columnsInside(column, static_cast<long>(grid.width)) & 0xFFFEu;
        _mm512_mask_storeu_ps(at(grid.out, r, column), lanes, served);
    }
};

/// Rows [r0, r1) of sixteen lines (Lines: ColumnLines or ShearedLines), each lane's hull empty at r0.
/// kPerLine: each lane its own spacing, drop and curvature factors (lf), else the tables' (t).
template <bool kVarying, bool kPerLine, class Lines>
DEMLIGHT_AVX512 void groupLines(Lines& lines, const RowTables& t, const LaneFloats& lf, const GroupPoints& points,
                                std::size_t r0, std::size_t r1) {
    static_assert(!(kVarying && kPerLine), "line factors need a uniform spacing");
    const __m512 nan = _mm512_set1_ps(std::numeric_limits<float>::quiet_NaN());
    const __m512 none = _mm512_set1_ps(-1.0f), zero = _mm512_setzero_ps();
    // Each lane's window of hull vertices, top first: dropped height g (NaN: no vertex), row and
    // offset; U: the row of the vertex under the window's lowest one (-1: none, the window holds
    // the whole hull).
    __m512 G[kWindow], R[kWindow], O[kWindow];
    for (int j = 0; j < kWindow; ++j) {
        G[j] = nan;
        R[j] = none;
        O[j] = zero;
    }
    __m512 U = none;
    const __m512 noHorizon = _mm512_set1_ps(kNoHorizon);
    const __m512 spacing = kPerLine ? _mm512_load_ps(lf.spacing) : _mm512_set1_ps(t.spacing);
    const __m512 dropScale = kPerLine ? _mm512_load_ps(lf.dropScale) : zero;
    const __m512 curveScale = kPerLine ? _mm512_load_ps(lf.curveScale) : zero;
    // Locals, so that the stores below cannot make the compiler read them again.
    const float* const drop = t.drop;
    const float* const curve = t.curve;
    const float* const offsets = t.offset;
    float* const pointG = points.g;
    float* const pointLink = points.link;
    for (std::size_t r = r0; r < r1; ++r) {
        lines.prefetch(r);
        const __m512 h = lines.load(r, nan);
        const __mmask16 valid = _mm512_cmp_ps_mask(h, h, _CMP_ORD_Q);
        if (!valid) {  // nodata only (sea): every hull stays as it is
            lines.store(r, h);
            continue;
        }
        const __m512 rf = _mm512_set1_ps(static_cast<float>(r));
        const __m512 offR = _mm512_set1_ps(offsets[r]);
        const __m512 g = _mm512_sub_ps(
            h, kPerLine ? _mm512_mul_ps(_mm512_mul_ps(rf, rf), dropScale) : _mm512_set1_ps(drop[r]));

        // Pop test j (vertex j of the window, 0 on top): pop it unless the slope to vertex j + 1
        // is under the slope to vertex j. NaN (no vertex, or no data) compares false: no pop.
        __m512 a[kWindow], d[kWindow];
        for (int j = 0; j < kWindow; ++j) {
            a[j] = _mm512_sub_ps(G[j], g);
            d[j] = testDistance<kVarying>(rf, R[j], offR, O[j], spacing);
        }
        __mmask16 pop[kWindow - 1];
        for (int j = 0; j < kWindow - 1; ++j)
            pop[j] = _mm512_cmp_ps_mask(_mm512_mul_ps(a[j + 1], d[j]), _mm512_mul_ps(a[j], d[j + 1]), _CMP_GE_OQ);
        // On a convex chain the pops are a leading run (the new point above the line through
        // vertices j, j + 1 is above the line through j - 1, j too): lanes in m[k] pop at least
        // k + 1 vertices. Taking the run, not the tests, keeps the masks nested where rounding
        // breaks that order.
        __mmask16 m[kWindow - 1];
        // A lane without data at this row pops its top and pushes it back: the window stays, and
        // the push below needs no mask but the top's.
        m[0] = pop[0] | static_cast<__mmask16>(~valid);
        for (int j = 1; j < kWindow - 1; ++j) m[j] = m[j - 1] & pop[j];

        // The vertex that falls off the window's bottom at the push (no pop, full window) is the
        // one under the new bottom.
        U = _mm512_mask_mov_ps(U, valid & ~m[0] & _mm512_cmp_ps_mask(G[kWindow - 1], G[kWindow - 1], _CMP_ORD_Q),
                               R[kWindow - 1]);
        // Slot j after k pops holds old slot j + k, NaN past the window.
        __m512 S[kSlots], Q[kSlots], Os[kSlots];
        for (int j = 0; j < kSlots; ++j) {
            S[j] = G[j];
            Q[j] = R[j];
            Os[j] = O[j];
            for (int k = 1; k <= kWindow - 1; ++k) {
                if (j + k < kWindow) {
                    S[j] = _mm512_mask_mov_ps(S[j], m[k - 1], G[j + k]);
                    Q[j] = _mm512_mask_mov_ps(Q[j], m[k - 1], R[j + k]);
                    if constexpr (kVarying) Os[j] = _mm512_mask_mov_ps(Os[j], m[k - 1], O[j + k]);
                } else {
                    S[j] = _mm512_mask_mov_ps(S[j], m[k - 1], nan);
                    break;
                }
            }
        }
        const __mmask16 topLeft = _mm512_cmp_ps_mask(S[0], S[0], _CMP_ORD_Q);
        const __mmask16 more = valid & topLeft & _mm512_cmp_ps_mask(U, zero, _CMP_GE_OQ);
        const __mmask16 walk = more & _mm512_cmp_ps_mask(S[1], S[1], _CMP_UNORD_Q);
        if (walk) [[unlikely]] {
            const __mmask16 refill = walk | (more & _mm512_cmp_ps_mask(S[kRefillKept], S[kRefillKept], _CMP_UNORD_Q));
            WalkLanes w;
            _mm512_store_ps(w.g, g);
            _mm512_store_ps(w.u, U);
            for (int j = 0; j < kRefillKept; ++j) {
                _mm512_store_ps(w.s[j], S[j]);
                _mm512_store_ps(w.q[j], Q[j]);
            }
            walkLanes<kVarying>(walk, refill, r, t, points, w);
            U = _mm512_mask_load_ps(U, refill, w.u);
            for (int j = 0; j < kSlots; ++j) {
                S[j] = _mm512_mask_load_ps(S[j], refill, w.s[j]);
                Q[j] = _mm512_mask_load_ps(Q[j], refill, w.q[j]);
                if constexpr (kVarying) Os[j] = _mm512_mask_load_ps(Os[j], refill, w.o[j]);
            }
        }

        // The slope to the top vertex: one correctly rounded division, so that the portable
        // kernel, which divides too, gets the same bits.
        const __m512 k1 = _mm512_sub_ps(rf, Q[0]);
        const __m512 d1 = kVarying ? _mm512_fmadd_ps(k1, spacing, _mm512_sub_ps(offR, Os[0]))
                                   : _mm512_mul_ps(k1, spacing);
        const __m512 curveR = kPerLine ? _mm512_mul_ps(rf, curveScale) : _mm512_set1_ps(curve[r]);
        __m512 slope = _mm512_sub_ps(_mm512_div_ps(_mm512_sub_ps(S[0], g), d1), curveR);
        slope = _mm512_mask_blend_ps(topLeft, noHorizon, slope);
        lines.store(r, _mm512_mask_blend_ps(valid, h, slope));

        // Push: the point's height and the row of the vertex below it, stored whole (slots of
        // points that never become vertices are never read).
        _mm512_storeu_ps(pointG + r * kLanes, g);
        _mm512_storeu_ps(pointLink + r * kLanes, _mm512_mask_blend_ps(topLeft, none, Q[0]));
        for (int j = kWindow - 1; j >= 1; --j) {
            G[j] = S[j - 1];
            R[j] = Q[j - 1];
            if constexpr (kVarying) O[j] = Os[j - 1];
        }
        G[0] = _mm512_mask_mov_ps(G[0], valid, g);
        R[0] = _mm512_mask_mov_ps(R[0], valid, rf);
        if constexpr (kVarying) O[0] = _mm512_mask_mov_ps(O[0], valid, offR);
    }
}

template <bool kVarying, bool kPerLine>
DEMLIGHT_AVX512 void vectorBlock(const HullGeometry& geometry, const HullBlock& block, std::size_t n,
                                 const RowTables& t, HullScratch& scratch) {
    const std::size_t groups = (block.lines + kLanes - 1) / kLanes;
    scratch.pointG.resize(n * kLanes);
    scratch.pointLink.resize(n * kLanes);
    const GroupPoints points{scratch.pointG.data(), scratch.pointLink.data()};
    for (std::size_t q = 0; q < groups; ++q) {
        const std::size_t col0 = q * kLanes, count = std::min<std::size_t>(kLanes, block.lines - col0);
        LaneFloats lf{};
        if constexpr (kPerLine) {
            for (std::size_t l = 0; l < count; ++l) {
                const LineFloats f = lineFloats(geometry, t, col0 + l);
                lf.spacing[l] = f.spacing;
                lf.dropScale[l] = f.dropScale;
                lf.curveScale[l] = f.curveScale;
            }
        }
        ColumnLines lines{block.heightsM, block.out, heightsStep(block), outStep(block), col0, n, block.firstOutRow,
                          static_cast<__mmask16>((1u << count) - 1u)};
        groupLines<kVarying, kPerLine>(lines, t, lf, points, 0, n);
    }
}

}  // namespace

bool hullVectorKernelAvailable() { return processorHasAvx512(); }

namespace {


template <bool kVarying>
DEMLIGHT_AVX512 void vectorShear(const HullShear& grid, const RowTables& t, HullScratch& scratch) {
    const std::size_t n = grid.height;
    scratch.pointG.resize(n * kLanes);
    scratch.pointLink.resize(n * kLanes);
    const GroupPoints points{scratch.pointG.data(), scratch.pointLink.data()};
    const long w = static_cast<long>(grid.width);
    // Groups overlap by a line: each serves the fifteen cells between its lanes.
    for (long first = shearFirstLine(grid); first + 1 <= w - 1; first += kLanes - 1) {
        // The rows where the group's lanes read cells of the grid (the columns only grow).
        std::size_t r0 = 0;
        while (r0 < n && first + shearRow(grid, r0).whole + kLanes < 0) ++r0;
        std::size_t r1 = r0;
        while (r1 < n && first + shearRow(grid, r1).whole <= w - 1) ++r1;
        ShearedLines lines{grid, first};
        groupLines<kVarying, false>(lines, t, LaneFloats{}, points, r0, r1);
    }
}

}  // namespace

void hullSlopesVector(const HullGeometry& geometry, const HullBlock& block, HullScratch& scratch) {
    if (!hullVectorKernelAvailable()) throw Error("hull kernel: this processor (or this build) has no AVX-512");
    checkBlock(geometry, block);
    const std::size_t n = geometry.sigmaM.size();
    if (n == 0 || block.lines == 0) return;
    RowTables t{};
    const bool varying = makeRowTables(geometry, scratch, t);
    if (perLine(geometry, varying))
        vectorBlock<false, true>(geometry, block, n, t, scratch);
    else if (varying)
        vectorBlock<true, false>(geometry, block, n, t, scratch);
    else
        vectorBlock<false, false>(geometry, block, n, t, scratch);
}

void hullShearVector(const HullGeometry& geometry, const HullShear& grid, HullScratch& scratch) {
    if (!hullVectorKernelAvailable()) throw Error("hull kernel: this processor (or this build) has no AVX-512");
    checkShear(geometry, grid);
    if (grid.height == 0 || grid.width == 0) return;
    RowTables t{};
    if (makeRowTables(geometry, scratch, t))
        vectorShear<true>(grid, t, scratch);
    else
        vectorShear<false>(grid, t, scratch);
}

#else

bool hullVectorKernelAvailable() { return false; }

void hullSlopesVector(const HullGeometry&, const HullBlock&, HullScratch&) {
    throw Error("hull kernel: this build has no AVX-512 kernels");
}

void hullShearVector(const HullGeometry&, const HullShear&, HullScratch&) {
    throw Error("hull kernel: this build has no AVX-512 kernels");
}

#endif

void hullSlopes(const HullGeometry& geometry, const HullBlock& block, HullScratch& scratch) {
    if (simdPath() == SimdPath::Avx512) return hullSlopesVector(geometry, block, scratch);
    hullSlopesPortable(geometry, block, scratch);
}

}  // namespace demlight
