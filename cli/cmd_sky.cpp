// demlight sky DEM -o OUT.tif: sky-view factors and skylight (Hoffman & Mitchell with Stewart &
// Langer, seed Eq. 8-12), from horizons in --directions evenly spaced azimuths; or, with
// --model hemisphere, Hargreaves' hemisphere lighting (no horizons, one band).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "lighting/directions.h"
#include "lighting/lighting_models.h"
#include "lighting/sky.h"
#include "lighting/surface.h"
#include "src/error.h"

#include <chrono>
#include <optional>
#include <utility>

namespace demlight::cli {
namespace {

/// Default --directions: kDefaultSkyDirections (lighting/sky.h), the smallest direction count
/// whose sky errors meet the budget on the three real test DEMs (README "Sky accuracy").
constexpr int kDefaultDirections = static_cast<int>(kDefaultSkyDirections);

struct SkyOptions {
    std::string demPath;
    OutputOptions out;
    SearchOptions search;
    std::optional<int> directions;  ///< default: the scene plan's (kDefaultDirections for auto)
    double albedo = 0.2;
    std::string albedoRaster;
    std::string patches;
    std::string model = "stewart-langer";
};

/// --model hemisphere: sky x (1 + N_up)/2 + albedo x (1 - N_up)/2 for a unit sky (Hargreaves).
void runHemisphere(const SkyOptions& o, const CliContext& ctx, const Dem& dem,
                   const Grid<float>* albedo) {
    const auto start = std::chrono::steady_clock::now();
    const Normals normals = computeNormals(dem.terrain, o.search.threads);
    HemisphereParams hp;
    hp.albedo = o.albedo;
    const Grid<float> light = applyHemisphereLight(normals.up, hp, albedo, o.search.threads);
    const double seconds = secondsSince(start);
    const std::map<std::string, std::string> meta = {
        {"DEMLIGHT_PRODUCT", "sky"},
        {"DEMLIGHT_MODEL", "hemisphere"},
        {"DEMLIGHT_ALBEDO", o.albedoRaster.empty() ? formatNumber(o.albedo) : o.albedoRaster},
    };
    writeRaster(o.out.path,
                {{&light, nullptr, "sky_hemisphere",
                  "normalised irradiance from a unit sky and ground of albedo C, "
                  "(1 + N_up)/2 + C (1 - N_up)/2 (Hargreaves; no terrain occlusion)"}},
                dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    note(ctx, "wrote " + o.out.path + " (1 band: sky_hemisphere); " + formatSeconds(seconds) + " compute");
}

void runSky(const SkyOptions& o, const CliContext& ctx) {
    checkOutputPath(o.out.path, o.demPath);
    if (o.model == "hemisphere" && !o.patches.empty())
        throw Error("--patches needs --model stewart-langer (the hemisphere model has no sky patches)");
    const SkyPatches patches = o.patches.empty() ? SkyPatches{} : parseSkyPatches(o.patches);
    const auto loadStart = std::chrono::steady_clock::now();
    const Dem dem = loadDem(o.demPath);
    const double loadSeconds = secondsSince(loadStart);
    const Terrain& t = dem.terrain;
    std::vector<Grid<float>> albedoRaster;
    if (!o.albedoRaster.empty()) {
        albedoRaster = readRasterResampled(o.albedoRaster, dem.band.ref, t.width(), t.height());
        albedoRaster.resize(1);  // band 1 is the albedo
    }
    if (o.model == "hemisphere") {
        runHemisphere(o, ctx, dem, albedoRaster.empty() ? nullptr : &albedoRaster[0]);
        return;
    }

    const ScenePlan plan = planFor(o.search, t, kDefaultLowestElevationDeg, ctx);
    const int directions = o.directions.value_or(plan.skyDirections);
    const HorizonParams params = integralParams(o.search, plan, t, static_cast<std::size_t>(directions));

    if (o.search.verbose && !ctx.quiet)
        note(ctx, "  sky sweeps: " + std::to_string(directions) + " directions, direction tolerance " +
                      formatNumber(params.directionToleranceDeg) + " deg, search distance " +
                      formatDistance(params.maxDistanceM));
    const auto start = std::chrono::steady_clock::now();
    const Normals normals = computeNormals(t, o.search.threads);
    SkyAccumulator sky(normals.east, normals.north, normals.up,
                       static_cast<std::size_t>(directions), patches, o.search.threads);
    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), "sky", t.heightsM.size() * static_cast<std::size_t>(directions));
    sweepDirections(t, params, static_cast<std::size_t>(directions),
                    [&](std::size_t i, const HorizonMap& h) { sky.addDirection(i, h.angleDeg); },
                    &counter);
    const SkyMaps maps = albedoRaster.empty() ? std::move(sky).finish(o.albedo) : std::move(sky).finish(albedoRaster[0]);
    bar.finish();
    const double seconds = secondsSince(start);

    std::vector<OutputBand> bands = {
        {&maps.svfHorizontal, nullptr, "svf_horizontal", "fraction (cosine-weighted, horizontal plane)"},
        {&maps.skyFraction, nullptr, "sky_fraction", "fraction of the upper hemisphere"},
        {&maps.skyK, nullptr, "sky_K", "normalised irradiance from a unit-radiance sky"},
        {&maps.skyFactor, nullptr, "sky_factor", "normalised irradiance with interreflection"},
    };
    for (std::size_t i = 0; i < maps.patchK.size(); ++i)
        bands.push_back({&maps.patchK[i], nullptr, "sky_K_patch=" + patches.patches[i].name,
                         "normalised irradiance"});
    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_PRODUCT", "sky"},
        {"DEMLIGHT_METHOD", "sweep"},
        {"DEMLIGHT_DIRECTIONS", std::to_string(directions)},
        {"DEMLIGHT_ALBEDO", o.albedoRaster.empty() ? formatNumber(o.albedo) : o.albedoRaster},
        {"DEMLIGHT_PATCHES", o.patches},
        {"DEMLIGHT_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, params.maxDistanceM)},
        {"DEMLIGHT_REFRACTION", formatNumber(params.refraction)},
    });
    const auto writeStart = std::chrono::steady_clock::now();
    writeRaster(o.out.path, bands, dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    const double writeSeconds = secondsSince(writeStart);
    note(ctx, "wrote " + o.out.path + " (" + std::to_string(bands.size()) + " bands: svf_horizontal, "
              "sky_fraction, sky_K, sky_factor" + (maps.patchK.empty() ? "" : ", patches") + "); " +
              std::to_string(directions) + " directions, max distance " +
              formatDistance(params.maxDistanceM) + "; " + formatSeconds(loadSeconds) + " reading, " +
              formatSeconds(seconds) + " compute, " + formatSeconds(writeSeconds) + " writing");
}

}  // namespace

void registerSky(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SkyOptions>();
    CLI::App* cmd = app.add_subcommand("sky", "Sky-view factors and skylight K / f_sky");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--directions", o->directions,
                    "Number of horizon directions (sectors) integrated (default: 16 with --quality "
                    "auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    auto* albedo = cmd->add_option("--albedo", o->albedo, "Constant ground albedo C for f_sky, in [0, 1]")
                       ->check(finiteRange(0.0, 1.0))
                       ->capture_default_str();
    cmd->add_option("--albedo-raster", o->albedoRaster,
                    "Albedo raster (band 1, 0-1), resampled bilinearly onto the DEM grid")
        ->check(CLI::ExistingFile)
        ->excludes(albedo);
    cmd->add_option("--patches", o->patches,
                    "Sky patches, one sky_K band each, summing to sky_K: 'sky' (one patch), 'sectors:N', "
                    "'bands:E0,E1,...,90' (elevations, deg; the first band reaches down to -90), or "
                    "'sectors:N,bands:...'");
    cmd->add_option("--model", o->model,
                    "Sky model: stewart-langer (horizon-based SVF, K and f_sky) or hemisphere "
                    "(Hargreaves (1 + N_up)/2 sky + albedo (1 - N_up)/2 ground, no occlusion)")
        ->check(CLI::IsMember({"stewart-langer", "hemisphere"}))
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runSky(*o, ctx); });
}

}  // namespace demlight::cli
