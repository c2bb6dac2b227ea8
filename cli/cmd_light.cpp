// demlight light DEM -o OUT.tif --time T [--tz ZONE]: the combined lightmap, sun + sky, Float32
// linear (Hoffman & Mitchell: lightmap = sun term + sky term, times colour; DESIGN §1
// normalisation):
//   light = sunColor · sun term · cloud + skyColor · sky term           (one band, or R, G, B)
//   light_c = albedo_c · (sunColor_c · sun term · cloud + skyColor_c · sky term_c)   (--color-raster)
// The sun term (--model) is demlight sun's irradiance band:
//   horizon          visibility of the disk from the horizon in the sun's azimuth × max(0, N·s),
//                    from exact per-region sweeps (lighting/sun_frame.h)
//   aperture         the sun cap intersected with each cell's ambient-aperture cap, Lambert
//                    integral over the intersection (lighting/lighting_models.h applyApertureSun)
//   aperture-smooth  the same with Oat & Sander's smoothstep intersection
// and the sky term (--sky-model):
//   stewart-langer  f_sky = K / (1 − C(1 − K)) (seed Eq. 8) from --sky-directions sweeps
//   hemisphere      (1 + N_up)/2 + C (1 − N_up)/2 (Hargreaves; no shadows)
//   none            0
// with C the albedo (--albedo, --albedo-raster, or per channel the --color-raster). The aperture
// and the sky share one pass of direction sweeps. Search distance, curvature, directions and the
// sun lattice come from the scene plan (--quality, --tolerance; lighting/quality.h), recorded in
// the metadata and printed with -v.
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/sun_field.h"
#include "geo/time.h"
#include "lighting/aperture.h"
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

/// Ground albedo C for interreflection when neither --albedo-raster nor --color-raster is given.
constexpr double kDefaultAlbedo = 0.2;

struct LightOptions {
    std::string demPath;
    OutputOptions out;
    SearchOptions search;
    std::string time, tz;
    std::string model = "horizon";
    std::string skyModel = "stewart-langer";
    std::string sunColor, skyColor;
    std::optional<double> albedo;  ///< default kDefaultAlbedo
    std::string albedoRaster, colorRaster, cloudShadow;
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

/// --color-raster: exactly three bands (R, G, B) of linear albedo in [0, 1], resampled onto the
/// DEM grid; NaN where the raster has no data. Throws Error naming the option and the file.
std::vector<Grid<float>> loadColorRaster(const std::string& path, const Dem& dem) {
    std::vector<Grid<float>> bands;
    try {
        bands = readRasterResampled(path, dem.band.ref, dem.terrain.width(), dem.terrain.height());
    } catch (const Error& e) {
        throw Error("--color-raster " + path + ": " + e.what());
    }
    if (bands.size() != 3)
        throw Error("--color-raster " + path + ": expected 3 bands (R, G, B linear albedo), found " +
                    std::to_string(bands.size()) + " (use --albedo-raster for one band)");
    for (std::size_t b = 0; b < 3; ++b)
        for (float v : bands[b].values())
            if (!std::isnan(v) && !(v >= 0.0f && v <= 1.0f))
                throw Error("--color-raster " + path + ": band " + std::to_string(b + 1) + " holds " +
                            formatNumber(v) + "; expected linear albedo 0-1 (convert an 8-bit image "
                            "first, e.g. gdal_translate -ot Float32 -scale 0 255 0 1 -exponent 2.2)");
    return bands;
}

/// The sun term of either model (normalised irradiance, NaN at nodata) and how it was made.
struct SunTerm {
    Grid<float> irradiance;
    double maxDistanceM = 0;
    std::size_t sweepRegions = 0;  ///< horizon model: regions of the sun sweep
};

void runLight(const LightOptions& o, const CliContext& ctx) {
    const ZonedInstant when = parseZonedInstant(o.time, o.tz);
    if (o.model == "hemisphere")
        throw Error("--model hemisphere has no sun term; use --sky-model hemisphere for Hargreaves' "
                    "sky, and --model horizon, aperture or aperture-smooth for the sun");
    if (o.model != "horizon" && o.model != "aperture" && o.model != "aperture-smooth")
        throw Error("--model '" + o.model + "': expected horizon, aperture or aperture-smooth");
    const LightingModel model = parseLightingModel(o.model);
    const bool aperture = model != LightingModel::Horizon;
    if (o.skyModel != "stewart-langer" && o.skyModel != "hemisphere" && o.skyModel != "none")
        throw Error("--sky-model '" + o.skyModel + "': expected stewart-langer, hemisphere or none");
    if (!o.colorRaster.empty() && (o.albedo || !o.albedoRaster.empty()))
        throw Error("--color-raster gives the albedo of each channel; do not combine it with " +
                    std::string(o.albedo ? "--albedo" : "--albedo-raster"));
    const bool colorRaster = !o.colorRaster.empty();
    const bool colour = colorRaster || !o.sunColor.empty() || !o.skyColor.empty();
    const auto sunC = o.sunColor.empty() ? std::array<double, 3>{1, 1, 1} : parseColor(o.sunColor, "--sun-color");
    const auto skyC = o.skyColor.empty() ? std::array<double, 3>{1, 1, 1} : parseColor(o.skyColor, "--sky-color");
    const double albedo = o.albedo.value_or(kDefaultAlbedo);
    checkOutputPath(o.out.path, o.demPath);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;
    Grid<float> albedoGrid, cloud;
    std::vector<Grid<float>> colorAlbedo;
    if (!o.albedoRaster.empty()) albedoGrid = loadGridFor(o.albedoRaster, dem, "--albedo-raster");
    if (colorRaster) colorAlbedo = loadColorRaster(o.colorRaster, dem);
    if (!o.cloudShadow.empty()) cloud = loadGridFor(o.cloudShadow, dem, "--cloud-shadow");

    const ScenePlan plan = planFor(o.search, t, kDefaultLowestElevationDeg, ctx);
    const auto start = std::chrono::steady_clock::now();
    const SunField field = computeSunField(dem, when.utc, SolarSite{}, SpaOptions{}, plan.sunLatticeStepCells);
    const Normals normals = computeNormals(t, o.search.threads);
    const bool skySweeps = o.skyModel == "stewart-langer";
    const auto directions = static_cast<std::size_t>(o.skyDirections.value_or(plan.skyDirections));
    const std::size_t sweeps = skySweeps || aperture ? directions : 0;
    const HorizonParams hp = integralParams(o.search, plan, t, std::max<std::size_t>(directions, 1));
    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), "light", t.heightsM.size() * (sweeps + (aperture ? 0 : 1)));

    // One pass over the directions feeds the sky and the aperture alike.
    std::optional<SkyAccumulator> skyAcc;
    std::optional<ApertureAccumulator> apertureAcc;
    if (skySweeps) skyAcc.emplace(normals.east, normals.north, normals.up, directions, SkyPatches{}, o.search.threads);
    if (aperture) apertureAcc.emplace(normals.east, normals.north, normals.up, directions, o.search.threads);
    if (sweeps > 0)
        sweepDirections(t, hp, sweeps, [&](std::size_t i, const HorizonMap& h) {
            if (skyAcc) skyAcc->addDirection(i, h.angleDeg);
            if (apertureAcc) apertureAcc->addDirection(i, h.angleDeg);
        }, &counter);

    // Sun term.
    SunTerm sun;
    if (aperture) {
        ApertureLightParams lp;
        lp.sunRadiusDeg = 0.5 * o.sunDiameterDeg;
        lp.smoothIntersection = model == LightingModel::ApertureSmooth;
        sun.irradiance = applyApertureSun(apertureAcc->finish(), normals.east, normals.north, normals.up, field,
                                          lp, o.search.threads).irradiance;
        sun.maxDistanceM = hp.maxDistanceM;  // the aperture is the sky's: the sky's distance
    } else {
        // auto: the distance this sun needs (sunSearchDistanceM); full: the plan's DEM diagonal.
        const SunFrameParams sp = sunFrameParams(o.search, o.sunDiameterDeg, plan);
        SunFrame frame = computeSunFrame(t, normals, field, sp, &counter);
        sun = {std::move(frame.light.irradiance), frame.maxDistanceM, frame.sweepRegions};
    }

    // Sky term: one grid, or one per channel when the colour raster sets the albedo.
    const std::size_t channels = colour ? 3 : 1;
    std::vector<Grid<float>> sky;
    for (std::size_t c = 0; c < (colorRaster ? 3 : 1); ++c) {
        const Grid<float>* albedoC = colorRaster ? &colorAlbedo[c] : albedoGrid.empty() ? nullptr : &albedoGrid;
        if (skySweeps) {
            sky.push_back((albedoC ? skyAcc->finish(*albedoC) : skyAcc->finish(albedo)).skyFactor);
        } else if (o.skyModel == "hemisphere") {
            HemisphereParams hemi;
            hemi.albedo = albedo;
            sky.push_back(applyHemisphereLight(normals.up, hemi, albedoC, o.search.threads));
        }
    }
    bar.finish();

    // Combine.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<Grid<float>> light(channels, Grid<float>(t.width(), t.height(), nan));
    for (std::size_t k = 0; k < t.heightsM.size(); ++k) {
        if (std::isnan(t.heightsM.data()[k])) continue;
        double s = sun.irradiance.data()[k];
        if (!cloud.empty()) s *= std::isnan(cloud.data()[k]) ? 1.0 : cloud.data()[k];
        for (std::size_t c = 0; c < channels; ++c) {
            const double skyTerm = sky.empty() ? 0.0 : sky[std::min(c, sky.size() - 1)].data()[k];
            const double reflectance = colorRaster ? colorAlbedo[c].data()[k] : 1.0;
            light[c].data()[k] = static_cast<float>(reflectance * (sunC[c] * s + skyC[c] * skyTerm));
        }
    }
    const double seconds = secondsSince(start);

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_PRODUCT", "light"},
        {"DEMLIGHT_TIME_UTC", formatInstant(when.utc, std::string())},
        {"DEMLIGHT_TIME_LOCAL", formatInstant(when.utc, when.zone)},
        {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
        {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(o.sunDiameterDeg)},
        {"DEMLIGHT_SUN_SWEEP_REGIONS", aperture ? std::string() : std::to_string(sun.sweepRegions)},
        {"DEMLIGHT_MODEL", std::string(lightingModelName(model))},
        {"DEMLIGHT_DIRECTIONS", aperture ? std::to_string(directions) : std::string()},
        {"DEMLIGHT_SKY_MODEL", o.skyModel},
        {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(skySweeps ? directions : 0)},
        {"DEMLIGHT_ALBEDO", colorRaster ? std::string("--color-raster")
                            : o.albedoRaster.empty() ? formatNumber(albedo) : o.albedoRaster},
        {"DEMLIGHT_COLOR_RASTER", o.colorRaster},
        {"DEMLIGHT_CLOUD_SHADOW", o.cloudShadow},
        {"DEMLIGHT_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, sun.maxDistanceM)},
        {"DEMLIGHT_SKY_MAX_DISTANCE_M", sweeps > 0 ? metadataDistanceM(dem.terrain, hp.maxDistanceM) : std::string()},
        {"DEMLIGHT_REFRACTION", formatNumber(o.search.refraction)},
    });
    const std::string unit =
        colorRaster ? "albedo x normalised irradiance: light reflected by the ground, relative to the "
                      "source radiance (white ground under a unit zenith sun = 1)"
                    : "normalised irradiance (1 = unit zenith sun, or unit sky, on open flat ground)";
    const std::string prefix = colorRaster ? "reflected" : "light";
    std::vector<OutputBand> bands;
    if (colour) {
        const char* suffixes[3] = {"_r", "_g", "_b"};
        for (std::size_t c = 0; c < 3; ++c) bands.push_back({&light[c], nullptr, prefix + suffixes[c], unit});
    } else {
        bands.push_back({&light[0], nullptr, prefix, unit});
    }
    writeRaster(o.out.path, bands, dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    note(ctx, "wrote " + o.out.path + " (" + (colour ? prefix + "_r, _g, _b" : prefix) + "; " +
                  std::string(lightingModelName(model)) + " sun + " + o.skyModel + " sky), " +
                  formatSeconds(seconds) + " compute");
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
    cmd->add_option("--model", o->model,
                    "Sun model: horizon (horizon angle in the sun's azimuth), aperture (sun cap "
                    "intersected with the ambient-aperture cap), aperture-smooth (the same with "
                    "the smoothstep intersection)")
        ->capture_default_str();
    cmd->add_option("--sky-model", o->skyModel, "stewart-langer, hemisphere or none")->capture_default_str();
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions for the stewart-langer sky and the aperture models "
                    "(default: 16 with --quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    cmd->add_option("--sun-color", o->sunColor, "Linear sun radiance R,G,B (gives three bands)");
    cmd->add_option("--sky-color", o->skyColor, "Linear sky radiance R,G,B (gives three bands)");
    auto* albedo = cmd->add_option("--albedo", o->albedo, "Albedo C for interreflection (0-1; default 0.2)")
                       ->check(finiteRange(0.0, 1.0));
    cmd->add_option("--albedo-raster", o->albedoRaster, "Per-cell albedo raster (band 1, 0-1)")
        ->check(CLI::ExistingFile)
        ->excludes(albedo);
    cmd->add_option("--color-raster", o->colorRaster,
                    "3-band linear albedo raster (R, G, B, 0-1), resampled to the DEM: per-channel "
                    "albedo for interreflection, and the output is albedo x light in three bands "
                    "reflected_r/g/b; excludes --albedo and --albedo-raster")
        ->check(CLI::ExistingFile);
    cmd->add_option("--cloud-shadow", o->cloudShadow, "Raster multiplying the sun term (band 1)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--sun-diameter", o->sunDiameterDeg, "Angular diameter of the sun disk (degrees)")
        ->check(finiteRange(0.0, 20.0))
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runLight(*o, ctx); });
}

}  // namespace demlight::cli
