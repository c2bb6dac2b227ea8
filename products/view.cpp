#include "products/view.h"

#include "geo/dem.h"
#include "lighting/surface.h"
#include "src/angles.h"
#include "src/error.h"
#include "src/parallel.h"
#include "src/timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace demlight {
namespace {

/// Default orbit distance as a share of the DEM's diagonal: the whole DEM in a 50 degree view.
constexpr double kOrbitDistanceShare = 0.75;
/// Largest picture side (pixels) and the range of the field of view (degrees).
constexpr std::size_t kMaxPictureSide = 16384;
constexpr double kMinFovDeg = 1, kMaxFovDeg = 150;
constexpr double kMaxExaggeration = 100;
constexpr double kMaxExposure = 1000;
/// Half-width of the blends at the tree line and the snow line (metres).
constexpr double kLineBlendM = 150;
/// Up component of a normal within about 0.25 degrees of vertical: flat ground.
constexpr double kFlatUp = 0.99999;
constexpr Rgb kVegetation{0.045, 0.075, 0.030}, kRock{0.20, 0.18, 0.15}, kSnow{0.80, 0.82, 0.85};

double smoothstep(double lo, double hi, double x) {
    const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}
Rgb mix(const Rgb& a, const Rgb& b, double t) {
    return {a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)};
}

void validateView(const ViewRequest& r) {
    const ViewCameraRequest& c = r.camera;
    if (!std::isfinite(c.azimuthDeg)) throw FieldError("cameraAzimuth", ": must be a finite number of degrees");
    if (!(c.elevationDeg > -90 && c.elevationDeg < 90))
        throw FieldError("cameraElevation", " " + formatNumber(c.elevationDeg) + ": must be in (-90, 90) degrees");
    if (c.distanceM && !(*c.distanceM > 0 && std::isfinite(*c.distanceM)))
        throw FieldError("cameraDistance", " " + formatNumber(*c.distanceM) + ": must be a distance > 0 (metres)");
    if (!(c.fieldOfViewDeg >= kMinFovDeg && c.fieldOfViewDeg <= kMaxFovDeg))
        throw FieldError("fieldOfView", " " + formatNumber(c.fieldOfViewDeg) + ": must be in [1, 150] degrees");
    if (c.width < 1 || c.height < 1 || c.width > kMaxPictureSide || c.height > kMaxPictureSide)
        throw FieldError("size", " " + std::to_string(c.width) + " x " + std::to_string(c.height) +
                                     ": each side must be in [1, 16384] pixels");
    if (!(c.exaggeration > 0 && c.exaggeration <= kMaxExaggeration))
        throw FieldError("exaggeration", " " + formatNumber(c.exaggeration) + ": must be in (0, 100]");
    if (c.eye && !c.eye->heightM) throw FieldError("eye", ": needs a height (metres)");
    for (const auto* p : {&c.eye, &c.target})
        if (*p && (!std::isfinite((*p)->first) || !std::isfinite((*p)->second) ||
                   ((*p)->heightM && !std::isfinite(*(*p)->heightM))))
            throw FieldError(p == &c.eye ? "eye" : "target", ": must be finite numbers");
    if (!(r.atmosphere.visibilityKm > 0 && std::isfinite(r.atmosphere.visibilityKm)))
        throw FieldError("visibility", " " + formatNumber(r.atmosphere.visibilityKm) + ": must be > 0 (km)");
    if (!(r.exposure >= 0 && r.exposure <= kMaxExposure))
        throw FieldError("exposure", " " + formatNumber(r.exposure) + ": must be in [0, 1000]");
    if (r.albedo && !(*r.albedo >= 0 && *r.albedo <= 1))
        throw FieldError("albedo", " " + formatNumber(*r.albedo) + ": must be in [0, 1]");
    if (r.albedo && !r.colorRaster.empty()) throw Error("give albedo or colorRaster, not both");
    for (const auto& [name, v] : {std::pair{"treeLine", r.treeLineM}, std::pair{"snowLine", r.snowLineM}})
        if (!std::isfinite(v) || std::abs(v) > 1e5) throw FieldError(name, " " + formatNumber(v) + ": must be a height in metres");
}

/// A camera point in the frame: grid position of its CRS coordinates, height in metres.
struct FramePoint {
    double col = 0, row = 0;
    std::optional<double> heightM;
};

FramePoint framePoint(const Dem& dem, const ViewPoint& p) {
    const auto [x, y] = p.wgs84 ? crsPointOfWgs84(dem, p.first, p.second) : std::pair(p.first, p.second);
    const auto& gt = dem.band.ref.geoTransform;
    return {(x - gt[0]) / gt[1] - 0.5, (y - gt[3]) / gt[5] - 0.5, p.heightM};
}

/// Bilinear height at a grid position inside the grid; NaN outside it or next to nodata.
double heightAt(const Grid<float>& h, double col, double row) {
    if (!(col >= 0 && row >= 0 && col <= static_cast<double>(h.width() - 1) && row <= static_cast<double>(h.height() - 1)))
        return std::numeric_limits<double>::quiet_NaN();
    const auto i = std::min(static_cast<std::size_t>(col), h.width() - 2);
    const auto j = std::min(static_cast<std::size_t>(row), h.height() - 2);
    const double u = col - static_cast<double>(i), v = row - static_cast<double>(j);
    return (1 - v) * ((1 - u) * h(i, j) + u * h(i + 1, j)) + v * ((1 - u) * h(i, j + 1) + u * h(i + 1, j + 1));
}

}  // namespace

Rgb landscapeAlbedo(double heightM, double normalUp, double treeLineM, double snowLineM) {
    // DEMs such as SRTM hold the sea as flat cells at 0 m.
    if (heightM <= 0 && normalUp >= kFlatUp) return kSeaAlbedo;
    const double slopeDeg = std::acos(std::clamp(normalUp, -1.0, 1.0)) * kRadToDeg;
    const double rocky = std::max(smoothstep(treeLineM - kLineBlendM, treeLineM + kLineBlendM, heightM),
                                  smoothstep(35.0, 45.0, slopeDeg));
    const double snowy = smoothstep(snowLineM - kLineBlendM, snowLineM + kLineBlendM, heightM) *
                         (1.0 - smoothstep(45.0, 55.0, slopeDeg));
    return mix(mix(kVegetation, kRock, rocky), kSnow, snowy);
}

ViewResult viewProduct(const DemSource& source, const ViewRequest& request, const ProgressFn& progress) {
    validateView(request);
    const ViewCameraRequest& cam = request.camera;
    const std::shared_ptr<const Dem> whole = source.readWhole();
    const Dem& dem = *whole;
    const Terrain& t = dem.terrain;
    const std::size_t W = t.width(), H = t.height();
    if (W < 2 || H < 2) throw Error("a view needs a DEM of at least 2 x 2 cells");
    const int threads = request.search.threads;
    ViewResult out;

    // The light of every cell, as the light product gives it (colour raster: albedo included).
    const auto lightStart = std::chrono::steady_clock::now();
    LightRequest lr;
    lr.time = request.time;
    lr.sunColor = request.sunColor;
    lr.skyColor = request.skyColor;
    lr.colorRaster = request.colorRaster;
    lr.colorEncoding = request.colorEncoding;
    lr.albedo = request.albedo;
    lr.skyDirections = request.skyDirections;
    lr.sunDiameterDeg = request.sunDiameterDeg;
    lr.search = request.search;
    LightResult light = lightProduct(source, source.whole(), lr, progress);
    out.sunAzimuthDeg = light.centreAzimuthDeg;
    out.sunElevationDeg = light.centreElevationDeg;
    std::array<Grid<float>, 3> radiance{std::move(light.bands.at(0).values), std::move(light.bands.at(1).values),
                                        std::move(light.bands.at(2).values)};
    out.quality = planFor(request.search, t).quality;
    out.skyDirections = request.skyDirections.value_or(static_cast<std::size_t>(planFor(request.search, t).skyDirections));

    // Ground colour: albedo x light (the colour raster's light has its albedo already).
    const bool sea = request.nodata == ViewNodata::Sea;
    const double sunUp = std::clamp(0.5 + out.sunElevationDeg / request.sunDiameterDeg, 0.0, 1.0) *
                         std::max(0.0, std::sin(out.sunElevationDeg * kDegToRad));
    const Rgb seaLight{kSeaAlbedo.r * (request.sunColor[0] * sunUp + request.skyColor[0]),
                       kSeaAlbedo.g * (request.sunColor[1] * sunUp + request.skyColor[1]),
                       kSeaAlbedo.b * (request.sunColor[2] * sunUp + request.skyColor[2])};
    {
        const Normals normals = request.colorRaster.empty() && !request.albedo ? computeNormals(t, threads) : Normals{};
        parallelFor(0, H, threads, [&](std::size_t r) {
            for (std::size_t c = 0; c < W; ++c) {
                const float h = t.heightsM(c, r);
                if (std::isnan(h)) {
                    if (sea) radiance[0](c, r) = static_cast<float>(seaLight.r), radiance[1](c, r) = static_cast<float>(seaLight.g),
                             radiance[2](c, r) = static_cast<float>(seaLight.b);
                    continue;
                }
                if (!request.colorRaster.empty()) continue;
                const Rgb a = request.albedo ? Rgb{*request.albedo, *request.albedo, *request.albedo}
                                             : landscapeAlbedo(h, normals.up(c, r), request.treeLineM, request.snowLineM);
                radiance[0](c, r) *= static_cast<float>(a.r);
                radiance[1](c, r) *= static_cast<float>(a.g);
                radiance[2](c, r) *= static_cast<float>(a.b);
            }
        }, 16);
    }
    out.lightSeconds = secondsSince(lightStart);

    // The frame: cell (0, 0)'s centre at the origin, E along columns, N against rows.
    const auto renderStart = std::chrono::steady_clock::now();
    const double cw = t.cellWidthM[H / 2], ch = t.cellHeightM[H / 2];
    const double gammaDeg = t.convergence.empty() ? 0.0 : t.convergence.at(0.5 * (W - 1), 0.5 * (H - 1));
    const double exag = cam.exaggeration;
    const double rEff = kEarthRadiusM / (1.0 - request.search.refraction);
    const double drop = 0.5 / rEff;
    const auto toEnu = [&](double col, double row, double u) { return Enu3{col * cw, -row * ch, u}; };
    const double centreCol = 0.5 * static_cast<double>(W - 1), centreRow = 0.5 * static_cast<double>(H - 1);
    const auto terrainHeight = [&](double col, double row) {
        const double h = heightAt(t.heightsM, col, row);
        return std::isfinite(h) ? h : (sea ? 0.0 : source.meanHeightM());
    };

    FramePoint target{centreCol, centreRow, std::nullopt};
    if (cam.target) target = framePoint(dem, *cam.target);
    const double targetHeightM = target.heightM.value_or(terrainHeight(target.col, target.row));
    ViewCamera camera;
    camera.fieldOfViewDeg = cam.fieldOfViewDeg;
    camera.width = cam.width;
    camera.height = cam.height;
    camera.target = toEnu(target.col, target.row, exag * targetHeightM);
    if (cam.eye) {
        const FramePoint eye = framePoint(dem, *cam.eye);
        camera.eye = toEnu(eye.col, eye.row, exag * *eye.heightM);
    } else {
        const double distance = cam.distanceM.value_or(kOrbitDistanceShare * diagonalM(t));
        const double az = (cam.azimuthDeg - gammaDeg) * kDegToRad, el = cam.elevationDeg * kDegToRad;
        camera.eye = {camera.target.e + distance * std::cos(el) * std::sin(az),
                      camera.target.n + distance * std::cos(el) * std::cos(az), camera.target.u + distance * std::sin(el)};
    }
    // The target sinks with the earth's curvature as seen from the eye.
    const double targetGround = std::hypot(camera.target.e - camera.eye.e, camera.target.n - camera.eye.n);
    camera.target.u -= drop * targetGround * targetGround;
    if (std::hypot(targetGround, camera.target.u - camera.eye.u) < 1e-6)
        throw FieldError("target", ": is where the eye is; the camera needs a direction to look");

    Grid<float> heights = t.heightsM;
    if (sea)
        for (float& h : heights.values())
            if (std::isnan(h)) h = 0.0f;
    const Grid<float> surfaceHeights = viewHeights(heights, cw, ch, exag, camera.eye, rEff, threads);
    const double eyeCol = camera.eye.e / cw, eyeRow = -camera.eye.n / ch;
    const double groundBelow = heightAt(surfaceHeights, eyeCol, eyeRow);
    if (std::isfinite(groundBelow) && !(camera.eye.u > groundBelow))
        throw FieldError(cam.eye ? "eye" : "camera",
                         ": the camera is under the terrain (at " + formatNumber(camera.eye.u / exag) +
                             " m, the ground below it at " + formatNumber(groundBelow / exag) + " m)");
    const MaxMipmap surface(surfaceHeights, threads);

    ViewScene scene;
    scene.heightsM = &surfaceHeights;
    scene.radiance = {&radiance[0], &radiance[1], &radiance[2]};
    scene.cellWidthM = cw;
    scene.cellHeightM = ch;
    scene.exaggeration = exag;
    scene.effectiveRadiusM = rEff;
    ViewLight vl;
    vl.sunAzimuthDeg = out.sunAzimuthDeg;
    vl.sunElevationDeg = out.sunElevationDeg;
    vl.gridConvergenceDeg = gammaDeg;
    vl.sunDiameterDeg = request.sunDiameterDeg;
    vl.sunColor = {request.sunColor[0], request.sunColor[1], request.sunColor[2]};
    vl.skyColor = {request.skyColor[0], request.skyColor[1], request.skyColor[2]};
    PreviewParams display;
    display.exposure = request.exposure;
    out.view = renderView(scene, surface, camera, vl, request.atmosphere, display, threads);
    out.renderSeconds = secondsSince(renderStart);

    out.camera = camera;
    out.cellWidthM = cw;
    out.cellHeightM = ch;
    out.effectiveRadiusM = rEff;
    out.exaggeration = exag;
    std::tie(out.eyeLatitudeDeg, out.eyeLongitudeDeg) = cellLatLon(dem, eyeCol, eyeRow);
    out.eyeHeightM = camera.eye.u / exag;
    out.distanceToTargetM = std::hypot(targetGround, camera.target.u - camera.eye.u);
    return out;
}

}  // namespace demlight
