// demlight light DEM -o OUT.tif --time T [--tz ZONE]: the combined lightmap, sun + sky, Float32
// linear (Hoffman & Mitchell: lightmap = sun term + sky term; DESIGN §1 normalisation):
//   light = sunColor · sun_irradiance · cloud + skyColor · sky term
// with the sun term from exact per-region sweeps (lighting/sun_frame.h) and the sky term
//   stewart-langer  f_sky = K / (1 − C(1 − K)) (seed Eq. 8) from --sky-directions sweeps
//   hemisphere      (1 + N_up)/2 + C (1 − N_up)/2 (Hargreaves; no shadows)
//   none            0
// One band, or three (R, G, B) when --sun-color or --sky-color is given.
// Search distance, curvature, sky directions and the sun lattice come from the scene plan
// (--quality, --tolerance; lighting/quality.h), recorded in the metadata and printed with -v.
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/sun_field.h"
#include "geo/time.h"
#include "lighting/directions.h"
#include "lighting/horizon.h"
#include "lighting/lighting_models.h"
#include "lighting/sky.h"
#include "lighting/sun_frame.h"
#include "src/error.h"

#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace demlight::cli {
namespace {

struct LightOptions {
    std::string demPath;
    OutputOptions out;
    SearchOptions search;
    std::string time, tz;
    std::string skyModel = "stewart-langer";
    std::string sunColor, skyColor;
    double albedo = 0.2;
    std::string albedoRaster, cloudShadow;
    std::optional<int> skyDirections;  ///< default: the scene plan's
    double sunDiameterDeg = kSunDiameterDeg;
};

/// "R,G,B" linear, each >= 0; throws Error naming the option.
std::array<double, 3> parseColor(const std::string& text, const std::string& option) {
    std::array<double, 3> c{};
    std::stringstream ss(text);
    std::string part;
    std::size_t n = 0;
    while (std::getline(ss, part, ',')) {
        std::size_t used = 0;
        double v = -1;
        try {
            v = std::stod(part, &used);
        } catch (const std::exception&) {
        }
        if (n >= 3 || used != part.size() || !(v >= 0) || !std::isfinite(v))
            throw Error(option + " '" + text + "': expected three linear values >= 0 like 1,0.9,0.8");
        c[n++] = v;
    }
    if (n != 3) throw Error(option + " '" + text + "': expected three linear values >= 0 like 1,0.9,0.8");
    return c;
}

/// A single-band raster resampled onto the DEM grid, named by its option on failure.
Grid<float> loadGridFor(const std::string& path, const Dem& dem, const std::string& option) {
    try {
        auto bands = readRasterResampled(path, dem.band.ref, dem.terrain.width(), dem.terrain.height());
        if (bands.empty()) throw Error("no bands");
        return std::move(bands[0]);
    } catch (const Error& e) {
        throw Error(option + " " + path + ": " + e.what());
    }
}

void runLight(const LightOptions& o, const CliContext& ctx) {
    const ZonedInstant when = parseZonedInstant(o.time, o.tz);
    if (o.skyModel != "stewart-langer" && o.skyModel != "hemisphere" && o.skyModel != "none")
        throw Error("--sky-model '" + o.skyModel + "': expected stewart-langer, hemisphere or none");
    const bool colour = !o.sunColor.empty() || !o.skyColor.empty();
    const auto sunC = o.sunColor.empty() ? std::array<double, 3>{1, 1, 1} : parseColor(o.sunColor, "--sun-color");
    const auto skyC = o.skyColor.empty() ? std::array<double, 3>{1, 1, 1} : parseColor(o.skyColor, "--sky-color");
    checkOutputPath(o.out.path, o.demPath);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;
    Grid<float> albedoGrid, cloud;
    if (!o.albedoRaster.empty()) albedoGrid = loadGridFor(o.albedoRaster, dem, "--albedo-raster");
    if (!o.cloudShadow.empty()) cloud = loadGridFor(o.cloudShadow, dem, "--cloud-shadow");

    const ScenePlan plan = planFor(o.search, t, kDefaultLowestElevationDeg, ctx);
    const auto start = std::chrono::steady_clock::now();
    const SunField field = computeSunField(dem, when.utc, SolarSite{}, SpaOptions{}, plan.sunLatticeStepCells);
    SunFrameParams sp = sunFrameParams(o.search, o.sunDiameterDeg);
    // auto: the distance this sun needs (sunSearchDistanceM); full: the plan's DEM diagonal.
    sp.maxDistanceM = o.search.maxDistanceM.value_or(plan.quality == Quality::Full ? plan.maxDistanceM : 0.0);
    const Normals normals = computeNormals(t, o.search.threads);
    const std::size_t sweeps =
        o.skyModel == "stewart-langer" ? static_cast<std::size_t>(o.skyDirections.value_or(plan.skyDirections)) : 0;
    const HorizonParams hp = horizonParams(o.search, plan);
    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), "light", t.heightsM.size() * (sweeps + 1));
    const SunFrame frame = computeSunFrame(t, normals, field, sp, &counter);

    // Sky term.
    Grid<float> sky(t.width(), t.height(), 0.0f);
    if (o.skyModel == "stewart-langer") {
        SkyAccumulator acc(normals.east, normals.north, normals.up, sweeps, {}, o.search.threads);
        sweepDirections(t, hp, sweeps, [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); },
                        &counter);
        sky = (albedoGrid.empty() ? acc.finish(o.albedo) : acc.finish(albedoGrid)).skyFactor;
    } else if (o.skyModel == "hemisphere") {
        HemisphereParams hemi;
        hemi.albedo = o.albedo;
        sky = applyHemisphereLight(normals.up, hemi, albedoGrid.empty() ? nullptr : &albedoGrid,
                                   o.search.threads);
    }
    bar.finish();

    // Combine.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::size_t channels = colour ? 3 : 1;
    std::vector<Grid<float>> light(channels, Grid<float>(t.width(), t.height(), nan));
    for (std::size_t k = 0; k < t.heightsM.size(); ++k) {
        if (std::isnan(t.heightsM.data()[k])) continue;
        double s = frame.light.irradiance.data()[k];
        if (!cloud.empty()) s *= std::isnan(cloud.data()[k]) ? 1.0 : cloud.data()[k];
        const double k2 = o.skyModel == "none" ? 0.0 : sky.data()[k];
        for (std::size_t c = 0; c < channels; ++c)
            light[c].data()[k] = static_cast<float>(sunC[c] * s + skyC[c] * k2);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_PRODUCT", "light"},
        {"DEMLIGHT_TIME_UTC", formatInstant(when.utc, std::string())},
        {"DEMLIGHT_TIME_LOCAL", formatInstant(when.utc, when.zone)},
        {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
        {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(o.sunDiameterDeg)},
        {"DEMLIGHT_MODEL", "horizon"},
        {"DEMLIGHT_SKY_MODEL", o.skyModel},
        {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(sweeps)},
        {"DEMLIGHT_ALBEDO", o.albedoRaster.empty() ? formatNumber(o.albedo) : o.albedoRaster},
        {"DEMLIGHT_CLOUD_SHADOW", o.cloudShadow},
        {"DEMLIGHT_MAX_DISTANCE_M", formatNumber(frame.maxDistanceM)},
        {"DEMLIGHT_SKY_MAX_DISTANCE_M", sweeps > 0 ? formatNumber(hp.maxDistanceM) : std::string()},
        {"DEMLIGHT_REFRACTION", formatNumber(sp.refraction)},
    });
    const std::string unit = "normalised irradiance (1 = unit zenith sun, or unit sky, on open flat ground)";
    std::vector<OutputBand> bands;
    if (colour) {
        const char* names[3] = {"light_r", "light_g", "light_b"};
        for (std::size_t c = 0; c < 3; ++c) bands.push_back({&light[c], nullptr, names[c], unit});
    } else {
        bands.push_back({&light[0], nullptr, "light", unit});
    }
    writeRaster(o.out.path, bands, dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    note(ctx, "wrote " + o.out.path + " (" + (colour ? "light_r, light_g, light_b" : "light") +
                  "; sun + " + o.skyModel + " sky), " + formatNumber(seconds) + " s compute");
}

}  // namespace

void registerLight(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<LightOptions>();
    CLI::App* cmd = app.add_subcommand("light", "Combined sun + sky lightmap at one instant (Float32, linear)");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--time", o->time, "Instant: ISO 8601 with offset or Z, or local time with --tz")
        ->required();
    cmd->add_option("--tz", o->tz, "IANA time zone for a local --time");
    cmd->add_option("--sky-model", o->skyModel, "stewart-langer, hemisphere or none")->capture_default_str();
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions for stewart-langer (default: 16 with --quality auto, 64 "
                    "with full)")
        ->check(CLI::Range(1, 360));
    cmd->add_option("--sun-color", o->sunColor, "Linear sun radiance R,G,B (gives three bands)");
    cmd->add_option("--sky-color", o->skyColor, "Linear sky radiance R,G,B (gives three bands)");
    cmd->add_option("--albedo", o->albedo, "Albedo C for interreflection (0-1)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--albedo-raster", o->albedoRaster, "Per-cell albedo raster (band 1, 0-1)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--cloud-shadow", o->cloudShadow, "Raster multiplying the sun term (band 1)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--sun-diameter", o->sunDiameterDeg, "Angular diameter of the sun disk (degrees)")
        ->check(CLI::Range(0.0, 20.0))
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runLight(*o, ctx); });
}

}  // namespace demlight::cli
