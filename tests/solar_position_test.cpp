// Tests of NREL SPA (geo/solar_position.h) against the report's own example and published
// values, and against PyEphem (tests/data/solar_cases.inc, from scripts/gen_solar_cases.py).
#include "geo/solar_position.h"
#include "geo/time.h"

#include <gtest/gtest.h>

using namespace demlight;

namespace {

// Reda & Andreas (2008), Table A5.1 example: 2003-10-17 12:30:30 −07:00, Golden, Colorado.
SolarSite spaReportSite() {
    SolarSite s;
    s.latitudeDeg = 39.742476;
    s.longitudeDeg = -105.1786;
    s.elevationM = 1830.14;
    s.pressureHpa = 820;
    s.temperatureC = 11;
    return s;
}
SpaOptions spaReportOptions() {
    SpaOptions o;
    o.deltaTSec = 67;
    return o;
}

}  // namespace

TEST(SolarPosition, SpaReportExample) {
    SpaTrace tr{};
    const UtcInstant t = parseInstant("2003-10-17T12:30:30-07:00", "");
    const SolarPosition p = solarPosition(spaReportSite(), t, spaReportOptions(), &tr);
    EXPECT_NEAR(tr.julianDay, 2452930.312847, 1e-6);
    EXPECT_NEAR(tr.heliocentricLongitudeDeg, 24.0182616917, 1e-9);
    EXPECT_NEAR(tr.heliocentricLatitudeDeg, -0.0001011219, 1e-9);
    EXPECT_NEAR(tr.earthSunDistanceAu, 0.9965422974, 1e-9);
    EXPECT_NEAR(tr.geocentricLongitudeDeg, 204.0182616917, 1e-9);
    EXPECT_NEAR(tr.geocentricLatitudeDeg, 0.0001011219, 1e-9);
    EXPECT_NEAR(tr.nutationLongitudeDeg, -0.00399840, 1e-8);
    EXPECT_NEAR(tr.nutationObliquityDeg, 0.00166657, 1e-8);
    EXPECT_NEAR(tr.trueObliquityDeg, 23.440465, 1e-6);
    EXPECT_NEAR(tr.apparentSunLongitudeDeg, 204.0085519281, 1e-9);
    EXPECT_NEAR(tr.geocentricRightAscensionDeg, 202.22741, 1e-5);
    EXPECT_NEAR(tr.geocentricDeclinationDeg, -9.31434, 1e-5);
    EXPECT_NEAR(tr.observerHourAngleDeg, 11.105900, 5e-6);  // report rounds α, JD
    EXPECT_NEAR(tr.equatorialParallaxDeg, 0.002451, 1e-6);
    EXPECT_NEAR(tr.rightAscensionParallaxDeg, -0.000369, 1e-6);
    EXPECT_NEAR(p.declinationDeg, -9.316179, 1e-6);
    EXPECT_NEAR(p.geometricElevationDeg, 39.872046, 1e-6);
    EXPECT_NEAR(p.refractionDeg, 0.016332, 1e-6);
    EXPECT_NEAR(p.elevationDeg, 39.888378, 1e-6);
    EXPECT_NEAR(p.zenithDeg, 50.111622, 1e-4);
    EXPECT_NEAR(p.azimuthDeg, 194.340241, 1e-4);
    EXPECT_NEAR(p.equationOfTimeMin, 14.641503, 1e-5);
    EXPECT_DOUBLE_EQ(p.deltaTSec, 67);
}

namespace {
/// Seconds from the instant `want` (ISO text with offset) to `got`.
double secondsAfter(UtcInstant got, const char* want) {
    return std::chrono::duration<double>(got - parseInstant(want, "")).count();
}
}  // namespace

TEST(SolarPosition, SpaReportSunriseTransitSunsetOnUtDay) {
    // The report's A.2 example works on the UT day (origin 0 h UT of 2003-10-17) and prints
    // sunrise 06:12:43, transit 11:46:04, sunset 17:20:19 at −07:00, seconds truncated. With a
    // 0 h UT origin the sunset fraction wraps, so that sunset is the one of 16 October local.
    const UtcInstant utMidnight = parseInstant("2003-10-17T00:00Z", "");
    const SunEvents ev = sunEvents(spaReportSite(), utMidnight, spaReportOptions());
    ASSERT_EQ(ev.kind, DayKind::Normal);
    ASSERT_TRUE(ev.sunrise && ev.sunset);
    EXPECT_NEAR(secondsAfter(*ev.sunrise, "2003-10-17T06:12:43-07:00"), 0.5, 0.5);
    EXPECT_NEAR(secondsAfter(ev.transit, "2003-10-17T11:46:04-07:00"), 0.5, 0.5);
    EXPECT_NEAR(secondsAfter(*ev.sunset, "2003-10-16T17:20:19-07:00"), 0.5, 0.5);
}

TEST(SolarPosition, SpaReportSunEventsOfLocalDay) {
    // Origin at local midnight: all three events fall on 17 October local. Sunset 17:18:51 is
    // also what PyEphem gives (centre at −0°50′, no refraction model): 17:18:51.
    const TimeZoneSpec zone = TimeZoneSpec::fixedOffset(std::chrono::hours(-7));
    const LocalDay day = localDayOf(parseInstant("2003-10-17T12:30:30-07:00", ""), zone);
    const SunEvents ev = sunEvents(spaReportSite(), day.startUtc, spaReportOptions());
    ASSERT_TRUE(ev.sunrise && ev.sunset);
    EXPECT_NEAR(secondsAfter(*ev.sunrise, "2003-10-17T06:12:43-07:00"), 0.5, 0.5);
    EXPECT_NEAR(secondsAfter(ev.transit, "2003-10-17T11:46:04-07:00"), 0.5, 0.5);
    EXPECT_NEAR(secondsAfter(*ev.sunset, "2003-10-17T17:18:51-07:00"), 0.5, 1.0);
}

TEST(SolarPosition, GrassSolposExample) {
    // GRASS r.sunmask manual: 2012-02-22 10:30 −05:00, 35.736160 N, 78.678856 W, SOLPOS
    // (refraction with 1013.25 hPa / 15 °C): azimuth 143.006409°, elevation 36.233879°.
    SolarSite site;
    site.latitudeDeg = 35.736160;
    site.longitudeDeg = -78.678856;
    const SolarPosition p = solarPosition(site, parseInstant("2012-02-22T10:30-05:00", ""));
    EXPECT_NEAR(p.azimuthDeg, 143.006409, 0.01);
    EXPECT_NEAR(p.elevationDeg, 36.233879, 0.01);
}
