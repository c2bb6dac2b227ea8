// planScene: what `--quality auto` and `full` choose, against hand-computed values.
#include "demlight/lighting/quality.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace demlight {
namespace {

/// A cone of the given peak height falling `slope` metres per cell, clipped at 0.
Terrain cone(std::size_t n, double cellM, float peakM, float slope = 1.0f) {
    Grid<float> z(n, n);
    for (std::size_t r = 0; r < n; ++r)
        for (std::size_t c = 0; c < n; ++c)
            z(c, r) = std::max(0.0f, peakM - slope * static_cast<float>(std::hypot(double(c) - n / 2.0, double(r) - n / 2.0)));
    return makeUniformTerrain(std::move(z), cellM);
}

TEST(Quality, AutoDistanceIsReliefOverTanLowestElevationCappedByDiagonal) {
    const Terrain t = cone(200, 30, 50);  // relief 50 m, diagonal 8485 m
    QualityBudget b;
    b.lowestElevationDeg = 2;
    const ScenePlan p = planScene(t, Quality::Auto, b);
    EXPECT_NEAR(p.maxDistanceM, 50 / std::tan(2 * M_PI / 180), 1e-6);  // 1431.8 m
    // Drop over 1432 m at R/(1-0.13): 1432 / (2 * 7.32e6) rad = 0.0056 deg < 0.1 * 0.1 deg.
    EXPECT_FALSE(p.curvature);
    const ScenePlan tall = planScene(cone(200, 30, 1000, 10), Quality::Auto, b);
    EXPECT_NEAR(tall.maxDistanceM, std::hypot(6000.0, 6000.0), 1e-6);  // capped by the diagonal
    EXPECT_TRUE(tall.curvature);  // 8.5 km: 0.033 deg >= 0.01 deg
    EXPECT_EQ(p.skyDirections, kAutoSkyDirections);
    EXPECT_FALSE(p.reasons.empty());
}

TEST(Quality, FarFieldCrossingsOnlyWhereStepsAreSteep) {
    // 1 m per 30 m cell: no step steeper than 45 deg, so no edges between scan steps to sample.
    const Terrain smooth = cone(200, 30, 50);
    // 10 m per 1 m cell: every step is steep (a surface model by the same share).
    const Terrain steep = cone(200, 1, 1000, 10);
    for (const Quality q : {Quality::Auto, Quality::Full}) {
        const ScenePlan s = planScene(smooth, q, {}), t = planScene(steep, q, {});
        EXPECT_FALSE(s.farFieldCrossings);
        EXPECT_TRUE(t.farFieldCrossings);
        EXPECT_FALSE(planHorizonParams(s, 0.13).farFieldCrossings);
        EXPECT_TRUE(planHorizonParams(t, 0.13).farFieldCrossings);
        EXPECT_FALSE(planSunFrameParams(s, 0.53, 0.13).farFieldCrossings);
        const auto has = [](const ScenePlan& p, const char* what) {
            for (const std::string& r : p.reasons)
                if (r.find(what) != std::string::npos) return true;
            return false;
        };
        EXPECT_TRUE(has(s, "far_field_crossings=off"));
        EXPECT_TRUE(has(t, "far_field_crossings=on"));
    }
    // A given near field keeps the scene's choice.
    QualityBudget given;
    given.nearFieldSteps = 8;
    EXPECT_FALSE(planScene(smooth, Quality::Auto, given).farFieldCrossings);
}

TEST(Quality, AutoSearchesTheWholeDemWhenTheDistanceIsHalfTheDiagonalOrMore) {
    // Relief 200 m: 200 / tan 2 deg = 5727 m, two thirds of the 8485 m diagonal: a range limit
    // that long saves no sweep work, so auto searches the whole DEM.
    const ScenePlan p = planScene(cone(200, 30, 200, 2), Quality::Auto, {});
    EXPECT_NEAR(p.maxDistanceM, std::hypot(6000.0, 6000.0), 1e-6);
    // Relief 100 m: 2864 m, a third of the diagonal: kept.
    EXPECT_NEAR(planScene(cone(200, 30, 100), Quality::Auto, {}).maxDistanceM, 100 / std::tan(2 * M_PI / 180), 1e-6);
}

TEST(Quality, FullTurnsEverythingOn) {
    const ScenePlan p = planScene(cone(100, 10, 5), Quality::Full, {});
    EXPECT_NEAR(p.maxDistanceM, std::hypot(1000.0, 1000.0), 1e-6);
    EXPECT_TRUE(p.curvature);
    EXPECT_EQ(p.skyDirections, kFullSkyDirections);
    EXPECT_LT(p.sunLatticeStepCells, 64u);
}

TEST(Quality, ExpectedErrorScope) {
    QualityBudget b;
    b.lowestElevationDeg = 3;
    // auto: horizons from the budget's lowest elevation up, whether or not its distance is
    // capped by the diagonal; full: every horizon.
    const ScenePlan shortSearch = planScene(cone(200, 30, 50), Quality::Auto, b);
    EXPECT_EQ(shortSearch.expectedError.aboveElevationDeg, 3.0);
    EXPECT_NE(describeExpectedError(shortSearch.expectedError).find("at or above 3 deg"), std::string::npos);
    EXPECT_EQ(planScene(cone(200, 30, 1000, 10), Quality::Auto, b).expectedError.aboveElevationDeg, 3.0);
    EXPECT_EQ(planScene(cone(200, 30, 50), Quality::Full, b).expectedError.aboveElevationDeg, -90.0);
    EXPECT_EQ(describeExpectedError(planScene(cone(200, 30, 50), Quality::Full, b).expectedError).find("at or above"),
              std::string::npos);
    // What a shorter --max-distance resolves: atan(relief / d), 50 m seen from 500 m; -90 when d
    // covers the diagonal (8485 m).
    EXPECT_NEAR(resolvedElevationDeg(cone(200, 30, 50), 500), std::atan(0.1) * 180 / M_PI, 1e-9);
    EXPECT_EQ(resolvedElevationDeg(cone(200, 30, 50), 9000), -90.0);
}

// The figures were measured at the default budget; a looser --tolerance lets auto add up to it
// to full's error, and the statement must say so. A tighter one models more, within them.
TEST(Quality, ExpectedErrorGrowsWithALooserTolerance) {
    const Terrain t = cone(200, 30, 50);
    const ExpectedError measured = planScene(t, Quality::Auto, {}).expectedError;
    QualityBudget loose;
    loose.toleranceDeg = 2.0;
    const ExpectedError e = planScene(t, Quality::Auto, loose).expectedError;
    EXPECT_DOUBLE_EQ(e.medianDeg, measured.medianDeg + 2.0);
    EXPECT_DOUBLE_EQ(e.p99Deg, measured.p99Deg + 2.0);
    EXPECT_NE(e.source.find("tolerance 2 deg"), std::string::npos) << e.source;
    QualityBudget tight;
    tight.toleranceDeg = 0.01;
    EXPECT_EQ(planScene(t, Quality::Auto, tight).expectedError.medianDeg, measured.medianDeg);
    EXPECT_EQ(planScene(t, Quality::Full, loose).expectedError.medianDeg,
              planScene(t, Quality::Full, {}).expectedError.medianDeg);
}

// Auto's scan tolerance is at least the angle budget (a direction error theta changes a horizon
// by about theta |dh/dA| at any distance), so large DEMs need no more regions than the budget
// asks; full keeps its fixed 0.01 deg.
TEST(Quality, AutoScanToleranceIsAtLeastTheBudget) {
    const Terrain big = cone(2000, 30, 5000);  // 85 km diagonal, searched whole: the cell rule gives 0.02 deg
    HorizonParams rule;
    rule.maxDistanceM = 1e9;
    ASSERT_LT(effectiveDirectionToleranceDeg(big, rule), 0.05);
    QualityBudget b;
    const ScenePlan autoPlan = planScene(big, Quality::Auto, b);
    EXPECT_EQ(autoPlan.directionToleranceFloorDeg, b.toleranceDeg);
    EXPECT_DOUBLE_EQ(effectiveDirectionToleranceDeg(big, planHorizonParams(autoPlan, 0.13)), b.toleranceDeg);
    b.toleranceDeg = 3;
    EXPECT_EQ(planScene(big, Quality::Auto, b).directionToleranceFloorDeg, kMaxDirectionFloorDeg);
    const ScenePlan full = planScene(big, Quality::Full, {});
    EXPECT_EQ(full.directionToleranceFloorDeg, 0.0);
    EXPECT_EQ(effectiveDirectionToleranceDeg(big, planHorizonParams(full, 0.13)), 0.01);
    // A cell rule looser than the budget stays (small DEMs).
    const Terrain small = cone(50, 30, 50);
    EXPECT_GT(effectiveDirectionToleranceDeg(small, planHorizonParams(planScene(small, Quality::Auto, {}), 0.13)), 0.1);
}

TEST(Quality, ExpectedErrorIsLargerOnElongatedCells) {
    // The stability suite measured a larger sweep error on 4.8:1 cells (78 N lat/lon).
    Terrain elongated = cone(100, 30, 50);
    for (double& w : elongated.cellWidthM) w = 6.4;
    const ScenePlan square = planScene(cone(100, 30, 50), Quality::Auto, {});
    const ScenePlan thin = planScene(elongated, Quality::Auto, {});
    EXPECT_GT(thin.expectedError.medianDeg, square.expectedError.medianDeg);
    EXPECT_GT(thin.expectedError.p99Deg, square.expectedError.p99Deg);
}

TEST(Quality, SweepWorkOfAnOnAxisSweepIsOneStepPerCellPlusTheCombine) {
    // One region (uniform projected grid, on-axis): every line walks the whole grid once (the
    // distance reaches across it) and every cell is combined once: 2 x cells.
    const Terrain t = cone(100, 30, 50);
    HorizonParams p;
    p.maxDistanceM = 1e6;
    for (double az : {0.0, 90.0, 180.0, 270.0}) {
        p.azimuthDeg = az;
        EXPECT_EQ(estimateSweepSteps(t, p), 2.0 * 100 * 100) << az;
    }
    // A short distance on a tall grid: lines still walk from the far window end to the near one.
    p.azimuthDeg = 0;
    p.maxDistanceM = 300;  // 10 cells
    EXPECT_EQ(estimateSweepSteps(t, p), 2.0 * 100 * 100);
    // More directions cost proportionally more.
    const ScenePlan plan = planScene(t, Quality::Auto, {});
    EXPECT_EQ(estimateSweepWork(t, plan, 4, 0.13), 4 * 2.0 * 100 * 100);
}

TEST(Quality, RejectsBadBudgetsAndNames) {
    QualityBudget b;
    b.toleranceDeg = 0;
    EXPECT_THROW(planScene(cone(10, 10, 5), Quality::Auto, b), Error);
    EXPECT_THROW(parseQuality("best"), Error);
    EXPECT_EQ(parseQuality("full"), Quality::Full);
}

}  // namespace
}  // namespace demlight

namespace demlight {
namespace {

// A range limit saves work only where it shortens the line walks: a window far from the far
// edge (the walk stops maxDistanceM beyond it), not a whole-DEM sweep (lines walk the DEM anyway).
TEST(Quality, RangeLimitPaysOnlyWhereItShortensTheWalks) {
    const Terrain t = makeUniformTerrain(Grid<float>(400, 300, 10.0f), 30.0);
    HorizonParams p;
    p.azimuthDeg = 0;
    p.maxDistanceM = 600;
    EXPECT_FALSE(rangeLimitPays(t, p));
    p.window = CellWindow{0, 280, 400, 300};  // southern rows, looking north across the DEM
    EXPECT_TRUE(rangeLimitPays(t, p));
    p.maxDistanceM = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(rangeLimitPays(t, p));
}

/// A 50 x 50 tile of a uniform full grid of `side` x `side` 30 m cells with 100 m of relief:
/// one sweep region, where a whole-DEM search costs no more steps than a range limit.
Terrain tileOfUniformGrid(std::size_t side) {
    auto frame = std::make_shared<GridFrame>();
    frame->width = frame->height = side;
    frame->cellWidthM.assign(side, 30.0);
    frame->cellHeightM.assign(side, 30.0);
    frame->lowM = 0, frame->highM = 100;
    Terrain t = makeUniformTerrain(Grid<float>(50, 50, 50.0f), 30.0);
    t.frame = frame;
    t.frameCol0 = t.frameRow0 = side / 2;
    return t;
}

TEST(Quality, DemsTooLargeForOneTileKeepTheRangeLimit) {
    QualityBudget budget;
    budget.lowestElevationDeg = 2;
    budget.toleranceDeg = 0.1;
    // 4000^2 (16 Mi cells): the step counts decide, and on one region they choose the whole DEM.
    const Terrain small = tileOfUniformGrid(4000);
    const ScenePlan smallPlan = planScene(small, Quality::Auto, budget);
    ASSERT_TRUE(std::isfinite(smallPlan.maxDistanceM));
    EXPECT_FALSE(std::isfinite(planIntegralParams(small, smallPlan, 32, 0.13).maxDistanceM));
    EXPECT_FALSE(rangeLimitPays(small, planHorizonParams(smallPlan, 0.13)));
    // 9000^2 (77 Mi cells): computed in tiles, so the plan's range limit stays.
    const Terrain large = tileOfUniformGrid(9000);
    const ScenePlan largePlan = planScene(large, Quality::Auto, budget);
    EXPECT_EQ(planIntegralParams(large, largePlan, 32, 0.13).maxDistanceM, largePlan.maxDistanceM);
    EXPECT_TRUE(rangeLimitPays(large, planHorizonParams(largePlan, 0.13)));
}

}  // namespace
}  // namespace demlight
