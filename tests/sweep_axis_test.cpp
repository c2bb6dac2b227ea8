// The sweep along the grid axes (demlight/lighting/sweep/axis_walk.h): each cell's angle is its
// line's slope from the gather-free float kernel (hull_lanes.h), on lines laid out as the sweep
// lays them, rows of different heights and widths included; with a range limit, the kernel's
// slope within the cell's chunk raised by the steepest sample of the previous chunk within range
// (found by brute force here); windows and thread counts give the same bits, and so do the
// portable and AVX-512 paths.
#include "demlight/core/parallel.h"
#include "demlight/core/angles.h"
#include "demlight/core/fast_math.h"
#include "demlight/core/simd.h"
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/hull_lanes.h"
#include "demlight/lighting/sweep/hull.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace demlight {
namespace {

/// Rough ground with a void, on rows whose cells widen and lengthen from north to south (a
/// geographic grid's are narrower toward the pole; their heights vary a little too).
Terrain roughGeographic(std::size_t w, std::size_t h) {
    Terrain t;
    t.heightsM = Grid<float>(w, h, 0.0f);
    std::mt19937 rng(17);
    std::normal_distribution<double> step(0.0, 9.0);
    for (std::size_t r = 0; r < h; ++r) {
        double z = 400.0 + 3.0 * static_cast<double>(r);
        for (std::size_t c = 0; c < w; ++c) {
            z += step(rng);
            const bool voidCell = c > w / 3 && c < w / 3 + 9 && r > h / 2 && r < h / 2 + 14;
            t.heightsM(c, r) = voidCell ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(z);
        }
        t.cellWidthM.push_back(18.0 + 0.013 * static_cast<double>(r));
        t.cellHeightM.push_back(30.8 + 2e-4 * static_cast<double>(r));
    }
    return t;
}

HorizonMap sweepAt(const Terrain& t, double azimuthDeg, int threads, std::optional<CellWindow> window = {},
                   double maxDistanceM = std::numeric_limits<double>::infinity()) {
    HorizonParams p;
    p.azimuthDeg = azimuthDeg;
    p.maxDistanceM = maxDistanceM;
    p.window = window;
    return withThreads(threads, [&] { return sweepHorizon(t, p); });
}

/// The angles the float kernel gives each cell: lines walked from the far edge toward the
/// azimuth's opposite, distances summed from the far edge as the sweep sums them (along rows: a
/// row's own cell width a step), slopes turned into angles as the sweep's combine does.
Grid<float> kernelAngles(const Terrain& t, double azimuthDeg, bool doubleHull = false) {
    const std::size_t w = t.width(), h = t.height();
    const bool alongRows = azimuthDeg == 90.0 || azimuthDeg == 270.0;
    const bool fromHighEnd = azimuthDeg == 180.0 || azimuthDeg == 90.0;  // south / east far edges
    const std::size_t lines = alongRows ? h : w, n = alongRows ? w : h;
    // The cell of sample i of line b, in walking order.
    const auto cell = [&](std::size_t i, std::size_t b) {
        const std::size_t m = fromHighEnd ? n - 1 - i : i;
        return alongRows ? std::pair{m, b} : std::pair{b, m};
    };
    HullGeometry g;
    g.invRadius = inverseEffectiveRadius(HorizonParams{});
    g.sigmaM.assign(n, 0.0);
    for (std::size_t i = 1; i < n; ++i) {
        if (alongRows) {
            g.sigmaM[i] = static_cast<double>(i);
        } else {
            const std::size_t prevRow = fromHighEnd ? n - i : i - 1;
            g.sigmaM[i] = g.sigmaM[i - 1] + t.cellHeightM[prevRow];
        }
    }
    if (alongRows) g.lineScale = t.cellWidthM;
    std::vector<float> heights(n * lines), slopes(n * lines);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t b = 0; b < lines; ++b) {
            const auto [c, r] = cell(i, b);
            heights[i * lines + b] = t.heightsM(c, r);
        }
    HullScratch scratch;
    const HullBlock block{heights.data(), slopes.data(), lines, lines};
    if (doubleHull)
        hullSlopesReference(g, block, scratch);
    else
        hullSlopesPortable(g, block, scratch);
    Grid<float> angles(w, h, std::numeric_limits<float>::quiet_NaN());
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t b = 0; b < lines; ++b) {
            const auto [c, r] = cell(i, b);
            const float s = slopes[i * lines + b];
            if (std::isnan(s)) continue;
            angles(c, r) = s == -std::numeric_limits<float>::infinity()
                               ? static_cast<float>(kNoHorizonDeg)
                               : static_cast<float>(fastAtan(static_cast<double>(s)) * kRadToDeg);
        }
    return angles;
}

/// The angle of a slope as the sweep's combine gives it.
float slopeAngle(float s) {
    return s == -std::numeric_limits<float>::infinity() ? static_cast<float>(kNoHorizonDeg)
                                                        : static_cast<float>(fastAtan(static_cast<double>(s)) * kRadToDeg);
}

/// The angles of a sweep with a range limit of maxDistanceM, one line at a time: each line cut
/// into chunks floor(sigma / maxDistanceM) of its distance from the far edge (sigma as
/// kernelAngles sums it), each chunk's samples through the float kernel (or the double hull) on
/// their own, distances from the chunk's first sample; each cell then raised by brute force to
/// its steepest sample of the previous chunk within maxDistanceM, in double.
Grid<float> limitedKernelAngles(const Terrain& t, double azimuthDeg, double maxDistanceM, bool doubleHull = false) {
    const std::size_t w = t.width(), h = t.height();
    const bool alongRows = azimuthDeg == 90.0 || azimuthDeg == 270.0;
    const bool fromHighEnd = azimuthDeg == 180.0 || azimuthDeg == 90.0;
    const std::size_t lines = alongRows ? h : w, n = alongRows ? w : h;
    const double invR = inverseEffectiveRadius(HorizonParams{});
    Grid<float> angles(w, h, std::numeric_limits<float>::quiet_NaN());
    HullScratch scratch;
    for (std::size_t b = 0; b < lines; ++b) {
        std::vector<double> sigma(n, 0.0), g(n);
        std::vector<float> heights(n);
        std::vector<std::pair<std::size_t, std::size_t>> cells(n);
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t m = fromHighEnd ? n - 1 - i : i;
            cells[i] = alongRows ? std::pair{m, b} : std::pair{b, m};
            if (alongRows) {
                sigma[i] = static_cast<double>(i) * t.cellWidthM[b];
            } else if (i > 0) {
                sigma[i] = sigma[i - 1] + t.cellHeightM[fromHighEnd ? n - i : i - 1];
            }
            heights[i] = t.heightsM(cells[i].first, cells[i].second);
            g[i] = static_cast<double>(heights[i]) - sigma[i] * sigma[i] * (0.5 * invR);
        }
        const auto chunk = [&](std::size_t i) { return static_cast<long>(std::floor(sigma[i] / maxDistanceM)); };
        std::vector<float> slopes(n);
        for (std::size_t s0 = 0, s1; s0 < n; s0 = s1) {
            for (s1 = s0 + 1; s1 < n && chunk(s1) == chunk(s0);) ++s1;
            HullGeometry geometry;
            geometry.invRadius = invR;
            geometry.sigmaM.resize(s1 - s0);
            for (std::size_t i = s0; i < s1; ++i)
                geometry.sigmaM[i - s0] = alongRows ? static_cast<double>(i - s0) : sigma[i] - sigma[s0];
            if (alongRows)
                geometry.lineScale = {t.cellWidthM[b]};
            else
                geometry.spacingM = sigma[n - 1] / static_cast<double>(n - 1);
            const HullBlock block{heights.data() + s0, slopes.data() + s0, 1, 1};
            if (doubleHull)
                hullSlopesReference(geometry, block, scratch);
            else
                hullSlopesPortable(geometry, block, scratch);
        }
        for (std::size_t i = 0; i < n; ++i) {
            float s = slopes[i];
            if (std::isnan(heights[i])) continue;
            for (std::size_t p = 0; p < i; ++p)
                if (chunk(p) == chunk(i) - 1 && sigma[p] >= sigma[i] - maxDistanceM && !std::isnan(heights[p]))
                    s = std::max(s, sweep::rangeSlope(g[p], sigma[p], g[i], sigma[i], invR));
            angles(cells[i].first, cells[i].second) = slopeAngle(s);
        }
    }
    return angles;
}

std::size_t differingCells(const Grid<float>& a, const Grid<float>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const float x = a.data()[i], y = b.data()[i];
        n += !(std::memcmp(&x, &y, sizeof x) == 0 || (std::isnan(x) && std::isnan(y)));
    }
    return n;
}

TEST(SweepAxis, EachCellIsItsLinesFloatKernelSlope) {
    const Terrain t = roughGeographic(83, 71);
    for (const double az : {0.0, 90.0, 180.0, 270.0}) {
        const HorizonMap map = sweepAt(t, az, 1);
        EXPECT_EQ(differingCells(map.angleDeg, kernelAngles(t, az)), 0u) << "azimuth " << az;
    }
}

TEST(SweepAxis, RangeLimitedCellIsItsChunksKernelSlopeRaisedByThePreviousChunk) {
    const Terrain t = roughGeographic(83, 71);
    for (const double L : {400.0, 1000.0})
        for (const double az : {0.0, 90.0, 180.0, 270.0}) {
            const HorizonMap map = sweepAt(t, az, 1, {}, L);
            EXPECT_EQ(differingCells(map.angleDeg, limitedKernelAngles(t, az, L)), 0u) << "azimuth " << az << " L " << L;
        }
}

TEST(SweepAxis, WindowsThreadsAndPathsGiveTheSameBits) {
    const Terrain t = roughGeographic(97, 64);
    const CellWindow win{13, 9, 70, 41};  // col0, row0, col1, row1
    // Without a range limit, and with one whose chunks start inside and outside the window.
    for (const double L : {std::numeric_limits<double>::infinity(), 300.0, 710.0})
    for (const double az : {0.0, 90.0, 180.0, 270.0}) {
        SCOPED_TRACE("range limit " + std::to_string(L));
        const HorizonMap whole = sweepAt(t, az, 1, {}, L);
        EXPECT_EQ(differingCells(sweepAt(t, az, 2, {}, L).angleDeg, whole.angleDeg), 0u) << "two threads, azimuth " << az;
        const HorizonMap part = sweepAt(t, az, 2, win, L);
        std::size_t wrong = 0;
        for (std::size_t r = 0; r < t.height(); ++r)
            for (std::size_t c = 0; c < t.width(); ++c) {
                const bool inside = c >= win.col0 && c < win.col1 && r >= win.row0 && r < win.row1;
                const float x = part.angleDeg(c, r), y = whole.angleDeg(c, r);
                wrong += inside ? !(std::memcmp(&x, &y, sizeof x) == 0 || (std::isnan(x) && std::isnan(y)))
                                : !std::isnan(x);
            }
        EXPECT_EQ(wrong, 0u) << "window, azimuth " << az;
        detail::ScopedSimdPath portable(SimdPath::Portable);
        EXPECT_EQ(differingCells(sweepAt(t, az, 1, {}, L).angleDeg, whole.angleDeg), 0u) << "portable path, azimuth " << az;
    }
}

/// The float kernel's angles against the double hull's on the lines of real terrain and a
/// surface model (walls a metre apart), every axis direction: within 1e-3 deg at the 99.9th
/// percentile and 2e-3 deg at worst (measured: 3e-4 and 5e-4 on the shared DEMs and surface
/// models, demlight_axis_precision_bench), the same cells with and without terrain.
TEST(SweepAxis, FloatKernelWithinAThousandthOfADegreeOfTheDoubleHull) {
    for (const char* file : {"rocky_mountain_np_dem.tif", "harlem_dsm_trees_1m.tif"}) {
        const Terrain t = loadDem(std::string(DEMLIGHT_SAMPLES_DIR) + "/" + file).terrain;
        // The whole line, and chunks of a quarter of the DEM's height with the previous chunk's
        // part in double (as the sweep's range limit cuts them).
        const double L = 0.25 * static_cast<double>(t.height()) * t.cellHeightM.front();
        for (const bool limited : {false, true})
        for (const double az : {0.0, 90.0, 180.0, 270.0}) {
            SCOPED_TRACE(limited ? "range-limited" : "whole lines");
            const Grid<float> f = limited ? limitedKernelAngles(t, az, L) : kernelAngles(t, az);
            const Grid<float> d = limited ? limitedKernelAngles(t, az, L, true) : kernelAngles(t, az, true);
            std::vector<double> diffs;
            std::size_t oneSided = 0;
            for (std::size_t i = 0; i < f.size(); ++i) {
                const float x = f.data()[i], y = d.data()[i];
                const bool noneX = std::isnan(x) || x == static_cast<float>(kNoHorizonDeg);
                const bool noneY = std::isnan(y) || y == static_cast<float>(kNoHorizonDeg);
                if (noneX || noneY) {
                    oneSided += noneX != noneY;
                    continue;
                }
                diffs.push_back(std::abs(static_cast<double>(x) - y));
            }
            ASSERT_GT(diffs.size(), t.width() * t.height() / 2) << file;
            std::sort(diffs.begin(), diffs.end());
            EXPECT_EQ(oneSided, 0u) << file << " azimuth " << az;
            EXPECT_LE(diffs[diffs.size() * 999 / 1000], 1e-3) << file << " azimuth " << az;
            EXPECT_LE(diffs.back(), 2e-3) << file << " azimuth " << az;
        }
    }
}

}  // namespace
}  // namespace demlight
