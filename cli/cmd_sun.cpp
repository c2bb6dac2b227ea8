// demlight sun DEM -o OUT.tif --time T [--tz ZONE]: how much of the sun's disk each cell sees.
//
// Sun position per region: SPA on a lattice every 64 cells (geo/sun_field.h), interpolated per
// cell; tiles swept along their own sun azimuth (lighting/sun_frame.h).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/sun_field.h"
#include "geo/time.h"
#include "lighting/sun_frame.h"
#include "src/angles.h"
#include "src/error.h"

#include <chrono>
#include <cmath>

namespace demlight::cli {
namespace {

struct SunOptions {
    std::string demPath;
    OutputOptions out;
    SearchOptions search;
    std::string time;
    std::string tz;
    double sunDiameterDeg = kSunDiameterDeg;
    double pressureHpa = 1013.25;
    double temperatureC = 15;
};

void runSun(const SunOptions& o, const CliContext& ctx) {
    const ZonedInstant when = parseZonedInstant(o.time, o.tz);
    checkOutputPath(o.out.path, o.demPath);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;

    SolarSite site;
    site.pressureHpa = o.pressureHpa;
    site.temperatureC = o.temperatureC;
    const SunField field = computeSunField(dem, when.utc, site, SpaOptions{});
    const auto [lowestSun, highestSun] = field.elevationRange();

    SunFrameParams params;
    params.sunDiameterDeg = o.sunDiameterDeg;
    params.refraction = o.search.refraction;
    params.threads = o.search.threads;
    params.maxDistanceM = o.search.maxDistanceM.value_or(0.0);

    const auto start = std::chrono::steady_clock::now();
    const Normals normals = computeNormals(t, o.search.threads);
    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), "sun", t.heightsM.size());
    const SunFrame frame = computeSunFrame(t, normals, field, params, &counter);
    bar.finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const bool sunUp = !frame.tiles.empty();

    const std::map<std::string, std::string> meta = {
        {"DEMLIGHT_PRODUCT", "sun"},
        {"DEMLIGHT_TIME_UTC", formatInstant(when.utc, std::string())},
        {"DEMLIGHT_TIME_LOCAL", formatInstant(when.utc, when.zone)},
        {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
        {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
        {"DEMLIGHT_SUN_ELEVATION_RANGE_DEG", formatNumber(lowestSun) + "," + formatNumber(highestSun)},
        {"DEMLIGHT_SUN_REGIONS", std::to_string(frame.tiles.size())},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(o.sunDiameterDeg)},
        {"DEMLIGHT_METHOD", "sweep"},
        {"DEMLIGHT_MAX_DISTANCE_M", formatNumber(frame.maxDistanceM)},
        {"DEMLIGHT_REFRACTION", formatNumber(params.refraction)},
    };
    writeRaster(o.out.path,
                {{&frame.light.visibility, nullptr, "sun_visibility", "fraction of sun disk (0-1)"},
                 {&frame.light.irradiance, nullptr, "sun_irradiance",
                  "normalised irradiance (1 = unit-radiance zenith sun on flat ground)"}},
                dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(field.centreAzimuthDeg) +
                  " deg, elevation " + formatNumber(field.centreElevationDeg) + " deg (" +
                  formatInstant(when.utc, std::string()) + ")" +
                  (sunUp ? "" : "; the sun is below the horizon: everything is in shadow"));
    note(ctx, "wrote " + o.out.path + " (band 1 sun_visibility, band 2 sun_irradiance); " +
                  std::to_string(frame.tiles.size()) + " sun region(s), max distance " +
                  formatNumber(std::round(frame.maxDistanceM)) + " m, " + formatNumber(seconds) +
                  " s compute");
}

}  // namespace

void registerSun(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SunOptions>();
    CLI::App* cmd = app.add_subcommand("sun", "Sun visibility and direct-sun irradiance at one instant");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--time", o->time,
                    "Instant: ISO 8601 with offset or Z (2024-06-21T05:30:00+02:00), or local "
                    "time with --tz")
        ->required();
    cmd->add_option("--tz", o->tz, "IANA time zone for a local --time (e.g. Europe/Zurich)");
    cmd->add_option("--sun-diameter", o->sunDiameterDeg,
                    "Angular diameter of the sun disk (degrees); larger = softer shadows")
        ->check(CLI::Range(0.0, 20.0))
        ->capture_default_str();
    cmd->add_option("--pressure", o->pressureHpa, "Air pressure for solar refraction (hPa)")
        ->check(CLI::Range(0.0, 1200.0))
        ->capture_default_str();
    cmd->add_option("--temperature", o->temperatureC, "Air temperature for solar refraction (C)")
        ->check(CLI::Range(-100.0, 60.0))
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runSun(*o, ctx); });
}

}  // namespace demlight::cli
