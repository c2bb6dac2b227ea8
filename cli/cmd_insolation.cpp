// demlight insolation DEM -o OUT.tif (--date D | --start D --end D | --month M | --year Y) --tz ZONE:
// beam, diffuse, reflected and global irradiation in kWh m-2 and hours of direct sun over a
// period of local days or times, by binned sun positions (demlight/products/insolation.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/run/raster_commands.h"
#include "cli/point_options.h"
#include "cli/progress_bar.h"
#include "demlight/products/insolation.h"
#include "demlight/products/point.h"
#include "demlight/core/error.h"

#include <memory>
#include <optional>

namespace demlight::cli {
namespace {

struct InsolationOptions {
    std::unique_ptr<RasterCommandOf<InsolationParameters>> command = insolationCommand();
    std::string& demPath = command->demPath;
    OutputOptions& out = command->out;
    bool& verbose = command->verbose;
    PointOptions point;
    InsolationParameters& p = command->values;
};

/// --at / --at-xy: the irradiation of one cell, every instant with its own sun and horizon, printed.
void printInsolationAt(const InsolationOptions& o, const PointSpec& spec, const CliContext& ctx) {
    refuseRasterOptions(o.p.tiling);
    const InsolationRequest request = insolationRequest(o.p);
    const DemSource dem = openPointDem({o.demPath, o.p.heights}, request.search, ctx);
    const PointInsolation p = pointInsolation(dem, locatePoint(dem, spec), request);
    const std::string start = formatInstant(p.start, request.zone), end = formatInstant(p.end, request.zone);
    nlohmann::ordered_json j;
    j["point"] = pointJson(p.point);
    j["start"] = start;
    j["end"] = end;
    j["step_s"] = std::chrono::duration<double>(request.step).count();
    j["instants"] = p.instants;
    j["sun_up_instants"] = p.sunUpInstants;
    j["method"] = "per instant, reference ray march";
    j["linke"] = formatNumberList(request.linke);
    j["albedo"] = request.albedo;
    j["coeff_bh"] = request.coeffBh;
    j["coeff_dh"] = request.coeffDh;
    j["diffuse_model"] = o.p.sky.diffuseModel;
    j["max_distance_m"] = p.maxDistanceM;
    j["sky_k0"] = p.skyK0 ? nlohmann::ordered_json(*p.skyK0) : nlohmann::ordered_json(nullptr);
    j["sky_directions"] = p.skyDirections;
    j["beam_kwh_m2"] = p.irradiation.beam;
    j["diffuse_kwh_m2"] = p.irradiation.diffuse;
    j["reflected_kwh_m2"] = p.irradiation.reflected;
    j["global_kwh_m2"] = p.irradiation.global();
    j["sun_hours"] = p.sunHours;
    printPoint(o.point, j,
               {"start", "end", "beam_kwh_m2", "diffuse_kwh_m2", "reflected_kwh_m2", "global_kwh_m2", "sun_hours"},
               {{start, end, formatNumber(p.irradiation.beam), formatNumber(p.irradiation.diffuse),
                 formatNumber(p.irradiation.reflected), formatNumber(p.irradiation.global()),
                 formatNumber(p.sunHours)}});
}

void runInsolation(const InsolationOptions& o, const CliContext& ctx) {
    if (const auto spec = pointOf(o.point)) return printInsolationAt(o, *spec, ctx);
    requireOutputOrPoint(o.out, o.point);
    const InsolationRequest request = insolationRequest(o.p);
    const auto [r, cells, readSeconds, seconds] =
        runRasterCommand(insolationWork(request, o.p), o.demPath, {{o.out, {}}}, &request.search, o.verbose, ctx);
    note(ctx, "wrote " + o.out.path + " (beam, diffuse, reflected, global in kWh/m2, sun_hours; diffuse model " +
                  o.p.sky.diffuseModel + "): " + std::to_string(r.instants) + " instants every " + o.p.step + " in " +
                  std::to_string(r.bins) + " bins of " + std::to_string(r.directions) + " azimuth sectors, " +
                  formatSeconds(seconds) + " compute");
}

}  // namespace

void registerInsolation(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<InsolationOptions>();
    declarePointOptions(o->command->declaration(), o->point);
    CLI::App* cmd = addDeclaredCommand(app, o->command->declaration(), ctx);
    cmd->callback([o, &ctx] { runInsolation(*o, ctx); });
}

}  // namespace demlight::cli
