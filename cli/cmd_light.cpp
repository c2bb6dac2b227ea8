// demlight light DEM -o OUT.tif --time T [--tz ZONE]: the combined sun + sky lightmap, Float32
// linear (demlight/products/light.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/run/raster_commands.h"
#include "cli/progress_bar.h"
#include "demlight/core/error.h"

#include <memory>
#include <optional>

namespace demlight::cli {
namespace {

struct LightOptions {
    std::unique_ptr<RasterCommandOf<LightParameters>> command = lightCommand();
    std::string& demPath = command->demPath;
    OutputOptions& out = command->out;
    bool& verbose = command->verbose;
    LightParameters& p = command->values;
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
    CLI::App* cmd = addDeclaredCommand(app, o->command->declaration(), ctx);
    cmd->callback([o, &ctx] { runLight(*o, ctx); });
}

}  // namespace demlight::cli
