// demlight aperture DEM -o OUT.tif: ambient aperture per cell (demlight/products/aperture.h).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "demlight/products/aperture.h"

#include <optional>

namespace demlight::cli {
namespace {

struct ApertureOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    SearchOptions search;
    std::optional<std::size_t> directions;
};

/// Bands of the output: bent normal E, N, U, aperture radius, visible solid angle.

ApertureRequest apertureRequest(const ApertureOptions& o) {
    ApertureRequest request;
    request.directions = o.directions;
    request.search = o.search.request;
    return request;
}

RasterCall apertureCall(const ApertureOptions& o) {
    return singleRasterCall(
        "aperture", o.dem, o.tiling, o.search.request, apertureTileBytes(),
        [request = apertureRequest(o)](const DemSource& dem, const CellWindow& w, const ProgressFn& p) {
            return apertureProduct(dem, w, request, p);
        });
}

void runAperture(const ApertureOptions& o, const CliContext& ctx) {
    checkOutputPath(o.out, o.dem.path);
    const DemSource dem = openDem(o.dem, ctx);
    const ApertureRequest request = apertureRequest(o);
    notePlan(o.search, dem.geometry().terrain, ctx);
    const RasterRun run = planRasterRun(dem, o.tiling, request.search, apertureTileBytes(), ctx);
    const auto start = std::chrono::steady_clock::now();
    const ApertureResult result = runRaster<ApertureResult>(
        run, {{o.out, {}}}, ctx, o.dem.path,
        [&](const CellWindow& w, const ProgressFn& p) { return apertureProduct(dem, w, request, p); },
        [](const ApertureResult& r) { return std::vector<const ProductResult*>{&r}; });
    const double seconds = secondsSince(start);
    note(ctx, "wrote " + o.out.path + " (bent normal E/N/U, aperture radius, visible solid angle); " +
                  std::to_string(result.directions) + " directions, " + formatSeconds(seconds) + " compute");
}

}  // namespace

void registerAperture(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<ApertureOptions>();
    CLI::App* cmd = app.add_subcommand("aperture", "Ambient aperture: bent normal, cap radius, visible solid angle");
    addDemArgument(cmd, o->dem);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--sky-directions,--directions", o->directions,
                    "Number of horizon directions integrated (default: 16 with --quality auto, 64 with full); "
                    "--directions is the older spelling")
        ->check(finiteRange(4, 1024));
    addSearchOptions(cmd, o->search);
    addTilingOptions(cmd, o->tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(apertureCall(*o)) : runAperture(*o, ctx); });
}

}  // namespace demlight::cli
