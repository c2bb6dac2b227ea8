#!/usr/bin/python3
"""Generate tests/data/solar_cases.inc: sun positions and sun events from PyEphem, used by
tests/solar_position_test.cpp to check demlight's NREL SPA independently of its own code.

Run with the system Python that has python3-ephem:  /usr/bin/python3 scripts/gen_solar_cases.py

For each case (a local time with an offset, or a local time plus an IANA zone, and a site):
  - ephem's delta_t at that instant (TT - UT, seconds); the C++ test passes the same delta T so
    both sides evaluate the sun at the same TT.
  - the topocentric GEOMETRIC elevation and azimuth of the sun's centre (observer.pressure = 0
    switches ephem's refraction off; ephem and SPA use different refraction models, so only
    geometric positions are compared).
  - sunrise, transit and sunset of the local day (local midnight to local midnight in the case's
    zone, from Python's zoneinfo). SPA's convention is the sun's centre at -0.8333 degrees
    (0.26667 radius + 0.5667 refraction) with no refraction model, so ephem runs with
    horizon = -0:50 (= -0.8333 deg), pressure = 0 and use_center = True. ephem's AlwaysUpError /
    NeverUpError give the polar day / polar night cases.
"""
import datetime as dt
import math
import os
import sys
from zoneinfo import ZoneInfo

import ephem

# label, time text, IANA zone ('' when the text carries its offset), lat, lon (deg, east +), elevation (m)
CASES = [
    ("spa_report_golden", "2003-10-17T12:30:30-07:00", "", 39.742476, -105.1786, 1830.14),
    ("zurich_dst_start_noon", "2024-03-31T12:00:00", "Europe/Zurich", 47.3769, 8.5417, 408),
    ("zurich_dst_start_morning", "2024-03-31T07:30:00", "Europe/Zurich", 47.3769, 8.5417, 408),
    ("new_york_dst_end_morning", "2024-11-03T08:00:00", "America/New_York", 40.7128, -74.0060, 10),
    ("new_york_dst_end_afternoon", "2024-11-03T15:45:00", "America/New_York", 40.7128, -74.0060, 10),
    ("kathmandu_0545", "2024-06-21T09:15:00", "Asia/Kathmandu", 27.7172, 85.3240, 1400),
    ("chatham_1245", "2024-06-21T14:00:00", "Pacific/Chatham", -43.95, -176.55, 20),
    ("kiritimati_1400", "2024-06-21T06:45:00", "Pacific/Kiritimati", 1.87, -157.43, 3),
    ("marquesas_m0930", "2024-03-20T17:00:00", "Pacific/Marquesas", -9.0, -139.5, 50),
    ("longyearbyen_polar_day", "2024-06-21T01:00:00", "Arctic/Longyearbyen", 78.22, 15.65, 10),
    ("longyearbyen_polar_night", "2024-12-21T12:00:00", "Arctic/Longyearbyen", 78.22, 15.65, 10),
    ("mcmurdo_polar_day", "2024-12-21T03:00:00", "Antarctica/McMurdo", -77.85, 166.67, 10),
    ("mcmurdo_polar_night", "2024-06-21T12:00:00", "Antarctica/McMurdo", -77.85, 166.67, 10),
    ("tromso_midnight_sun_1950", "1950-06-21T23:30:00+01:00", "", 69.6492, 18.9553, 0),
    ("greenwich_1900", "1900-01-01T12:00:00Z", "", 51.4779, -0.0015, 46),
    ("philadelphia_1905", "1905-07-04T10:00:00-05:00", "", 39.9526, -75.1652, 12),
    ("tranquility_1969", "1969-07-20T20:17:40Z", "", 0.6741, 23.4730, 0),
    ("equator_j2000", "2000-01-01T12:00:00Z", "", 0.0, 0.0, 0),
    ("sydney_2050_equinox", "2050-09-23T16:20:00", "Australia/Sydney", -33.8688, 151.2093, 58),
    ("cape_town_2100", "2100-12-31T23:59:59Z", "", -33.9249, 18.4241, 0),
    ("honolulu_2099", "2099-06-15T07:10:00", "Pacific/Honolulu", 21.3069, -157.8583, 5),
    ("quito_near_zenith", "2024-03-20T12:15:00", "America/Guayaquil", -0.1807, -78.4678, 2850),
    ("reykjavik_winter_solstice", "2024-12-21T13:00:00", "Atlantic/Reykjavik", 64.1466, -21.9426, 20),
    ("tokyo_1985", "1985-08-12T18:56:00", "Asia/Tokyo", 35.6762, 139.6503, 40),
    ("everest_2010", "2010-05-01T08:30:00+05:45", "", 27.9881, 86.9250, 8848),
    ("la_paz_1999", "1999-02-14T16:00:00-04:00", "", -16.4897, -68.1193, 3640),
    ("ushuaia_winter", "2024-06-21T13:30:00", "America/Argentina/Ushuaia", -54.8019, -68.3030, 20),
    ("alert_spring", "2024-03-15T12:00:00", "America/Toronto", 82.5018, -62.3481, 30),
    ("zurich_night", "2024-01-15T23:00:00", "Europe/Zurich", 47.3769, 8.5417, 408),
    ("anchorage_1964", "1964-03-27T17:36:00-10:00", "", 61.2181, -149.9003, 30),
]


def utc_of(text, zone):
    if zone:
        local = dt.datetime.fromisoformat(text).replace(tzinfo=ZoneInfo(zone))
    else:
        local = dt.datetime.fromisoformat(text.replace("Z", "+00:00"))
    return local.astimezone(dt.timezone.utc), local


def day_bounds(local):
    """UTC start and end of the local calendar day containing `local` (aware datetime)."""
    tz = local.tzinfo
    midnight = dt.datetime.combine(local.date(), dt.time(0), tzinfo=tz)
    nxt = dt.datetime.combine(local.date() + dt.timedelta(days=1), dt.time(0), tzinfo=tz)
    return midnight.astimezone(dt.timezone.utc), nxt.astimezone(dt.timezone.utc)


def to_ephem(t):
    return ephem.Date(t.replace(tzinfo=None))


def iso(d):
    """ephem Date -> ISO 8601 UTC with milliseconds."""
    t = ephem.Date(d).datetime()
    return t.strftime("%Y-%m-%dT%H:%M:%S.") + "%03dZ" % (t.microsecond // 1000)


def observer(lat, lon, elev, when):
    o = ephem.Observer()
    o.lat, o.lon, o.elevation = str(lat), str(lon), elev
    o.pressure = 0  # no refraction: geometric positions
    o.date = when
    return o


def case_row(label, text, zone, lat, lon, elev):
    utc, local = utc_of(text, zone)
    when = to_ephem(utc)
    delta_t = ephem.delta_t(when)
    o = observer(lat, lon, elev, when)
    sun = ephem.Sun(o)
    elev_deg, az_deg = math.degrees(sun.alt), math.degrees(sun.az)

    start, end = day_bounds(local)
    o = observer(lat, lon, elev, to_ephem(start))
    o.horizon = "-0:50"  # SPA: centre at -(0.26667 + 0.5667) deg
    transit = o.next_transit(ephem.Sun())
    kind, rise, sets = "normal", "", ""
    try:
        r = o.next_rising(ephem.Sun(), use_center=True)
        s = o.next_setting(ephem.Sun(), use_center=True)
        if r < to_ephem(end):
            rise = iso(r)
        if s < to_ephem(end):
            sets = iso(s)
    except ephem.AlwaysUpError:
        kind = "polar_day"
    except ephem.NeverUpError:
        kind = "polar_night"
    return (f'{{"{label}", "{text}", "{zone}", {lat!r}, {lon!r}, {float(elev)!r}, {delta_t:.4f},\n'
            f'     {elev_deg:.7f}, {az_deg:.7f}, "{iso(to_ephem(start))}", "{kind}",\n'
            f'     "{rise}", "{iso(transit)}", "{sets}"}},')


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "solar_cases.inc")
    rows = [case_row(*c) for c in CASES]
    with open(out, "w") as f:
        f.write("// Generated by scripts/gen_solar_cases.py with PyEphem %s. Do not edit.\n" % ephem.__version__)
        f.write("// label, time, tz, latDeg, lonDeg, elevationM, deltaTSec (ephem),\n")
        f.write("//   ephem geometric elevationDeg, azimuthDeg, local day start (UTC, zoneinfo), kind,\n")
        f.write("//   sunrise, transit, sunset (UTC; empty = none in the local day)\n")
        for r in rows:
            f.write(r + "\n")
    print("wrote %d cases to %s" % (len(rows), os.path.normpath(out)), file=sys.stderr)


if __name__ == "__main__":
    main()
