// A window of a wide DEM costs its own cells: the sweep's regions and the per-row step bounds
// are found without a pass over the whole grid, with the whole grid's bits
// (demlight/lighting/horizon.h, demlight/lighting/sweep/row_steps.h).
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/sweep/row_steps.h"

#include "demlight/core/angles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace demlight {
namespace {

/// Cell widths of a geographic grid of 3-arc-second rows from latitude lat0Deg southward.
void geographicRows(std::size_t rows, double lat0Deg, std::vector<double>& widthM, std::vector<double>& heightM) {
    widthM.resize(rows);
    heightM.resize(rows);
    for (std::size_t r = 0; r < rows; ++r) {
        const double lat = (lat0Deg - (static_cast<double>(r) + 0.5) / 1200.0) * kDegToRad;
        widthM[r] = 92.6 * std::cos(lat);
        heightM[r] = 92.2 + 0.6 * std::sin(lat) * std::sin(lat);  // the meridian arc grows poleward
    }
}

std::pair<double, double> scanAllRows(const std::vector<double>& w, const std::vector<double>& h, double dc,
                                      double dr) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (std::size_t r = 0; r < w.size(); ++r) {
        lo = std::min(lo, lineStepM(dc, dr, w[r], h[r]));
        hi = std::max(hi, lineStepM(dc, dr, w[r], h[r]));
    }
    return {lo, hi};
}

TEST(RowStepBounds, GivesTheBitsOfAScanOfEveryRow) {
    std::vector<double> w, h;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    // Geographic rows (sizes monotone in latitude), and rows of random sizes (no order at all).
    for (int grid = 0; grid < 2; ++grid) {
        if (grid == 0) {
            geographicRows(40834, 61.0, w, h);
        } else {
            w.resize(5001);
            h.resize(5001);
            for (std::size_t r = 0; r < w.size(); ++r) w[r] = 20 + 10 * unit(rng), h[r] = 30 + 10 * unit(rng);
        }
        const RowStepBounds bounds(w, h);
        for (int i = 0; i < 200; ++i) {
            const double slope = i == 0 ? 0.0 : unit(rng);
            for (const bool xMajor : {true, false}) {
                const double dc = xMajor ? 1.0 : slope, dr = xMajor ? slope : 1.0;
                const auto [lo, hi] = bounds.range(dc, dr);
                const auto [loAll, hiAll] = scanAllRows(w, h, dc, dr);
                EXPECT_EQ(std::memcmp(&lo, &loAll, sizeof lo), 0) << grid << " " << slope << " " << xMajor;
                EXPECT_EQ(std::memcmp(&hi, &hiAll, sizeof hi), 0) << grid << " " << slope << " " << xMajor;
            }
        }
    }
}

TEST(RowStepBounds, EvaluatesFewRowsOfAGeographicGrid) {
    std::vector<double> w, h;
    geographicRows(100000, 70.0, w, h);  // 83 degrees of latitude
    const RowStepBounds bounds(w, h);
    for (const double slope : {0.0, 0.3, -0.75, 1.0}) {
        std::size_t rows = 0;
        bounds.range(1.0, slope, &rows);
        EXPECT_LE(rows, 40 * RowStepBounds::kLeafRows) << slope;
        bounds.range(slope, 1.0, &rows);
        EXPECT_LE(rows, 40 * RowStepBounds::kLeafRows) << slope;
    }
}

/// A 64 x 64 tile in the middle of a full grid `width` cells wide and 512 rows high (geographic
/// rows), heights of a hill.
Terrain tileOfWideGrid(std::size_t width) {
    auto frame = std::make_shared<GridFrame>();
    frame->width = width;
    frame->height = 512;
    geographicRows(frame->height, 45.0, frame->cellWidthM, frame->cellHeightM);
    frame->lowM = 0, frame->highM = 500;
    Grid<float> heights(64, 64);
    for (std::size_t r = 0; r < 64; ++r)
        for (std::size_t c = 0; c < 64; ++c)
            heights(c, r) = static_cast<float>(250 + 200 * std::sin(0.1 * static_cast<double>(c + 2 * r)));
    Terrain t = makeUniformTerrain(std::move(heights), 90.0);
    t.cellWidthM.assign(frame->cellWidthM.begin() + 224, frame->cellWidthM.begin() + 288);
    t.cellHeightM.assign(frame->cellHeightM.begin() + 224, frame->cellHeightM.begin() + 288);
    t.frame = frame;
    t.frameCol0 = width / 2 - 32;
    t.frameRow0 = 224;
    return t;
}

/// A sun-like azimuth field: the same change per column whatever the grid's width (the sun's
/// azimuth follows longitude), so a wider grid holds more regions.
HorizonParams sunLikeParams() {
    HorizonParams p;
    p.azimuthDeg = 120;
    p.maxDistanceM = 3000;
    p.directionToleranceDeg = 0.05;
    p.azimuthAtDeg = [](double col, double row) { return 120.0 + 0.004 * col - 0.001 * row; };
    return p;
}

TEST(SweepWindow, RegionsExaminedForAWindowDoNotGrowWithTheGridsWidth) {
    const HorizonParams p = sunLikeParams();
    const auto regionsOf = [&](std::size_t width, std::size_t& examined) {
        const Terrain t = tileOfWideGrid(width);
        return sweepRegionsOnFullGrid(t, p, cellsOnFullGrid(t), &examined).size();
    };
    std::size_t examinedNarrow = 0;
    const std::size_t regionsNarrow = regionsOf(2048, examinedNarrow);
    ASSERT_GE(regionsNarrow, 2u);
    // Wider grids halve differently, so the window meets other region edges, and their splits
    // are deeper by a halving per doubling: bounded, not in proportion to the width (128x).
    for (const std::size_t width : {8192u, 65536u, 262144u}) {
        std::size_t examined = 0;
        EXPECT_LE(regionsOf(width, examined), 2 * regionsNarrow) << width;
        EXPECT_LE(examined, 2 * examinedNarrow) << width;
    }
    // The whole wide grid splits into thousands.
    std::size_t examinedWhole = 0;
    sweepRegionsOnFullGrid(tileOfWideGrid(262144), p, CellWindow{0, 0, 262144, 512}, &examinedWhole);
    EXPECT_GT(examinedWhole, 100 * examinedNarrow);
}

TEST(SweepWindow, AWindowOfAWideGeographicGridGetsTheWholeGridsBits) {
    // A 3000 x 200 grid of geographic rows with a sun-like field: a tile with its halo, swept for
    // the window's cells, against the whole grid.
    Grid<float> heights(3000, 200);
    for (std::size_t r = 0; r < heights.height(); ++r)
        for (std::size_t c = 0; c < heights.width(); ++c)
            heights(c, r) = static_cast<float>(300 * std::sin(0.021 * static_cast<double>(c)) *
                                                   std::cos(0.037 * static_cast<double>(r)) +
                                               40 * std::sin(0.3 * static_cast<double>(c + r)));
    Terrain whole = makeUniformTerrain(std::move(heights), 90.0);
    geographicRows(whole.height(), 50.0, whole.cellWidthM, whole.cellHeightM);
    HorizonParams p = sunLikeParams();
    ASSERT_GE(sweepRegions(whole, p).size(), 4u);
    const HorizonMap all = sweepHorizon(whole, p);
    const CellWindow window{1400, 60, 1500, 140};
    const CellWindow read{1360, 20, 1540, 180};  // 40 cells of halo = 3.6 km > maxDistanceM
    const Terrain tile = tileOf(whole, read);
    p.window = CellWindow{window.col0 - read.col0, window.row0 - read.row0, window.col1 - read.col0,
                          window.row1 - read.row0};
    const HorizonMap part = sweepHorizon(tile, p);
    std::size_t different = 0;
    for (std::size_t r = window.row0; r < window.row1; ++r) {
        for (std::size_t c = window.col0; c < window.col1; ++c) {
            const float x = all.angleDeg(c, r), y = part.angleDeg(c - read.col0, r - read.row0);
            different += std::memcmp(&x, &y, sizeof x) != 0;
        }
    }
    EXPECT_EQ(different, 0u);
}

}  // namespace
}  // namespace demlight
