#include "demlight/run/options.h"

#include "demlight/core/error.h"

#include <cmath>
#include <sstream>

namespace demlight {

std::optional<double> parseFiniteNumber(const std::string& text, bool trailingSpaces) {
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    while (trailingSpaces && used < text.size() && text[used] == ' ') ++used;
    if (used == 0 || used != text.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::array<double, 3> parseColor(const std::string& text, const std::string& field) {
    const auto bad = [&] { return FieldError(field, " '" + text + "': expected three linear values >= 0 like 1,0.9,0.8"); };
    std::array<double, 3> c{};
    std::stringstream ss(text);
    std::string part;
    std::size_t n = 0;
    while (std::getline(ss, part, ',')) {
        const std::optional<double> v = parseFiniteNumber(part);
        if (n >= 3 || !v || !(*v >= 0)) throw bad();
        c[n++] = *v;
    }
    if (n != 3) throw bad();
    return c;
}

std::chrono::milliseconds parseStepOption(const std::string& text, std::chrono::milliseconds bareUnit) {
    try {
        return parseDurationOr(text, "{step}", bareUnit);
    } catch (const Error& e) {
        throw ParameterError(e.what());  // the message names the parameter as {step}
    }
}

ZonedInstant parseTimeOptions(const std::string& time, const std::string& tz) { return parseZonedInstant(time, tz); }

LocalDays parseDayOptions(const DayOptions& o, const std::string& command) {
    LocalDays days{{}, {}, zoneOfDays(o.tz), std::nullopt};
    const bool range = !o.startDate.empty() || !o.endDate.empty();
    const int given = int(!o.date.empty()) + int(range) + int(!o.month.empty()) + int(!o.year.empty());
    const std::string choices = o.periods ? "{date} D, {start} D {end} D, {month} YYYY-MM or {year} YYYY"
                                          : "{date} D, or both {start} D and {end} D";
    if (given > 1) throw ParameterError(command + ": give one of " + choices + ", not several");
    if (!o.date.empty()) {
        days.first = days.last = parseDate(o.date);
    } else if (!o.month.empty()) {
        const DateRange month = parseMonth(o.month);
        days.first = month.first;
        days.last = month.last;
    } else if (!o.year.empty()) {
        const DateRange year = parseYear(o.year);
        days.first = year.first;
        days.last = year.last;
    } else if (o.startDate.empty() || o.endDate.empty()) {
        throw ParameterError(command + ": give " + choices);
    } else if (o.periods && (o.startDate.find('T') != std::string::npos || o.endDate.find('T') != std::string::npos)) {
        const UtcInstant start = parseTimeOptions(o.startDate, o.tz).utc, end = parseTimeOptions(o.endDate, o.tz).utc;
        if (end <= start) throw ParameterError(command + ": {end} " + o.endDate + " is not after {start} " + o.startDate);
        days.interval = std::pair(start, end);
        days.first = localDayOf(start, days.zone).date;
        days.last = localDayOf(end, days.zone).date;
    } else {
        days.first = parseDate(o.startDate);
        days.last = parseDate(o.endDate);
        if (days.last < days.first) throw ParameterError(command + ": {end} " + o.endDate + " is before {start} " + o.startDate);
    }
    return days;
}

ClearSkyRasters clearSkyRasters(const ClearSkyOptions& o) {
    return {o.linkeRaster, o.albedoRaster, o.coeffBhRaster, o.coeffDhRaster};
}

std::vector<double> parseLinkeOption(const std::string& text) {
    std::vector<double> values;
    std::stringstream ss(text);
    std::string part;
    while (std::getline(ss, part, ',')) {
        const std::optional<double> v = parseFiniteNumber(part, /*trailingSpaces=*/true);
        if (!v) throw ParameterError("{linke} '" + text + "': expected a number or 12 comma-separated monthly numbers like 3.1");
        values.push_back(*v);
    }
    if (values.empty()) throw ParameterError("{linke} '" + text + "': expected a number or 12 comma-separated monthly numbers");
    return values;
}

}  // namespace demlight
