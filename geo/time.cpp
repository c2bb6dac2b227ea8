// Time parsing and formatting. Zone rules come from date/tz (system tz database).
#include "geo/time.h"

#include "src/error.h"

#include <date/date.h>
#include <date/tz.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace demlight {

namespace chr = std::chrono;

namespace {

constexpr int kMaxOffsetMinutes = 18 * 60;

/// Signed offset as "+05:45".
std::string offsetText(chr::minutes offset) {
    const long long total = offset.count();
    const long long absMin = total < 0 ? -total : total;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%c%02lld:%02lld", total < 0 ? '-' : '+', absMin / 60, absMin % 60);
    return buf;
}

std::string hhmm(chr::minutes sinceMidnight) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "%02d:%02d", static_cast<int>(sinceMidnight.count() / 60),
                  static_cast<int>(sinceMidnight.count() % 60));
    return buf;
}

const date::time_zone* findZone(const std::string& name) {
    try {
        return date::locate_zone(name);
    } catch (const std::exception&) {
        throw Error("unknown time zone '" + name +
                    "': expected an IANA zone name such as Europe/Zurich or America/New_York");
    }
}

/// Fields of the accepted ISO 8601 text, before any calendar validation.
struct ParsedFields {
    int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
    long long millis = 0;  // 0..1000 (1000 after rounding .9995 up; carried when building)
    std::optional<chr::minutes> offset;
};

/// A strict left-to-right scanner over the text; every failure names the text and the
/// expected form.
class Scanner {
public:
    Scanner(std::string_view text, std::string what) : text_(text), what_(std::move(what)) {}

    bool atEnd() const { return pos_ == text_.size(); }
    char peek() const { return atEnd() ? '\0' : text_[pos_]; }
    void advance() { ++pos_; }

    int digits(int count, const char* field) {
        int value = 0;
        for (int i = 0; i < count; ++i) {
            if (atEnd() || !std::isdigit(static_cast<unsigned char>(text_[pos_])))
                fail(std::string("expected ") + std::to_string(count) + " digits for the " + field);
            value = value * 10 + (text_[pos_++] - '0');
        }
        return value;
    }
    void expect(char c, const char* where) {
        if (peek() != c) fail(std::string("expected '") + c + "' " + where);
        advance();
    }
    [[noreturn]] void fail(const std::string& why) const {
        throw Error(what_ + " '" + std::string(text_) + "': " + why);
    }

private:
    std::string_view text_;
    std::string what_;
    std::size_t pos_ = 0;
};

constexpr const char* kInstantForm =
    " (expected YYYY-MM-DDTHH:MM[:SS[.fff]] followed by Z or an offset like +02:00)";

ParsedFields scanInstant(const std::string& text) {
    Scanner s(text, "time");
    ParsedFields f;
    try {
        f.year = s.digits(4, "year");
        s.expect('-', "after the year");
        f.month = s.digits(2, "month");
        s.expect('-', "after the month");
        f.day = s.digits(2, "day");
        if (s.peek() == 'T' || s.peek() == 't' || s.peek() == ' ')
            s.advance();
        else
            s.fail("expected 'T' or a space between date and time");
        f.hour = s.digits(2, "hour");
        s.expect(':', "between hour and minute");
        f.minute = s.digits(2, "minute");
        if (s.peek() == ':') {
            s.advance();
            f.second = s.digits(2, "second");
            if (s.peek() == '.' || s.peek() == ',') {
                s.advance();
                // Fraction of a second, rounded to the millisecond.
                double scale = 100.0, fractionMs = 0;
                int n = 0;
                while (std::isdigit(static_cast<unsigned char>(s.peek()))) {
                    fractionMs += (s.peek() - '0') * scale;
                    scale /= 10;
                    s.advance();
                    ++n;
                }
                if (n == 0) s.fail("expected digits after the decimal point of the seconds");
                f.millis = static_cast<long long>(fractionMs + 0.5);
            }
        }
        if (s.peek() == 'Z' || s.peek() == 'z') {
            s.advance();
            f.offset = chr::minutes(0);
        } else if (s.peek() == '+' || s.peek() == '-') {
            const int sign = s.peek() == '-' ? -1 : 1;
            s.advance();
            const int oh = s.digits(2, "offset hours");
            int om = 0;
            if (s.peek() == ':') {
                s.advance();
                om = s.digits(2, "offset minutes");
            } else if (!s.atEnd()) {
                om = s.digits(2, "offset minutes");
            }
            if (om > 59) s.fail("offset minutes must be 00-59");
            const int total = oh * 60 + om;
            if (total > kMaxOffsetMinutes) s.fail("offset beyond ±18:00");
            f.offset = chr::minutes(sign * total);
        }
        if (!s.atEnd()) s.fail("unexpected characters after the time");
    } catch (const Error& e) {
        throw Error(e.what() + std::string(kInstantForm));
    }

    // Calendar and clock validation.
    const date::year_month_day ymd{date::year{f.year}, date::month{static_cast<unsigned>(f.month)},
                                   date::day{static_cast<unsigned>(f.day)}};
    if (f.month < 1 || f.month > 12) s.fail("month " + std::to_string(f.month) + " is not 01-12");
    if (!ymd.ok())
        s.fail("day " + std::to_string(f.day) + " does not exist in " + std::to_string(f.year) +
               "-" + (f.month < 10 ? "0" : "") + std::to_string(f.month));
    if (f.hour > 23) s.fail("hour " + std::to_string(f.hour) + " is not 00-23");
    if (f.minute > 59) s.fail("minute " + std::to_string(f.minute) + " is not 00-59");
    if (f.second > 59) s.fail("second " + std::to_string(f.second) + " is not 00-59 (no leap seconds)");
    return f;
}

/// Local wall-clock reading of the fields (no zone attached).
date::local_time<chr::milliseconds> localReading(const ParsedFields& f) {
    const date::year_month_day ymd{date::year{f.year}, date::month{static_cast<unsigned>(f.month)},
                                   date::day{static_cast<unsigned>(f.day)}};
    return date::local_days{ymd} + chr::hours(f.hour) + chr::minutes(f.minute) +
           chr::seconds(f.second) + chr::milliseconds(f.millis);
}

UtcInstant toSys(date::local_time<chr::milliseconds> local, chr::minutes offset) {
    return UtcInstant{local.time_since_epoch() - offset};
}

}  // namespace

// --- TimeZoneSpec ----------------------------------------------------------------------------

TimeZoneSpec TimeZoneSpec::iana(const std::string& name) {
    findZone(name);
    TimeZoneSpec z;
    z.ianaName_ = name;
    return z;
}

TimeZoneSpec TimeZoneSpec::fixedOffset(chr::minutes offsetEastOfUtc) {
    if (offsetEastOfUtc.count() > kMaxOffsetMinutes || offsetEastOfUtc.count() < -kMaxOffsetMinutes)
        throw Error("UTC offset " + offsetText(offsetEastOfUtc) + " is beyond ±18:00");
    TimeZoneSpec z;
    z.fixedOffset_ = offsetEastOfUtc;
    return z;
}

TimeZoneSpec TimeZoneSpec::fromName(const std::string& nameOrEmpty) {
    return nameOrEmpty.empty() ? TimeZoneSpec{} : iana(nameOrEmpty);
}

chr::minutes TimeZoneSpec::offsetAt(UtcInstant t) const {
    if (!isIana()) return fixedOffset_;
    const date::sys_info info = findZone(ianaName_)->get_info(t);
    return chr::duration_cast<chr::minutes>(info.offset);
}

std::string TimeZoneSpec::describe() const {
    if (isIana()) return ianaName_;
    if (fixedOffset_.count() == 0) return "UTC";
    return "UTC" + offsetText(fixedOffset_);
}

// --- Parsing ---------------------------------------------------------------------------------

ZonedInstant parseZonedInstant(const std::string& text, const std::string& tzName) {
    const ParsedFields f = scanInstant(text);
    const auto local = localReading(f);

    if (tzName.empty()) {
        if (!f.offset)
            throw Error("time '" + text +
                        "' has no zone: add an offset like +02:00 or Z, or give --tz ZONE");
        return {toSys(local, *f.offset), TimeZoneSpec::fixedOffset(*f.offset)};
    }

    const date::time_zone* zone = findZone(tzName);
    const TimeZoneSpec spec = TimeZoneSpec::iana(tzName);

    if (f.offset) {
        // The offset fixes the instant; it must be one the zone actually uses then.
        const UtcInstant t = toSys(local, *f.offset);
        const chr::minutes zoneOffset = spec.offsetAt(t);
        if (zoneOffset != *f.offset)
            throw Error("time '" + text + "' has offset " + offsetText(*f.offset) + " but " +
                        tzName + " is at " + offsetText(zoneOffset) +
                        " then: drop the offset or the --tz, or make them agree");
        return {t, spec};
    }

    const date::local_info info = zone->get_info(local);
    switch (info.result) {
    case date::local_info::unique:
        return {toSys(local, chr::duration_cast<chr::minutes>(info.first.offset)), spec};
    case date::local_info::nonexistent: {
        // The gap runs from the transition (first.end) in the old offset to the same instant in
        // the new offset.
        const auto before = chr::duration_cast<chr::minutes>(info.first.offset);
        const auto after = chr::duration_cast<chr::minutes>(info.second.offset);
        const auto gapStart = date::floor<chr::minutes>(info.first.end + before);
        const auto gapEnd = date::floor<chr::minutes>(info.first.end + after);
        const auto dayOf = [](auto t) { return t - date::floor<date::days>(t); };
        throw Error("time '" + text + "' does not exist in " + tzName +
                    ": clocks jump from " + hhmm(dayOf(gapStart)) + " to " + hhmm(dayOf(gapEnd)) +
                    " (" + offsetText(before) + " to " + offsetText(after) +
                    ") that day; choose a time outside the gap");
    }
    case date::local_info::ambiguous: {
        const auto first = chr::duration_cast<chr::minutes>(info.first.offset);
        const auto second = chr::duration_cast<chr::minutes>(info.second.offset);
        throw Error("time '" + text + "' is ambiguous in " + tzName +
                    ": it happens twice as clocks fall back, at " + offsetText(first) + " and at " +
                    offsetText(second) + "; add the offset you mean (e.g. " + text +
                    offsetText(first) + ")");
    }
    }
    throw Error("time '" + text + "': unexpected result from the time zone database");
}

UtcInstant parseInstant(const std::string& text, const std::string& tzName) {
    return parseZonedInstant(text, tzName).utc;
}

// --- Formatting ------------------------------------------------------------------------------

std::string formatInstant(UtcInstant t, const TimeZoneSpec& zone) {
    const chr::minutes offset = zone.offsetAt(t);
    const auto local = t + offset;
    const auto day = date::floor<date::days>(local);
    const date::year_month_day ymd{day};
    const date::hh_mm_ss<chr::milliseconds> tod{local - day};
    char buf[64];
    std::snprintf(buf, sizeof buf, "%04d-%02u-%02uT%02d:%02d:%02d", static_cast<int>(ymd.year()),
                  static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()),
                  static_cast<int>(tod.hours().count()), static_cast<int>(tod.minutes().count()),
                  static_cast<int>(tod.seconds().count()));
    std::string out = buf;
    if (const auto ms = tod.subseconds().count(); ms != 0) {
        std::snprintf(buf, sizeof buf, ".%03d", static_cast<int>(ms));
        out += buf;
    }
    out += (!zone.isIana() && offset.count() == 0) ? std::string("Z") : offsetText(offset);
    return out;
}

std::string formatInstant(UtcInstant t, const std::string& tzName) {
    return formatInstant(t, TimeZoneSpec::fromName(tzName));
}

// --- Days ------------------------------------------------------------------------------------

LocalDay localDay(chr::sys_days date, const TimeZoneSpec& zone) {
    const auto startOf = [&zone](chr::sys_days d) -> UtcInstant {
        const date::local_time<chr::milliseconds> midnight{
            chr::duration_cast<chr::milliseconds>(d.time_since_epoch())};
        if (!zone.isIana()) return toSys(midnight, zone.offsetAt(UtcInstant{}));
        const date::local_info info = findZone(zone.ianaName())->get_info(midnight);
        switch (info.result) {
        case date::local_info::nonexistent:
            // Midnight skipped: the day starts where the gap ends (the transition instant).
            return chr::time_point_cast<chr::milliseconds>(info.first.end);
        case date::local_info::ambiguous:  // earliest midnight
        case date::local_info::unique:
        default:
            return toSys(midnight, chr::duration_cast<chr::minutes>(info.first.offset));
        }
    };
    return {date, startOf(date), startOf(date + chr::days(1))};
}

LocalDay localDayOf(UtcInstant t, const TimeZoneSpec& zone) {
    const auto local = t + zone.offsetAt(t);
    return localDay(chr::floor<chr::days>(local), zone);
}

chr::sys_days parseDate(const std::string& text) {
    Scanner s(text, "date");
    int y = 0, m = 0, d = 0;
    try {
        y = s.digits(4, "year");
        s.expect('-', "after the year");
        m = s.digits(2, "month");
        s.expect('-', "after the month");
        d = s.digits(2, "day");
        if (!s.atEnd()) s.fail("unexpected characters after the date");
    } catch (const Error& e) {
        throw Error(e.what() + std::string(" (expected YYYY-MM-DD)"));
    }
    if (m < 1 || m > 12) s.fail("month " + std::to_string(m) + " is not 01-12");
    const chr::year_month_day ymd{chr::year{y}, chr::month{static_cast<unsigned>(m)},
                                  chr::day{static_cast<unsigned>(d)}};
    if (!ymd.ok())
        s.fail("day " + std::to_string(d) + " does not exist in " + std::to_string(y) + "-" +
               (m < 10 ? "0" : "") + std::to_string(m));
    return chr::sys_days{ymd};
}

std::string formatDate(chr::sys_days date) {
    const chr::year_month_day ymd{date};
    char buf[16];
    std::snprintf(buf, sizeof buf, "%04d-%02u-%02u", static_cast<int>(ymd.year()),
                  static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()));
    return buf;
}

double decimalYear(UtcInstant t) {
    const chr::year_month_day ymd{chr::floor<chr::days>(t)};
    const chr::sys_days start{ymd.year() / chr::January / 1};
    const chr::sys_days next{(ymd.year() + chr::years(1)) / chr::January / 1};
    const double into = chr::duration<double>(t - start).count();
    const double length = chr::duration<double>(next - start).count();
    return static_cast<int>(ymd.year()) + into / length;
}

double julianDay(UtcInstant t) {
    constexpr double kJulianDayOfUnixEpoch = 2440587.5;
    constexpr double kMsPerDay = 86400000.0;
    // Split whole days and the fraction to keep full precision for distant dates.
    const auto day = chr::floor<chr::days>(t);
    const double wholeDays = static_cast<double>(day.time_since_epoch().count());
    const double fraction = static_cast<double>((t - day).count()) / kMsPerDay;
    return kJulianDayOfUnixEpoch + wholeDays + fraction;
}

}  // namespace demlight
