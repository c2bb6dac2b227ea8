// demlight sun DEM -o OUT.tif --time T [--tz ZONE]: how much of the sun's disk each cell sees
// (demlight/products/sun.h).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "demlight/run/raster_commands.h"

#include <optional>

namespace demlight::cli {
namespace {

struct SunOptions {
    std::string demPath;
    OutputOptions out;
    bool verbose = false;
    SunParameters p;
};

void runSun(const SunOptions& o, const CliContext& ctx) {
    const SunRequest request = sunRequest(o.p);
    if (request.model == SunModel::Horizon && o.p.directions)
        note(ctx, "note: --sky-directions is used by the aperture models only; --model horizon sweeps the sun's azimuth");
    const auto [r, cells, readSeconds, seconds] =
        runRasterCommand(sunWork(request, o.p), o.demPath, {{o.out, {}}}, &request.search, o.verbose, ctx);
    const std::string sweeps = request.model == SunModel::Horizon
                                   ? std::to_string(r.sweepRegions) + " sweep region(s), " + r.strategy + " strategy"
                                   : std::to_string(r.directions) + " aperture directions";
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(r.centreAzimuthDeg) + " deg, elevation " +
                  formatNumber(r.centreElevationDeg) + " deg (" + formatInstant(request.time.utc, std::string()) + ")" +
                  (r.sunUp ? "" : "; the sun is below the horizon: everything is in shadow"));
    note(ctx, "wrote " + o.out.path + " (band 1 sun_visibility, band 2 sun_irradiance); model " + o.p.model + ", " +
                  sweeps + ", max distance " + formatDistance(r.maxDistanceM) + ", " + formatSeconds(seconds) +
                  " compute");
}

}  // namespace

void registerSun(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SunOptions>();
    CLI::App* cmd = app.add_subcommand("sun", "Sun visibility and direct-sun irradiance at one instant");
    SunParameters& p = o->p;
    addDemArgument(cmd, o->demPath, p.heights);
    addOutputOptions(cmd, o->out);
    addTimeOptions(cmd, p.time, p.tz);
    addSunDiameterOption(cmd, p.sunDiameterDeg);
    addCanopyOptions(cmd, p.canopy);
    cmd->add_option("--pressure", p.atmosphere.pressureHpa, "Air pressure for solar refraction (hPa)")
        ->check(finiteRange(0, kMaxPressureHpa))
        ->capture_default_str();
    cmd->add_option("--temperature", p.atmosphere.temperatureC, "Air temperature for solar refraction (C)")
        ->check(finiteRange(-100, 100))
        ->capture_default_str();
    cmd->add_option("--model", p.model,
                    "Sun model: horizon (horizon angle in the sun's azimuth), aperture (sun cap intersected with "
                    "the ambient-aperture cap), aperture-smooth (the same with the smoothstep intersection)")
        ->capture_default_str();
    cmd->add_option("--sky-directions,--directions", p.directions,
                    "Aperture models: number of horizon directions integrated into the aperture (default: 16 with "
                    "--quality auto, 64 with full); --directions is the older spelling")
        ->check(finiteRange(4, 1024));
    addSearchOptions(cmd, p.search, o->verbose);
    addTilingOptions(cmd, p.tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(rasterWork(sunWork(o->p))) : runSun(*o, ctx); });
}

}  // namespace demlight::cli
