// demlight irradiance DEM -o OUT.tif --time T [--tz ZONE]: beam, diffuse, reflected and global
// irradiance in W m-2 on each cell's surface, ESRA clear sky (demlight/products/irradiance.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/run/raster_commands.h"
#include "cli/point_options.h"
#include "cli/progress_bar.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/point.h"
#include "demlight/core/error.h"

#include <cmath>
#include <memory>
#include <optional>

namespace demlight::cli {
namespace {

struct IrradianceOptions {
    std::unique_ptr<RasterCommandOf<IrradianceParameters>> command = irradianceCommand();
    std::string& demPath = command->demPath;
    OutputOptions& out = command->out;
    bool& verbose = command->verbose;
    PointOptions point;
    IrradianceParameters& p = command->values;
};

void printIrradianceAt(const IrradianceOptions& o, const PointSpec& spec, const CliContext& ctx) {
    refuseRasterOptions(o.p.tiling);
    const IrradianceRequest request = irradianceRequest(o.p);
    const DemSource dem = openPointDem({o.demPath, o.p.heights}, request.search, ctx);
    const PointIrradiance p = pointIrradiance(dem, locatePoint(dem, spec), request);
    nlohmann::ordered_json j;
    j["point"] = pointJson(p.point);
    j["time_utc"] = formatInstant(request.time.utc, std::string());
    j["method"] = "reference ray march";
    j["sun_azimuth_deg"] = p.sunAzimuthDeg;
    j["sun_elevation_deg"] = p.sunElevationDeg;
    j["extraterrestrial_wm2"] = p.extraterrestrialWm2;
    j["linke"] = p.linke;
    j["albedo"] = request.albedo;
    j["coeff_bh"] = request.coeffBh;
    j["coeff_dh"] = request.coeffDh;
    j["diffuse_model"] = o.p.sky.diffuseModel;
    j["max_distance_m"] = p.maxDistanceM;
    j["horizon_at_sun_deg"] = p.horizonAtSunDeg;
    j["sun_visibility"] = p.sunVisibility;
    j["sky_k0"] = p.skyK0 ? nlohmann::ordered_json(*p.skyK0) : nlohmann::ordered_json(nullptr);
    j["sky_directions"] = p.skyDirections;
    j["beam_wm2"] = p.irradiance.beam;
    j["diffuse_wm2"] = p.irradiance.diffuse;
    j["reflected_wm2"] = p.irradiance.reflected;
    j["global_wm2"] = p.irradiance.global();
    printPoint(o.point, j,
               {"time_utc", "sun_azimuth_deg", "sun_elevation_deg", "horizon_at_sun_deg", "sun_visibility", "beam_wm2",
                "diffuse_wm2", "reflected_wm2", "global_wm2"},
               {{formatInstant(request.time.utc, std::string()), formatNumber(p.sunAzimuthDeg),
                 formatNumber(p.sunElevationDeg), formatNumber(p.horizonAtSunDeg), formatNumber(p.sunVisibility),
                 formatNumber(p.irradiance.beam), formatNumber(p.irradiance.diffuse),
                 formatNumber(p.irradiance.reflected), formatNumber(p.irradiance.global())}});
}

void runIrradiance(const IrradianceOptions& o, const CliContext& ctx) {
    if (const auto spec = pointOf(o.point)) return printIrradianceAt(o, *spec, ctx);
    requireOutputOrPoint(o.out, o.point);
    const IrradianceRequest request = irradianceRequest(o.p);
    if (request.diffuseModel == DiffuseModel::RSun && o.p.skyDirections)
        note(ctx, "note: --sky-directions is used by --diffuse-model visible-sky only; rsun sweeps the sun's azimuth");
    const auto [r, cells, readSeconds, seconds] =
        runRasterCommand(irradianceWork(request, o.p), o.demPath, {{o.out, {}}}, &request.search, o.verbose, ctx);
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(r.centreAzimuthDeg) + " deg, elevation " +
                  formatNumber(r.centreElevationDeg) + " deg (" + formatInstant(request.time.utc, std::string()) +
                  "); extraterrestrial " + formatNumber(std::round(r.extraterrestrialWm2 * 10) / 10) + " W/m2, Linke " +
                  formatNumber(r.linke) + (r.centreElevationDeg > 0 ? "" : "; the sun is below the horizon: all zero"));
    note(ctx, "wrote " + o.out.path + " (beam, diffuse, reflected, global in W/m2; diffuse model " + o.p.sky.diffuseModel +
                  "), " + formatSeconds(seconds) + " compute");
}

}  // namespace

void registerIrradiance(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<IrradianceOptions>();
    declarePointOptions(o->command->declaration(), o->point);
    CLI::App* cmd = addDeclaredCommand(app, o->command->declaration(), ctx);
    cmd->callback([o, &ctx] { runIrradiance(*o, ctx); });
}

}  // namespace demlight::cli
