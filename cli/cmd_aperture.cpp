// demlight aperture DEM -o OUT.tif: ambient aperture per cell (demlight/products/aperture.h).
#include "cli/common.h"
#include "demlight/run/raster_commands.h"
#include "cli/progress_bar.h"

#include <optional>

namespace demlight::cli {
namespace {

struct ApertureOptions {
    std::string demPath;
    OutputOptions out;
    bool verbose = false;
    ApertureParameters p;
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
    CLI::App* cmd = app.add_subcommand("aperture", "Ambient aperture: bent normal, cap radius, visible solid angle");
    ApertureParameters& p = o->p;
    addDemArgument(cmd, o->demPath, p.heights);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--sky-directions,--directions", p.directions,
                    "Number of horizon directions integrated (default: 16 with --quality auto, 64 with full); "
                    "--directions is the older spelling")
        ->check(finiteRange(4, 1024));
    addSearchOptions(cmd, p.search, o->verbose);
    addTilingOptions(cmd, p.tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(rasterWork(apertureWork(o->p))) : runAperture(*o, ctx); });
}

}  // namespace demlight::cli
