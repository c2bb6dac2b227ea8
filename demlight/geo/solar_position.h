// Solar position by the NREL Solar Position Algorithm (SPA):
//   I. Reda and A. Andreas, "Solar Position Algorithm for Solar Radiation Applications",
//   NREL/TP-560-34302, revised January 2008. Stated uncertainty ±0.0003° for years −2000..6000.
// Written from the report's equations and periodic-term tables (section 3, appendix A.2).
//
// Conventions (docs/design.md §3): topocentric, apparent positions; azimuth in degrees clockwise
// from TRUE north in [0, 360); elevation above the local horizontal; refraction from pressure and
// temperature with SPA's model.
#pragma once

#include "demlight/geo/time.h"

#include <optional>

namespace demlight {

/// Observer and the air the sun is seen through.
struct SolarSite {
    double latitudeDeg = 0;     ///< geodetic latitude (degrees, north positive), [-90, 90]
    double longitudeDeg = 0;    ///< longitude (degrees, east positive), [-180, 180]
    double elevationM = 0;      ///< height above sea level (metres)
    double pressureHpa = 1013.25;  ///< mean local air pressure (hPa); 0 disables refraction
    double temperatureC = 15;   ///< mean local air temperature (°C)
};

/// Parameters that are not part of the site. Defaults are SPA's.
struct SpaOptions {
    /// ΔT = TT − UT (seconds). Empty: deltaTSeconds() of the date (Espenak & Meeus 2006).
    std::optional<double> deltaTSec;
    /// Apparent radius of the sun's disk (degrees), for rise/set and the refraction cut-off.
    double sunRadiusDeg = 0.26667;
    /// Atmospheric refraction at the horizon (degrees), for rise/set and the refraction cut-off.
    double horizonRefractionDeg = 0.5667;
};

/// Topocentric position of the sun's centre at one instant.
struct SolarPosition {
    double zenithDeg;              ///< apparent (refracted) zenith angle (degrees)
    double elevationDeg;           ///< apparent elevation angle = 90° − zenith (degrees)
    double azimuthDeg;             ///< clockwise from true north, [0, 360) (degrees)
    double geometricElevationDeg;  ///< elevation without refraction (degrees)
    double refractionDeg;          ///< refraction added to the geometric elevation (degrees)
    double rightAscensionDeg;      ///< topocentric right ascension, [0, 360) (degrees)
    double declinationDeg;         ///< topocentric declination (degrees)
    double hourAngleDeg;           ///< topocentric local hour angle, [0, 360) (degrees)
    double equationOfTimeMin;      ///< apparent − mean solar time (minutes)
    double deltaTSec;              ///< ΔT used (seconds)
};

/// Intermediate quantities of one SPA evaluation, named as in the report (degrees unless
/// stated). For tests and diagnostics.
struct SpaTrace {
    double julianDay, julianEphemerisDay, julianEphemerisMillennium;
    double heliocentricLongitudeDeg;  ///< L
    double heliocentricLatitudeDeg;   ///< B
    double earthSunDistanceAu;        ///< R (astronomical units)
    double geocentricLongitudeDeg;    ///< Θ
    double geocentricLatitudeDeg;     ///< β
    double nutationLongitudeDeg;      ///< Δψ
    double nutationObliquityDeg;      ///< Δε
    double trueObliquityDeg;          ///< ε
    double aberrationDeg;             ///< Δτ
    double apparentSunLongitudeDeg;   ///< λ
    double apparentSiderealTimeDeg;   ///< ν
    double geocentricRightAscensionDeg;  ///< α
    double geocentricDeclinationDeg;     ///< δ
    double observerHourAngleDeg;         ///< H
    double equatorialParallaxDeg;        ///< ξ
    double rightAscensionParallaxDeg;    ///< Δα
};

/// The years SPA states its uncertainty for (Reda & Andreas, abstract and Table 1), inclusive.
inline constexpr int kSpaFirstYear = -2000;
inline constexpr int kSpaLastYear = 6000;

/// Throws Error naming the instant unless its UTC year is in [kSpaFirstYear, kSpaLastYear]:
/// SPA states no accuracy outside them, so a position there would look as exact as any other
/// and be wrong by an unknown amount.
void checkSpaValidity(UtcInstant t);

/// Position of the sun seen from site at instant t (UTC). Cheap enough to call per frame
/// (a few microseconds). Fills trace if non-null. Throws as checkSpaValidity.
SolarPosition solarPosition(const SolarSite& site, UtcInstant t, const SpaOptions& options = {},
                            SpaTrace* trace = nullptr);

/// What kind of day: whether the sun's upper limb crosses the (refracted) horizon.
enum class DayKind {
    Normal,     ///< the sun rises and sets
    PolarDay,   ///< the sun stays up all day: no sunrise, no sunset
    PolarNight  ///< the sun stays down all day: no sunrise, no sunset
};

/// Sunrise, sun transit and sunset (SPA appendix A.2). Sunrise and sunset are when the sun's
/// centre is at −(sunRadius + horizonRefraction) = −0.8333° by default, geocentric, as in SPA.
struct SunEvents {
    std::optional<UtcInstant> sunrise;  ///< empty on polar day / polar night
    UtcInstant transit;                 ///< local (upper) meridian transit; always present
    std::optional<UtcInstant> sunset;   ///< empty on polar day / polar night
    DayKind kind = DayKind::Normal;
};

/// Events of the 24 hours starting at dayStartUtc, normally local midnight of the day wanted
/// (localDay(...).startUtc). SPA's A.2 takes 0 h UT as the origin; using local midnight instead
/// makes the events those of the local day for any offset (+14:00 included). On the 23 h / 25 h
/// DST switch days the window stays 24 h from local midnight. Site pressure and temperature are
/// not used: SPA rise/set uses the fixed horizon refraction of options.
SunEvents sunEvents(const SolarSite& site, UtcInstant dayStartUtc, const SpaOptions& options = {});

/// ΔT = TT − UT (seconds) for a decimal year, from the polynomial expressions of F. Espenak and
/// J. Meeus (NASA Five Millennium Canon of Solar Eclipses, 2006), valid for years −500..3000
/// (outside that, their long-term parabola). Near 2024 it is about 4 s above the observed
/// ~69 s. ΔT only shifts the sun along its orbit (0.04°/h), so 4 s moves it by < 0.0001°.
double deltaTSeconds(double decimalYear);

}  // namespace demlight
