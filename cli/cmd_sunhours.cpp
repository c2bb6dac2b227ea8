// demlight sunhours DEM -o OUT.tif (--date D | --start D --end D) --tz ZONE: hours of direct
// sun, sun and sky irradiation and the cell's own sunrise/sunset over local days
// (demlight/products/sunhours.h).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "demlight/products/sunhours.h"
#include "demlight/products/timelapse.h"
#include "demlight/core/error.h"

#include <optional>

namespace demlight::cli {
namespace {

struct SunhoursOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    CanopyRequest canopy;
    SearchOptions search;
    DayOptions days;
    std::string step = "10m";
    double sunDiameterDeg = kSunDiameterDeg;
    double albedo = kDefaultAlbedo;
    std::optional<std::size_t> skyDirections;
    std::string horizonMode = "auto";
};

SunhoursRequest sunhoursRequest(const SunhoursOptions& o) {
    SunhoursRequest r;
    const LocalDays days = parseDayOptions(o.days, "sunhours");
    r.zone = days.zone;
    r.firstDay = days.first;
    r.lastDay = days.last;
    r.step = parseStepOption(o.step, std::chrono::minutes(1));
    if (r.step < std::chrono::seconds(6) || r.step > std::chrono::hours(2))
        throw Error("--step " + o.step + ": must be from 6 s to 2 h");
    r.sunDiameterDeg = o.sunDiameterDeg;
    r.albedo = o.albedo;
    r.skyDirections = o.skyDirections;
    if (o.horizonMode != "auto") r.stackDirections = parseHorizonMode(o.horizonMode, "--horizon-mode");
    r.canopy = o.canopy;
    r.search = o.search.request;
    return r;
}

/// Bands of the output: sun_hours, sun_irradiation, sky_irradiation, first_lit, last_lit.
constexpr std::size_t kSunhoursBands = 5;

/// Grids per cell a window holds (for tile sizes): the bands, and the stack's directions (under
/// `auto` those of a stack wherever the period may take one: the plan is not made yet).
TileBytes sunhoursGrids(const SunhoursRequest& r) {
    return productTileBytes(kSunhoursBands + sunhoursStackDirectionsAtMost(r));
}

RasterCall sunhoursCall(const SunhoursOptions& o) {
    SunhoursRequest request = sunhoursRequest(o);
    // The memory of tiles counts the stack's directions too.
    return singleRasterCall("sunhours", o.dem, o.tiling, o.search.request, sunhoursGrids(request),
                            [request](const DemSource& dem, const CellWindow& w, const ProgressFn& p) {
                                return sunhoursProduct(dem, w, request, p);
                            });
}

void runSunhours(const SunhoursOptions& o, const CliContext& ctx) {
    const SunhoursRequest request = sunhoursRequest(o);
    checkOutputPath(o.out, o.dem.path);
    const DemSource dem = openDem(o.dem, ctx);
    notePlan(o.search, dem.geometry().terrain, ctx);
    // Tiles are sized for the bands and the stack's directions.
    const RasterRun run = planRasterRun(dem, o.tiling, request.search, sunhoursGrids(request), ctx);
    const auto start = std::chrono::steady_clock::now();
    const SunhoursResult r = runRaster<SunhoursResult>(
        run, {{o.out, {}}}, ctx, o.dem.path,
        [&](const CellWindow& w, const ProgressFn& p) { return sunhoursProduct(dem, w, request, p); },
        [](const SunhoursResult& s) { return std::vector<const ProductResult*>{&s}; });
    const double seconds = secondsSince(start);
    note(ctx, "wrote " + o.out.path + " (sun_hours, sun_irradiation, sky_irradiation, first_lit, last_lit): " +
                  std::to_string(r.instants) + " instants every " + o.step + ", " + std::to_string(r.instantsSwept) +
                  " with the sun up, horizons " +
                  (r.stackDirections > 0 ? "interpolated from " + std::to_string(r.stackDirections) + " directions"
                                         : std::string("swept exactly per instant")) +
                  ", " + formatSeconds(seconds) + " compute");
}

}  // namespace

void registerSunhours(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SunhoursOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sunhours", "Hours of direct sun, sun and sky irradiation and first/last lit time over local days");
    addDemArgument(cmd, o->dem);
    addOutputOptions(cmd, o->out);
    addDayOptions(cmd, o->days, "IANA time zone of the days and clock times (required; UTC for universal time)");
    cmd->add_option("--step", o->step,
                    "Integration step (trapezoid rule), 6 s to 2 h: 10m, 90s, 1h (a bare number = minutes)")
        ->capture_default_str();
    addSunDiameterOption(cmd, o->sunDiameterDeg);
    addCanopyOptions(cmd, o->canopy);
    cmd->add_option("--albedo", o->albedo, "Ground albedo C of the sky term f_sky = K / (1 - C(1 - K)) (0-1)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions of the sky term (default: 16 with --quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    cmd->add_option("--horizon-mode", o->horizonMode,
                    "auto, exact (a sweep per instant along its sun azimuth) or interpolated[:N] (N directions "
                    "swept once, 4..720, 64 by default; each instant's horizons interpolated in azimuth, and the "
                    "sky term from the same N directions; close to exact, not the same bits). auto: interpolated "
                    "for periods of " + std::to_string(kAutoStackMinInstants) +
                    " instants or more (2 days at 10 min) on terrain under --quality auto, where it costs less; "
                    "else exact")
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    addTilingOptions(cmd, o->tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(sunhoursCall(*o)) : runSunhours(*o, ctx); });
}

}  // namespace demlight::cli
