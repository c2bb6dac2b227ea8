// demlight view DEM -o OUT.png --time T [--tz ZONE]: an oblique, perspective picture of the lit
// terrain through an atmosphere (products/view.h).
#include "cli/common.h"
#include "geo/image_out.h"
#include "products/view.h"

#include <sstream>

namespace demlight::cli {
namespace {

struct ViewOptions {
    DemOptions dem;
    std::string outPath;
    SearchOptions search;
    std::string time, tz;
    double cameraAzimuthDeg = ViewCameraRequest{}.azimuthDeg, cameraElevationDeg = ViewCameraRequest{}.elevationDeg;
    std::optional<double> cameraDistanceM;
    std::string eye, eyeXy, target, targetXy;
    double fovDeg = ViewCameraRequest{}.fieldOfViewDeg;
    std::string size = "1280x720";
    double exaggeration = 1;
    std::string colorRaster, colorEncoding = "auto";
    std::optional<double> albedo;
    double treeLineM = ViewRequest{}.treeLineM, snowLineM = ViewRequest{}.snowLineM;
    double exposure = 1;
    bool noHaze = false, noSky = false;
    double visibilityKm = ViewAtmosphere{}.visibilityKm;
    std::string nodata = "hole";
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
};

/// "A,B" or "A,B,H" as numbers; `heightRequired` refuses the first.
ViewPoint parsePoint(const std::string& text, const std::string& option, bool wgs84, bool heightRequired) {
    const std::string form = wgs84 ? (heightRequired ? "LAT,LON,HEIGHT" : "LAT,LON[,HEIGHT]")
                                   : (heightRequired ? "X,Y,HEIGHT" : "X,Y[,HEIGHT]");
    const auto bad = [&] { return Error(option + " '" + text + "': expected " + form + " (degrees or CRS units, metres)"); };
    std::vector<double> v;
    std::stringstream ss(text);
    std::string part;
    while (std::getline(ss, part, ',')) {
        const std::optional<double> x = parseFiniteNumber(part);
        if (!x) throw bad();
        v.push_back(*x);
    }
    if (v.size() < (heightRequired ? 3u : 2u) || v.size() > 3) throw bad();
    ViewPoint p{v[0], v[1], std::nullopt, wgs84};
    if (v.size() == 3) p.heightM = v[2];
    return p;
}

std::pair<std::size_t, std::size_t> parseSize(const std::string& text) {
    const std::size_t x = text.find('x');
    const auto bad = [&] { return Error("--size '" + text + "': expected WIDTHxHEIGHT in pixels, like 1920x1080"); };
    if (x == std::string::npos) throw bad();
    const std::optional<double> w = parseFiniteNumber(text.substr(0, x)), h = parseFiniteNumber(text.substr(x + 1));
    if (!w || !h || *w < 1 || *h < 1 || *w != std::floor(*w) || *h != std::floor(*h) || *w > 16384 || *h > 16384)
        throw bad();
    return {static_cast<std::size_t>(*w), static_cast<std::size_t>(*h)};
}

ViewRequest viewRequest(const ViewOptions& o) {
    ViewRequest r;
    r.time = parseTimeOptions(o.time, o.tz);
    ViewCameraRequest& c = r.camera;
    c.azimuthDeg = o.cameraAzimuthDeg;
    c.elevationDeg = o.cameraElevationDeg;
    c.distanceM = o.cameraDistanceM;
    if (!o.eye.empty()) c.eye = parsePoint(o.eye, "--eye", true, true);
    if (!o.eyeXy.empty()) c.eye = parsePoint(o.eyeXy, "--eye-xy", false, true);
    if (!o.target.empty()) c.target = parsePoint(o.target, "--target", true, false);
    if (!o.targetXy.empty()) c.target = parsePoint(o.targetXy, "--target-xy", false, false);
    c.fieldOfViewDeg = o.fovDeg;
    std::tie(c.width, c.height) = parseSize(o.size);
    c.exaggeration = o.exaggeration;
    r.colorRaster = o.colorRaster;
    r.colorEncoding = parseColorEncoding(o.colorEncoding, "--color-encoding");
    r.albedo = o.albedo;
    r.treeLineM = o.treeLineM;
    r.snowLineM = o.snowLineM;
    r.exposure = o.exposure;
    r.atmosphere.haze = !o.noHaze;
    r.atmosphere.sky = !o.noSky;
    r.atmosphere.visibilityKm = o.visibilityKm;
    r.nodata = o.nodata == "sea" ? ViewNodata::Sea : ViewNodata::Hole;
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
    CLI::App* cmd = app.add_subcommand("view", "Oblique perspective picture of the lit terrain through haze, with sky");
    ctx.outputs[cmd->get_name()].kind = "picture";
    addDemArgument(cmd, o->dem);
    cmd->add_option("-o,--output", o->outPath, "Output picture; format from the extension (.png, .jpg, .exr)")
        ->required()
        ->type_name("OUT.png");
    addTimeOptions(cmd, o->time, o->tz);
    cmd->add_option("--camera-azimuth", o->cameraAzimuthDeg,
                    "Camera's azimuth from the target, degrees from true north (180: south of it, looking north)")
        ->capture_default_str()
        ->check(finiteRange(-360, 360));
    cmd->add_option("--camera-elevation", o->cameraElevationDeg, "Camera's elevation angle above the target (degrees)")
        ->capture_default_str()
        ->check(finiteRange(-89.9, 89.9));
    cmd->add_option("--camera-distance", o->cameraDistanceM,
                    "Camera's distance from the target (metres; default 0.75 x the DEM's diagonal)")
        ->check(finiteRange(0, 1e8, true));
    auto* eye = cmd->add_option("--eye", o->eye, "Camera position: WGS84 latitude, longitude, height (m)")
                    ->type_name("LAT,LON,HEIGHT");
    auto* eyeXy = cmd->add_option("--eye-xy", o->eyeXy, "Camera position in the DEM's CRS and height (m)")
                      ->type_name("X,Y,HEIGHT")
                      ->excludes(eye);
    auto* target = cmd->add_option("--target", o->target,
                                   "Where the camera looks: WGS84 latitude, longitude[, height (m); default the terrain's]")
                       ->type_name("LAT,LON[,HEIGHT]");
    cmd->add_option("--target-xy", o->targetXy, "Where the camera looks, in the DEM's CRS[, height (m)]")
        ->type_name("X,Y[,HEIGHT]")
        ->excludes(target);
    (void)eyeXy;
    cmd->add_option("--fov", o->fovDeg, "Horizontal field of view (degrees)")->capture_default_str()->check(finiteRange(1, 150));
    cmd->add_option("--size", o->size, "Picture size in pixels")->capture_default_str()->type_name("WxH");
    cmd->add_option("--exaggeration", o->exaggeration, "Vertical exaggeration of the terrain")
        ->capture_default_str()
        ->check(finiteRange(0, 100, true));
    addColorRasterOptions(cmd, o->colorRaster, o->colorEncoding, "the ground's albedo per channel");
    cmd->add_option("--albedo", o->albedo,
                    "Grey ground albedo (0-1) instead of the default landscape (vegetation, rock, snow by height and slope)")
        ->check(finiteRange(0.0, 1.0))
        ->excludes("--color-raster");
    cmd->add_option("--tree-line", o->treeLineM, "Default landscape: rock instead of vegetation above this height (m)")
        ->capture_default_str()
        ->check(finiteRange(-1e5, 1e5));
    cmd->add_option("--snow-line", o->snowLineM, "Default landscape: snow above this height (m)")
        ->capture_default_str()
        ->check(finiteRange(-1e5, 1e5));
    cmd->add_option("--exposure", o->exposure, "Multiplies linear light before gamma")
        ->capture_default_str()
        ->check(finiteRange(0, 1000));
    cmd->add_flag("--no-haze", o->noHaze, "No aerial perspective (haze) on the terrain");
    cmd->add_flag("--no-sky", o->noSky, "No sky behind the terrain (transparent)");
    cmd->add_option("--visibility", o->visibilityKm, "Meteorological visibility at sea level (km): the haze's density")
        ->capture_default_str()
        ->check(finiteRange(0, 1e6, true));
    cmd->add_option("--nodata", o->nodata, "Nodata cells: hole (see through) or sea (flat water at 0 m)")
        ->capture_default_str()
        ->check(CLI::IsMember({"hole", "sea"}));
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions of the sky term (default: " + std::to_string(kAutoSkyDirections) +
                        " with --quality auto, " + std::to_string(kFullSkyDirections) + " with full)")
        ->check(finiteRange(1, 1024));
    addSunDiameterOption(cmd, o->sunDiameterDeg);
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runView(*o, ctx); });
}

}  // namespace demlight::cli
