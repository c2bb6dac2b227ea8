// Sun-hour integrals (lighting/sunhours.h) on analytic terrain with the real SPA sun.
#include "geo/solar_position.h"
#include "geo/time.h"
#include "lighting/sunhours.h"
#include "src/error.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <vector>

namespace demlight {
namespace {

using namespace std::chrono;

struct Day {
    std::vector<SunInstant> instants;
    std::vector<UtcInstant> utc;
};

/// A UTC day sampled every stepMin minutes, midnight to midnight inclusive.
Day utcDay(sys_days date, int stepMin) {
    Day d;
    for (int m = 0; m <= 24 * 60; m += stepMin) {
        d.utc.push_back(UtcInstant(date) + minutes(m));
        d.instants.push_back({m / 60.0, m / 60.0});
    }
    return d;
}

SunHoursMaps integrate(const Terrain& t, const SolarSite& site, const Day& day) {
    const Normals normals = computeNormals(t, 1);
    SunHoursParams params;
    params.frame.threads = 1;
    return integrateSunHours(t, normals, day.instants, [&](std::size_t i) {
        const SolarPosition p = solarPosition(site, day.utc[i]);
        return SunField::uniform(p.azimuthDeg, p.elevationDeg);
    }, params);
}

constexpr double kCellM = 30.0;

// Guards the whole chain (trapezoid weights, visibility, lit times) on the simplest case.
TEST(SunHours, FlatEquatorEquinoxGetsAboutTwelveHours) {
    const Terrain t = makeUniformTerrain(Grid<float>(16, 16, 100.0f), kCellM);
    SolarSite site;  // 0 N, 0 E: the UTC day is the local solar day
    const SunHoursMaps m = integrate(t, site, utcDay(sys_days(2024y / March / 20), 10));
    // Day length at the equator on the equinox: 12 h plus refraction and the disk (~6 min).
    EXPECT_NEAR(m.sunHours(8, 8), 12.1, 0.1);
    EXPECT_NEAR(m.firstLitClock(8, 8), 6.05, 0.1);  // sunrise ~06:03 UTC at 0 E
    EXPECT_NEAR(m.lastLitClock(8, 8), 18.15, 0.1);
    // ∫ sin(elevation) dt over a 12 h day with a zenith noon sun ≈ 24/π h.
    EXPECT_NEAR(m.sunIrradiation(8, 8), 24.0 / M_PI, 0.1);
}

// A north-facing slope steeper than the December noon sun never sees it.
TEST(SunHours, NorthFacingSlopeAt60NInDecemberGetsNone) {
    Grid<float> heights(24, 24);
    const double rise = std::tan(30.0 * M_PI / 180.0) * kCellM;
    for (std::size_t r = 0; r < 24; ++r)
        for (std::size_t c = 0; c < 24; ++c)
            heights(c, r) = static_cast<float>(1000.0 + rise * static_cast<double>(r));  // rises to the south
    const Terrain t = makeUniformTerrain(heights, kCellM);
    SolarSite site;
    site.latitudeDeg = 60;
    site.longitudeDeg = 0;
    const SunHoursMaps m = integrate(t, site, utcDay(sys_days(2024y / December / 21), 10));
    for (std::size_t r = 0; r < 24; ++r)
        for (std::size_t c = 0; c < 24; ++c) {
            EXPECT_EQ(m.sunHours(c, r), 0.0f) << c << "," << r;
            EXPECT_TRUE(std::isnan(m.firstLitClock(c, r)));
        }
}

// Polar day: the sun never sets, so a flat cell is lit for the whole 24 h.
TEST(SunHours, PolarDayGetsTwentyFourHours) {
    const Terrain t = makeUniformTerrain(Grid<float>(16, 16, 10.0f), kCellM);
    SolarSite site;
    site.latitudeDeg = 78;
    site.longitudeDeg = 15;
    const SunHoursMaps m = integrate(t, site, utcDay(sys_days(2024y / June / 21), 30));
    EXPECT_NEAR(m.sunHours(8, 8), 24.0, 1e-4);
    EXPECT_EQ(m.firstLitClock(8, 8), 0.0f);
    EXPECT_EQ(m.lastLitClock(8, 8), 24.0f);
}

// On a stack direction the interpolated horizon is the exact sweep's: same light as the frame.
TEST(HorizonStack, MatchesExactSweepOnAStackDirection) {
    Grid<float> heights(48, 40);
    for (std::size_t r = 0; r < 40; ++r)
        for (std::size_t c = 0; c < 48; ++c)
            heights(c, r) = static_cast<float>(200.0 * std::sin(0.3 * c) * std::cos(0.2 * r) + 5.0 * c);
    const Terrain t = makeUniformTerrain(heights, kCellM);
    const Normals normals = computeNormals(t, 1);
    HorizonParams hp;
    hp.maxDistanceM = 2000;
    hp.threads = 1;
    const HorizonStack stack = computeHorizonStack(t, 8, hp);
    const SunField field = SunField::uniform(270.0, 8.0);  // direction 6 of 8
    SunFrameParams fp;
    fp.maxDistanceM = 2000;
    fp.threads = 1;
    const SunFrame exact = computeSunFrame(t, normals, field, fp);
    const SunLight interp = sunLightFromStack(t, normals, stack, field, fp.sunDiameterDeg, 1);
    double shadowed = 0;
    for (std::size_t k = 0; k < heights.size(); ++k) {
        EXPECT_NEAR(interp.visibility.data()[k], exact.light.visibility.data()[k], 1e-6) << k;
        EXPECT_NEAR(interp.irradiance.data()[k], exact.light.irradiance.data()[k], 1e-6) << k;
        shadowed += exact.light.visibility.data()[k] < 0.5;
    }
    EXPECT_GT(shadowed, 0);  // the case has shadows to get wrong
}

TEST(SunHours, RejectsTooFewInstants) {
    const Terrain t = makeUniformTerrain(Grid<float>(4, 4, 0.0f), kCellM);
    const std::vector<SunInstant> one{{0, 0}};
    EXPECT_THROW(integrateSunHours(t, computeNormals(t, 1), one,
                                   [](std::size_t) { return SunField::uniform(180, 45); }, {}),
                 Error);
}

}  // namespace
}  // namespace demlight
