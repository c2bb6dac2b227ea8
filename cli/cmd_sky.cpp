// demlight sky DEM -o OUT.tif: sky-view factors and skylight (demlight/products/sky.h), or with --model
// hemisphere Hargreaves' hemisphere lighting (no horizons, one band).
#include "cli/common.h"
#include "demlight/run/raster_commands.h"
#include "cli/progress_bar.h"
#include "demlight/core/error.h"

#include <optional>

namespace demlight::cli {
namespace {

struct SkyOptions {
    std::string demPath;
    OutputOptions out;
    bool verbose = false;
    SkyParameters p;
};

void runSky(const SkyOptions& o, const CliContext& ctx) {
    const SkyRequest request = skyRequest(o.p);
    // The hemisphere model has no horizons to plan.
    const bool horizons = request.model == SkyModel::StewartLanger;
    const auto [result, cells, loadSeconds, seconds] = runRasterCommand(
        skyWork(request, o.p), o.demPath, {{o.out, {}}}, horizons ? &request.search : nullptr, o.verbose, ctx);
    if (o.verbose && horizons)
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
    SkyParameters& p = o->p;
    addDemArgument(cmd, o->demPath, p.heights);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--sky-directions,--directions", p.directions,
                    "Number of horizon directions (sectors) integrated (default: 16 with --quality auto, 64 with "
                    "full); --directions is the older spelling")
        ->check(finiteRange(4, 1024));
    auto* albedo = cmd->add_option("--albedo", p.albedo, "Constant ground albedo C for f_sky, in [0, 1]")
                       ->check(finiteRange(0.0, 1.0))
                       ->capture_default_str();
    cmd->add_option("--albedo-raster", p.albedoRaster, "Albedo raster (band 1, 0-1), resampled bilinearly onto the DEM grid")
        ->excludes(albedo);
    cmd->add_option("--patches", p.patches,
                    "Sky patches, one sky_K band each, summing to sky_K: 'sky' (one patch), 'sectors:N', "
                    "'bands:E0,E1,...,90' (elevations, deg; the first band reaches down to -90), or "
                    "'sectors:N,bands:...'");
    cmd->add_option("--model", p.model,
                    "Sky model: stewart-langer (horizon-based SVF, K and f_sky) or hemisphere "
                    "(Hargreaves (1 + N_up)/2 sky + albedo (1 - N_up)/2 ground, no occlusion)")
        ->check(CLI::IsMember({"stewart-langer", "hemisphere"}))
        ->capture_default_str();
    addSearchOptions(cmd, p.search, o->verbose);
    addTilingOptions(cmd, p.tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(rasterWork(skyWork(o->p))) : runSky(*o, ctx); });
}

}  // namespace demlight::cli
