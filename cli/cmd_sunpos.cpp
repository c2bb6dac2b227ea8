// demlight sunpos --time T [--tz ZONE] --lat DEG --lon DEG [...] [--json]: where the sun is (NREL
// SPA, topocentric and refracted) and sunrise, transit and sunset of the local day.
#include "cli/commands.h"
#include "cli/common.h"
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

/// SPA's stated input limits (Reda & Andreas, Table 1) where tighter than physics.
constexpr double kMaxAbsDeltaTSec = 8000;

struct SunposOptions {
    std::string time;
    std::string tz;
    SolarSite site;
    std::optional<double> deltaTSec;
    bool json = false;
};

std::string fixed6(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6f", v);
    return buf;
}

/// Event instants are good to about a second (SPA A.2); show whole seconds.
UtcInstant wholeSecond(UtcInstant t) {
    return std::chrono::round<std::chrono::seconds>(t);
}

const char* polarName(DayKind k) {
    switch (k) {
    case DayKind::PolarDay: return "day";
    case DayKind::PolarNight: return "night";
    case DayKind::Normal: break;
    }
    return nullptr;
}

void runSunpos(const SunposOptions& o) {
    const ZonedInstant when = parseZonedInstant(o.time, o.tz);
    SpaOptions spa;
    spa.deltaTSec = o.deltaTSec;
    const SolarPosition p = solarPosition(o.site, when.utc, spa);
    // Events of the local day in the input's zone (its offset's day for an offset-only time).
    const LocalDay day = localDayOf(when.utc, when.zone);
    const SunEvents ev = sunEvents(o.site, day.startUtc, spa);

    const auto eventText = [&](const std::optional<UtcInstant>& t) -> std::optional<std::string> {
        if (!t) return std::nullopt;
        return formatInstant(wholeSecond(*t), when.zone);
    };
    const auto sunrise = eventText(ev.sunrise), sunset = eventText(ev.sunset);
    const std::string transit = formatInstant(wholeSecond(ev.transit), when.zone);
    const char* polar = polarName(ev.kind);
    const char* deltaTSource = o.deltaTSec ? "given" : "Espenak-Meeus 2006 estimate";

    if (o.json) {
        nlohmann::ordered_json j;
        j["utc"] = formatInstant(when.utc, TimeZoneSpec{});
        j["local"] = formatInstant(when.utc, when.zone);
        j["zone"] = when.zone.describe();
        j["latitude_deg"] = o.site.latitudeDeg;
        j["longitude_deg"] = o.site.longitudeDeg;
        j["elevation_m"] = o.site.elevationM;
        j["pressure_hpa"] = o.site.pressureHpa;
        j["temperature_c"] = o.site.temperatureC;
        j["zenith_deg"] = p.zenithDeg;
        j["elevation_deg"] = p.elevationDeg;
        j["azimuth_deg"] = p.azimuthDeg;
        j["geometric_elevation_deg"] = p.geometricElevationDeg;
        j["refraction_deg"] = p.refractionDeg;
        j["declination_deg"] = p.declinationDeg;
        j["equation_of_time_min"] = p.equationOfTimeMin;
        j["delta_t_s"] = p.deltaTSec;
        j["delta_t_source"] = deltaTSource;
        j["day"] = formatDate(day.date);
        j["sunrise"] = sunrise ? nlohmann::ordered_json(*sunrise) : nlohmann::ordered_json(nullptr);
        j["transit"] = transit;
        j["sunset"] = sunset ? nlohmann::ordered_json(*sunset) : nlohmann::ordered_json(nullptr);
        j["polar"] = polar ? nlohmann::ordered_json(polar) : nlohmann::ordered_json(nullptr);
        std::cout << j.dump(2) << "\n";
        return;
    }

    const std::string none =
        polar ? std::string("none (polar ") + polar +
                    (ev.kind == DayKind::PolarDay ? ": the sun stays up all day)"
                                                  : ": the sun stays down all day)")
              : std::string("none");
    std::cout << "time (UTC)        " << formatInstant(when.utc, TimeZoneSpec{}) << "\n"
              << "time (local)      " << formatInstant(when.utc, when.zone) << "  ["
              << when.zone.describe() << "]\n"
              << "zenith            " << fixed6(p.zenithDeg) << " deg (topocentric, refracted)\n"
              << "elevation         " << fixed6(p.elevationDeg) << " deg (geometric "
              << fixed6(p.geometricElevationDeg) << ", refraction " << fixed6(p.refractionDeg)
              << ")\n"
              << "azimuth           " << fixed6(p.azimuthDeg)
              << " deg (clockwise from true north)\n"
              << "declination       " << fixed6(p.declinationDeg) << " deg\n"
              << "equation of time  " << fixed6(p.equationOfTimeMin) << " min\n"
              << "delta T           " << fixed6(p.deltaTSec) << " s (" << deltaTSource << ")\n"
              << "local day         " << formatDate(day.date) << "\n"
              << "sunrise           " << sunrise.value_or(none) << "\n"
              << "transit           " << transit << "\n"
              << "sunset            " << sunset.value_or(none) << "\n";
}

}  // namespace

void registerSunpos(CLI::App& app, CliContext& /*ctx*/) {
    auto o = std::make_shared<SunposOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sunpos", "Sun position (NREL SPA) and sunrise/transit/sunset for a time and place");
    cmd->add_option("--time", o->time,
                    "Instant: ISO 8601 with offset or Z (2024-06-21T05:30:00+02:00), or local "
                    "time with --tz")
        ->required()
        ->type_name("TIME");
    cmd->add_option("--tz", o->tz, "IANA time zone for a local --time (e.g. Europe/Zurich)");
    cmd->add_option("--lat", o->site.latitudeDeg, "Latitude (degrees, north positive)")
        ->required()
        ->type_name("DEG")
        ->check(finiteRange(-90, 90));
    cmd->add_option("--lon", o->site.longitudeDeg, "Longitude (degrees, east positive)")
        ->required()
        ->type_name("DEG")
        ->check(finiteRange(-180, 180));
    cmd->add_option("--elevation", o->site.elevationM, "Observer height above sea level (m)")
        ->check(finiteRange(-1000, 100000))
        ->capture_default_str();
    cmd->add_option("--pressure", o->site.pressureHpa, "Mean air pressure for refraction (hPa)")
        ->check(finiteRange(0, kMaxPressureHpa))
        ->capture_default_str();
    cmd->add_option("--temperature", o->site.temperatureC,
                    "Mean air temperature for refraction (degrees C)")
        ->check(finiteRange(-100, 100))
        ->capture_default_str();
    cmd->add_option("--delta-t", o->deltaTSec,
                    "TT - UT (s); default: Espenak-Meeus estimate for the date")
        ->check(finiteRange(-kMaxAbsDeltaTSec, kMaxAbsDeltaTSec));
    cmd->add_flag("--json", o->json, "Print one JSON object");
    cmd->callback([o] { runSunpos(*o); });
}

}  // namespace demlight::cli
