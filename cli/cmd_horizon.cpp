// demlight horizon DEM -o OUT.tif (--azimuth DEG... | --directions N): horizon angle maps, one
// Float32 band per azimuth (products/horizon.h), and the truncation mask in OUT.truncated.tif.
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "products/horizon.h"
#include "src/error.h"

#include <cmath>
#include <filesystem>

namespace demlight::cli {
namespace {

struct HorizonOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    SearchOptions search;
    std::vector<double> azimuthsDeg;
    int directions = 0;
    std::string method = "sweep";
};

/// The horizon raster's metadata item that names its truncation mask raster.
constexpr const char* kTruncationMaskKey = "DEMLIGHT_TRUNCATION_MASK";

std::string truncationPath(const std::string& outPath) {
    std::filesystem::path p(outPath);
    return (p.parent_path() / (p.stem().string() + ".truncated.tif")).string();
}

void runHorizon(const HorizonOptions& o, const CliContext& ctx) {
    if (o.azimuthsDeg.empty() == (o.directions == 0)) throw Error("give either --azimuth DEG [DEG ...] or --directions N");
    checkOutputPath(o.out, o.dem.path);
    const std::string masks = truncationPath(o.out.path);
    checkOutputPath(masks, o.dem.path);
    const DemSource dem = openDem(o.dem, ctx);
    HorizonRequest request;
    request.azimuthsDeg = o.azimuthsDeg;
    for (double az : evenAzimuthsDeg(static_cast<std::size_t>(o.directions))) request.azimuthsDeg.push_back(az);
    request.method = parseHorizonMethod(o.method);
    request.search = o.search.request;
    notePlan(o.search, dem.geometry().terrain, ctx);

    OutputOptions maskOut = o.out;  // the same format and creation options as the horizons
    maskOut.path = masks;
    const RasterRun run = planRasterRun(dem, o.tiling, request.search, 2 * request.azimuthsDeg.size(), ctx);
    const auto start = std::chrono::steady_clock::now();
    const HorizonResult result = runRaster<HorizonResult>(
        run, {{o.out, {{kTruncationMaskKey, masks}}}, {maskOut, {{kTruncationMaskKey, masks}}}}, ctx,
        o.dem.path, [&](const CellWindow& w, const ProgressFn& p) { return horizonProduct(dem, w, request, p); },
        [](const HorizonResult& r) { return std::vector<const ProductResult*>{&r.horizons, &r.truncation}; });
    const double seconds = secondsSince(start);

    const std::size_t bands = request.azimuthsDeg.size();
    const double nsPerCellDir = seconds * 1e9 / static_cast<double>(dem.width() * dem.height() * bands);
    note(ctx, "wrote " + o.out.path + " (" + std::to_string(bands) + (bands == 1 ? " horizon band" : " horizon bands") +
                  ", degrees) and " + masks + " (truncation mask); max distance " +
                  formatDistance(result.maxDistanceM) + "; " + formatSeconds(seconds) + " compute, " +
                  formatNumber(std::round(nsPerCellDir * 10) / 10) + " ns per cell per direction");
}

}  // namespace

void registerHorizon(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<HorizonOptions>();
    CLI::App* cmd = app.add_subcommand("horizon", "Horizon elevation angle maps along true azimuths");
    ctx.outputs[cmd->get_name()].companionKeys = {kTruncationMaskKey};
    addDemArgument(cmd, o->dem);
    addOutputOptions(cmd, o->out);
    auto* az = cmd->add_option("--azimuth", o->azimuthsDeg, "True azimuth(s), degrees clockwise from north (repeatable)")
                   ->expected(1, -1);
    auto* dirs = cmd->add_option("--directions", o->directions, "N azimuths evenly spaced from 0 (0, 360/N, ...)")
                     ->check(finiteRange(1, 4096));
    az->excludes(dirs);
    addSearchOptions(cmd, o->search);
    addTilingOptions(cmd, o->tiling);
    cmd->add_option("--method", o->method, "sweep (fast, default) or reference (brute-force ray march)")
        ->check(CLI::IsMember({"sweep", "reference"}))
        ->capture_default_str();
    cmd->callback([o, &ctx] { runHorizon(*o, ctx); });
}

}  // namespace demlight::cli
