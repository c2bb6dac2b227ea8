// Tests of time parsing, zones and local days (demlight/geo/time.h).
#include "demlight/geo/time.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <string>

using namespace demlight;
using namespace std::chrono;

namespace {

UtcInstant utc(int y, unsigned m, unsigned d, int h = 0, int min = 0, int s = 0, int ms = 0) {
    return UtcInstant{sys_days{year{y} / month{m} / day{d}} + hours(h) + minutes(min) + seconds(s) +
                      milliseconds(ms)};
}

/// The Error message of parseInstant(text, tz), or "" if it parses.
std::string parseError(const std::string& text, const std::string& tz) {
    try {
        parseInstant(text, tz);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(TimeParse, OffsetsAndZ) {
    EXPECT_EQ(parseInstant("2024-06-21T05:30:00+02:00", ""), utc(2024, 6, 21, 3, 30));
    EXPECT_EQ(parseInstant("2024-06-21T05:30:00Z", ""), utc(2024, 6, 21, 5, 30));
    EXPECT_EQ(parseInstant("2024-06-21t05:30z", ""), utc(2024, 6, 21, 5, 30));
    EXPECT_EQ(parseInstant("2024-06-21T05:30+0545", ""), utc(2024, 6, 20, 23, 45));
    EXPECT_EQ(parseInstant("2024-06-21T05:30-09:30", ""), utc(2024, 6, 21, 15, 0));
    EXPECT_EQ(parseInstant("2024-06-21T05:30+14", ""), utc(2024, 6, 20, 15, 30));
    EXPECT_EQ(parseInstant("2024-06-21 05:30:15.25+12:45", ""), utc(2024, 6, 20, 16, 45, 15, 250));
    EXPECT_EQ(parseInstant("2024-06-21T05:30:15.0004Z", ""), utc(2024, 6, 21, 5, 30, 15, 0));
    EXPECT_EQ(parseInstant("2024-06-21T05:30:15,9996Z", ""), utc(2024, 6, 21, 5, 30, 16, 0));
    EXPECT_EQ(parseInstant("2024-02-29T00:00Z", ""), utc(2024, 2, 29));
    EXPECT_EQ(parseInstant("1900-01-01T00:00Z", ""), utc(1900, 1, 1));
    EXPECT_EQ(parseInstant("2100-12-31T23:59:59Z", ""), utc(2100, 12, 31, 23, 59, 59));
}

TEST(TimeParse, ZonedInstantKeepsTheZone) {
    const ZonedInstant a = parseZonedInstant("2024-06-21T05:30:00+05:45", "");
    EXPECT_FALSE(a.zone.isIana());
    EXPECT_EQ(a.zone.offsetAt(a.utc), minutes(345));
    EXPECT_EQ(a.zone.describe(), "UTC+05:45");
    const ZonedInstant b = parseZonedInstant("2024-06-21T05:30:00", "Europe/Zurich");
    EXPECT_EQ(b.zone.ianaName(), "Europe/Zurich");
    EXPECT_EQ(b.utc, utc(2024, 6, 21, 3, 30));
    EXPECT_EQ(parseZonedInstant("2024-06-21T05:30Z", "").zone.describe(), "UTC");
}

TEST(TimeParse, IanaZonesApplyDaylightSaving) {
    EXPECT_EQ(parseInstant("2024-01-15T12:00", "Europe/Zurich"), utc(2024, 1, 15, 11));
    EXPECT_EQ(parseInstant("2024-07-15T12:00", "Europe/Zurich"), utc(2024, 7, 15, 10));
    EXPECT_EQ(parseInstant("2024-06-21T12:00", "Asia/Kathmandu"), utc(2024, 6, 21, 6, 15));
    EXPECT_EQ(parseInstant("2024-06-21T12:00", "Pacific/Chatham"), utc(2024, 6, 20, 23, 15));
    EXPECT_EQ(parseInstant("2024-12-21T12:00", "Pacific/Chatham"), utc(2024, 12, 20, 22, 15));
    EXPECT_EQ(parseInstant("2024-06-21T12:00", "Pacific/Kiritimati"), utc(2024, 6, 20, 22));
    EXPECT_EQ(parseInstant("2024-06-21T12:00", "Pacific/Marquesas"), utc(2024, 6, 21, 21, 30));
    // Just before and after the switches.
    EXPECT_EQ(parseInstant("2024-03-31T01:59", "Europe/Zurich"), utc(2024, 3, 31, 0, 59));
    EXPECT_EQ(parseInstant("2024-03-31T03:00", "Europe/Zurich"), utc(2024, 3, 31, 1, 0));
    EXPECT_EQ(parseInstant("2024-11-03T00:59", "America/New_York"), utc(2024, 11, 3, 4, 59));
    EXPECT_EQ(parseInstant("2024-11-03T02:00", "America/New_York"), utc(2024, 11, 3, 7, 0));
}

TEST(TimeParse, SpringForwardGapIsAnError) {
    const std::string zurich = parseError("2024-03-31T02:30", "Europe/Zurich");
    EXPECT_NE(zurich.find("does not exist in Europe/Zurich"), std::string::npos) << zurich;
    EXPECT_NE(zurich.find("from 02:00 to 03:00"), std::string::npos) << zurich;
    EXPECT_NE(zurich.find("+01:00 to +02:00"), std::string::npos) << zurich;
    const std::string ny = parseError("2024-03-10T02:15:00", "America/New_York");
    EXPECT_NE(ny.find("from 02:00 to 03:00"), std::string::npos) << ny;
    EXPECT_NE(ny.find("-05:00 to -04:00"), std::string::npos) << ny;
}

TEST(TimeParse, FallBackOverlapIsAnErrorUnlessTheOffsetSaysWhich) {
    const std::string msg = parseError("2024-10-27T02:30", "Europe/Zurich");
    EXPECT_NE(msg.find("ambiguous in Europe/Zurich"), std::string::npos) << msg;
    EXPECT_NE(msg.find("+02:00 and at +01:00"), std::string::npos) << msg;
    EXPECT_NE(parseError("2024-11-03T01:30", "America/New_York").find("ambiguous"),
              std::string::npos);
    // The offset picks one of the two; --tz still names the display zone.
    EXPECT_EQ(parseInstant("2024-10-27T02:30+02:00", "Europe/Zurich"), utc(2024, 10, 27, 0, 30));
    EXPECT_EQ(parseInstant("2024-10-27T02:30+01:00", "Europe/Zurich"), utc(2024, 10, 27, 1, 30));
    EXPECT_EQ(parseZonedInstant("2024-10-27T02:30+01:00", "Europe/Zurich").zone.ianaName(),
              "Europe/Zurich");
}

TEST(TimeParse, OffsetMustAgreeWithTz) {
    EXPECT_EQ(parseInstant("2024-07-01T12:00+02:00", "Europe/Zurich"), utc(2024, 7, 1, 10));
    const std::string msg = parseError("2024-07-01T12:00+01:00", "Europe/Zurich");
    EXPECT_NE(msg.find("has offset +01:00 but Europe/Zurich is at +02:00"), std::string::npos) << msg;
}

TEST(TimeParse, MissingZoneIsAnError) {
    EXPECT_EQ(parseError("2024-06-21T05:30:00", ""),
              "time '2024-06-21T05:30:00' has no zone: add an offset like +02:00 or Z, or give a time "
              "zone (tz, an IANA name such as Europe/Zurich)");
}

TEST(TimeParse, UnknownZoneIsAnError) {
    const std::string msg = parseError("2024-06-21T05:30:00", "Europe/Atlantis");
    EXPECT_NE(msg.find("unknown time zone 'Europe/Atlantis'"), std::string::npos) << msg;
    EXPECT_THROW(TimeZoneSpec::iana("Mars/Olympus_Mons"), Error);
}

TEST(TimeParse, ImpossibleDatesAndBadFormats) {
    struct Bad {
        const char* text;
        const char* expect;
    };
    const Bad cases[] = {
        {"2023-02-30T10:00Z", "day 30 does not exist in 2023-02"},
        {"2023-02-29T10:00Z", "day 29 does not exist in 2023-02"},
        {"2024-04-31T10:00Z", "day 31 does not exist in 2024-04"},
        {"2024-13-01T10:00Z", "month 13 is not 01-12"},
        {"2024-00-01T10:00Z", "month 0 is not 01-12"},
        {"2024-06-21T25:00Z", "hour 25 is not 00-23"},
        {"2024-06-21T24:00Z", "hour 24 is not 00-23"},
        {"2024-06-21T12:60Z", "minute 60 is not 00-59"},
        {"2024-06-21T12:00:60Z", "second 60 is not 00-59"},
        {"2024-06-21", "expected 'T' or a space"},
        {"2024-6-21T12:00Z", "expected 2 digits for the month"},
        {"2024-06-21T12:00+19:00", "offset beyond"},
        {"2024-06-21T12:00+05:75", "offset minutes must be 00-59"},
        {"2024-06-21T12:00Z junk", "unexpected characters"},
        {"2024-06-21T12:00:00.Z", "expected digits after the decimal point"},
        {"noon", "expected 4 digits for the year"},
        {"", "expected 4 digits for the year"},
        // Found by fuzz/time_fuzz.cpp: it rounded to 10000-01-01, which demlight writes and cannot read.
        {"9999-12-31T23:59:59.99999+00", "past 9999-12-31T23:59:59.999"},
    };
    for (const Bad& b : cases) {
        const std::string msg = parseError(b.text, "");
        EXPECT_NE(msg.find(b.expect), std::string::npos) << b.text << " -> " << msg;
        EXPECT_NE(msg.find(std::string("'") + b.text + "'"), std::string::npos) << msg;
    }
    // Impossible dates fail with a zone too.
    EXPECT_NE(parseError("2023-02-30T10:00", "Europe/Zurich").find("does not exist in 2023-02"),
              std::string::npos);
}

TEST(TimeFormat, IsoWithOffset) {
    const UtcInstant t = utc(2024, 6, 21, 3, 30);
    EXPECT_EQ(formatInstant(t, ""), "2024-06-21T03:30:00Z");
    EXPECT_EQ(formatInstant(t, "Europe/Zurich"), "2024-06-21T05:30:00+02:00");
    EXPECT_EQ(formatInstant(t, "Asia/Kathmandu"), "2024-06-21T09:15:00+05:45");
    EXPECT_EQ(formatInstant(t, "Pacific/Marquesas"), "2024-06-20T18:00:00-09:30");
    EXPECT_EQ(formatInstant(t, "Pacific/Kiritimati"), "2024-06-21T17:30:00+14:00");
    EXPECT_EQ(formatInstant(t, "Pacific/Chatham"), "2024-06-21T16:15:00+12:45");
    EXPECT_EQ(formatInstant(t, "Etc/UTC"), "2024-06-21T03:30:00+00:00");
    EXPECT_EQ(formatInstant(t + milliseconds(7), TimeZoneSpec::fixedOffset(-hours(7))),
              "2024-06-20T20:30:00.007-07:00");
    // Round trip through the parser, including the overlap hour.
    for (const char* text : {"2024-10-27T02:30:00+02:00", "2024-10-27T02:30:00+01:00",
                             "1969-07-20T20:17:40Z", "2099-06-15T07:10:00-10:00"}) {
        const ZonedInstant z = parseZonedInstant(text, "");
        EXPECT_EQ(formatInstant(z.utc, z.zone), text);
    }
    // Before standard time Zurich kept Bern mean time, +0:29:46: seconds appear in the offset.
    EXPECT_EQ(formatInstant(utc(1890, 1, 1, 12), "Europe/Zurich"), "1890-01-01T12:29:46+00:29:46");
}

TEST(TimeZones, RulesContinueAfter2037) {
    // tz tables list transitions to 2037; later ones come from the POSIX TZ rule.
    EXPECT_EQ(formatInstant(utc(2050, 9, 23, 6), "Australia/Sydney"), "2050-09-23T16:00:00+10:00");
    EXPECT_EQ(formatInstant(utc(2050, 12, 1, 6), "Australia/Sydney"), "2050-12-01T17:00:00+11:00");
    EXPECT_EQ(formatInstant(utc(2040, 7, 1, 12), "Europe/Zurich"), "2040-07-01T14:00:00+02:00");
    EXPECT_EQ(formatInstant(utc(2040, 12, 1, 12), "Europe/Zurich"), "2040-12-01T13:00:00+01:00");
    EXPECT_EQ(formatInstant(utc(2099, 7, 1, 12), "America/New_York"), "2099-07-01T08:00:00-04:00");
    EXPECT_EQ(formatInstant(utc(2060, 6, 21, 0), "Pacific/Chatham"), "2060-06-21T12:45:00+12:45");
    // The 2040 switch in Zurich: last Sunday of March (25th) 01:00 UTC.
    EXPECT_EQ(parseInstant("2040-03-25T01:59", "Europe/Zurich"), utc(2040, 3, 25, 0, 59));
    EXPECT_EQ(parseInstant("2040-03-25T03:00", "Europe/Zurich"), utc(2040, 3, 25, 1, 0));
    EXPECT_NE(parseError("2040-03-25T02:30", "Europe/Zurich").find("from 02:00 to 03:00"),
              std::string::npos);
    EXPECT_NE(parseError("2040-10-28T02:30", "Europe/Zurich").find("ambiguous"), std::string::npos);
    // Southern hemisphere: Sydney DST ends first Sunday of April (2050-04-03) at 03:00 local.
    EXPECT_EQ(parseInstant("2050-04-03T03:30", "Australia/Sydney"), utc(2050, 4, 2, 17, 30));
    EXPECT_NE(parseError("2050-04-03T02:30", "Australia/Sydney").find("ambiguous"),
              std::string::npos);
}

TEST(TimeZones, LocalDays) {
    const TimeZoneSpec zurich = TimeZoneSpec::iana("Europe/Zurich");
    const LocalDay spring = localDay(parseDate("2024-03-31"), zurich);
    EXPECT_EQ(spring.startUtc, utc(2024, 3, 30, 23));
    EXPECT_EQ(spring.endUtc - spring.startUtc, hours(23));
    const LocalDay autumn = localDayOf(utc(2024, 10, 27, 12), zurich);
    EXPECT_EQ(autumn.date, parseDate("2024-10-27"));
    EXPECT_EQ(autumn.endUtc - autumn.startUtc, hours(25));
    // Midnight skipped (Chile starts DST at 24:00): the day starts at 01:00 −03:00.
    const LocalDay santiago = localDay(parseDate("2024-09-08"), TimeZoneSpec::iana("America/Santiago"));
    EXPECT_EQ(santiago.startUtc, utc(2024, 9, 8, 4));
    EXPECT_EQ(santiago.endUtc - santiago.startUtc, hours(23));
    // Far offsets: the local day, not the UTC day.
    const LocalDay kiritimati =
        localDayOf(utc(2024, 6, 20, 12), TimeZoneSpec::iana("Pacific/Kiritimati"));
    EXPECT_EQ(kiritimati.date, parseDate("2024-06-21"));
    EXPECT_EQ(kiritimati.startUtc, utc(2024, 6, 20, 10));
    const LocalDay fixed = localDayOf(utc(2024, 6, 21, 3), TimeZoneSpec::fixedOffset(-hours(7)));
    EXPECT_EQ(fixed.date, parseDate("2024-06-20"));
    EXPECT_EQ(fixed.startUtc, utc(2024, 6, 20, 7));
    EXPECT_EQ(fixed.endUtc, utc(2024, 6, 21, 7));
    EXPECT_EQ(localDayOf(utc(2024, 6, 21, 3), TimeZoneSpec{}).startUtc, utc(2024, 6, 21));
}

TEST(TimeParse, PlainDates) {
    EXPECT_EQ(parseDate("2024-02-29"), sys_days{year{2024} / 2 / 29});
    EXPECT_EQ(formatDate(parseDate("1900-01-01")), "1900-01-01");
    EXPECT_THROW(parseDate("2023-02-29"), Error);
    EXPECT_THROW(parseDate("2023-13-01"), Error);
    EXPECT_THROW(parseDate("2023-01-01T00:00Z"), Error);
    EXPECT_THROW(parseDate("23-01-01"), Error);
}

TEST(TimeParse, MonthsAndYearsAreTheirCalendarDays) {
    const DateRange feb = parseMonth("2024-02");
    EXPECT_EQ(formatDate(feb.first), "2024-02-01");
    EXPECT_EQ(formatDate(feb.last), "2024-02-29");
    EXPECT_EQ(formatDate(parseMonth("2023-02").last), "2023-02-28");
    EXPECT_EQ(formatDate(parseMonth("2023-12").last), "2023-12-31");
    const DateRange y = parseYear("2024");
    EXPECT_EQ(formatDate(y.first), "2024-01-01");
    EXPECT_EQ(formatDate(y.last), "2024-12-31");
    EXPECT_EQ((y.last - y.first).count(), 365);
    for (const char* bad : {"2024-13", "2024-6", "2024", "2024-06-01", ""})
        EXPECT_THROW(parseMonth(bad), Error) << bad;
    for (const char* bad : {"24", "2024-01", "year", ""}) EXPECT_THROW(parseYear(bad), Error) << bad;
}

TEST(TimeScales, JulianDayAndDecimalYear) {
    EXPECT_DOUBLE_EQ(julianDay(utc(2000, 1, 1, 12)), 2451545.0);
    EXPECT_DOUBLE_EQ(julianDay(utc(1970, 1, 1)), 2440587.5);
    EXPECT_NEAR(julianDay(utc(1900, 1, 1)), 2415020.5, 1e-9);
    EXPECT_DOUBLE_EQ(decimalYear(utc(2024, 1, 1)), 2024.0);
    EXPECT_NEAR(decimalYear(utc(2024, 7, 2)), 2024.0 + 183.0 / 366.0, 1e-12);
}
