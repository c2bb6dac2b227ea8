// planScene: what `--quality auto` and `full` choose, against hand-computed values.
#include "lighting/quality.h"
#include "src/error.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(Quality, FullTurnsEverythingOn) {
    const ScenePlan p = planScene(cone(100, 10, 5), Quality::Full, {});
    EXPECT_NEAR(p.maxDistanceM, std::hypot(1000.0, 1000.0), 1e-6);
    EXPECT_TRUE(p.curvature);
    EXPECT_EQ(p.skyDirections, kFullSkyDirections);
    EXPECT_LT(p.sunLatticeStepCells, 64u);
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
