// Core types: grid layout, convergence lattice interpolation, parallel-for determinism.
#include "demlight/core/grid.h"
#include "demlight/core/parallel.h"
#include "demlight/core/progress.h"
#include "demlight/core/terrain.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <cmath>
#include <limits>
#include <random>

namespace demlight {
namespace {

TEST(Grid, IsRowMajorWithRowZeroFirst) {
    Grid<int> g(3, 2, 0);
    g(2, 1) = 7;
    EXPECT_EQ(g.data()[1 * 3 + 2], 7);
    EXPECT_EQ(g.rowPtr(1)[2], 7);
    EXPECT_EQ(g.size(), 6u);
}

// darkCells: the NaN bitmap of values that are all +0 or one NaN pattern, and none for
// anything else, wherever the odd value sits (first, inside a word, last, after a NaN).
TEST(Grid, DarkCellsAreTheNanBitmapOfZerosAndOneNan) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const std::size_t n : {std::size_t{1}, std::size_t{63}, std::size_t{64}, std::size_t{65}, std::size_t{200}}) {
        std::vector<float> v(n, 0.0f);
        const auto none = demlight::darkCells(v.data(), n);
        ASSERT_TRUE(none.has_value()) << n;
        EXPECT_EQ(none->nan, std::vector<std::uint64_t>((n + 63) / 64, 0)) << n;
        for (std::size_t i = 0; i < n; i += 3) v[i] = nan;
        const auto dark = demlight::darkCells(v.data(), n);
        ASSERT_TRUE(dark.has_value()) << n;
        for (std::size_t i = 0; i < n; ++i)
            ASSERT_EQ((dark->nan[i / 64] >> (i % 64)) & 1u, i % 3 == 0 ? 1u : 0u) << n << " " << i;
        for (const std::size_t at : {std::size_t{0}, n / 2, n - 1}) {
            // A value other than +0 and NaN, after NaNs or first.
            for (const float odd : {1.0f, -0.0f, 1e-45f}) {
                std::vector<float> w = v;
                w[at] = odd;
                EXPECT_FALSE(demlight::darkCells(w.data(), n).has_value()) << n << " " << at << " " << odd;
            }
            // A second NaN pattern after the first (v[0] is NaN).
            if (at > 0) {
                std::vector<float> w = v;
                w[at] = -nan;
                EXPECT_FALSE(demlight::darkCells(w.data(), n).has_value()) << n << " " << at;
            }
        }
    }
}

TEST(ConvergenceField, InterpolatesBilinearlyBetweenNodes) {
    ConvergenceField f;
    f.stepCells = 10;
    f.gammaDeg = Grid<float>(2, 2);
    f.gammaDeg(0, 0) = 0;
    f.gammaDeg(1, 0) = 1;
    f.gammaDeg(0, 1) = 2;
    f.gammaDeg(1, 1) = 3;
    EXPECT_DOUBLE_EQ(f.at(5, 5), 1.5);
    EXPECT_DOUBLE_EQ(f.at(10, 0), 1.0);
    EXPECT_DOUBLE_EQ(f.at(100, 100), 3.0);  // clamped beyond the last node
    EXPECT_EQ(f.range(), std::make_pair(0.0, 3.0));
    EXPECT_DOUBLE_EQ(ConvergenceField{}.at(3, 3), 0.0);
}

TEST(HeightRange, SkipsNodataAtEveryPositionAndLength) {
    // Against a plain loop that skips NaN: lengths across the vector lanes' remainder, nodata
    // first, last and in between, extremes in the tail, and an all-nodata grid.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> height(-50.0f, 3000.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t n : {1u, 7u, 16u, 17u, 33u, 100u, 1000u}) {
        for (int trial = 0; trial < 20; ++trial) {
            Grid<float> g(n, 1);
            for (std::size_t i = 0; i < n; ++i) g(i, 0) = rng() % 4 == 0 ? nan : height(rng);
            if (trial == 1) g(0, 0) = nan;
            if (trial == 2) g(n - 1, 0) = 5000.0f;
            if (trial == 3) g(n - 1, 0) = -400.0f;
            float lo = std::numeric_limits<float>::infinity(), hi = -lo;
            for (float z : g.values())
                if (!std::isnan(z)) lo = std::min(lo, z), hi = std::max(hi, z);
            const auto [gotLo, gotHi] = heightRangeM(g);
            EXPECT_EQ(gotLo, lo) << n << " " << trial;
            EXPECT_EQ(gotHi, hi) << n << " " << trial;
        }
    }
    const auto [lo, hi] = heightRangeM(Grid<float>(20, 3, nan));
    EXPECT_EQ(lo, std::numeric_limits<float>::infinity());
    EXPECT_EQ(hi, -std::numeric_limits<float>::infinity());
}

TEST(Grid, NonNanSpanIsBetweenTheEndRunsOfNan) {
    // Against its definition, one value at a time: runs of NaN at either end of every length
    // across the sixteen-value steps (0 to 40, all of the row), with NaN and values inside.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t n : {0u, 1u, 15u, 16u, 17u, 33u, 64u, 70u}) {
        for (std::size_t lead = 0; lead <= std::min<std::size_t>(n, 40); ++lead) {
            for (std::size_t trail = 0; lead + trail <= n && trail <= 40; trail += 3) {
                std::vector<float> row(n, 1.0f);
                for (std::size_t i = 0; i < lead; ++i) row[i] = nan;
                for (std::size_t i = n - trail; i < n; ++i) row[i] = -nan;
                if (lead + trail + 3 <= n) row[lead + 1] = nan;  // NaN inside the span
                std::size_t first = 0, end = n;
                while (first < end && std::isnan(row[first])) ++first;
                while (end > first && std::isnan(row[end - 1])) --end;
                const RowSpan span = nonNanSpan(row.data(), n);
                ASSERT_EQ(span.first, first) << n << " " << lead << " " << trail;
                ASSERT_EQ(span.end, end) << n << " " << lead << " " << trail;
            }
        }
    }
}

TEST(ParallelFor, VisitsEveryIndexOnce) {
    std::vector<std::atomic<int>> hits(1000);
    parallelFor(0, hits.size(), [&](std::size_t i) { hits[i]++; });
    for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
}

// A run enters its thread pool once (withThreads); loops inside it run on that pool's threads,
// not on a pool of their own per loop.
TEST(ParallelFor, RunsOnTheThreadsOfTheRunItIsCalledIn) {
    if (resolveThreadCount(0) < 2) GTEST_SKIP() << "needs two cores";
    std::atomic<int> onOtherThreads{0};
    withThreads(1, [&] {
        EXPECT_EQ(runThreads(), 1);
        const std::thread::id caller = std::this_thread::get_id();
        parallelFor(0, 64, [&](std::size_t) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            if (std::this_thread::get_id() != caller) ++onOtherThreads;
        });
    });
    EXPECT_EQ(onOtherThreads.load(), 0);
    EXPECT_GE(runThreads(), 2);  // outside a run: every core
    // The same count again inside adds no pool: the loop still runs on the run's two threads.
    withThreads(2, [&] { withThreads(2, [&] { EXPECT_EQ(runThreads(), 2); }); });
}

TEST(ProgressCounter, CancelStopsWork) {
    int calls = 0;
    ProgressCounter counter([&](double, const std::string&) { return ++calls < 2; }, "x", 100, 10);
    bool ok = true;
    for (int i = 0; i < 100 && ok; ++i) ok = counter.advance();
    EXPECT_FALSE(ok);
    EXPECT_TRUE(counter.cancelled());
}

}  // namespace
}  // namespace demlight

#include "demlight/core/angles.h"

namespace demlight {
namespace {

TEST(Angles, WrapAzimuth) {
    EXPECT_EQ(wrapAzimuthDeg(360.0), 0.0);
    EXPECT_EQ(wrapAzimuthDeg(-90.0), 270.0);
    EXPECT_EQ(wrapAzimuthDeg(720.5), 0.5);
    EXPECT_FALSE(std::signbit(wrapAzimuthDeg(-0.0)));
}

}  // namespace
}  // namespace demlight
