// demlight sunhours DEM -o OUT.tif (--date D | --start D --end D) --tz ZONE: hours of direct
// sun, sun and sky irradiation and the cell's own sunrise/sunset over local days
// (demlight/products/sunhours.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/run/raster_commands.h"
#include "cli/progress_bar.h"
#include "demlight/products/sunhours.h"
#include "demlight/products/timelapse.h"
#include "demlight/core/error.h"

#include <memory>
#include <optional>

namespace demlight::cli {
namespace {

struct SunhoursOptions {
    std::unique_ptr<RasterCommandOf<SunhoursParameters>> command = sunhoursCommand();
    std::string& demPath = command->demPath;
    OutputOptions& out = command->out;
    bool& verbose = command->verbose;
    SunhoursParameters& p = command->values;
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
    CLI::App* cmd = addDeclaredCommand(app, o->command->declaration(), ctx);
    cmd->callback([o, &ctx] { runSunhours(*o, ctx); });
}

}  // namespace demlight::cli
