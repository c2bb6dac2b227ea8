// Core types: grid layout, convergence lattice interpolation, parallel-for determinism.
#include "src/grid.h"
#include "src/parallel.h"
#include "src/progress.h"
#include "src/terrain.h"

#include <gtest/gtest.h>

#include <atomic>

namespace demlight {
namespace {

TEST(Grid, IsRowMajorWithRowZeroFirst) {
    Grid<int> g(3, 2, 0);
    g(2, 1) = 7;
    EXPECT_EQ(g.data()[1 * 3 + 2], 7);
    EXPECT_EQ(g.rowPtr(1)[2], 7);
    EXPECT_EQ(g.size(), 6u);
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

TEST(ParallelFor, VisitsEveryIndexOnce) {
    std::vector<std::atomic<int>> hits(1000);
    parallelFor(0, hits.size(), 2, [&](std::size_t i) { hits[i]++; });
    for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
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

#include "src/angles.h"

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
