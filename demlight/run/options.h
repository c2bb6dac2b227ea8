// Parameter values a front end passes as text (times, days, durations, colours, Linke factors)
// parsed into what the product requests take, and the parameter groups several commands share.
#pragma once

#include "demlight/geo/time.h"
#include "demlight/lighting/irradiance.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/sky.h"

#include <array>
#include <chrono>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace demlight {

/// `text` as one finite number (trailing spaces allowed when `trailingSpaces`); nullopt when it
/// is not exactly that. The parameter parsers' number rule.
std::optional<double> parseFiniteNumber(const std::string& text, bool trailingSpaces = false);

/// "R,G,B" linear, each >= 0; throws FieldError naming `field`.
std::array<double, 3> parseColor(const std::string& text, const std::string& field);

/// A duration (the step of a period): 10m, 1h30m, 90s; a bare number counts `bareUnit`s.
std::chrono::milliseconds parseStepOption(const std::string& text, std::chrono::milliseconds bareUnit);

/// An instant: parseZonedInstant (its messages name the time zone parameter as {tz}).
ZonedInstant parseTimeOptions(const std::string& time, const std::string& tz);

/// The local days of a period: one date, a start and an end date, and with periods also a
/// month, a year, or a start and an end local time (an interval within days); tz their zone.
struct DayOptions {
    std::string date, startDate, endDate, month, year, tz;
    bool periods = false;  ///< month, year and local times in start/end are offered
};
/// The local days (inclusive) of the options.
struct LocalDays {
    std::chrono::sys_days first, last;
    TimeZoneSpec zone;
    /// start/end given as local times: the interval itself (first and last are its days).
    std::optional<std::pair<UtcInstant, UtcInstant>> interval;
};
/// `command` names the command in errors.
LocalDays parseDayOptions(const DayOptions& o, const std::string& command);

/// The clear-sky parameters of irradiance and insolation (demlight/products/irradiance.h).
struct ClearSkyOptions {
    std::string linke = formatNumber(kDefaultLinke);
    double albedo = kDefaultAlbedo;
    double coeffBh = 1, coeffDh = 1;
    std::vector<std::string> linkeRaster;  ///< one path, or twelve (one per use)
    std::string albedoRaster, coeffBhRaster, coeffDhRaster;
    std::string diffuseModel = "visible-sky";
    double solarConstantWm2 = kSolarConstantWm2;
};

/// The rasters of the clear-sky parameters as the requests take them.
ClearSkyRasters clearSkyRasters(const ClearSkyOptions& o);

/// A Linke factor: "3.2" or 12 comma-separated numbers (the product checks the count and range).
std::vector<double> parseLinkeOption(const std::string& text);

}  // namespace demlight
