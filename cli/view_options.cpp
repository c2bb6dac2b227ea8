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

void declareViewCameraOptions(ParameterSet& set, ViewCameraOptions& o) {
    set.add("camera_azimuth", o.cameraAzimuthDeg, "Camera azimuth (deg)",
            "Camera's azimuth from the target, degrees from true north (180: south of it, looking north)")
        .within(-360, 360)
        .inUnit("deg");
    set.add("camera_elevation", o.cameraElevationDeg, "Camera elevation (deg)",
            "Camera's elevation angle above the target (degrees)")
        .within(-89.9, 89.9)
        .inUnit("deg");
    set.add("camera_distance", o.cameraDistanceM, "Camera distance (m)",
            "Camera's distance from the target (metres; default 0.75 x the DEM's diagonal)")
        .within(0, 1e8, true)
        .inUnit("m");
    set.add("eye", o.eye, "Camera (lat, lon, height)", "Camera position: WGS84 latitude, longitude, height (m)")
        .type("LAT,LON,HEIGHT")
        .notWith("eye_xy");
    set.add("eye_xy", o.eyeXy, "Camera (x, y, height)", "Camera position in the DEM's CRS and height (m)")
        .type("X,Y,HEIGHT")
        .notWith("eye");
    set.add("target", o.target, "Target (lat, lon[, height])",
            "Where the camera looks: WGS84 latitude, longitude[, height (m); default the terrain's]")
        .type("LAT,LON[,HEIGHT]")
        .notWith("target_xy");
    set.add("target_xy", o.targetXy, "Target (x, y[, height])", "Where the camera looks, in the DEM's CRS[, height (m)]")
        .type("X,Y[,HEIGHT]")
        .notWith("target");
    set.add("fov", o.fovDeg, "Field of view (deg)", "Horizontal field of view (degrees)")
        .within(1, 150)
        .inUnit("deg")
        .field("fieldOfView");
    set.add("size", o.size, "Picture size (WxH)", "Picture size in pixels").type("WxH");
    set.add("exaggeration", o.exaggeration, "Vertical exaggeration", "Vertical exaggeration of the terrain")
        .within(0, 100, true);
    set.add("tree_line", o.treeLineM, "Tree line (m)", "Default landscape: rock instead of vegetation above this height (m)")
        .within(-1e5, 1e5)
        .inUnit("m");
    set.add("snow_line", o.snowLineM, "Snow line (m)", "Default landscape: snow above this height (m)")
        .within(-1e5, 1e5)
        .inUnit("m");
    set.add("no_haze", o.noHaze, "No haze", "No aerial perspective (haze) on the terrain");
    set.add("no_sky", o.noSky, "No sky", "No sky behind the terrain (transparent)");
    set.add("visibility", o.visibilityKm, "Visibility (km)", "Meteorological visibility at sea level (km): the haze's density")
        .within(0, 1e6, true)
        .inUnit("km");
    set.add("nodata", o.nodata, "Nodata cells", "Nodata cells: hole (see through) or sea (flat water at 0 m)")
        .oneOf({"hole", "sea"});
}

}  // namespace demlight::cli
