// demlight sunpos --time T [--tz ZONE] --lat DEG --lon DEG [...] [--json]: where the sun is (NREL
// SPA, topocentric and refracted) and sunrise, transit and sunset of the local day.
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/run/sunpos_command.h"
#include "demlight/geo/solar_position.h"
#include "demlight/geo/time.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace demlight::cli {
namespace {

std::string fixed6(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6f", v);
    return buf;
}

void runSunpos(const SunposCommand& o) {
    const SunposReport r = sunposReport(o.values);
    if (o.json) {
        std::cout << sunposJson(r) << "\n";
        return;
    }
    const SolarPosition& p = r.position;
    const std::string none =
        r.polar ? std::string("none (polar ") + r.polar +
                      (std::string(r.polar) == "day" ? ": the sun stays up all day)" : ": the sun stays down all day)")
                : std::string("none");
    std::cout << "time (UTC)        " << formatInstant(r.when.utc, TimeZoneSpec{}) << "\n"
              << "time (local)      " << formatInstant(r.when.utc, r.when.zone) << "  [" << r.when.zone.describe()
              << "]\n"
              << "zenith            " << fixed6(p.zenithDeg) << " deg (topocentric, refracted)\n"
              << "elevation         " << fixed6(p.elevationDeg) << " deg (geometric " << fixed6(p.geometricElevationDeg)
              << ", refraction " << fixed6(p.refractionDeg) << ")\n"
              << "azimuth           " << fixed6(p.azimuthDeg) << " deg (clockwise from true north)\n"
              << "declination       " << fixed6(p.declinationDeg) << " deg\n"
              << "equation of time  " << fixed6(p.equationOfTimeMin) << " min\n"
              << "delta T           " << fixed6(p.deltaTSec) << " s (" << r.deltaTSource << ")\n"
              << "local day         " << formatDate(r.day.date) << "\n"
              << "sunrise           " << r.sunrise.value_or(none) << "\n"
              << "transit           " << r.transit << "\n"
              << "sunset            " << r.sunset.value_or(none) << "\n";
}

}  // namespace

void registerSunpos(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SunposCommand>();
    CLI::App* cmd = addDeclaredCommand(app, o->declaration(), ctx);
    cmd->callback([o] { runSunpos(*o); });
}

}  // namespace demlight::cli
