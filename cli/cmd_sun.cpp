// demlight sun DEM -o OUT.tif --time T [--tz ZONE]: how much of the sun's disk each cell sees
// (demlight/products/sun.h).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "demlight/products/sun.h"

#include <optional>

namespace demlight::cli {
namespace {

struct SunOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    SearchOptions search;
    std::string time, tz;
    double sunDiameterDeg = kSunDiameterDeg;
    Atmosphere atmosphere;
    std::string model = "horizon";
    std::optional<std::size_t> directions;
    CanopyRequest canopy;
};

/// Bands of the output: sun_visibility, sun_irradiance.
constexpr std::size_t kSunBands = 2;

SunRequest sunRequest(const SunOptions& o) {
    SunRequest request;
    request.time = parseTimeOptions(o.time, o.tz);
    request.model = parseSunModel(o.model);
    request.sunDiameterDeg = o.sunDiameterDeg;
    request.atmosphere = o.atmosphere;
    request.directions = o.directions;
    request.canopy = o.canopy;
    request.search = o.search.request;
    return request;
}

RasterCall sunCall(const SunOptions& o) {
    return singleRasterCall("sun", o.dem, o.tiling, o.search.request, productTileBytes(kSunBands),
                            [request = sunRequest(o)](const DemSource& dem, const CellWindow& w, const ProgressFn& p) {
                                return sunProduct(dem, w, request, p);
                            });
}

void runSun(const SunOptions& o, const CliContext& ctx) {
    const SunRequest request = sunRequest(o);
    if (request.model == SunModel::Horizon && o.directions)
        note(ctx, "note: --sky-directions is used by the aperture models only; --model horizon sweeps the sun's azimuth");
    checkOutputPath(o.out, o.dem.path);
    const DemSource dem = openDem(o.dem, ctx);
    notePlan(o.search, dem.geometry().terrain, ctx);
    const RasterRun run = planRasterRun(dem, o.tiling, request.search, productTileBytes(kSunBands), ctx);
    const auto start = std::chrono::steady_clock::now();
    const SunResult r = runRaster<SunResult>(
        run, {{o.out, {}}}, ctx, o.dem.path,
        [&](const CellWindow& w, const ProgressFn& p) { return sunProduct(dem, w, request, p); },
        [](const SunResult& s) { return std::vector<const ProductResult*>{&s}; });
    const double seconds = secondsSince(start);
    const std::string sweeps = request.model == SunModel::Horizon
                                   ? std::to_string(r.sweepRegions) + " sweep region(s), " + r.strategy + " strategy"
                                   : std::to_string(r.directions) + " aperture directions";
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(r.centreAzimuthDeg) + " deg, elevation " +
                  formatNumber(r.centreElevationDeg) + " deg (" + formatInstant(request.time.utc, std::string()) + ")" +
                  (r.sunUp ? "" : "; the sun is below the horizon: everything is in shadow"));
    note(ctx, "wrote " + o.out.path + " (band 1 sun_visibility, band 2 sun_irradiance); model " + o.model + ", " +
                  sweeps + ", max distance " + formatDistance(r.maxDistanceM) + ", " + formatSeconds(seconds) +
                  " compute");
}

}  // namespace

void registerSun(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SunOptions>();
    CLI::App* cmd = app.add_subcommand("sun", "Sun visibility and direct-sun irradiance at one instant");
    addDemArgument(cmd, o->dem);
    addOutputOptions(cmd, o->out);
    addTimeOptions(cmd, o->time, o->tz);
    addSunDiameterOption(cmd, o->sunDiameterDeg);
    addCanopyOptions(cmd, o->canopy);
    cmd->add_option("--pressure", o->atmosphere.pressureHpa, "Air pressure for solar refraction (hPa)")
        ->check(finiteRange(0, kMaxPressureHpa))
        ->capture_default_str();
    cmd->add_option("--temperature", o->atmosphere.temperatureC, "Air temperature for solar refraction (C)")
        ->check(finiteRange(-100, 100))
        ->capture_default_str();
    cmd->add_option("--model", o->model,
                    "Sun model: horizon (horizon angle in the sun's azimuth), aperture (sun cap intersected with "
                    "the ambient-aperture cap), aperture-smooth (the same with the smoothstep intersection)")
        ->capture_default_str();
    cmd->add_option("--sky-directions,--directions", o->directions,
                    "Aperture models: number of horizon directions integrated into the aperture (default: 16 with "
                    "--quality auto, 64 with full); --directions is the older spelling")
        ->check(finiteRange(4, 1024));
    addSearchOptions(cmd, o->search);
    addTilingOptions(cmd, o->tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(sunCall(*o)) : runSun(*o, ctx); });
}

}  // namespace demlight::cli
