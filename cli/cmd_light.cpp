// demlight light DEM -o OUT.tif --time T [--tz ZONE]: the combined sun + sky lightmap, Float32
// linear (demlight/products/light.h).
#include "cli/common.h"
#include "demlight/run/raster_commands.h"
#include "cli/progress_bar.h"
#include "demlight/core/error.h"

#include <optional>

namespace demlight::cli {
namespace {

struct LightOptions {
    std::string demPath;
    OutputOptions out;
    bool verbose = false;
    LightParameters p;
};

void runLight(const LightOptions& o, const CliContext& ctx) {
    const LightRequest request = lightRequest(o.p);
    const auto [result, cells, readSeconds, seconds] =
        runRasterCommand(lightWork(request, o.p), o.demPath, {{o.out, {}}}, &request.search, o.verbose, ctx);
    std::string names;
    for (const auto& b : result.bands) names += (names.empty() ? "" : ", ") + b.name;
    note(ctx, "wrote " + o.out.path + " (" + names + "; " + o.p.model + " sun + " + o.p.skyModel + " sky), " +
                  formatSeconds(seconds) + " compute");
}

}  // namespace

void registerLight(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<LightOptions>();
    CLI::App* cmd = app.add_subcommand("light", "Combined sun + sky lightmap at one instant (Float32, linear)");
    LightParameters& p = o->p;
    addDemArgument(cmd, o->demPath, p.heights);
    addOutputOptions(cmd, o->out);
    addTimeOptions(cmd, p.time, p.tz);
    cmd->add_option("--model", p.model,
                    "Sun model: horizon (horizon angle in the sun's azimuth), aperture (sun cap intersected with "
                    "the ambient-aperture cap), aperture-smooth (the same with the smoothstep intersection)")
        ->capture_default_str();
    cmd->add_option("--sky-model", p.skyModel, "stewart-langer, hemisphere or none")->capture_default_str();
    cmd->add_option("--sky-directions", p.skyDirections,
                    "Horizon directions for the stewart-langer sky and the aperture models (default: 16 with "
                    "--quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    cmd->add_option("--sun-color", p.sunColor, "Linear sun radiance R,G,B (gives three bands)");
    cmd->add_option("--sky-color", p.skyColor, "Linear sky radiance R,G,B (gives three bands)");
    auto* albedo = cmd->add_option("--albedo", p.albedo, "Albedo C for interreflection (0-1; default 0.2)")
                       ->check(finiteRange(0.0, 1.0));
    cmd->add_option("--albedo-raster", p.albedoRaster, "Per-cell albedo raster (band 1, 0-1)")->excludes(albedo);
    addColorRasterOptions(cmd, p.colorRaster, p.colorEncoding,
                          "per-channel albedo for interreflection, and the output is albedo x light in three bands "
                          "reflected_r/g/b; excludes --albedo and --albedo-raster");
    cmd->add_option("--cloud-shadow", p.cloudShadow, "Raster multiplying the sun term (band 1, 0-1)");
    addCanopyOptions(cmd, p.canopy);
    addSunDiameterOption(cmd, p.sunDiameterDeg);
    addSearchOptions(cmd, p.search, o->verbose);
    addTilingOptions(cmd, p.tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(rasterWork(lightWork(o->p))) : runLight(*o, ctx); });
}

}  // namespace demlight::cli
