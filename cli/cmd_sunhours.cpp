// demlight sunhours DEM -o OUT.tif (--date D | --start D --end D) --tz ZONE: hours of direct
// sun, sun and sky irradiation and the cell's own sunrise/sunset over local days
// (demlight/products/sunhours.h).
#include "cli/common.h"
#include "demlight/run/raster_commands.h"
#include "cli/progress_bar.h"
#include "demlight/products/sunhours.h"
#include "demlight/products/timelapse.h"
#include "demlight/core/error.h"

#include <optional>

namespace demlight::cli {
namespace {

struct SunhoursOptions {
    std::string demPath;
    OutputOptions out;
    bool verbose = false;
    SunhoursParameters p;
};

void runSunhours(const SunhoursOptions& o, const CliContext& ctx) {
    const SunhoursRequest request = sunhoursRequest(o.p);
    const auto [r, cells, readSeconds, seconds] =
        runRasterCommand(sunhoursWork(request, o.p), o.demPath, {{o.out, {}}}, &request.search, o.verbose, ctx);
    note(ctx, "wrote " + o.out.path + " (sun_hours, sun_irradiation, sky_irradiation, first_lit, last_lit): " +
                  std::to_string(r.instants) + " instants every " + o.p.step + ", " + std::to_string(r.instantsSwept) +
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
    SunhoursParameters& p = o->p;
    addDemArgument(cmd, o->demPath, p.heights);
    addOutputOptions(cmd, o->out);
    addDayOptions(cmd, p.days, "IANA time zone of the days and clock times (required; UTC for universal time)");
    cmd->add_option("--step", p.step,
                    "Integration step (trapezoid rule), 6 s to 2 h: 10m, 90s, 1h (a bare number = minutes)")
        ->capture_default_str();
    addSunDiameterOption(cmd, p.sunDiameterDeg);
    addCanopyOptions(cmd, p.canopy);
    cmd->add_option("--albedo", p.albedo, "Ground albedo C of the sky term f_sky = K / (1 - C(1 - K)) (0-1)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--sky-directions", p.skyDirections,
                    "Horizon directions of the sky term (default: 16 with --quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    cmd->add_option("--horizon-mode", p.horizonMode,
                    "auto, exact (a sweep per instant along its sun azimuth) or interpolated[:N] (N directions "
                    "swept once, 4..720, 64 by default; each instant's horizons interpolated in azimuth, and the "
                    "sky term from the same N directions; close to exact, not the same bits). auto: interpolated "
                    "for periods of " + std::to_string(kAutoStackMinInstants) +
                    " instants or more (2 days at 10 min) on terrain under --quality auto, where it costs less; "
                    "else exact")
        ->capture_default_str();
    addSearchOptions(cmd, p.search, o->verbose);
    addTilingOptions(cmd, p.tiling);
    cmd->callback([o, &ctx] { ctx.takeCall ? ctx.takeCall(rasterWork(sunhoursWork(o->p))) : runSunhours(*o, ctx); });
}

}  // namespace demlight::cli
