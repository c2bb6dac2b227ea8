// demlight sky DEM -o OUT.tif: sky-view factors and skylight (demlight/products/sky.h), or with --model
// hemisphere Hargreaves' hemisphere lighting (no horizons, one band).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/run/raster_commands.h"
#include "cli/progress_bar.h"
#include "demlight/core/error.h"

#include <memory>
#include <optional>

namespace demlight::cli {
namespace {

struct SkyOptions {
    std::unique_ptr<RasterCommandOf<SkyParameters>> command = skyCommand();
    std::string& demPath = command->demPath;
    OutputOptions& out = command->out;
    bool& verbose = command->verbose;
    SkyParameters& p = command->values;
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
    CLI::App* cmd = addDeclaredCommand(app, o->command->declaration(), ctx);
    cmd->callback([o, &ctx] { runSky(*o, ctx); });
}

}  // namespace demlight::cli
