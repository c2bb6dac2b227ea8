// demlight irradiance DEM -o OUT.tif --time T [--tz ZONE]: beam, diffuse, reflected and global
// irradiance in W m-2 on each cell's surface, ESRA clear sky (products/irradiance.h).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "products/irradiance.h"
#include "src/error.h"

#include <cmath>
#include <optional>
#include <sstream>

namespace demlight::cli {
namespace {

struct IrradianceOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    SearchOptions search;
    std::string time, tz;
    std::string linke = formatNumber(kDefaultLinke);
    double albedo = kDefaultAlbedo;
    double coeffBh = 1, coeffDh = 1;
    std::string diffuseModel = "visible-sky";
    double solarConstantWm2 = kSolarConstantWm2;
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
};

/// "3.2" or twelve comma-separated numbers; the product checks the count and range.
std::vector<double> parseLinke(const std::string& text) {
    std::vector<double> values;
    std::stringstream ss(text);
    std::string part;
    while (std::getline(ss, part, ',')) {
        std::size_t used = 0;
        double v = 0;
        try {
            v = std::stod(part, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        while (used < part.size() && part[used] == ' ') ++used;
        if (used == 0 || used != part.size() || !std::isfinite(v))
            throw Error("--linke '" + text + "': expected a number or 12 comma-separated monthly numbers like 3.1");
        values.push_back(v);
    }
    if (values.empty()) throw Error("--linke '" + text + "': expected a number or 12 comma-separated monthly numbers");
    return values;
}

void runIrradiance(const IrradianceOptions& o, const CliContext& ctx) {
    IrradianceRequest request;
    request.time = parseTimeOptions(o.time, o.tz);
    request.linke = parseLinke(o.linke);
    request.albedo = o.albedo;
    request.coeffBh = o.coeffBh;
    request.coeffDh = o.coeffDh;
    request.diffuseModel = parseDiffuseModel(o.diffuseModel);
    request.solarConstantWm2 = o.solarConstantWm2;
    request.skyDirections = o.skyDirections;
    request.sunDiameterDeg = o.sunDiameterDeg;
    request.search = o.search.request;
    linkeFor(request);  // a bad --linke fails before the DEM is read
    if (request.diffuseModel == DiffuseModel::RSun && o.skyDirections)
        note(ctx, "note: --sky-directions is used by --diffuse-model visible-sky only; rsun sweeps the sun's azimuth");
    checkOutputPath(o.out, o.dem.path);
    const DemSource dem = openDem(o.dem);
    notePlan(o.search, dem.dem().terrain, ctx);
    const RasterRun run = planRasterRun(dem, o.tiling, request.search, 4, ctx);
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
    note(ctx, "wrote " + o.out.path + " (beam, diffuse, reflected, global in W/m2; diffuse model " + o.diffuseModel +
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
    cmd->add_option("--linke", o->linke,
                    "Linke turbidity factor (air mass 2, 1-10): one value, or 12 comma-separated monthly values "
                    "(January first) of which the month of --time in its zone is used")
        ->capture_default_str();
    cmd->add_option("--albedo", o->albedo, "Ground albedo of the reflected component (0-1)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--coeff-bh", o->coeffBh,
                    "Real-sky beam index: fraction of the clear-sky beam that reaches the ground (0-1, r.sun coeff_bh)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--coeff-dh", o->coeffDh,
                    "Real-sky diffuse index: fraction of the clear-sky diffuse that reaches the ground (0-1, r.sun "
                    "coeff_dh)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--diffuse-model", o->diffuseModel,
                    "visible-sky: diffuse horizontal x the sky the horizons leave above the horizontal, reflected "
                    "from the rest of the view; rsun: r.sun's Muneer tilted-surface diffuse and (1 - cos slope)/2 "
                    "reflected")
        ->check(CLI::IsMember({"visible-sky", "rsun"}))
        ->capture_default_str();
    cmd->add_option("--solar-constant", o->solarConstantWm2,
                    "Solar constant (W/m2); the extraterrestrial irradiance is this / R^2 at the sun-earth distance R")
        ->check(finiteRange(1000, 1500))
        ->capture_default_str();
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions of the visible sky (default: 16 with --quality auto, 64 with full)")
        ->check(finiteRange(4, 1024));
    addSunDiameterOption(cmd, o->sunDiameterDeg);
    addSearchOptions(cmd, o->search);
    addTilingOptions(cmd, o->tiling);
    cmd->callback([o, &ctx] { runIrradiance(*o, ctx); });
}

}  // namespace demlight::cli
