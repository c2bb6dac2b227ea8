// demlight irradiance DEM -o OUT.tif --time T [--tz ZONE]: beam, diffuse, reflected and global
// irradiance in W m-2 on each cell's surface, ESRA clear sky (products/irradiance.h).
#include "cli/clear_sky_options.h"
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "products/irradiance.h"
#include "src/error.h"

#include <cmath>
#include <optional>

namespace demlight::cli {
namespace {

struct IrradianceOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    SearchOptions search;
    ClearSkyOptions sky;
    std::string time, tz;
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
};

/// Bands of the output: beam, diffuse, reflected, global.
constexpr std::size_t kIrradianceBands = 4;

IrradianceRequest irradianceRequest(const IrradianceOptions& o) {
    IrradianceRequest request;
    request.time = parseTimeOptions(o.time, o.tz);
    request.linke = parseLinkeOption(o.sky.linke);
    request.albedo = o.sky.albedo;
    request.coeffBh = o.sky.coeffBh;
    request.coeffDh = o.sky.coeffDh;
    request.diffuseModel = parseDiffuseModel(o.sky.diffuseModel);
    request.solarConstantWm2 = o.sky.solarConstantWm2;
    request.skyDirections = o.skyDirections;
    request.sunDiameterDeg = o.sunDiameterDeg;
    request.search = o.search.request;
    linkeFor(request);  // a bad --linke fails before the DEM is read
    return request;
}

RasterCall irradianceCall(const IrradianceOptions& o) {
    return singleRasterCall(
        "irradiance", o.dem, o.tiling, o.search.request, productTileBytes(kIrradianceBands),
        [request = irradianceRequest(o)](const DemSource& dem, const CellWindow& w, const ProgressFn& p) {
            return irradianceProduct(dem, w, request, p);
        });
}

void runIrradiance(const IrradianceOptions& o, const CliContext& ctx) {
    const IrradianceRequest request = irradianceRequest(o);
    if (request.diffuseModel == DiffuseModel::RSun && o.skyDirections)
        note(ctx, "note: --sky-directions is used by --diffuse-model visible-sky only; rsun sweeps the sun's azimuth");
    checkOutputPath(o.out, o.dem.path);
    const DemSource dem = openDem(o.dem, ctx);
    notePlan(o.search, dem.geometry().terrain, ctx);
    const RasterRun run = planRasterRun(dem, o.tiling, request.search, productTileBytes(kIrradianceBands), ctx);
    const auto start = std::chrono::steady_clock::now();
    const IrradianceResult r = runRaster<IrradianceResult>(
        run, {{o.out, {}}}, ctx, o.dem.path,
        [&](const CellWindow& w, const ProgressFn& p) { return irradianceProduct(dem, w, request, p); },
        [](const IrradianceResult& s) { return std::vector<const ProductResult*>{&s}; });
    const double seconds = secondsSince(start);
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(r.centreAzimuthDeg) + " deg, elevation " +
                  formatNumber(r.centreElevationDeg) + " deg (" + formatInstant(request.time.utc, std::string()) +
                  "); extraterrestrial " + formatNumber(std::round(r.extraterrestrialWm2 * 10) / 10) + " W/m2, Linke " +
                  formatNumber(r.linke) + (r.centreElevationDeg > 0 ? "" : "; the sun is below the horizon: all zero"));
    note(ctx, "wrote " + o.out.path + " (beam, diffuse, reflected, global in W/m2; diffuse model " + o.sky.diffuseModel +
                  "), " + formatSeconds(seconds) + " compute");
}

}  // namespace

void registerIrradiance(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<IrradianceOptions>();
    CLI::App* cmd = app.add_subcommand(
        "irradiance", "Clear-sky solar irradiance (W/m2) at one instant: beam, diffuse, reflected, global (ESRA)");
    addDemArgument(cmd, o->dem);
    addOutputOptions(cmd, o->out);
    addTimeOptions(cmd, o->time, o->tz);
    addClearSkyOptions(cmd, o->sky, "--time in its zone");
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions of the visible sky (default: 16 with --quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    addSunDiameterOption(cmd, o->sunDiameterDeg);
    addSearchOptions(cmd, o->search);
    addTilingOptions(cmd, o->tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(irradianceCall(*o)) : runIrradiance(*o, ctx); });
}

}  // namespace demlight::cli
