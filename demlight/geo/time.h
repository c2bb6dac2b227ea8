// Time input for demlight: ISO 8601 instants with an explicit offset, or local times in an IANA
// zone (daylight saving from the system tz database through Howard Hinnant's date/tz). A time
// with no zone is an error, never silently UTC (docs/design.md §3).
//
// Accepted instant text:  YYYY-MM-DD('T'|' ')HH:MM[:SS[.fraction]][zone]
// where zone is 'Z', ±HH:MM, ±HHMM or ±HH (at most ±18:00). Fractions are rounded to the
// millisecond. The date is proleptic Gregorian; no leap seconds (second 60 is rejected).
//
// Rules when text and --tz meet:
//  - text with an offset, no tz: that offset fixes the instant and is the display zone.
//  - text without an offset, tz given: a local time in tz. A local time inside a
//    spring-forward gap is an error naming the gap; one inside a fall-back overlap (it happens
//    twice) is an error naming both offsets: write the offset you mean, together with --tz.
//  - text with an offset and tz: the offset must be the one tz uses at that instant (this is
//    how an overlap time is given); the instant comes from the offset, tz is the display zone.
//    A different offset is an error.
//  - neither: error.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

namespace demlight {

/// An instant on the UTC time line (Unix clock, no leap seconds), millisecond resolution.
using UtcInstant = std::chrono::sys_time<std::chrono::milliseconds>;

/// The zone local clock times are read in and written in: an IANA zone, or a fixed offset from
/// UTC (a fixed offset of 0 is plain UTC).
class TimeZoneSpec {
public:
    /// UTC (written as "Z").
    TimeZoneSpec() = default;
    /// An IANA zone such as "Europe/Zurich". Throws Error naming the zone if it is unknown.
    static TimeZoneSpec iana(const std::string& name);
    /// A fixed offset east of UTC. Throws Error if beyond ±18:00.
    static TimeZoneSpec fixedOffset(std::chrono::seconds offsetEastOfUtc);
    /// The empty name is UTC, anything else an IANA zone (see iana()).
    static TimeZoneSpec fromName(const std::string& nameOrEmpty);

    bool isIana() const { return !ianaName_.empty(); }
    /// IANA zone name, or empty for a fixed offset.
    const std::string& ianaName() const { return ianaName_; }
    /// Offset east of UTC in force at instant t. IANA zones follow the tz tables and, after
    /// their last listed transition (2037), the zone's POSIX TZ rule, so DST continues.
    std::chrono::seconds offsetAt(UtcInstant t) const;
    /// "Europe/Zurich", "UTC" or "UTC+05:45".
    std::string describe() const;

private:
    std::string ianaName_;
    std::chrono::seconds fixedOffset_{0};
};

/// An instant together with the zone it was given in (used to display results in that zone and
/// to find "the local day" for sunrise/sunset).
struct ZonedInstant {
    UtcInstant utc;
    TimeZoneSpec zone;
};

/// Parses an instant (format and rules above). tzName may be empty. Throws Error with the text
/// and what was expected on any problem: no zone, unknown zone, impossible date or clock time,
/// DST gap or overlap, offset inconsistent with tzName.
ZonedInstant parseZonedInstant(const std::string& text, const std::string& tzName);

/// As parseZonedInstant, returning only the instant.
UtcInstant parseInstant(const std::string& text, const std::string& tzName);

/// Writes t as ISO 8601 local time with its offset in zone, e.g. "2024-06-21T05:30:00+02:00"
/// (UTC as "...Z"). Milliseconds appear only when non-zero.
std::string formatInstant(UtcInstant t, const TimeZoneSpec& zone);
/// As above; an empty tzName means UTC, otherwise an IANA zone.
std::string formatInstant(UtcInstant t, const std::string& tzName);

/// A calendar day in some zone and the UTC instants where it starts and ends. A day is 24 h,
/// or 23 h / 25 h on daylight-saving switch days. If local midnight falls in a DST gap the day
/// starts at the end of the gap.
struct LocalDay {
    std::chrono::sys_days date;  ///< the local calendar date (as days since 1970-01-01)
    UtcInstant startUtc;         ///< first instant of the day
    UtcInstant endUtc;           ///< first instant of the next day
};

/// The local day in zone of calendar date `date`.
LocalDay localDay(std::chrono::sys_days date, const TimeZoneSpec& zone);
/// The local day in zone that contains instant t.
LocalDay localDayOf(UtcInstant t, const TimeZoneSpec& zone);

/// The zone of local calendar days given as dates alone. A date has times too (where its day
/// starts and ends, the clock times in it), so the rule for a time without a zone holds:
/// an empty name throws FieldError "zone" instead of meaning UTC. "UTC" names UTC; anything else
/// is an IANA zone (TimeZoneSpec::iana).
TimeZoneSpec zoneOfDays(const std::string& tzName);

/// Parses a plain calendar date "YYYY-MM-DD". Throws Error naming the text on a bad format or
/// an impossible date (2023-02-30).
std::chrono::sys_days parseDate(const std::string& text);

/// "YYYY-MM-DD".
std::string formatDate(std::chrono::sys_days date);

/// The first and last calendar dates (inclusive) of a month or a year.
struct DateRange {
    std::chrono::sys_days first, last;
};
/// The days of the calendar month "YYYY-MM". Throws Error naming the text otherwise.
DateRange parseMonth(const std::string& text);
/// The days of the calendar year "YYYY". Throws Error naming the text otherwise.
DateRange parseYear(const std::string& text);

/// Decimal (Gregorian) year of t: 2024.0 at 2024-01-01T00:00Z, 2024.5 near 2 July.
double decimalYear(UtcInstant t);

/// Julian Day (UT) of t: 2451545.0 at 2000-01-01T12:00Z.
double julianDay(UtcInstant t);

/// Parses a duration: one or more terms, each a non-negative decimal number and a unit,
/// h (hours), m (minutes) or s (seconds), summed: "10m", "90s", "1.5h", "1h30m", "1h 30m",
/// "2h15m30s". Whitespace may stand before, between and after terms and between a number and its
/// unit; a number may have a leading '+', a fraction ("1.5", ".5", "5.") and an exponent ("1e3s").
/// The total is rounded to the nearest millisecond; zero is a duration (a caller with a minimum
/// checks it). Throws Error naming `field` and the text ("step '10x': expected a duration like
/// 15m, 1h, 90s or 1h30m") on empty text, a number without its unit, an unknown unit ("10d",
/// "10min"), a minus sign anywhere (even "-0m"), inf or NaN, hexadecimal numbers, or a total
/// beyond the range of std::chrono::milliseconds.
std::chrono::milliseconds parseDuration(std::string_view text, std::string_view field);

/// As parseDuration, but the last term may be a bare number, counted in `bareUnit` (> 0): with
/// minutes, "10" is 10 min and "1h30" is 1 h 30 min. For options whose bare numbers always meant
/// that unit; the error message then also offers "a number of minutes".
std::chrono::milliseconds parseDurationOr(std::string_view text, std::string_view field,
                                          std::chrono::milliseconds bareUnit);

}  // namespace demlight
