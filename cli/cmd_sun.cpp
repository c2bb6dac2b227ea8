// demlight sun DEM -o OUT.tif --time T [--tz ZONE]: how much of the sun's disk each cell sees.
//
// Sun position per region: SPA on a lattice every 64 cells (geo/sun_field.h), interpolated per
// cell. --model horizon (default): one sweep whose regions follow the sun's azimuth across the
// DEM (lighting/sun_frame.h). --model aperture / aperture-smooth: the ambient aperture of every cell
// from --directions sweeps, then the sun cap intersected with it per cell
// (lighting/lighting_models.h applyApertureSun).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/sun_field.h"
#include "geo/time.h"
#include "lighting/aperture.h"
#include "lighting/directions.h"
#include "lighting/lighting_models.h"
#include "lighting/sun_frame.h"
#include "src/angles.h"
#include "src/error.h"

#include <chrono>
#include <optional>
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
    std::string model = "horizon";
    std::optional<int> directions;  ///< aperture models; default: the scene plan's
};

/// The two output bands and how they were made, for either model.
struct SunBands {
    Grid<float> visibility, irradiance;
    double maxDistanceM = 0;
    std::string sweeps;          ///< what the closing note says about the sweeps
    std::size_t sunRegions = 0;  ///< horizon model: regions of the sun sweep (0 = sun down everywhere)
    std::string strategy;        ///< horizon model: the sun sweep's strategy (computeSunFrame)
};

SunBands horizonSun(const Terrain& t, const Normals& normals, const SunField& field,
                    const SunOptions& o, const ScenePlan& plan, ProgressCounter& counter) {
    // auto: the distance this sun needs (sunSearchDistanceM); full: the plan's DEM diagonal.
    const SunFrameParams params = sunFrameParams(o.search, o.sunDiameterDeg, plan);
    SunFrame frame = computeSunFrame(t, normals, field, params, &counter);
    return {std::move(frame.light.visibility), std::move(frame.light.irradiance), frame.maxDistanceM,
            std::to_string(frame.sweepRegions) + " sweep region(s), " + sunSweepStrategyName(frame.strategy) +
                " strategy",
            frame.sweepRegions, sunSweepStrategyName(frame.strategy)};
}

SunBands apertureSun(const Terrain& t, const Normals& normals, const SunField& field,
                     const SunOptions& o, const ScenePlan& plan, std::size_t d, bool smooth,
                     ProgressCounter& counter) {
    // The aperture does not depend on the sun: search distance and directions are the sky's.
    const HorizonParams hp = integralParams(o.search, plan, t, d);
    ApertureAccumulator acc(normals.east, normals.north, normals.up, d, o.search.threads);
    sweepDirections(t, hp, d, [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); },
                    &counter);
    ApertureLightParams lp;
    lp.sunRadiusDeg = 0.5 * o.sunDiameterDeg;
    lp.smoothIntersection = smooth;
    ApertureSunMaps m = applyApertureSun(acc.finish(), normals.east, normals.north, normals.up, field, lp,
                                         o.search.threads);
    return {std::move(m.visibility), std::move(m.irradiance), hp.maxDistanceM,
            std::to_string(d) + " aperture directions", 0, std::string()};
}

void runSun(const SunOptions& o, const CliContext& ctx) {
    const ZonedInstant when = parseZonedInstant(o.time, o.tz);
    const LightingModel model = parseLightingModel(o.model);
    if (model == LightingModel::Hemisphere)
        throw Error("--model hemisphere is a sky-only model (no sun term); use 'demlight sky "
                    "--model hemisphere', or --model horizon, aperture or aperture-smooth");
    const bool horizon = model == LightingModel::Horizon;
    if (horizon && o.directions)
        note(ctx, "note: --directions is used by the aperture models only; --model horizon sweeps the sun's azimuth");
    checkOutputPath(o.out.path, o.demPath);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;

    SolarSite site;
    site.pressureHpa = o.pressureHpa;
    site.temperatureC = o.temperatureC;
    const ScenePlan plan = planFor(o.search, t, kDefaultLowestElevationDeg, ctx);
    const SunField field = computeSunField(dem, when.utc, site, SpaOptions{}, plan.sunLatticeStepCells);
    const auto [lowestSun, highestSun] = field.elevationRange();

    const auto start = std::chrono::steady_clock::now();
    const Normals normals = computeNormals(t, o.search.threads);
    ProgressBar bar(!ctx.quiet);
    const auto directions = static_cast<std::size_t>(o.directions.value_or(plan.skyDirections));
    const std::size_t work = t.heightsM.size() * (horizon ? 1 : directions);
    ProgressCounter counter(bar.callback(), "sun", work);
    const SunBands out = horizon ? horizonSun(t, normals, field, o, plan, counter)
                                 : apertureSun(t, normals, field, o, plan, directions,
                                               model == LightingModel::ApertureSmooth, counter);
    bar.finish();
    const double seconds = secondsSince(start);
    const bool sunUp = horizon ? out.sunRegions > 0 : highestSun > -0.5 * o.sunDiameterDeg;

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_PRODUCT", "sun"},
        {"DEMLIGHT_TIME_UTC", formatInstant(when.utc, std::string())},
        {"DEMLIGHT_TIME_LOCAL", formatInstant(when.utc, when.zone)},
        {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
        {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
        {"DEMLIGHT_SUN_ELEVATION_RANGE_DEG", formatNumber(lowestSun) + "," + formatNumber(highestSun)},
        {"DEMLIGHT_SUN_SWEEP_REGIONS", std::to_string(out.sunRegions)},
        {"DEMLIGHT_SUN_SWEEP_STRATEGY", out.strategy},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(o.sunDiameterDeg)},
        {"DEMLIGHT_MODEL", std::string(lightingModelName(model))},
        {"DEMLIGHT_METHOD", "sweep"},
        {"DEMLIGHT_DIRECTIONS", horizon ? std::string() : std::to_string(directions)},
        {"DEMLIGHT_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, out.maxDistanceM)},
        {"DEMLIGHT_REFRACTION", formatNumber(o.search.refraction)},
    });
    writeRaster(o.out.path,
                {{&out.visibility, nullptr, "sun_visibility",
                  horizon ? "fraction of sun disk (0-1)"
                          : "fraction of the sun cap inside the aperture cap (0-1)"},
                 {&out.irradiance, nullptr, "sun_irradiance",
                  horizon ? "normalised irradiance (1 = unit-radiance zenith sun on flat ground)"
                          : "normalised irradiance, Lambert integral over the sun cap inside the "
                            "aperture cap (1 = unit-radiance zenith sun on flat ground)"}},
                dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(field.centreAzimuthDeg) +
                  " deg, elevation " + formatNumber(field.centreElevationDeg) + " deg (" +
                  formatInstant(when.utc, std::string()) + ")" +
                  (sunUp ? "" : "; the sun is below the horizon: everything is in shadow"));
    note(ctx, "wrote " + o.out.path + " (band 1 sun_visibility, band 2 sun_irradiance); model " +
                  std::string(lightingModelName(model)) + ", " + out.sweeps + ", max distance " +
                  formatDistance(out.maxDistanceM) + ", " + formatSeconds(seconds) +
                  " compute");
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
        ->check(finiteRange(0.0, 20.0))
        ->capture_default_str();
    cmd->add_option("--pressure", o->pressureHpa, "Air pressure for solar refraction (hPa)")
        ->check(finiteRange(0, kMaxPressureHpa))
        ->capture_default_str();
    cmd->add_option("--temperature", o->temperatureC, "Air temperature for solar refraction (C)")
        ->check(finiteRange(-100, 100))
        ->capture_default_str();
    cmd->add_option("--model", o->model,
                    "Sun model: horizon (horizon angle in the sun's azimuth), aperture (sun cap "
                    "intersected with the ambient-aperture cap), aperture-smooth (the same with "
                    "the smoothstep intersection)")
        ->capture_default_str();
    cmd->add_option("--directions", o->directions,
                    "Aperture models: number of horizon directions integrated into the aperture "
                    "(default: 16 with --quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runSun(*o, ctx); });
}

}  // namespace demlight::cli
