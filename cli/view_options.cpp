// The camera and atmosphere options of an oblique view; see view_options.h.
#include "cli/view_options.h"

#include "cli/common.h"

#include <cmath>
#include <sstream>
#include <vector>

namespace demlight::cli {
namespace {

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

}  // namespace

void applyViewCameraOptions(const ViewCameraOptions& o, ViewRequest& r) {
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
    r.treeLineM = o.treeLineM;
    r.snowLineM = o.snowLineM;
    r.atmosphere.haze = !o.noHaze;
    r.atmosphere.sky = !o.noSky;
    r.atmosphere.visibilityKm = o.visibilityKm;
    r.nodata = o.nodata == "sea" ? ViewNodata::Sea : ViewNodata::Hole;
}

void addViewCameraOptions(CLI::App* cmd, ViewCameraOptions& o) {
    cmd->add_option("--camera-azimuth", o.cameraAzimuthDeg,
                    "Camera's azimuth from the target, degrees from true north (180: south of it, looking north)")
        ->capture_default_str()
        ->check(finiteRange(-360, 360));
    cmd->add_option("--camera-elevation", o.cameraElevationDeg, "Camera's elevation angle above the target (degrees)")
        ->capture_default_str()
        ->check(finiteRange(-89.9, 89.9));
    cmd->add_option("--camera-distance", o.cameraDistanceM,
                    "Camera's distance from the target (metres; default 0.75 x the DEM's diagonal)")
        ->check(finiteRange(0, 1e8, true));
    auto* eye = cmd->add_option("--eye", o.eye, "Camera position: WGS84 latitude, longitude, height (m)")
                    ->type_name("LAT,LON,HEIGHT");
    cmd->add_option("--eye-xy", o.eyeXy, "Camera position in the DEM's CRS and height (m)")
        ->type_name("X,Y,HEIGHT")
        ->excludes(eye);
    auto* target = cmd->add_option("--target", o.target,
                                   "Where the camera looks: WGS84 latitude, longitude[, height (m); default the terrain's]")
                       ->type_name("LAT,LON[,HEIGHT]");
    cmd->add_option("--target-xy", o.targetXy, "Where the camera looks, in the DEM's CRS[, height (m)]")
        ->type_name("X,Y[,HEIGHT]")
        ->excludes(target);
    cmd->add_option("--fov", o.fovDeg, "Horizontal field of view (degrees)")->capture_default_str()->check(finiteRange(1, 150));
    cmd->add_option("--size", o.size, "Picture size in pixels")->capture_default_str()->type_name("WxH");
    cmd->add_option("--exaggeration", o.exaggeration, "Vertical exaggeration of the terrain")
        ->capture_default_str()
        ->check(finiteRange(0, 100, true));
    cmd->add_option("--tree-line", o.treeLineM, "Default landscape: rock instead of vegetation above this height (m)")
        ->capture_default_str()
        ->check(finiteRange(-1e5, 1e5));
    cmd->add_option("--snow-line", o.snowLineM, "Default landscape: snow above this height (m)")
        ->capture_default_str()
        ->check(finiteRange(-1e5, 1e5));
    cmd->add_flag("--no-haze", o.noHaze, "No aerial perspective (haze) on the terrain");
    cmd->add_flag("--no-sky", o.noSky, "No sky behind the terrain (transparent)");
    cmd->add_option("--visibility", o.visibilityKm, "Meteorological visibility at sea level (km): the haze's density")
        ->capture_default_str()
        ->check(finiteRange(0, 1e6, true));
    cmd->add_option("--nodata", o.nodata, "Nodata cells: hole (see through) or sea (flat water at 0 m)")
        ->capture_default_str()
        ->check(CLI::IsMember({"hole", "sea"}));
}

}  // namespace demlight::cli
