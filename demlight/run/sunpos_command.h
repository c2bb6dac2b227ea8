// The sunpos command for every front end: its declaration (time, place, atmosphere, delta T),
// and what it reports: the sun's position (NREL SPA, topocentric and refracted) and the
// sunrise, transit and sunset of the local day.
#pragma once

#include "demlight/geo/solar_position.h"
#include "demlight/geo/time.h"
#include "demlight/run/parameters.h"

#include <optional>
#include <string>

namespace demlight {

struct SunposParameters {
    std::string time, tz;
    SolarSite site;
    std::optional<double> deltaTSec;
};

/// What sunpos reports for its parameters.
struct SunposReport {
    ZonedInstant when;
    SolarSite site;
    SolarPosition position;
    LocalDay day;
    std::optional<std::string> sunrise, sunset;  ///< on the zone's clocks, whole seconds
    std::string transit;
    const char* polar = nullptr;  ///< "day", "night", or null
    const char* deltaTSource = "";
};
SunposReport sunposReport(const SunposParameters& p);
/// The report as one JSON object (docs/commands.md, sunpos --json).
std::string sunposJson(const SunposReport& r);

/// The sunpos command's declaration and the values set through it.
class SunposCommand {
public:
    SunposCommand();
    SunposCommand(const SunposCommand&) = delete;
    SunposCommand& operator=(const SunposCommand&) = delete;
    ParameterSet& declaration() { return set_; }
    const ParameterSet& declaration() const { return set_; }

    SunposParameters values;
    bool json = false;  ///< the command line's --json

private:
    ParameterSet set_;
};

}  // namespace demlight
