// demlight view DEM -o OUT.png --time T [--tz ZONE]: an oblique, perspective picture of the lit
// terrain through an atmosphere (demlight/products/view.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "cli/view_options.h"
#include "demlight/geo/image_out.h"
#include "demlight/products/view.h"

namespace demlight::cli {
namespace {

struct ViewOptions {
    ParameterSet set{"view", "Oblique perspective picture of the lit terrain through haze, with sky"};
    DemOptions dem;
    std::string outPath;
    SearchOptions search;
    std::string time, tz;
    ViewCameraOptions camera;
    std::string colorRaster, colorEncoding = "auto";
    std::optional<double> albedo;
    double exposure = 1;
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
};

ViewRequest viewRequest(const ViewOptions& o) {
    ViewRequest r;
    r.time = parseTimeOptions(o.time, o.tz);
    applyViewCameraOptions(o.camera, r);
    r.colorRaster = o.colorRaster;
    r.colorEncoding = parseColorEncoding(o.colorEncoding, "--color-encoding");
    r.albedo = o.albedo;
    r.exposure = o.exposure;
    r.skyDirections = o.skyDirections;
    r.sunDiameterDeg = o.sunDiameterDeg;
    r.search = o.search.request;
    return r;
}

void runView(const ViewOptions& o, const CliContext& ctx) {
    const ViewRequest request = viewRequest(o);
    checkOutputPath(o.outPath, o.dem.path);
    checkImagePath(o.outPath);
    const DemSource dem = openDem(o.dem, ctx);
    notePlan(o.search, dem.geometry().terrain, ctx);
    const auto start = std::chrono::steady_clock::now();
    ProgressBar bar(!ctx.quiet);
    const ViewResult r = viewProduct(dem, request, bar.callback());
    bar.finish();
    writeImage(o.outPath, r.view.image);
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(r.sunAzimuthDeg) + " deg, elevation " +
                  formatNumber(r.sunElevationDeg) + " deg (" + formatInstant(request.time.utc, request.time.zone) + ")");
    note(ctx, "camera at " + formatNumber(r.eyeLatitudeDeg) + ", " + formatNumber(r.eyeLongitudeDeg) + ", " +
                  formatNumber(r.eyeHeightM) + " m, " + formatDistance(r.distanceToTargetM) + " from its target");
    note(ctx, "wrote " + o.outPath + " (" + std::to_string(r.view.image.width) + " x " +
                  std::to_string(r.view.image.height) + "); light " + formatSeconds(r.lightSeconds) + " (" +
                  std::to_string(r.skyDirections) + " sky directions), view " + formatSeconds(r.renderSeconds) +
                  ", in all " + formatSeconds(secondsSince(start)));
}


}  // namespace

void registerView(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<ViewOptions>();
    ParameterSet& set = o->set;
    declareDemOptions(set, o->dem);
    declarePictureOutput(set, o->outPath, ".png, .jpg, .exr");
    declareTime(set, o->time, o->tz);
    declareViewCameraOptions(set, o->camera);
    declareColorRaster(set, o->colorRaster, o->colorEncoding, "the ground's albedo per channel");
    set.add("albedo", o->albedo, "Ground albedo",
            "Grey ground albedo (0-1) instead of the default landscape (vegetation, rock, snow by height and slope)")
        .within(0.0, 1.0)
        .notWith("color_raster");
    set.add("exposure", o->exposure, "Exposure", "Multiplies linear light before gamma").within(0, 1000);
    set.add("sky_directions", o->skyDirections, "Sky directions",
            "Horizon directions of the sky term (default: " + std::to_string(kAutoSkyDirections) + " with {quality} auto, " +
                std::to_string(kFullSkyDirections) + " with full)")
        .within(1, 1024);
    declareSunDiameter(set, o->sunDiameterDeg);
    declareSearchOptions(set, o->search);
    notInPython(set);
    CLI::App* cmd = addDeclaredCommand(app, set, ctx);
    ctx.outputs[cmd->get_name()].kind = "picture";
    cmd->callback([o, &ctx] { runView(*o, ctx); });
}

}  // namespace demlight::cli
