// demlight aperture DEM -o OUT.tif: ambient aperture per cell (demlight/products/aperture.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/run/raster_commands.h"
#include "cli/progress_bar.h"

#include <memory>
#include <optional>

namespace demlight::cli {
namespace {

struct ApertureOptions {
    std::unique_ptr<RasterCommandOf<ApertureParameters>> command = apertureCommand();
    std::string& demPath = command->demPath;
    OutputOptions& out = command->out;
    bool& verbose = command->verbose;
    ApertureParameters& p = command->values;
};

void runAperture(const ApertureOptions& o, const CliContext& ctx) {
    const ApertureRequest request = apertureRequest(o.p);
    const auto [result, cells, readSeconds, seconds] =
        runRasterCommand(apertureWork(request, o.p), o.demPath, {{o.out, {}}}, &request.search, o.verbose, ctx);
    note(ctx, "wrote " + o.out.path + " (bent normal E/N/U, aperture radius, visible solid angle); " +
                  std::to_string(result.directions) + " directions, " + formatSeconds(seconds) + " compute");
}

}  // namespace

void registerAperture(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<ApertureOptions>();
    CLI::App* cmd = addDeclaredCommand(app, o->command->declaration(), ctx);
    cmd->callback([o, &ctx] { runAperture(*o, ctx); });
}

}  // namespace demlight::cli
