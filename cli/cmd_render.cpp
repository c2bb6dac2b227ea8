// demlight render DEM -o OUT.png --time T [--tz ZONE]: a picture of the lit DEM for a person,
// with the preview rig (lighting/preview.h; DESIGN §3 after Quilez): sun key light with a
// coloured penumbra, sky fill weighted by K from exact horizon sweeps, bounce from opposite the
// sun, albedo 0.2 or a colour raster, gamma only at the end. One pixel per DEM cell.
// The scene plan (--quality, lighting/quality.h) sets the sun-position lattice, the sun's search
// distance (full: the DEM diagonal), and the sky's directions, distance, curvature and
// scan-direction tolerance.
#include "cli/common.h"
#include "cli/image_out.h"
#include "cli/progress_bar.h"
#include "geo/sun_field.h"
#include "geo/time.h"
#include "lighting/preview.h"
#include "lighting/sun_frame.h"
#include "src/error.h"

#include <chrono>
#include <cmath>
#include <optional>

namespace demlight::cli {
namespace {

struct RenderOptions {
    std::string demPath;
    std::string outPath;
    SearchOptions search;
    std::string time;
    std::string tz;
    std::string colorRaster;
    double albedo = PreviewParams{}.albedo;
    double exposure = 1.0;
    std::optional<std::size_t> skyDirections;  ///< default: the scene plan's
    double sunDiameterDeg = kSunDiameterDeg;
};

void runRender(const RenderOptions& o, const CliContext& ctx) {
    const ZonedInstant when = parseZonedInstant(o.time, o.tz);
    checkOutputPath(o.outPath, o.demPath);
    checkImagePath(o.outPath);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;
    std::vector<Grid<float>> albedo;
    if (!o.colorRaster.empty()) albedo = loadAlbedoRaster(o.colorRaster, dem, "--color-raster");

    const auto start = std::chrono::steady_clock::now();
    const ScenePlan plan = planFor(o.search, t, kDefaultLowestElevationDeg, ctx);
    const std::size_t skyDirections = o.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));
    const HorizonParams skyParams = integralParams(o.search, plan, t, skyDirections);
    const SunField field = computeSunField(dem, when.utc, SolarSite{}, SpaOptions{}, plan.sunLatticeStepCells);
    const Normals normals = computeNormals(t, o.search.threads);
    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), "render", t.heightsM.size() * (skyDirections + 1));
    const SunFrame frame =
        computeSunFrame(t, normals, field, sunFrameParams(o.search, o.sunDiameterDeg, plan), &counter);
    const Grid<float> sky = planSkyLight(t, normals, skyDirections, skyParams, &counter);
    bar.finish();
    PreviewParams pp;
    pp.albedo = o.albedo;
    pp.exposure = o.exposure;
    const Image8 image = renderPreview(normals, frame.light.visibility, sky, albedo,
                                       field.centreAzimuthDeg, field.centreElevationDeg, pp,
                                       o.search.threads);
    writeImage(o.outPath, image);
    const double seconds = secondsSince(start);
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(field.centreAzimuthDeg) +
                  " deg, elevation " + formatNumber(field.centreElevationDeg) + " deg (" +
                  formatInstant(when.utc, when.zone) + ")" +
                  (field.centreElevationDeg < 0 ? "; sun below the horizon: twilight sky fill only" : ""));
    note(ctx, "wrote " + o.outPath + " (" + std::to_string(image.width) + " x " +
                  std::to_string(image.height) + "); quality " + std::string(qualityName(plan.quality)) +
                  ": sun max distance " + formatDistance(frame.maxDistanceM) + ", " +
                  std::to_string(skyDirections) + " sky directions to " +
                  formatDistance(skyParams.maxDistanceM) + "; " + formatSeconds(seconds));
}

}  // namespace

void registerRender(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Picture of the lit DEM (PNG, JPEG, EXR, ...) at one instant");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", o->outPath, "Output picture; format from the extension (.png, .jpg, .exr)")
        ->required();
    cmd->add_option("--time", o->time,
                    "Instant: ISO 8601 with offset or Z, or local time with --tz")
        ->required();
    cmd->add_option("--tz", o->tz, "IANA time zone for a local --time (e.g. Europe/Zurich)");
    cmd->add_option("--color-raster", o->colorRaster,
                    "RGB raster used as albedo (resampled to the DEM; 0-255 or 0-1, gamma 2.2)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--albedo", o->albedo, "Linear albedo without a colour raster")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--exposure", o->exposure, "Multiplies linear light before gamma")
        ->check(finiteRange(0.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions for the sky fill (default: " + std::to_string(kAutoSkyDirections) +
                        " with --quality auto, " + std::to_string(kFullSkyDirections) + " with full)")
        ->check(finiteRange(4, 1024));
    cmd->add_option("--sun-diameter", o->sunDiameterDeg,
                    "Angular diameter of the sun disk (degrees); larger = softer shadows")
        ->check(finiteRange(0.0, 20.0))
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runRender(*o, ctx); });
}

}  // namespace demlight::cli
