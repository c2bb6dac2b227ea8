// Preview rig; see preview.h. Quilez, "outdoors lighting" (seed 004): lighting equation with
// key, sky and indirect lights, coloured penumbra, gamma at the end.
#include "lighting/preview.h"

#include "lighting/directions.h"
#include "lighting/horizon.h"
#include "lighting/sky.h"
#include "lighting/sun.h"
#include "src/error.h"
#include "src/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace demlight {
namespace {

double smoothstep(double lo, double hi, double x) {
    const double u = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    return u * u * (3 - 2 * u);
}

/// What previewRadiance needs of the sun, computed once per image rather than per cell.
struct SunRig {
    Enu sun, bounce;
    double skyScale, bounceScale;
};

SunRig sunRig(double sunAzimuthDeg, double sunElevationDeg) {
    return {directionEnu(sunAzimuthDeg, sunElevationDeg), directionEnu(sunAzimuthDeg + 180.0, 0.0),
            twilightSkyScale(sunElevationDeg), bounceScale(sunElevationDeg)};
}

/// vis^exponent with the common ends (fully lit, fully shadowed) without a pow call.
double penumbra(double vis, double exponent) {
    if (vis == 1.0) return 1.0;
    if (vis == 0.0 && exponent > 0.0) return 0.0;
    return std::pow(vis, exponent);
}

Rgb radiance(const Enu& n, const Rgb& albedo, double sunVisibility, const SunRig& rig, double skyLight,
             const PreviewParams& p) {
    const double sun = std::max(0.0, n.east * rig.sun.east + n.north * rig.sun.north + n.up * rig.sun.up);
    const double vis = std::clamp(sunVisibility, 0.0, 1.0);
    // Bounce from the horizontal direction opposite the sun (Quilez: sunDir * (-1, 0, -1)).
    const double ind = std::max(0.0, n.east * rig.bounce.east + n.north * rig.bounce.north);
    const double occ = std::clamp(skyLight, 0.0, 1.0);
    const double sky = occ * rig.skyScale;
    const double bounce = ind * occ * rig.bounceScale;
    auto channel = [&](double sunC, double exponent, double skyC, double bounceC, double a) {
        const double key = sun * sunC * penumbra(vis, exponent);  // coloured penumbra
        return a * (key + sky * skyC + bounce * bounceC);
    };
    return {channel(p.sunColor.r, p.penumbraExponent.r, p.skyColor.r, p.bounceColor.r, albedo.r),
            channel(p.sunColor.g, p.penumbraExponent.g, p.skyColor.g, p.bounceColor.g, albedo.g),
            channel(p.sunColor.b, p.penumbraExponent.b, p.skyColor.b, p.bounceColor.b, albedo.b)};
}

}  // namespace

Grid<float> previewSkyLight(const Terrain& terrain, const Normals& normals, std::size_t directions,
                            double maxDistanceM, double refraction, int threads,
                            ProgressCounter* progress) {
    if (directions == 0) throw Error("previewSkyLight: need at least one direction");
    SkyAccumulator acc(normals.east, normals.north, normals.up, directions, {}, threads);
    HorizonParams hp;
    hp.maxDistanceM = maxDistanceM > 0 ? maxDistanceM : defaultMaxDistanceM(terrain);
    hp.refraction = refraction;
    hp.threads = threads;
    sweepDirections(terrain, hp, directions,
                    [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); },
                    progress);
    return acc.finish(0.0).skyK;
}

double twilightSkyScale(double sunElevationDeg) {
    return kNightSkyFloor +
           (1 - kNightSkyFloor) * smoothstep(kTwilightLowDeg, kTwilightHighDeg, sunElevationDeg);
}

double bounceScale(double sunElevationDeg) {
    return smoothstep(kBounceLowDeg, kBounceHighDeg, sunElevationDeg);
}

Rgb previewRadiance(const Enu& n, const Rgb& albedo, double sunVisibility, double sunAzimuthDeg,
                    double sunElevationDeg, double skyLight, const PreviewParams& p) {
    return radiance(n, albedo, sunVisibility, sunRig(sunAzimuthDeg, sunElevationDeg), skyLight, p);
}

DisplayBytes::DisplayBytes(const PreviewParams& p) {
    for (int k = 0; k < 255; ++k)
        thresholds_[static_cast<std::size_t>(k)] = std::pow((k + 0.5) / 255.0, p.gamma) / p.exposure;
}

std::uint8_t DisplayBytes::operator()(double linear) const {
    return static_cast<std::uint8_t>(std::upper_bound(thresholds_.begin(), thresholds_.end(), linear) -
                                     thresholds_.begin());
}

Rgb toDisplay(const Rgb& x, const PreviewParams& p) {
    const double inv = 1.0 / p.gamma;
    auto f = [&](double v) { return std::clamp(std::pow(std::max(0.0, v * p.exposure), inv), 0.0, 1.0); };
    return {f(x.r), f(x.g), f(x.b)};
}

Image8 renderPreview(const Normals& normals, const Grid<float>& sunVisibility,
                     const Grid<float>& skyLight, const std::vector<Grid<float>>& albedoRgb,
                     double sunAzimuthDeg, double sunElevationDeg, const PreviewParams& params,
                     int threads) {
    const std::size_t w = normals.up.width(), h = normals.up.height();
    if (!sunVisibility.sameShape(normals.up) || !skyLight.sameShape(normals.up))
        throw Error("renderPreview: grids differ in size");
    if (!albedoRgb.empty() && (albedoRgb.size() != 3 || !albedoRgb[0].sameShape(normals.up) ||
                               !albedoRgb[1].sameShape(normals.up) || !albedoRgb[2].sameShape(normals.up)))
        throw Error("renderPreview: the albedo needs three grids of the DEM's size");
    Image8 img;
    img.width = w;
    img.height = h;
    img.rgba.assign(w * h * 4, 0);
    const SunRig rig = sunRig(sunAzimuthDeg, sunElevationDeg);
    const DisplayBytes toDisplayByte(params);
    parallelFor(0, h, threads, [&](std::size_t row) {
        for (std::size_t col = 0; col < w; ++col) {
            std::uint8_t* px = img.rgba.data() + (row * w + col) * 4;
            const Enu n = normals.at(col, row);
            const float vis = sunVisibility(col, row);
            const float sky = skyLight(col, row);
            if (std::isnan(n.up) || std::isnan(vis) || std::isnan(sky)) {
                px[0] = px[1] = px[2] = kNodataGrey;
                px[3] = 0;
                continue;
            }
            Rgb a{params.albedo, params.albedo, params.albedo};
            if (!albedoRgb.empty()) {
                const float r = albedoRgb[0](col, row), g = albedoRgb[1](col, row),
                            b = albedoRgb[2](col, row);
                if (!std::isnan(r) && !std::isnan(g) && !std::isnan(b)) a = {r, g, b};
            }
            const Rgb lin = radiance(n, a, vis, rig, sky, params);
            px[0] = toDisplayByte(lin.r);
            px[1] = toDisplayByte(lin.g);
            px[2] = toDisplayByte(lin.b);
            px[3] = 255;
        }
    });
    return img;
}

}  // namespace demlight
