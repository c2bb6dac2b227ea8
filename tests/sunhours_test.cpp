// Sun-hour integrals (demlight/lighting/sunhours.h) on analytic terrain with the real SPA sun.
#include "demlight/geo/solar_position.h"
#include "demlight/geo/time.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/sunhours.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
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
    const Normals normals = computeNormals(t);
    SunHoursParams params;
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
    const Normals normals = computeNormals(t);
    HorizonParams hp;
    hp.maxDistanceM = 2000;
    const HorizonStack stack = computeHorizonStack(t, 8, hp);
    const SunField field = SunField::uniform(270.0, 8.0);  // direction 6 of 8
    SunFrameParams fp;
    fp.maxDistanceM = 2000;
    const SunFrame exact = computeSunFrame(t, normals, field, fp);
    const SunLight interp = sunLightFromStack(t, normals, stack, field, fp.sunDiameterDeg);
    double shadowed = 0;
    for (std::size_t k = 0; k < heights.size(); ++k) {
        EXPECT_NEAR(interp.visibility.data()[k], exact.light.visibility.data()[k], 1e-6) << k;
        EXPECT_NEAR(interp.irradiance.data()[k], exact.light.irradiance.data()[k], 1e-6) << k;
        shadowed += exact.light.visibility.data()[k] < 0.5;
    }
    EXPECT_GT(shadowed, 0);  // the case has shadows to get wrong
}

/// SPA's own day length (hours) for the UTC day starting at `date`: sunset - sunrise from the
/// rise/set routine (SPA A.2, sun centre at -0.8333 deg true elevation), a separate code path
/// from the per-instant positions the integral uses. 24 on polar day.
double spaDayLengthHours(const SolarSite& site, sys_days date) {
    const SunEvents e = sunEvents(site, UtcInstant(date));
    if (e.kind == DayKind::PolarDay) return 24.0;
    if (e.kind == DayKind::PolarNight) return 0.0;
    return duration<double, std::ratio<3600>>(*e.sunset - *e.sunrise).count();
}

/// Daylight over a UTC day at `site`, from the geometric SPA position (no refraction).
Grid<float> daylight(const Terrain& t, SolarSite site, const Day& day) {
    site.pressureHpa = 0;  // no refraction: the geometric elevation
    return integrateDaylight(t, day.instants, [&](std::size_t i) {
        const SolarPosition p = solarPosition(site, day.utc[i]);
        return SunField::uniform(p.azimuthDeg, p.elevationDeg);
    });
}

// Sky irradiation on flat open ground = 1 (the sky normalisation, docs/design.md §3) integrated
// over the daytime. The sky term comes from the real sky driver (sweeps + Stewart-Langer f_sky) and
// the daytime from SPA's own sunrise and sunset routine (A.2, interpolated transit and hour
// angles), a separate code path from the per-instant positions the integral uses.
TEST(SunHours, SkyIrradiationOnFlatOpenGroundIsTheDayLength) {
    const Terrain t = makeUniformTerrain(Grid<float>(16, 16, 100.0f), kCellM);
    const Normals normals = computeNormals(t);
    HorizonParams hp;
    hp.maxDistanceM = 1000;
    SkyAccumulator acc(normals.east, normals.north, normals.up, 8, {});
    sweepDirections(t, hp, 8, [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); });
    const Grid<float> skyFactor = acc.finish(0.2).skyFactor;
    const struct {
        double latitudeDeg;
        sys_days date;
        double expectHours;  // rough value, guards the case itself
    } cases[] = {
        {0, sys_days(2024y / March / 20), 12.1},
        {60, sys_days(2024y / June / 21), 18.9},
        {60, sys_days(2024y / December / 21), 5.9},
        {78, sys_days(2024y / June / 21), 24.0},
    };
    for (const auto& c : cases) {
        SolarSite site;
        site.latitudeDeg = c.latitudeDeg;
        const double dayHours = spaDayLengthHours(site, c.date);
        ASSERT_NEAR(dayHours, c.expectHours, 0.1) << c.latitudeDeg;
        // Linear interpolation of the elevation between instants: its error grows with the step
        // squared where the sun rises at a slant (26-33 s at 60 N with 30 min steps).
        for (const auto& [stepMin, toleranceS] : {std::pair{10, 10.0}, std::pair{30, 60.0}}) {
            const Grid<float> sky = skyIrradiation(skyFactor, daylight(t, site, utcDay(c.date, stepMin)));
            for (std::size_t k = 0; k < sky.size(); ++k) {
                ASSERT_NEAR(skyFactor.data()[k], 1.0, 1e-6);  // open flat ground: the unit sky's normalisation
                ASSERT_NEAR(sky.data()[k], 1.0 * dayHours, toleranceS / 3600)
                    << c.latitudeDeg << " N, step " << stepMin << " min, cell " << k;
            }
        }
    }
}

// Daylight ignores terrain (it is the sky's clock, not the sun's visibility): a cell that never
// sees the sun still has its full day of sky, and a nodata cell stays NaN.
TEST(SunHours, DaylightIgnoresTerrainShadowAndKeepsNodata) {
    Grid<float> heights(24, 24);
    const double rise = std::tan(30.0 * M_PI / 180.0) * kCellM;
    for (std::size_t r = 0; r < 24; ++r)
        for (std::size_t c = 0; c < 24; ++c)
            heights(c, r) = static_cast<float>(1000.0 + rise * static_cast<double>(r));  // faces north
    heights(3, 3) = std::numeric_limits<float>::quiet_NaN();
    const Terrain t = makeUniformTerrain(heights, kCellM);
    SolarSite site;
    site.latitudeDeg = 60;
    const Day day = utcDay(sys_days(2024y / December / 21), 10);
    const SunHoursMaps m = integrate(t, site, day);
    const Grid<float> d = daylight(t, site, day);
    EXPECT_EQ(m.sunHours(12, 12), 0.0f);
    EXPECT_NEAR(d(12, 12), spaDayLengthHours(site, sys_days(2024y / December / 21)), 10.0 / 3600);
    EXPECT_TRUE(std::isnan(d(3, 3)));
}

TEST(SunHours, SkyIrradiationKeepsNodataAndChecksShapes) {
    Grid<float> sky(2, 1, 0.5f), day(2, 1, 10.0f);
    sky(1, 0) = std::numeric_limits<float>::quiet_NaN();
    const Grid<float> out = skyIrradiation(sky, day);
    EXPECT_FLOAT_EQ(out(0, 0), 5.0f);
    EXPECT_TRUE(std::isnan(out(1, 0)));
    EXPECT_THROW(skyIrradiation(sky, Grid<float>(1, 1, 1.0f)), Error);
}

TEST(SunHours, RejectsTooFewInstants) {
    const Terrain t = makeUniformTerrain(Grid<float>(4, 4, 0.0f), kCellM);
    const std::vector<SunInstant> one{{0, 0}};
    EXPECT_THROW(integrateSunHours(t, computeNormals(t), one,
                                   [](std::size_t) { return SunField::uniform(180, 45); }, {}),
                 Error);
}

}  // namespace
}  // namespace demlight
