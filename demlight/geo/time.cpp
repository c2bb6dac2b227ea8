// Time parsing and formatting. Zone rules come from date/tz (system tz database).
#include "demlight/geo/time.h"

#include "demlight/core/error.h"

#include <date/date.h>
#include <date/tz.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <string_view>

namespace demlight {

namespace chr = std::chrono;

namespace {

constexpr int kMaxOffsetMinutes = 18 * 60;

/// Signed offset as "+05:45" ("+00:34:08" for a local mean time with seconds).
std::string offsetText(chr::seconds offset) {
    const long long total = offset.count();
    const long long absSec = total < 0 ? -total : total;
    char buf[48];
    std::snprintf(buf, sizeof buf, "%c%02lld:%02lld", total < 0 ? '-' : '+', absSec / 3600,
                  absSec / 60 % 60);
    std::string out = buf;
    if (absSec % 60 != 0) {
        std::snprintf(buf, sizeof buf, ":%02lld", absSec % 60);
        out += buf;
    }
    return out;
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
    std::optional<chr::seconds> offset;
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
            f.offset = chr::seconds(0);
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
    // Rounding to the millisecond must not carry past the last time a four-digit year can
    // write: demlight could not read its own output of 10000-01-01T00:00:00.
    if (f.millis == 1000 && f.year == 9999 && f.month == 12 && f.day == 31 && f.hour == 23 && f.minute == 59 &&
        f.second == 59)
        s.fail("rounds to the millisecond past 9999-12-31T23:59:59.999, the last time the format can write");
    return f;
}

/// Local wall-clock reading of the fields (no zone attached).
date::local_time<chr::milliseconds> localReading(const ParsedFields& f) {
    const date::year_month_day ymd{date::year{f.year}, date::month{static_cast<unsigned>(f.month)},
                                   date::day{static_cast<unsigned>(f.day)}};
    return date::local_days{ymd} + chr::hours(f.hour) + chr::minutes(f.minute) +
           chr::seconds(f.second) + chr::milliseconds(f.millis);
}

UtcInstant toSys(date::local_time<chr::milliseconds> local, chr::seconds offset) {
    return UtcInstant{local.time_since_epoch() - offset};
}

// --- IANA zones beyond the tables: the POSIX TZ footer -------------------------------------
//
// TZif files list explicit transitions only up to 2037; later instants follow the POSIX TZ rule
// in the file's footer (RFC 8536 §3.3). date/tz (3.0.1, USE_OS_TZDB) ignores that footer and
// would keep the last offset forever (Sydney in September 2050 on daylight time), so rules
// after the last listed transition are applied here.

/// One "start" or "end" field of a POSIX TZ DST rule: Mm.w.d, Jn or n, then /time.
struct PosixDateRule {
    enum class Form { MonthWeekDay, JulianNoLeap, ZeroBased } form = Form::MonthWeekDay;
    int month = 0, week = 0, weekday = 0, dayNumber = 0;
    chr::seconds wallTime{2 * 3600};  // local wall-clock time of the switch, may be <0 or >24 h

    chr::sys_days dateIn(int y) const {
        const chr::year year{y};
        switch (form) {
        case Form::JulianNoLeap: {
            const int leapShift = (year.is_leap() && dayNumber >= 60) ? 1 : 0;
            return chr::sys_days{year / chr::January / 1} + chr::days(dayNumber - 1 + leapShift);
        }
        case Form::ZeroBased:
            return chr::sys_days{year / chr::January / 1} + chr::days(dayNumber);
        case Form::MonthWeekDay:
        default: {
            const chr::sys_days first{year / chr::month(static_cast<unsigned>(month)) / 1};
            const unsigned firstWeekday = chr::weekday{first}.c_encoding();
            chr::sys_days d = first + chr::days((weekday - static_cast<int>(firstWeekday) + 7) % 7 +
                                                7 * (week - 1));
            // Week 5 means the last such weekday of the month.
            while (chr::year_month_day{d}.month() != chr::month(static_cast<unsigned>(month)))
                d -= chr::days(7);
            return d;
        }
        }
    }
};

struct PosixTz {
    chr::seconds stdOffset{0};  // east of UTC
    chr::seconds dstOffset{0};
    bool hasDst = false;
    PosixDateRule start, end;

    chr::seconds offsetAt(chr::sys_seconds t) const {
        if (!hasDst) return stdOffset;
        const int y = static_cast<int>(chr::year_month_day{chr::floor<chr::days>(t)}.year());
        // Latest switch at or before t among the neighbouring years decides.
        chr::sys_seconds latest = chr::sys_seconds::min();
        chr::seconds offset = stdOffset;
        for (int year = y - 1; year <= y + 1; ++year) {
            const chr::sys_seconds dstOn = start.dateIn(year) + start.wallTime - stdOffset;
            const chr::sys_seconds dstOff = end.dateIn(year) + end.wallTime - dstOffset;
            if (dstOn <= t && dstOn > latest) latest = dstOn, offset = dstOffset;
            if (dstOff <= t && dstOff > latest) latest = dstOff, offset = stdOffset;
        }
        return offset;
    }
};

/// Parser of a POSIX TZ string such as "AEST-10AEDT,M10.1.0,M4.1.0/3" or "<+0545>-5:45".
class PosixTzParser {
public:
    explicit PosixTzParser(std::string_view s) : s_(s) {}

    std::optional<PosixTz> parse() {
        PosixTz tz;
        if (!skipName()) return std::nullopt;
        const auto stdWest = clockValue(/*allowSign=*/true);
        if (!stdWest) return std::nullopt;
        tz.stdOffset = -*stdWest;
        if (pos_ == s_.size()) return tz;
        if (!skipName()) return std::nullopt;
        tz.hasDst = true;
        tz.dstOffset = tz.stdOffset + chr::hours(1);
        if (pos_ < s_.size() && s_[pos_] != ',') {
            const auto dstWest = clockValue(true);
            if (!dstWest) return std::nullopt;
            tz.dstOffset = -*dstWest;
        }
        // Without rules POSIX leaves the dates implementation-defined; tzdata always gives them.
        if (!eat(',') || !dateRule(tz.start) || !eat(',') || !dateRule(tz.end)) return std::nullopt;
        if (pos_ != s_.size()) return std::nullopt;
        return tz;
    }

private:
    bool eat(char c) {
        if (pos_ < s_.size() && s_[pos_] == c) return ++pos_, true;
        return false;
    }
    std::optional<int> number() {
        int v = 0, n = 0;
        while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_])))
            v = v * 10 + (s_[pos_++] - '0'), ++n;
        return n ? std::optional<int>(v) : std::nullopt;
    }
    bool skipName() {
        if (eat('<')) {
            while (pos_ < s_.size() && s_[pos_] != '>') ++pos_;
            return eat('>');
        }
        const std::size_t begin = pos_;
        while (pos_ < s_.size() && std::isalpha(static_cast<unsigned char>(s_[pos_]))) ++pos_;
        return pos_ - begin >= 3;
    }
    /// [+-]hh[:mm[:ss]] as a duration (sign as written).
    std::optional<chr::seconds> clockValue(bool allowSign) {
        int sign = 1;
        if (allowSign && eat('-'))
            sign = -1;
        else if (allowSign)
            eat('+');
        const auto h = number();
        if (!h) return std::nullopt;
        chr::seconds v = chr::hours(*h);
        if (eat(':')) {
            const auto m = number();
            if (!m) return std::nullopt;
            v += chr::minutes(*m);
            if (eat(':')) {
                const auto sec = number();
                if (!sec) return std::nullopt;
                v += chr::seconds(*sec);
            }
        }
        return sign * v;
    }
    bool dateRule(PosixDateRule& r) {
        if (eat('M')) {
            r.form = PosixDateRule::Form::MonthWeekDay;
            const auto m = number();
            if (!m || !eat('.')) return false;
            const auto w = number();
            if (!w || !eat('.')) return false;
            const auto d = number();
            if (!d || *m < 1 || *m > 12 || *w < 1 || *w > 5 || *d > 6) return false;
            r.month = *m, r.week = *w, r.weekday = *d;
        } else {
            r.form = eat('J') ? PosixDateRule::Form::JulianNoLeap : PosixDateRule::Form::ZeroBased;
            const auto n = number();
            if (!n || *n > 365) return false;
            r.dayNumber = *n;
        }
        if (eat('/')) {
            const auto t = clockValue(true);  // RFC 8536 allows -167..167 h
            if (!t) return false;
            r.wallTime = *t;
        }
        return true;
    }

    std::string_view s_;
    std::size_t pos_ = 0;
};

/// The POSIX TZ footer of the zone's TZif file, if it has DST rules. Cached per zone name.
const std::optional<PosixTz>& footerRule(const std::string& name) {
    static std::mutex mutex;
    static std::map<std::string, std::optional<PosixTz>> cache;
    const std::lock_guard lock(mutex);
    if (const auto it = cache.find(name); it != cache.end()) return it->second;

    std::optional<PosixTz> rule;
    const char* dir = std::getenv("TZDIR");
    std::ifstream in(std::string(dir && *dir ? dir : "/usr/share/zoneinfo") + "/" + name,
                     std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    // Version 2+ files end with "\n<POSIX TZ string>\n".
    if (bytes.size() > 6 && bytes.compare(0, 4, "TZif") == 0 && bytes[4] >= '2' &&
        bytes.back() == '\n') {
        const std::size_t open = bytes.rfind('\n', bytes.size() - 2);
        if (open != std::string::npos)
            rule = PosixTzParser(std::string_view(bytes).substr(open + 1, bytes.size() - open - 2))
                       .parse();
    }
    return cache.emplace(name, rule).first->second;
}

/// UTC offset (east) of an IANA zone at t: the tz tables, then the footer rule.
chr::seconds ianaOffsetAt(const std::string& name, chr::sys_seconds t) {
    const date::sys_info info = findZone(name)->get_info(t);
    constexpr auto kOpenEnded = chr::sys_days{chr::year{9999} / 1 / 1};
    if (info.end < kOpenEnded) return info.offset;  // a listed transition is still ahead
    const std::optional<PosixTz>& footer = footerRule(name);
    return (footer && footer->hasDst) ? footer->offsetAt(t) : info.offset;
}

/// How a local wall-clock reading maps to UTC in a zone.
struct LocalResolution {
    enum class Kind { Unique, Gap, Overlap } kind = Kind::Unique;
    UtcInstant first;           ///< Unique/Overlap: the (earlier) instant; Gap: end of the gap
    UtcInstant second;          ///< Overlap: the later instant
    chr::seconds offsetBefore{0}, offsetAfter{0};  ///< Gap/Overlap: offsets around the switch
};

/// Resolves a local reading with the zone's offset function. Assumes at most one offset change
/// within a day of the reading (true of every zone in tzdata).
LocalResolution resolveLocal(const TimeZoneSpec& zone, date::local_time<chr::milliseconds> local) {
    const UtcInstant asUtc{local.time_since_epoch()};
    const auto offsetAt = [&zone](UtcInstant t) { return zone.offsetAt(t); };
    const chr::seconds before = offsetAt(asUtc - chr::days(1));
    const chr::seconds after = offsetAt(asUtc + chr::days(1));
    const UtcInstant tBefore = asUtc - before, tAfter = asUtc - after;
    const bool beforeValid = offsetAt(tBefore) == before;
    const bool afterValid = offsetAt(tAfter) == after;

    LocalResolution r;
    r.offsetBefore = before;
    r.offsetAfter = after;
    if (before == after || (beforeValid != afterValid)) {
        r.first = beforeValid ? tBefore : tAfter;
        return r;
    }
    if (beforeValid) {
        r.kind = LocalResolution::Kind::Overlap;
        r.first = std::min(tBefore, tAfter);
        r.second = std::max(tBefore, tAfter);
        return r;
    }
    // Gap: find the switch instant by bisection; the gap ends there.
    UtcInstant lo = asUtc - chr::days(1), hi = asUtc + chr::days(1);
    while (hi - lo > chr::milliseconds(1)) {
        const UtcInstant mid = lo + (hi - lo) / 2;
        (offsetAt(mid) == before ? lo : hi) = mid;
    }
    r.kind = LocalResolution::Kind::Gap;
    r.first = hi;
    return r;
}

}  // namespace

// --- TimeZoneSpec ----------------------------------------------------------------------------

TimeZoneSpec TimeZoneSpec::iana(const std::string& name) {
    findZone(name);
    TimeZoneSpec z;
    z.ianaName_ = name;
    return z;
}

TimeZoneSpec TimeZoneSpec::fixedOffset(chr::seconds offsetEastOfUtc) {
    if (offsetEastOfUtc > chr::minutes(kMaxOffsetMinutes) ||
        offsetEastOfUtc < -chr::minutes(kMaxOffsetMinutes))
        throw Error("UTC offset " + offsetText(offsetEastOfUtc) + " is beyond ±18:00");
    TimeZoneSpec z;
    z.fixedOffset_ = offsetEastOfUtc;
    return z;
}

TimeZoneSpec TimeZoneSpec::fromName(const std::string& nameOrEmpty) {
    return nameOrEmpty.empty() ? TimeZoneSpec{} : iana(nameOrEmpty);
}

chr::seconds TimeZoneSpec::offsetAt(UtcInstant t) const {
    if (!isIana()) return fixedOffset_;
    return ianaOffsetAt(ianaName_, chr::floor<chr::seconds>(t));
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
            throw ParameterError("time '" + text +
                                 "' has no zone: add an offset like +02:00 or Z, or give a time zone ({tz}, an "
                                 "IANA name such as Europe/Zurich)");
        return {toSys(local, *f.offset), TimeZoneSpec::fixedOffset(*f.offset)};
    }

    const TimeZoneSpec spec = TimeZoneSpec::iana(tzName);

    if (f.offset) {
        // The offset fixes the instant; it must be one the zone actually uses then.
        const UtcInstant t = toSys(local, *f.offset);
        const chr::seconds zoneOffset = spec.offsetAt(t);
        if (zoneOffset != *f.offset)
            throw ParameterError("time '" + text + "' has offset " + offsetText(*f.offset) + " but " + tzName +
                                 " is at " + offsetText(zoneOffset) +
                                 " then: drop the offset or the {tz}, or make them agree");
        return {t, spec};
    }

    const LocalResolution r = resolveLocal(spec, local);
    const auto clockOf = [](UtcInstant t, chr::seconds offset) {
        const auto wall = chr::floor<chr::minutes>(t + offset);
        return hhmm(wall - chr::floor<chr::days>(wall));
    };
    switch (r.kind) {
    case LocalResolution::Kind::Unique:
        return {r.first, spec};
    case LocalResolution::Kind::Gap:
        throw Error("time '" + text + "' does not exist in " + tzName + ": clocks jump from " +
                    clockOf(r.first, r.offsetBefore) + " to " + clockOf(r.first, r.offsetAfter) +
                    " (" + offsetText(r.offsetBefore) + " to " + offsetText(r.offsetAfter) +
                    ") that day; choose a time outside the gap");
    case LocalResolution::Kind::Overlap:
        throw Error("time '" + text + "' is ambiguous in " + tzName +
                    ": it happens twice as clocks fall back, at " + offsetText(r.offsetBefore) +
                    " and at " + offsetText(r.offsetAfter) + "; add the offset you mean (e.g. " +
                    text + offsetText(r.offsetBefore) + ")");
    }
    throw Error("time '" + text + "': could not resolve it in " + tzName);
}

UtcInstant parseInstant(const std::string& text, const std::string& tzName) {
    return parseZonedInstant(text, tzName).utc;
}

// --- Formatting ------------------------------------------------------------------------------

std::string formatInstant(UtcInstant t, const TimeZoneSpec& zone) {
    const chr::seconds offset = zone.offsetAt(t);
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
        // Unique or overlap: the (earliest) midnight. Gap: the day starts where the gap ends.
        return resolveLocal(zone, midnight).first;
    };
    return {date, startOf(date), startOf(date + chr::days(1))};
}

LocalDay localDayOf(UtcInstant t, const TimeZoneSpec& zone) {
    const auto local = t + zone.offsetAt(t);
    return localDay(chr::floor<chr::days>(local), zone);
}

TimeZoneSpec zoneOfDays(const std::string& tzName) {
    if (tzName.empty())
        throw FieldError("zone", " missing: a date is a day from midnight to midnight in some time zone (never "
                                 "silently UTC); give one: an IANA name such as Europe/Zurich, or UTC");
    return TimeZoneSpec::iana(tzName);
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

DateRange parseMonth(const std::string& text) {
    chr::sys_days first;
    try {
        first = parseDate(text + "-01");
    } catch (const Error&) {
        throw Error("month '" + text + "': expected YYYY-MM (e.g. 2024-06)");
    }
    const chr::year_month ym = chr::year_month_day{first}.year() / chr::year_month_day{first}.month();
    return {first, chr::sys_days{(ym + chr::months{1}) / chr::day{1}} - chr::days{1}};
}

DateRange parseYear(const std::string& text) {
    try {
        return {parseDate(text + "-01-01"), parseDate(text + "-12-31")};
    } catch (const Error&) {
        throw Error("year '" + text + "': expected YYYY (e.g. 2024)");
    }
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

namespace {

/// "minutes" for a bare-number unit of 1 min; how the error message names it.
std::string bareUnitName(chr::milliseconds unit) {
    if (unit == chr::hours(1)) return "hours";
    if (unit == chr::minutes(1)) return "minutes";
    if (unit == chr::seconds(1)) return "seconds";
    if (unit == chr::milliseconds(1)) return "milliseconds";
    return "multiples of " + std::to_string(unit.count()) + " ms";
}

/// The grammar of parseDuration; a unitless last term counts bareUnit when one is given.
chr::milliseconds parseDurationTerms(std::string_view text, std::string_view field,
                                     std::optional<chr::milliseconds> bareUnit) {
    auto fail = [&](const std::string& why) {
        return Error(std::string(field) + " '" + std::string(text) + "': " + why);
    };
    const std::string expected = "expected a duration like 15m, 1h, 90s or 1h30m" +
                                 (bareUnit ? ", or a number of " + bareUnitName(*bareUnit) : std::string());
    auto isSpace = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
    auto isDigit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
    const std::size_t n = text.size();
    std::size_t i = 0;
    auto skipSpace = [&] {
        while (i < n && isSpace(text[i])) ++i;
    };
    // Summed in this order and rounded once, as the CLI's step parser did, so the same text
    // gives the same milliseconds.
    double totalMs = 0;
    bool anyTerm = false;
    skipSpace();
    while (i < n) {
        if (text[i] == '-') throw fail("a duration cannot be negative");
        if (text[i] == '+') ++i;
        // The number: digits with an optional fraction, then an exponent only if digits follow
        // (in "1em" the 'e' is a unit, and an unknown one).
        const std::size_t start = i;
        std::size_t digits = 0;
        for (; i < n && isDigit(text[i]); ++i) ++digits;
        if (i < n && text[i] == '.')
            for (++i; i < n && isDigit(text[i]); ++i) ++digits;
        if (digits == 0) throw fail(expected);
        if (i < n && (text[i] == 'e' || text[i] == 'E')) {
            std::size_t j = i + 1;
            if (j < n && (text[j] == '+' || text[j] == '-')) ++j;
            if (j < n && isDigit(text[j]))
                for (i = j; i < n && isDigit(text[i]); ++i) {
                }
        }
        double value = 0;
        const auto [end, ec] = std::from_chars(text.data() + start, text.data() + i, value);
        if (ec == std::errc::result_out_of_range) throw fail("the number is out of range");
        if (ec != std::errc{} || end != text.data() + i) throw fail(expected);
        skipSpace();
        double unitMs = 0;
        if (i < n && (text[i] == 'h' || text[i] == 'm' || text[i] == 's')) {
            unitMs = text[i] == 'h' ? 3.6e6 : text[i] == 'm' ? 6e4 : 1e3;
            ++i;
            skipSpace();
        } else if (i == n && bareUnit) {
            unitMs = static_cast<double>(bareUnit->count());
        } else {
            throw fail(expected);
        }
        totalMs += value * unitMs;
        anyTerm = true;
    }
    if (!anyTerm) throw fail(expected);
    constexpr double kMaxMs = 0x1p63;  // std::chrono::milliseconds is a signed 64-bit count
    if (!(totalMs < kMaxMs)) throw fail("too long a duration");
    return chr::milliseconds(std::llround(totalMs));
}

}  // namespace

chr::milliseconds parseDuration(std::string_view text, std::string_view field) {
    return parseDurationTerms(text, field, std::nullopt);
}

chr::milliseconds parseDurationOr(std::string_view text, std::string_view field, chr::milliseconds bareUnit) {
    if (bareUnit <= chr::milliseconds::zero())
        throw Error(std::string(field) + ": the unit of a bare number must be positive");
    return parseDurationTerms(text, field, bareUnit);
}

}  // namespace demlight
