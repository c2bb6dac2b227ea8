// demlight sun DEM -o OUT.tif --time T [--tz ZONE]: how much of the sun's disk each cell sees
// (demlight/products/sun.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "cli/progress_bar.h"
#include "demlight/run/raster_commands.h"

#include <memory>
#include <optional>

namespace demlight::cli {
namespace {

struct SunOptions {
    std::unique_ptr<RasterCommandOf<SunParameters>> command = sunCommand();
    std::string& demPath = command->demPath;
    OutputOptions& out = command->out;
    bool& verbose = command->verbose;
    SunParameters& p = command->values;
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
    CLI::App* cmd = addDeclaredCommand(app, o->command->declaration(), ctx);
    cmd->callback([o, &ctx] { runSun(*o, ctx); });
}

}  // namespace demlight::cli
