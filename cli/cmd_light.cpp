// demlight light DEM -o OUT.tif --time T [--tz ZONE]: the combined sun + sky lightmap, Float32
// linear (demlight/products/light.h).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "demlight/products/light.h"
#include "demlight/core/error.h"

#include <optional>

namespace demlight::cli {
namespace {

struct LightOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    SearchOptions search;
    std::string time, tz;
    std::string model = "horizon";
    std::string skyModel = "stewart-langer";
    std::string sunColor, skyColor;
    std::optional<double> albedo;
    std::string albedoRaster, colorRaster, colorEncoding = "auto", cloudShadow;
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
    CanopyRequest canopy;
};

LightRequest lightRequest(const LightOptions& o) {
    LightRequest r;
    r.time = parseTimeOptions(o.time, o.tz);
    r.model = parseSunModel(o.model);
    r.skyModel = parseSkyModel(o.skyModel);
    if (!o.sunColor.empty()) r.sunColor = parseColor(o.sunColor, "--sun-color");
    if (!o.skyColor.empty()) r.skyColor = parseColor(o.skyColor, "--sky-color");
    if (!o.colorRaster.empty() && (o.albedo || !o.albedoRaster.empty()))
        throw Error("--color-raster gives the albedo of each channel; do not combine it with " +
                    std::string(o.albedo ? "--albedo" : "--albedo-raster"));
    r.albedo = o.albedo;
    r.albedoRaster = o.albedoRaster;
    r.colorRaster = o.colorRaster;
    r.colorEncoding = parseColorEncoding(o.colorEncoding, "--color-encoding");
    r.cloudShadow = o.cloudShadow;
    r.skyDirections = o.skyDirections;
    r.sunDiameterDeg = o.sunDiameterDeg;
    r.canopy = o.canopy;
    r.search = o.search.request;
    return r;
}

/// Bands of the output (for tile sizes): light, or three of colour.
constexpr std::size_t kLightBands = 3;

RasterCall lightCall(const LightOptions& o) {
    return singleRasterCall("light", o.dem, o.tiling, o.search.request, productTileBytes(kLightBands),
                            [request = lightRequest(o)](const DemSource& dem, const CellWindow& w, const ProgressFn& p) {
                                return lightProduct(dem, w, request, p);
                            });
}

void runLight(const LightOptions& o, const CliContext& ctx) {
    const LightRequest request = lightRequest(o);
    checkOutputPath(o.out, o.dem.path);
    const DemSource dem = openDem(o.dem, ctx);
    notePlan(o.search, dem.geometry().terrain, ctx);
    const RasterRun run = planRasterRun(dem, o.tiling, request.search, productTileBytes(kLightBands), ctx);
    const auto start = std::chrono::steady_clock::now();
    const LightResult result = runRaster<LightResult>(
        run, {{o.out, {}}}, ctx, o.dem.path,
        [&](const CellWindow& w, const ProgressFn& p) { return lightProduct(dem, w, request, p); },
        [](const LightResult& r) { return std::vector<const ProductResult*>{&r}; });
    const double seconds = secondsSince(start);
    std::string names;
    for (const auto& b : result.bands) names += (names.empty() ? "" : ", ") + b.name;
    note(ctx, "wrote " + o.out.path + " (" + names + "; " + o.model + " sun + " + o.skyModel + " sky), " +
                  formatSeconds(seconds) + " compute");
}

}  // namespace

void registerLight(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<LightOptions>();
    CLI::App* cmd = app.add_subcommand("light", "Combined sun + sky lightmap at one instant (Float32, linear)");
    addDemArgument(cmd, o->dem);
    addOutputOptions(cmd, o->out);
    addTimeOptions(cmd, o->time, o->tz);
    cmd->add_option("--model", o->model,
                    "Sun model: horizon (horizon angle in the sun's azimuth), aperture (sun cap intersected with "
                    "the ambient-aperture cap), aperture-smooth (the same with the smoothstep intersection)")
        ->capture_default_str();
    cmd->add_option("--sky-model", o->skyModel, "stewart-langer, hemisphere or none")->capture_default_str();
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions for the stewart-langer sky and the aperture models (default: 16 with "
                    "--quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    cmd->add_option("--sun-color", o->sunColor, "Linear sun radiance R,G,B (gives three bands)");
    cmd->add_option("--sky-color", o->skyColor, "Linear sky radiance R,G,B (gives three bands)");
    auto* albedo = cmd->add_option("--albedo", o->albedo, "Albedo C for interreflection (0-1; default 0.2)")
                       ->check(finiteRange(0.0, 1.0));
    cmd->add_option("--albedo-raster", o->albedoRaster, "Per-cell albedo raster (band 1, 0-1)")->excludes(albedo);
    addColorRasterOptions(cmd, o->colorRaster, o->colorEncoding,
                          "per-channel albedo for interreflection, and the output is albedo x light in three bands "
                          "reflected_r/g/b; excludes --albedo and --albedo-raster");
    cmd->add_option("--cloud-shadow", o->cloudShadow, "Raster multiplying the sun term (band 1, 0-1)");
    addCanopyOptions(cmd, o->canopy);
    addSunDiameterOption(cmd, o->sunDiameterDeg);
    addSearchOptions(cmd, o->search);
    addTilingOptions(cmd, o->tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(lightCall(*o)) : runLight(*o, ctx); });
}

}  // namespace demlight::cli
