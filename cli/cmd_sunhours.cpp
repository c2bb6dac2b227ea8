// demlight sunhours DEM -o OUT.tif (--date D | --start D --end D) [--tz ZONE] [--step MIN]:
// hours of direct sun, sun and sky irradiation and the cell's own sunrise/sunset over local days.
// The sky term f_sky = K / (1 - C(1 - K)) is computed once from the plan's direction sweeps and
// integrated over the cell's daylight hours (lighting/sunhours.h skyIrradiation).
//
// Instants every --step minutes from local midnight of the first day to local midnight after
// the last (inclusive), integrated with the trapezoid rule (lighting/sunhours.h). The default
// step of 10 min was measured against a 1-minute integral (README, `sunhours`). The sun lattice
// and, with --quality full, the search distance come from the scene plan (lighting/quality.h).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/sun_field.h"
#include "geo/time.h"
#include "lighting/directions.h"
#include "lighting/sky.h"
#include "lighting/sunhours.h"
#include "src/error.h"

#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

namespace demlight::cli {
namespace {

/// Default integration step (minutes): trapezoid error of sun hours ≤ ~0.3 % of a day's total
/// on the samples (README).
constexpr double kDefaultStepMin = 10.0;
/// first_lit / last_lit of a valid cell the sun never reaches (hours; no clock time is negative).
constexpr float kNeverLitClock = -1.0f;

struct SunhoursOptions {
    std::string demPath;
    OutputOptions out;
    SearchOptions search;
    std::string date, startDate, endDate;
    std::string tz;
    double stepMin = kDefaultStepMin;
    double sunDiameterDeg = kSunDiameterDeg;
    double albedo = 0.2;  ///< C of the sky term's interreflection
    std::optional<int> skyDirections;  ///< default: the scene plan's
};

struct Sequence {
    std::vector<SunInstant> instants;
    std::vector<UtcInstant> utc;
};

/// Instants every stepMin from the start of the first local day to the end of the last one.
Sequence makeSequence(const LocalDay& first, const LocalDay& last, const TimeZoneSpec& zone,
                      double stepMin) {
    using namespace std::chrono;
    const milliseconds step(static_cast<long long>(std::llround(stepMin * 60000.0)));
    Sequence s;
    auto add = [&](UtcInstant t, bool isEnd) {
        // Clock time within the local day the instant belongs to (24.0 for the final midnight).
        const LocalDay d = localDayOf(isEnd ? t - milliseconds(1) : t, zone);
        const auto local = t + zone.offsetAt(t);
        const double clock =
            duration<double, std::ratio<3600>>(local - UtcInstant(d.date)).count();
        const double hours = duration<double, std::ratio<3600>>(t - first.startUtc).count();
        s.utc.push_back(t);
        s.instants.push_back({hours, clock});
    };
    for (UtcInstant t = first.startUtc; t < last.endUtc; t += step) add(t, false);
    add(last.endUtc, true);
    return s;
}

void runSunhours(const SunhoursOptions& o, const CliContext& ctx) {
    const TimeZoneSpec zone = TimeZoneSpec::fromName(o.tz);
    std::chrono::sys_days d0, d1;
    if (!o.date.empty()) {
        if (!o.startDate.empty() || !o.endDate.empty())
            throw Error("sunhours: give either --date or --start/--end, not both");
        d0 = d1 = parseDate(o.date);
    } else {
        if (o.startDate.empty() || o.endDate.empty())
            throw Error("sunhours: give --date D, or both --start D and --end D");
        d0 = parseDate(o.startDate);
        d1 = parseDate(o.endDate);
        if (d1 < d0) throw Error("sunhours: --end " + o.endDate + " is before --start " + o.startDate);
    }
    checkOutputPath(o.out.path, o.demPath);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;
    const Sequence seq = makeSequence(localDay(d0, zone), localDay(d1, zone), zone, o.stepMin);

    const ScenePlan plan = planFor(o.search, t, kDefaultLowestElevationDeg, ctx);
    SunHoursParams params;
    // auto: each instant's sun sets its own distance (sunSearchDistanceM); full: the DEM diagonal.
    params.frame = sunFrameParams(o.search, o.sunDiameterDeg, plan);
    const SolarSite site;  // default pressure and temperature; position from each lattice node

    const auto start = std::chrono::steady_clock::now();
    const Normals normals = computeNormals(t, o.search.threads);
    ProgressBar bar(!ctx.quiet);

    // Sky term once: it does not depend on the sun's position.
    const auto skyDirections = static_cast<std::size_t>(o.skyDirections.value_or(plan.skyDirections));
    const HorizonParams hp = integralParams(o.search, plan, t, skyDirections);
    SkyAccumulator skyAcc(normals.east, normals.north, normals.up, skyDirections, SkyPatches{}, o.search.threads);
    ProgressCounter skyCounter(bar.callback(), "sky", t.heightsM.size() * skyDirections);
    sweepDirections(t, hp, skyDirections,
                    [&](std::size_t i, const HorizonMap& h) { skyAcc.addDirection(i, h.angleDeg); }, &skyCounter);
    const Grid<float> skyFactor = std::move(skyAcc).finish(o.albedo).skyFactor;

    ProgressCounter counter(bar.callback(), "sunhours", seq.instants.size());
    SunHoursMaps maps = integrateSunHours(
        t, normals, seq.instants,
        [&](std::size_t i) {
            return computeSunField(dem, seq.utc[i], site, SpaOptions{}, plan.sunLatticeStepCells);
        },
        params, &counter);
    // Daylight from the sun's geometric elevation (no refraction: pressure 0), SPA's sunrise/sunset.
    SolarSite geometric = site;
    geometric.pressureHpa = 0;
    const Grid<float> daylight = integrateDaylight(
        t, seq.instants,
        [&](std::size_t i) {
            return computeSunField(dem, seq.utc[i], geometric, SpaOptions{}, plan.sunLatticeStepCells);
        },
        o.search.threads);
    const Grid<float> skyIrr = skyIrradiation(skyFactor, daylight);
    bar.finish();
    const double seconds = secondsSince(start);

    // Never lit: -1, not NaN, which the writer turns into the DEM's nodata value (a void).
    for (Grid<float>* clock : {&maps.firstLitClock, &maps.lastLitClock}) {
        const float* h = dem.terrain.heightsM.data();
        float* v = clock->data();
        for (std::size_t i = 0; i < clock->size(); ++i)
            if (std::isnan(v[i]) && !std::isnan(h[i])) v[i] = kNeverLitClock;
    }
    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_PRODUCT", "sunhours"},
        {"DEMLIGHT_NEVER_LIT", formatNumber(kNeverLitClock) + " in first_lit and last_lit"},
        {"DEMLIGHT_FIRST_DATE", formatDate(d0)},
        {"DEMLIGHT_LAST_DATE", formatDate(d1)},
        {"DEMLIGHT_TIME_ZONE", zone.describe()},
        {"DEMLIGHT_START_UTC", formatInstant(seq.utc.front(), std::string())},
        {"DEMLIGHT_END_UTC", formatInstant(seq.utc.back(), std::string())},
        {"DEMLIGHT_STEP_MIN", formatNumber(o.stepMin)},
        {"DEMLIGHT_INTEGRATION", "trapezoid"},
        {"DEMLIGHT_INSTANTS", std::to_string(seq.instants.size())},
        {"DEMLIGHT_INSTANTS_SWEPT", std::to_string(maps.instantsSwept)},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(o.sunDiameterDeg)},
        {"DEMLIGHT_LIT_VISIBILITY", formatNumber(kLitVisibility)},
        {"DEMLIGHT_METHOD", "sweep"},
        {"DEMLIGHT_REFRACTION", formatNumber(params.frame.refraction)},
        {"DEMLIGHT_SKY_MODEL", "stewart-langer"},
        {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(skyDirections)},
        {"DEMLIGHT_SKY_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, hp.maxDistanceM)},
        {"DEMLIGHT_ALBEDO", formatNumber(o.albedo)},
        {"DEMLIGHT_DAYLIGHT", "SPA sunrise to sunset at the cell, no terrain (geometric elevation of the "
                              "sun's centre > " + formatNumber(kSunriseGeometricElevationDeg) + " deg)"},
    });
    writeRaster(o.out.path,
                {{&maps.sunHours, nullptr, "sun_hours", "hours of direct sun weighted by visibility (h)"},
                 {&maps.sunIrradiation, nullptr, "sun_irradiation",
                  "normalised irradiance x hours (1 h of unit zenith sun on flat ground = 1)"},
                 {&skyIrr, nullptr, "sky_irradiation",
                  "f_sky x daylight hours: a unit uniform sky from sunrise to sunset at the cell "
                  "(1 h of unit sky on open flat ground = 1)"},
                 {&maps.firstLitClock, nullptr, "first_lit",
                  "local clock hours (" + zone.describe() + ") when half the sun first shows; -1 = never"},
                 {&maps.lastLitClock, nullptr, "last_lit",
                  "local clock hours (" + zone.describe() + ") when half the sun last shows; -1 = never"}},
                dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    note(ctx, "wrote " + o.out.path + " (sun_hours, sun_irradiation, sky_irradiation, first_lit, last_lit): " +
                  std::to_string(seq.instants.size()) + " instants every " +
                  formatNumber(o.stepMin) + " min, " + std::to_string(maps.instantsSwept) +
                  " with the sun up, " + formatSeconds(seconds) + " compute");
}

}  // namespace

void registerSunhours(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SunhoursOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sunhours", "Hours of direct sun, sun and sky irradiation and first/last lit time over local days");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--date", o->date, "Local day YYYY-MM-DD (midnight to midnight in --tz)");
    cmd->add_option("--start", o->startDate, "First local day YYYY-MM-DD of a range");
    cmd->add_option("--end", o->endDate, "Last local day YYYY-MM-DD of a range (inclusive)");
    cmd->add_option("--tz", o->tz, "IANA time zone of the days and clock times (default UTC)");
    cmd->add_option("--step", o->stepMin, "Integration step (minutes, trapezoid rule)")
        ->check(finiteRange(0.1, 120.0))
        ->capture_default_str();
    cmd->add_option("--sun-diameter", o->sunDiameterDeg,
                    "Angular diameter of the sun disk (degrees)")
        ->check(finiteRange(0.0, 20.0))
        ->capture_default_str();
    cmd->add_option("--albedo", o->albedo,
                    "Ground albedo C of the sky term f_sky = K / (1 - C(1 - K)) (0-1)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions of the sky term (default: 16 with --quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runSunhours(*o, ctx); });
}

}  // namespace demlight::cli
