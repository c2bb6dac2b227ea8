// demlight sky DEM -o OUT.tif: sky-view factors and skylight (demlight/products/sky.h), or with --model
// hemisphere Hargreaves' hemisphere lighting (no horizons, one band).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "demlight/products/sky.h"
#include "demlight/core/error.h"

#include <optional>

namespace demlight::cli {
namespace {

struct SkyOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    SearchOptions search;
    std::optional<std::size_t> directions;
    double albedo = kDefaultAlbedo;
    std::string albedoRaster;
    std::string patches;
    std::string model = "stewart-langer";
};

SkyRequest skyRequest(const SkyOptions& o) {
    SkyRequest request;
    request.model = parseSkyModel(o.model);
    if (request.model == SkyModel::Hemisphere && !o.patches.empty())
        throw Error("--patches needs --model stewart-langer (the hemisphere model has no sky patches)");
    if (!o.patches.empty()) request.patches = parseSkyPatches(o.patches);
    request.directions = o.directions;
    request.albedo = o.albedo;
    request.albedoRaster = o.albedoRaster;
    request.search = o.search.request;
    return request;
}

RasterCall skyCall(const SkyOptions& o) {
    const SkyRequest request = skyRequest(o);
    return singleRasterCall("sky", o.dem, o.tiling, request.search, skyTileBytes(request),
                            [request](const DemSource& dem, const CellWindow& w, const ProgressFn& p) {
                                return skyProduct(dem, w, request, p);
                            });
}

void runSky(const SkyOptions& o, const CliContext& ctx) {
    checkOutputPath(o.out, o.dem.path);
    const SkyRequest request = skyRequest(o);
    const auto loadStart = std::chrono::steady_clock::now();
    const DemSource dem = openDem(o.dem, ctx);
    const double loadSeconds = secondsSince(loadStart);
    if (request.model == SkyModel::StewartLanger) notePlan(o.search, dem.geometry().terrain, ctx);

    const RasterRun run = planRasterRun(dem, o.tiling, request.search, skyTileBytes(request), ctx);
    const auto start = std::chrono::steady_clock::now();
    const SkyResult result = runRaster<SkyResult>(
        run, {{o.out, {}}}, ctx, o.dem.path,
        [&](const CellWindow& w, const ProgressFn& p) { return skyProduct(dem, w, request, p); },
        [](const SkyResult& r) { return std::vector<const ProductResult*>{&r}; });
    const double seconds = secondsSince(start);
    if (o.search.verbose && request.model == SkyModel::StewartLanger)
        note(ctx, "  sky sweeps: " + std::to_string(result.directions) + " directions, direction tolerance " +
                      formatNumber(result.directionToleranceDeg) + " deg, search distance " +
                      formatDistance(result.maxDistanceM));
    std::string names;
    for (const auto& b : result.bands) names += (names.empty() ? "" : ", ") + b.name;
    note(ctx, "wrote " + o.out.path + " (" + std::to_string(result.bands.size()) +
                  (result.bands.size() == 1 ? " band: " : " bands: ") + names + ")" +
                  (result.directions ? "; " + std::to_string(result.directions) + " directions, max distance " +
                                           formatDistance(result.maxDistanceM)
                                     : std::string()) +
                  "; " + formatSeconds(loadSeconds) + " reading, " + formatSeconds(seconds) + " compute and writing");
}

}  // namespace

void registerSky(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SkyOptions>();
    CLI::App* cmd = app.add_subcommand("sky", "Sky-view factors and skylight K / f_sky");
    addDemArgument(cmd, o->dem);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--sky-directions,--directions", o->directions,
                    "Number of horizon directions (sectors) integrated (default: 16 with --quality auto, 64 with "
                    "full); --directions is the older spelling")
        ->check(finiteRange(4, 1024));
    auto* albedo = cmd->add_option("--albedo", o->albedo, "Constant ground albedo C for f_sky, in [0, 1]")
                       ->check(finiteRange(0.0, 1.0))
                       ->capture_default_str();
    cmd->add_option("--albedo-raster", o->albedoRaster, "Albedo raster (band 1, 0-1), resampled bilinearly onto the DEM grid")
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
    addTilingOptions(cmd, o->tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(skyCall(*o)) : runSky(*o, ctx); });
}

}  // namespace demlight::cli
