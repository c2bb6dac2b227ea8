// demlight render DEM -o OUT.png --time T [--tz ZONE]: a picture of the lit DEM for a person
// (demlight/products/render.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/geo/image_out.h"
#include "cli/progress_bar.h"
#include "demlight/products/render.h"

#include <optional>

namespace demlight::cli {
namespace {

struct RenderOptions {
    ParameterSet set{"render", "Picture of the lit DEM (PNG, JPEG, EXR, ...) at one instant"};
    DemOptions dem;
    std::string outPath;
    SearchOptions search;
    std::string time, tz;
    PictureOptions picture;
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
};

void runRender(const RenderOptions& o, const CliContext& ctx) {
    RenderRequest request;
    request.time = parseTimeOptions(o.time, o.tz);
    request.picture = pictureRequest(o.picture);
    request.skyDirections = o.skyDirections;
    request.sunDiameterDeg = o.sunDiameterDeg;
    request.search = o.search.request;
    checkOutputPath(o.outPath, o.dem.path);
    checkImagePath(o.outPath);
    const DemSource dem = openDem(o.dem, ctx);
    notePlan(o.search, dem.geometry().terrain, ctx);
    const auto start = std::chrono::steady_clock::now();
    ProgressBar bar(!ctx.quiet);
    const RenderResult r = renderProduct(dem, request, bar.callback());
    bar.finish();
    writeImage(o.outPath, r.image);
    const double seconds = secondsSince(start);
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(r.centreAzimuthDeg) + " deg, elevation " +
                  formatNumber(r.centreElevationDeg) + " deg (" + formatInstant(request.time.utc, request.time.zone) +
                  ")" + (r.centreElevationDeg < 0 ? "; sun below the horizon: twilight sky fill only" : ""));
    note(ctx, "wrote " + o.outPath + " (" + std::to_string(r.image.width) + " x " + std::to_string(r.image.height) +
                  "); quality " + std::string(qualityName(r.quality)) + ": sun max distance " +
                  formatDistance(r.sunMaxDistanceM) + ", " + std::to_string(r.skyDirections) + " sky directions to " +
                  formatDistance(r.skyMaxDistanceM) + "; " + formatSeconds(seconds));
}

}  // namespace

void registerRender(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<RenderOptions>();
    ParameterSet& set = o->set;
    declareDemOptions(set, o->dem);
    declarePictureOutput(set, o->outPath, ".png, .jpg, .exr");
    declareTime(set, o->time, o->tz);
    declarePictureOptions(set, o->picture);
    set.add("sky_directions", o->skyDirections, "Sky directions",
            "Horizon directions for the sky fill (default: " + std::to_string(kAutoSkyDirections) +
                " with {quality} auto, " + std::to_string(kFullSkyDirections) + " with full)")
        .within(4, 1024);
    declareSunDiameter(set, o->sunDiameterDeg);
    declareSearchOptions(set, o->search);
    notInPython(set);
    CLI::App* cmd = addDeclaredCommand(app, set, ctx);
    ctx.outputs[cmd->get_name()].kind = "picture";
    cmd->callback([o, &ctx] { runRender(*o, ctx); });
}

}  // namespace demlight::cli
