// Sun visibility and irradiance (demlight/lighting/sun.h) and normals (demlight/lighting/surface.h).
#include "demlight/lighting/sun.h"

#include "demlight/lighting/horizon.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

namespace demlight {
namespace {

const Enu kUp{0.0, 0.0, 1.0};

TEST(SunVisibility, FullyVisibleHiddenAndHalfDisk) {
    // Hoffman & Mitchell 2001b, Eq. 5-7 with α = 0.533°.
    EXPECT_EQ(sunVisibility(5.0, 10.0, kSunDiameterDeg), 1.0);
    EXPECT_EQ(sunVisibility(15.0, 10.0, kSunDiameterDeg), 0.0);
    EXPECT_DOUBLE_EQ(sunVisibility(10.0, 10.0, kSunDiameterDeg), 0.5);
    EXPECT_NEAR(sunVisibility(10.0 + kSunDiameterDeg / 4, 10.0, kSunDiameterDeg), 0.25, 1e-12);
    EXPECT_EQ(sunVisibility(10.0 - kSunDiameterDeg / 2, 10.0, kSunDiameterDeg), 1.0);
    EXPECT_EQ(sunVisibility(10.0 + kSunDiameterDeg / 2, 10.0, kSunDiameterDeg), 0.0);
    // A point sun is a step.
    EXPECT_EQ(sunVisibility(9.99, 10.0, 0.0), 1.0);
    EXPECT_EQ(sunVisibility(10.01, 10.0, 0.0), 0.0);
    EXPECT_TRUE(std::isnan(sunVisibility(std::nan(""), 10.0, kSunDiameterDeg)));
}

TEST(SunVisibility, MonotoneNonIncreasingInHorizon) {
    for (double diameter : {0.0, kSunDiameterDeg, 5.0}) {
        double previous = 2.0;
        for (double h = -5.0; h <= 25.0; h += 0.01) {
            const double o = sunVisibility(h, 10.0, diameter);
            EXPECT_LE(o, previous) << h;
            EXPECT_GE(o, 0.0);
            EXPECT_LE(o, 1.0);
            previous = o;
        }
    }
}

TEST(SunIrradiance, FlatCellZenithSunIsOne) {
    EXPECT_DOUBLE_EQ(sunIrradiance(kUp, -90.0, 0.0, 90.0, kSunDiameterDeg), 1.0);
    // Lambert: elevation 30° on flat ground gives sin 30°.
    EXPECT_NEAR(sunIrradiance(kUp, 0.0, 123.0, 30.0, kSunDiameterDeg), 0.5, 1e-12);
    // Hidden.
    EXPECT_EQ(sunIrradiance(kUp, 40.0, 123.0, 30.0, kSunDiameterDeg), 0.0);
}

TEST(SunIrradiance, HorizonClampedToTheNormalHemisphere) {
    // A 30° slope facing east (normal tilted toward east). Looking west, the tangent plane rises
    // at 30°: a sun in the west at 20° is behind the surface even with a low horizon.
    const double s = std::sin(30.0 * kDegToRad), c = std::cos(30.0 * kDegToRad);
    const Enu eastFacing{s, 0.0, c};
    EXPECT_NEAR(tangentPlaneElevationDeg(eastFacing, 270.0), 30.0, 1e-12);
    EXPECT_NEAR(tangentPlaneElevationDeg(eastFacing, 90.0), -30.0, 1e-12);
    EXPECT_NEAR(tangentPlaneElevationDeg(eastFacing, 0.0), 0.0, 1e-12);
    EXPECT_EQ(sunVisibilityClamped(eastFacing, -10.0, 270.0, 20.0, kSunDiameterDeg), 0.0);
    EXPECT_EQ(sunIrradiance(eastFacing, -10.0, 270.0, 20.0, kSunDiameterDeg), 0.0);
    // Facing the sun straight on: irradiance 1.
    EXPECT_NEAR(sunIrradiance(eastFacing, -10.0, 90.0, 60.0, kSunDiameterDeg), 1.0, 1e-12);
}

TEST(SunIrradiance, Azimuth0And360Identical) {
    const Enu n{0.2, -0.3, std::sqrt(1.0 - 0.13)};
    const double a = sunIrradiance(n, 3.0, 0.0, 20.0, kSunDiameterDeg);
    const double b = sunIrradiance(n, 3.0, 360.0, 20.0, kSunDiameterDeg);
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
    EXPECT_EQ(tangentPlaneElevationDeg(n, 0.0), tangentPlaneElevationDeg(n, 360.0));
}

Terrain tiltedPlane(double slopeEast, double slopeNorth) {
    Grid<float> h(30, 20);
    for (std::size_t r = 0; r < 20; ++r)
        for (std::size_t c = 0; c < 30; ++c)
            h(c, r) = static_cast<float>(slopeEast * 10.0 * c - slopeNorth * 10.0 * r);
    return makeUniformTerrain(std::move(h), 10.0);
}

TEST(SunTerms, PrecomputedAnglesMatchTheLibraryTrigonometry) {
    // The SunAngles overload (used per cell by sun frames, with its polynomial arctangent)
    // against the <cmath> forms: random normals, horizons near the sun, suns all round.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        const double az = 180.0 * (unit(rng) + 1.0);
        const double el = 45.0 * (unit(rng) + 1.0) - 5.0;
        const double horizon = el + 2.0 * unit(rng);
        Enu n{0.6 * unit(rng), 0.6 * unit(rng), 1.0};
        const double len = std::sqrt(n.east * n.east + n.north * n.north + n.up * n.up);
        n = {n.east / len, n.north / len, n.up / len};
        const SunAngles a{az, el, std::sin(az * kDegToRad), std::cos(az * kDegToRad), std::sin(el * kDegToRad),
                          std::cos(el * kDegToRad)};
        const SunTerms fast = sunTerms(n, horizon, a, kSunDiameterDeg);
        // Against <cmath> throughout: the clamped visibility (atan2 tangent plane) and the Lambert
        // term from directionEnu.
        const double visibility = sunVisibilityClamped(n, horizon, az, el, kSunDiameterDeg);
        const Enu s = directionEnu(az, el);
        const double irradiance = visibility * std::max(0.0, n.east * s.east + n.north * s.north + n.up * s.up);
        worst = std::max({worst, std::abs(fast.visibility - visibility), std::abs(fast.irradiance - irradiance)});
    }
    EXPECT_LT(worst, 1e-6);
    const double s30 = std::sin(30.0 * kDegToRad), c30 = std::cos(30.0 * kDegToRad);
    const SunAngles a{10.0, 30.0, std::sin(10.0 * kDegToRad), std::cos(10.0 * kDegToRad), s30, c30};
    EXPECT_TRUE(std::isnan(sunTerms(kUp, std::nan(""), a, kSunDiameterDeg).visibility));
    EXPECT_DOUBLE_EQ(sunTerms(kUp, -90.0, a, kSunDiameterDeg).irradiance, std::sin(30.0 * kDegToRad));
}

TEST(Normals, TiltedPlaneInTrueMetres) {
    Terrain t = tiltedPlane(0.5, 0.25);
    // Non-square cells: heights built per metre so the normal must use true sizes.
    for (std::size_t r = 0; r < t.height(); ++r) {
        t.cellWidthM[r] = 20.0;
        for (std::size_t c = 0; c < t.width(); ++c)
            t.heightsM(c, r) = static_cast<float>(0.5 * 20.0 * c - 0.25 * 10.0 * r);
    }
    t.heightsM(5, 5) = std::numeric_limits<float>::quiet_NaN();
    const Normals n = computeNormals(t);
    const double len = std::sqrt(0.25 + 0.0625 + 1.0);
    for (auto [c, r] : {std::pair<std::size_t, std::size_t>{0, 0}, {10, 10}, {29, 19}, {6, 5}, {5, 6}}) {
        EXPECT_NEAR(n.east(c, r), -0.5 / len, 1e-6) << c << " " << r;
        EXPECT_NEAR(n.north(c, r), -0.25 / len, 1e-6) << c << " " << r;
        EXPECT_NEAR(n.up(c, r), 1.0 / len, 1e-6) << c << " " << r;
    }
    EXPECT_TRUE(std::isnan(n.up(5, 5)));
}

TEST(Normals, ConvergenceRotatesIntoTrueNorth) {
    Terrain t = tiltedPlane(0.5, 0.0);  // rises toward grid east
    t.convergence.stepCells = 100;
    t.convergence.gammaDeg = Grid<float>(2, 2, 90.0f);  // grid north points to true east
    const Normals n = computeNormals(t);
    // Grid east is then true south: the normal leans toward true north.
    EXPECT_NEAR(n.east(10, 10), 0.0, 1e-6);
    EXPECT_NEAR(n.north(10, 10), 0.5 / std::sqrt(1.25), 1e-6);
}

TEST(SunLight, GridDriverMatchesPerCellFunctions) {
    Grid<float> h(60, 40);
    for (std::size_t r = 0; r < 40; ++r)
        for (std::size_t c = 0; c < 60; ++c)
            h(c, r) = static_cast<float>(50.0 * std::sin(c / 6.0) * std::cos(r / 5.0));
    h(7, 7) = std::numeric_limits<float>::quiet_NaN();
    const Terrain t = makeUniformTerrain(std::move(h), 10.0);
    const Normals normals = computeNormals(t);
    HorizonParams p;
    p.azimuthDeg = 360.0;
    const HorizonMap horizon = sweepHorizon(t, p);
    const SunLight a = computeSunLight(t, horizon, normals, 360.0, 12.0);
    p.azimuthDeg = 0.0;
    const SunLight b = computeSunLight(t, sweepHorizon(t, p), normals, 0.0, 12.0);
    EXPECT_EQ(std::memcmp(a.irradiance.data(), b.irradiance.data(), a.irradiance.size() * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(a.visibility.data(), b.visibility.data(), a.visibility.size() * sizeof(float)), 0);
    EXPECT_TRUE(std::isnan(a.irradiance(7, 7)));
    EXPECT_TRUE(std::isnan(a.visibility(7, 7)));
    std::size_t shadowed = 0;
    for (std::size_t r = 0; r < 40; ++r)
        for (std::size_t c = 0; c < 60; ++c) {
            if (!t.valid(c, r)) continue;
            const double expected = sunIrradiance(normals.at(c, r), horizon.angleDeg(c, r), 0.0, 12.0, kSunDiameterDeg);
            EXPECT_FLOAT_EQ(a.irradiance(c, r), static_cast<float>(expected));
            shadowed += a.visibility(c, r) == 0.0f;
        }
    EXPECT_GT(shadowed, 0u);
    EXPECT_THROW(computeSunLight(t, horizon, normals, 0.0, 95.0), Error);
    EXPECT_THROW(computeSunLight(t, horizon, normals, std::nan(""), 10.0), Error);
    EXPECT_THROW(computeSunLight(t, horizon, normals, 0.0, 10.0, -1.0), Error);
    HorizonMap wrong;
    wrong.angleDeg = Grid<float>(3, 3);
    EXPECT_THROW(computeSunLight(t, wrong, normals, 0.0, 10.0), Error);
}

}  // namespace
}  // namespace demlight
