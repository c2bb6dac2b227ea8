#include "demlight/products/view.h"

#include "demlight/geo/dem.h"
#include "demlight/lighting/sky.h"
#include "demlight/products/sky.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"
#include "demlight/core/timing.h"

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

struct ViewStage::Impl {
    const DemSource* source = nullptr;
    std::shared_ptr<const Dem> whole;
    ViewRequest request;
    std::array<Grid<float>, 3> albedo;  ///< linear, per cell (NaN where no height); made by ensureAlbedo
    Grid<float> surfaceHeights;
    std::unique_ptr<MaxMipmap> surface;
    ViewCamera camera;
    double cellWidthM = 0, cellHeightM = 0, gammaDeg = 0, effectiveRadiusM = 0;
    double eyeCol = 0, eyeRow = 0, distanceToTargetM = 0;
};

/// The ground's albedo (the colour raster's, one grey, or the landscape's), made at the first
/// picture: after viewProduct's light, so the two never hold their grids at once.
void ensureAlbedo(ViewStage::Impl& m) {
    if (!m.albedo[0].empty()) return;
    const ViewRequest& request = m.request;
    const Terrain& t = m.whole->terrain;
    const std::size_t W = t.width(), H = t.height();
    // The ground's albedo: the colour raster's, one grey, or the landscape's.
    if (!request.colorRaster.empty()) {
        std::vector<Grid<float>> colour =
            loadAuxiliaryRaster(request.colorRaster, *m.source, {"colorRaster", 3, true, 0, 1, true, request.colorEncoding});
        for (std::size_t c = 0; c < 3; ++c) m.albedo[c] = std::move(colour[c]);
    } else {
        for (auto& g : m.albedo) g = Grid<float>(W, H);
        const Normals normals = request.albedo ? Normals{} : computeNormals(t);
        parallelFor(0, H, [&](std::size_t r) {
            for (std::size_t c = 0; c < W; ++c) {
                const float h = t.heightsM(c, r);
                const Rgb a = request.albedo ? Rgb{*request.albedo, *request.albedo, *request.albedo}
                              : std::isnan(h) ? Rgb{NAN, NAN, NAN}
                                              : landscapeAlbedo(h, normals.up(c, r), request.treeLineM, request.snowLineM);
                m.albedo[0](c, r) = static_cast<float>(a.r);
                m.albedo[1](c, r) = static_cast<float>(a.g);
                m.albedo[2](c, r) = static_cast<float>(a.b);
            }
        }, 16);
    }

}

ViewStage::ViewStage(const DemSource& source, const ViewRequest& request) : impl_(std::make_unique<Impl>()) {
    validateView(request);
    Impl& m = *impl_;
    m.request = request;
    m.source = &source;
    const ViewCameraRequest& cam = request.camera;
    m.whole = source.readWhole();
    const Dem& dem = *m.whole;
    const Terrain& t = dem.terrain;
    const std::size_t W = t.width(), H = t.height();
    if (W < 2 || H < 2) throw Error("a view needs a DEM of at least 2 x 2 cells");
    const bool sea = request.nodata == ViewNodata::Sea;

    // The frame: cell (0, 0)'s centre at the origin, E along columns, N against rows.
    const double cw = t.cellWidthM[H / 2], ch = t.cellHeightM[H / 2];
    m.cellWidthM = cw;
    m.cellHeightM = ch;
    m.gammaDeg = t.convergence.empty() ? 0.0 : t.convergence.at(0.5 * (W - 1), 0.5 * (H - 1));
    const double exag = cam.exaggeration;
    m.effectiveRadiusM = kEarthRadiusM / (1.0 - request.search.refraction);
    const double drop = 0.5 / m.effectiveRadiusM;
    const auto toEnu = [&](double col, double row, double u) { return Enu3{col * cw, -row * ch, u}; };
    const double centreCol = 0.5 * static_cast<double>(W - 1), centreRow = 0.5 * static_cast<double>(H - 1);
    const auto terrainHeight = [&](double col, double row) {
        const double h = heightAt(t.heightsM, col, row);
        return std::isfinite(h) ? h : (sea ? 0.0 : source.meanHeightM());
    };

    FramePoint target{centreCol, centreRow, std::nullopt};
    if (cam.target) target = framePoint(dem, *cam.target);
    const double targetHeightM = target.heightM.value_or(terrainHeight(target.col, target.row));
    ViewCamera& camera = m.camera;
    camera.fieldOfViewDeg = cam.fieldOfViewDeg;
    camera.width = cam.width;
    camera.height = cam.height;
    camera.target = toEnu(target.col, target.row, exag * targetHeightM);
    if (cam.eye) {
        const FramePoint eye = framePoint(dem, *cam.eye);
        camera.eye = toEnu(eye.col, eye.row, exag * *eye.heightM);
    } else {
        const double distance = cam.distanceM.value_or(kOrbitDistanceShare * diagonalM(t));
        const double az = (cam.azimuthDeg - m.gammaDeg) * kDegToRad, el = cam.elevationDeg * kDegToRad;
        camera.eye = {camera.target.e + distance * std::cos(el) * std::sin(az),
                      camera.target.n + distance * std::cos(el) * std::cos(az), camera.target.u + distance * std::sin(el)};
    }
    // The target sinks with the earth's curvature as seen from the eye.
    const double targetGround = std::hypot(camera.target.e - camera.eye.e, camera.target.n - camera.eye.n);
    camera.target.u -= drop * targetGround * targetGround;
    m.distanceToTargetM = std::hypot(targetGround, camera.target.u - camera.eye.u);
    if (m.distanceToTargetM < 1e-6) throw FieldError("target", ": is where the eye is; the camera needs a direction to look");

    Grid<float> heights = t.heightsM;
    if (sea)
        for (float& h : heights.values())
            if (std::isnan(h)) h = 0.0f;
    m.surfaceHeights = viewHeights(heights, cw, ch, exag, camera.eye, m.effectiveRadiusM);
    m.eyeCol = camera.eye.e / cw;
    m.eyeRow = -camera.eye.n / ch;
    const double groundBelow = heightAt(m.surfaceHeights, m.eyeCol, m.eyeRow);
    if (std::isfinite(groundBelow) && !(camera.eye.u > groundBelow))
        throw FieldError(cam.eye ? "eye" : "camera",
                         ": the camera is under the terrain (at " + formatNumber(camera.eye.u / exag) +
                             " m, the ground below it at " + formatNumber(groundBelow / exag) + " m)");
    m.surface = std::make_unique<MaxMipmap>(m.surfaceHeights);
}

ViewStage::~ViewStage() = default;

std::array<Grid<float>, 3> ViewStage::light(const Grid<float>& sunIrradiance, const Grid<float>& skyK) const {
    const ViewRequest& r = impl_->request;
    const double albedo = r.albedo.value_or(kDefaultAlbedo);
    std::array<Grid<float>, 3> out;
    for (auto& g : out) g = Grid<float>(skyK.width(), skyK.height());
    parallelFor(0, skyK.height(), [&](std::size_t row) {
        for (std::size_t c = 0; c < skyK.width(); ++c) {
            const double s = sunIrradiance(c, row), k = skyK(c, row);
            const double f = std::isnan(k) ? k : skyFactor(k, albedo);
            for (std::size_t ch = 0; ch < 3; ++ch)
                out[ch](c, row) = static_cast<float>(r.sunColor[ch] * s + r.skyColor[ch] * f);
        }
    }, 16);
    return out;
}

ViewImage ViewStage::render(const std::array<const Grid<float>*, 3>& light, double sunAzimuthDeg,
                            double sunElevationDeg) const {
    ensureAlbedo(*impl_);
    const Impl& m = *impl_;
    const ViewRequest& request = m.request;
    const Terrain& t = m.whole->terrain;
    // The sea: open water under the disk's visible share above the horizontal and the whole sky.
    const double sunUp = std::clamp(0.5 + sunElevationDeg / request.sunDiameterDeg, 0.0, 1.0) *
                         std::max(0.0, std::sin(sunElevationDeg * kDegToRad));
    ViewScene scene;
    scene.heightsM = &m.surfaceHeights;
    scene.albedo = {&m.albedo[0], &m.albedo[1], &m.albedo[2]};
    scene.light = light;
    scene.groundHeightsM = &t.heightsM;
    scene.sea = request.nodata == ViewNodata::Sea;
    scene.seaRadiance = {kSeaAlbedo.r * (request.sunColor[0] * sunUp + request.skyColor[0]),
                         kSeaAlbedo.g * (request.sunColor[1] * sunUp + request.skyColor[1]),
                         kSeaAlbedo.b * (request.sunColor[2] * sunUp + request.skyColor[2])};
    scene.cellWidthM = m.cellWidthM;
    scene.cellHeightM = m.cellHeightM;
    scene.exaggeration = request.camera.exaggeration;
    scene.effectiveRadiusM = m.effectiveRadiusM;
    ViewLight vl;
    vl.sunAzimuthDeg = sunAzimuthDeg;
    vl.sunElevationDeg = sunElevationDeg;
    vl.gridConvergenceDeg = m.gammaDeg;
    vl.sunDiameterDeg = request.sunDiameterDeg;
    vl.sunColor = {request.sunColor[0], request.sunColor[1], request.sunColor[2]};
    vl.skyColor = {request.skyColor[0], request.skyColor[1], request.skyColor[2]};
    PreviewParams display;
    display.exposure = request.exposure;
    return renderView(scene, *m.surface, m.camera, vl, request.atmosphere, display);
}

void ViewStage::describe(ViewResult& out) const {
    const Impl& m = *impl_;
    out.camera = m.camera;
    out.cellWidthM = m.cellWidthM;
    out.cellHeightM = m.cellHeightM;
    out.effectiveRadiusM = m.effectiveRadiusM;
    out.exaggeration = m.request.camera.exaggeration;
    std::tie(out.eyeLatitudeDeg, out.eyeLongitudeDeg) = cellLatLon(*m.whole, m.eyeCol, m.eyeRow);
    out.eyeHeightM = m.camera.eye.u / out.exaggeration;
    out.distanceToTargetM = m.distanceToTargetM;
}

ViewResult viewProduct(const DemSource& source, const ViewRequest& request, const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        validateView(request);
        ViewResult out;
        // The camera first: a camera under the terrain is refused before the light is computed.
        const auto stageStart = std::chrono::steady_clock::now();
        const ViewStage stage(source, request);
        double stageSeconds = secondsSince(stageStart);

        // The light of every cell, as the light product gives it; the stage multiplies in the albedo.
        const auto lightStart = std::chrono::steady_clock::now();
        LightRequest lr;
        lr.time = request.time;
        lr.sunColor = request.sunColor;
        lr.skyColor = request.skyColor;
        lr.albedo = request.albedo;
        lr.skyDirections = request.skyDirections;
        lr.sunDiameterDeg = request.sunDiameterDeg;
        lr.search = request.search;
        const LightResult light = lightProduct(source, source.whole(), lr, progress);
        out.lightSeconds = secondsSince(lightStart);
        out.sunAzimuthDeg = light.centreAzimuthDeg;
        out.sunElevationDeg = light.centreElevationDeg;
        const ScenePlan plan = planFor(request.search, source.readWhole()->terrain);
        out.quality = plan.quality;
        out.skyDirections = request.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));

        const auto renderStart = std::chrono::steady_clock::now();
        out.view = stage.render({&light.bands.at(0).values, &light.bands.at(1).values, &light.bands.at(2).values},
                                out.sunAzimuthDeg, out.sunElevationDeg);
        out.renderSeconds = stageSeconds + secondsSince(renderStart);
        stage.describe(out);
        return out;
    });
}

}  // namespace demlight
