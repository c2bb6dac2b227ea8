#include "demlight/run/sunpos_command.h"

#include "demlight/run/common_parameters.h"

#include <nlohmann/json.hpp>

#include <chrono>

namespace demlight {

namespace {

/// SPA's stated input limits (Reda & Andreas, Table 1) where tighter than physics.
constexpr double kMaxAbsDeltaTSec = 8000;

/// Event instants are good to about a second (SPA A.2); show whole seconds.
UtcInstant wholeSecond(UtcInstant t) { return std::chrono::round<std::chrono::seconds>(t); }

const char* polarName(DayKind k) {
    switch (k) {
    case DayKind::PolarDay: return "day";
    case DayKind::PolarNight: return "night";
    case DayKind::Normal: break;
    }
    return nullptr;
}

}  // namespace

SunposCommand::SunposCommand()
    : set_("sunpos", "Sun position (NREL SPA) and sunrise/transit/sunset for a time and place") {
    declareTime(set_, values.time, values.tz);
    set_.add("lat", values.site.latitudeDeg, "Latitude (deg)", "Latitude (degrees, north positive)")
        .type("DEG")
        .within(-90, 90)
        .inUnit("deg")
        .noDefault()
        .mandatory();
    set_.add("lon", values.site.longitudeDeg, "Longitude (deg)", "Longitude (degrees, east positive)")
        .type("DEG")
        .within(-180, 180)
        .inUnit("deg")
        .noDefault()
        .mandatory();
    set_.add("elevation", values.site.elevationM, "Height above sea level (m)", "Observer height above sea level (m)")
        .within(-1000, 100000)
        .inUnit("m");
    set_.add("pressure", values.site.pressureHpa, "Air pressure (hPa)", "Mean air pressure for refraction (hPa)")
        .within(0, kMaxPressureHpa)
        .inUnit("hPa");
    set_.add("temperature", values.site.temperatureC, "Air temperature (C)",
             "Mean air temperature for refraction (degrees C)")
        .within(-100, 100)
        .inUnit("C");
    set_.add("delta_t", values.deltaTSec, "TT - UT (s)", "TT - UT (s); default: Espenak-Meeus estimate for the date")
        .within(-kMaxAbsDeltaTSec, kMaxAbsDeltaTSec)
        .inUnit("s");
    set_.add("json", json, "JSON", "Print one JSON object").only(kCommandLine);
}

SunposReport sunposReport(const SunposParameters& p) {
    SunposReport r;
    r.when = parseZonedInstant(p.time, p.tz);
    r.site = p.site;
    SpaOptions spa;
    spa.deltaTSec = p.deltaTSec;
    r.position = solarPosition(p.site, r.when.utc, spa);
    // Events of the local day in the input's zone (its offset's day for an offset-only time).
    r.day = localDayOf(r.when.utc, r.when.zone);
    const SunEvents ev = sunEvents(p.site, r.day.startUtc, spa);
    const auto eventText = [&](const std::optional<UtcInstant>& t) -> std::optional<std::string> {
        if (!t) return std::nullopt;
        return formatInstant(wholeSecond(*t), r.when.zone);
    };
    r.sunrise = eventText(ev.sunrise);
    r.sunset = eventText(ev.sunset);
    r.transit = formatInstant(wholeSecond(ev.transit), r.when.zone);
    r.polar = polarName(ev.kind);
    r.deltaTSource = p.deltaTSec ? "given" : "Espenak-Meeus 2006 estimate";
    return r;
}

std::string sunposJson(const SunposReport& r) {
    const SolarPosition& p = r.position;
    nlohmann::ordered_json j;
    j["utc"] = formatInstant(r.when.utc, TimeZoneSpec{});
    j["local"] = formatInstant(r.when.utc, r.when.zone);
    j["zone"] = r.when.zone.describe();
    j["latitude_deg"] = r.site.latitudeDeg;
    j["longitude_deg"] = r.site.longitudeDeg;
    j["elevation_m"] = r.site.elevationM;
    j["pressure_hpa"] = r.site.pressureHpa;
    j["temperature_c"] = r.site.temperatureC;
    j["zenith_deg"] = p.zenithDeg;
    j["elevation_deg"] = p.elevationDeg;
    j["azimuth_deg"] = p.azimuthDeg;
    j["geometric_elevation_deg"] = p.geometricElevationDeg;
    j["refraction_deg"] = p.refractionDeg;
    j["declination_deg"] = p.declinationDeg;
    j["equation_of_time_min"] = p.equationOfTimeMin;
    j["delta_t_s"] = p.deltaTSec;
    j["delta_t_source"] = r.deltaTSource;
    j["day"] = formatDate(r.day.date);
    j["sunrise"] = r.sunrise ? nlohmann::ordered_json(*r.sunrise) : nlohmann::ordered_json(nullptr);
    j["transit"] = r.transit;
    j["sunset"] = r.sunset ? nlohmann::ordered_json(*r.sunset) : nlohmann::ordered_json(nullptr);
    j["polar"] = r.polar ? nlohmann::ordered_json(r.polar) : nlohmann::ordered_json(nullptr);
    return j.dump(2);
}

}  // namespace demlight
