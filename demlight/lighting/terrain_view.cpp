#include "demlight/lighting/terrain_view.h"

#include "demlight/core/angles.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demlight {
namespace {

/// Koschmieder's constant: extinction = 3.912 / visibility (2 % contrast threshold).
constexpr double kKoschmieder = 3.912;
/// Haze extinction per channel relative to 550 nm (the visibility's wavelength): Angstrom
/// exponent 1.3 at 650, 550 and 450 nm, so distant ground turns blue before it turns grey.
constexpr double kHazeSpectrum[3] = {0.805, 1.0, 1.298};
/// Rayleigh optical depth of the whole atmosphere per channel (650, 550, 450 nm; Bucholtz 1995's
/// fit): the sun's colour through `air mass` atmospheres reddens at low elevations.
constexpr double kRayleighDepth[3] = {0.053, 0.097, 0.222};
/// The haze's ambient radiance as a multiple of the sky fill's (the skylight it scatters).
constexpr double kHazeAmbient = 1.6;
/// Sunlight scattered by the haze towards the eye per unit of the Henyey-Greenstein phase.
constexpr double kHazeSun = 0.04;
/// Henyey-Greenstein asymmetry of the haze: aerosols scatter strongly forward.
constexpr double kHazeAsymmetry = 0.7;
/// Zenith sky as a multiple of the sky fill's colour: a deeper blue than the horizon.
constexpr double kZenith[3] = {0.6, 1.0, 1.9};
/// The sun's disk, as a multiple of the sun's radiance: it saturates to white in the picture.
constexpr double kSunDisk = 40;

Enu3 sub(const Enu3& a, const Enu3& b) { return {a.e - b.e, a.n - b.n, a.u - b.u}; }
double dot(const Enu3& a, const Enu3& b) { return a.e * b.e + a.n * b.n + a.u * b.u; }
Enu3 scaled(const Enu3& a, double s) { return {a.e * s, a.n * s, a.u * s}; }
Enu3 normalised(const Enu3& a) { return scaled(a, 1.0 / std::sqrt(dot(a, a))); }

struct Basis {
    Enu3 forward, right, up;
    double tanHalf = 1, aspect = 1;  ///< tan(fov / 2); height / width
};

Basis basisOf(const ViewCamera& c) {
    Basis b;
    b.forward = normalised(sub(c.target, c.eye));
    const double horizontal = std::hypot(b.forward.e, b.forward.n);
    b.right = horizontal > 1e-12 ? Enu3{b.forward.n / horizontal, -b.forward.e / horizontal, 0} : Enu3{1, 0, 0};
    const Enu3& f = b.forward;
    const Enu3& r = b.right;
    b.up = {r.n * f.u - r.u * f.n, r.u * f.e - r.e * f.u, r.e * f.n - r.n * f.e};
    b.tanHalf = std::tan(0.5 * c.fieldOfViewDeg * kDegToRad);
    b.aspect = static_cast<double>(c.height) / static_cast<double>(c.width);
    return b;
}

Enu3 directionOf(const Basis& b, const ViewCamera& c, double px, double py) {
    const double sx = (2.0 * px / static_cast<double>(c.width) - 1.0) * b.tanHalf;
    const double sy = (1.0 - 2.0 * py / static_cast<double>(c.height)) * b.tanHalf * b.aspect;
    return normalised({b.forward.e + sx * b.right.e + sy * b.up.e, b.forward.n + sx * b.right.n + sy * b.up.n,
                       b.forward.u + sx * b.right.u + sy * b.up.u});
}

double smoothstep(double lo, double hi, double x) {
    const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

/// The sun's unit direction in the frame (grid azimuth = true azimuth - convergence).
Enu3 sunDirection(const ViewLight& l) {
    const double az = (l.sunAzimuthDeg - l.gridConvergenceDeg) * kDegToRad, el = l.sunElevationDeg * kDegToRad;
    return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

/// The sun's light after the air between it and the ground (Kasten & Young 1989 air mass),
/// fading out as the sun sets.
Rgb sunThroughAir(const ViewLight& l) {
    const double el = std::max(l.sunElevationDeg, 0.0);
    const double airMass = 1.0 / (std::sin(el * kDegToRad) + 0.50572 * std::pow(el + 6.07995, -1.6364));
    const double up = smoothstep(-1.0, 1.0, l.sunElevationDeg);
    return {l.sunColor.r * up * std::exp(-kRayleighDepth[0] * airMass),
            l.sunColor.g * up * std::exp(-kRayleighDepth[1] * airMass),
            l.sunColor.b * up * std::exp(-kRayleighDepth[2] * airMass)};
}

double henyeyGreenstein(double cosTheta, double g) {
    return (1 - g * g) / std::pow(1 + g * g - 2 * g * cosTheta, 1.5);
}

/// The radiance leaving the ground at (x, y) in cell coordinates (centres at integers, clamped
/// inside): bilinear between the four cells' albedo x light (or the sea's).
Rgb groundRadiance(const ViewScene& s, double x, double y) {
    const Grid<float>& h = *s.groundHeightsM;
    const double xc = std::clamp(x, 0.0, static_cast<double>(h.width() - 1));
    const double yc = std::clamp(y, 0.0, static_cast<double>(h.height() - 1));
    const auto i = std::min(static_cast<std::size_t>(xc), h.width() - 2);
    const auto j = std::min(static_cast<std::size_t>(yc), h.height() - 2);
    const double u = xc - static_cast<double>(i), v = yc - static_cast<double>(j);
    const double w[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
    const std::size_t ci[4] = {i, i + 1, i, i + 1}, cj[4] = {j, j, j + 1, j + 1};
    const double sea[3] = {s.seaRadiance.r, s.seaRadiance.g, s.seaRadiance.b};
    double out[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k) {
        if (w[k] == 0) continue;
        const bool water = std::isnan(h(ci[k], cj[k]));
        for (std::size_t c = 0; c < 3; ++c) {
            const double r = water ? (s.sea ? sea[c] : 0.0)
                                   : static_cast<double>((*s.albedo[c])(ci[k], cj[k])) * (*s.light[c])(ci[k], cj[k]);
            out[c] += w[k] * (std::isnan(r) ? 0.0 : r);
        }
    }
    return {out[0], out[1], out[2]};
}

}  // namespace

Enu3 pixelDirection(const ViewCamera& camera, double px, double py) {
    return directionOf(basisOf(camera), camera, px, py);
}

std::array<double, 2> projectPoint(const ViewCamera& camera, const Enu3& point) {
    const Basis b = basisOf(camera);
    const Enu3 v = sub(point, camera.eye);
    const double z = dot(v, b.forward);
    if (!(z > 0)) return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
    const double x = dot(v, b.right) / z, y = dot(v, b.up) / z;
    return {(x / b.tanHalf + 1.0) * 0.5 * static_cast<double>(camera.width),
            (1.0 - y / (b.tanHalf * b.aspect)) * 0.5 * static_cast<double>(camera.height)};
}

Grid<float> viewHeights(const Grid<float>& h, double cellWidthM, double cellHeightM, double exaggeration,
                        const Enu3& eye, double effectiveRadiusM) {
    Grid<float> out(h.width(), h.height());
    const double curvature = effectiveRadiusM > 0 ? 0.5 / effectiveRadiusM : 0.0;
    parallelFor(0, h.height(), [&](std::size_t r) {
        const double dn = -static_cast<double>(r) * cellHeightM - eye.n;
        for (std::size_t c = 0; c < h.width(); ++c) {
            const double de = static_cast<double>(c) * cellWidthM - eye.e;
            out(c, r) = static_cast<float>(exaggeration * h(c, r) - curvature * (de * de + dn * dn));
        }
    }, 16);
    return out;
}

Rgb hazeTransmittance(const ViewAtmosphere& a, double lengthM, double z0M, double z1M) {
    if (!a.haze || !(lengthM > 0)) return {1, 1, 1};
    const double beta = kKoschmieder / (a.visibilityKm * 1000.0);
    const double H = a.scaleHeightM;
    // Optical depth of exp(-z / H) along a straight segment whose height goes linearly z0 -> z1.
    const double dz = z1M - z0M;
    const double mean = std::abs(dz) < 1e-3 * H ? std::exp(-0.5 * (z0M + z1M) / H)
                                                : H * (std::exp(-z0M / H) - std::exp(-z1M / H)) / dz;
    const double depth = beta * lengthM * mean;
    return {std::exp(-depth * kHazeSpectrum[0]), std::exp(-depth * kHazeSpectrum[1]), std::exp(-depth * kHazeSpectrum[2])};
}

Rgb hazeInscatter(const ViewLight& l, const Enu3& d) {
    const double twilight = twilightSkyScale(l.sunElevationDeg);
    const Rgb sun = sunThroughAir(l);
    const double phase = kHazeSun * henyeyGreenstein(dot(d, sunDirection(l)), kHazeAsymmetry);
    return {kHazeAmbient * twilight * l.skyColor.r + phase * sun.r, kHazeAmbient * twilight * l.skyColor.g + phase * sun.g,
            kHazeAmbient * twilight * l.skyColor.b + phase * sun.b};
}

Rgb skyRadiance(const ViewLight& l, const Enu3& d) {
    Rgb c = hazeInscatter(l, d);
    const double twilight = twilightSkyScale(l.sunElevationDeg);
    // Towards the zenith the haze's share falls off and the deeper blue of clear air shows.
    const double up = 1.0 - std::exp(-6.0 * std::max(d.u, 0.0));
    const Rgb zenith{kZenith[0] * twilight * l.skyColor.r, kZenith[1] * twilight * l.skyColor.g,
                     kZenith[2] * twilight * l.skyColor.b};
    c = {c.r + up * (zenith.r - c.r), c.g + up * (zenith.g - c.g), c.b + up * (zenith.b - c.b)};
    const double cosSun = std::cos(0.5 * l.sunDiameterDeg * kDegToRad);
    if (dot(d, sunDirection(l)) >= cosSun) {
        const Rgb sun = sunThroughAir(l);
        c = {c.r + kSunDisk * sun.r, c.g + kSunDisk * sun.g, c.b + kSunDisk * sun.b};
    }
    return c;
}

ViewImage renderView(const ViewScene& scene, const MaxMipmap& surface, const ViewCamera& camera, const ViewLight& light,
                     const ViewAtmosphere& atmosphere, const PreviewParams& display) {
    const std::size_t W = camera.width, H = camera.height;
    ViewImage out;
    out.image.width = W;
    out.image.height = H;
    out.image.rgba.assign(W * H * 4, 0);
    out.linear.assign(W * H * 3, 0.0f);
    out.distanceM.assign(W * H, std::numeric_limits<float>::infinity());
    const Basis basis = basisOf(camera);
    const DisplayBytes toByte(display);
    const double cw = scene.cellWidthM, ch = scene.cellHeightM;
    const double curvature = scene.effectiveRadiusM > 0 ? 0.5 / scene.effectiveRadiusM : 0.0;
    const double eyeAltitude = camera.eye.u / scene.exaggeration;
    parallelFor(0, H, [&](std::size_t py) {
        for (std::size_t px = 0; px < W; ++px) {
            const Enu3 d = directionOf(basis, camera, static_cast<double>(px) + 0.5, static_cast<double>(py) + 0.5);
            const GridRay ray{camera.eye.e / cw, -camera.eye.n / ch, camera.eye.u, d.e / cw, -d.n / ch, d.u};
            Rgb c;
            bool opaque = true;
            if (const auto hit = surface.cast(ray, std::numeric_limits<double>::infinity())) {
                c = groundRadiance(scene, hit->x, hit->y);
                const double ground2 = hit->t * hit->t * (d.e * d.e + d.n * d.n);
                const double altitude = (hit->z + curvature * ground2) / scene.exaggeration;
                const Rgb T = hazeTransmittance(atmosphere, hit->t, eyeAltitude, altitude);
                if (atmosphere.haze) {
                    const Rgb in = hazeInscatter(light, d);
                    c = {c.r * T.r + in.r * (1 - T.r), c.g * T.g + in.g * (1 - T.g), c.b * T.b + in.b * (1 - T.b)};
                }
                out.distanceM[py * W + px] = static_cast<float>(hit->t);
            } else if (atmosphere.sky) {
                c = skyRadiance(light, d);
            } else {
                opaque = false;
            }
            float* lin = out.linear.data() + (py * W + px) * 3;
            lin[0] = static_cast<float>(c.r), lin[1] = static_cast<float>(c.g), lin[2] = static_cast<float>(c.b);
            std::uint8_t* p = out.image.rgba.data() + (py * W + px) * 4;
            if (!opaque) continue;
            p[0] = toByte(c.r), p[1] = toByte(c.g), p[2] = toByte(c.b), p[3] = 255;
        }
    }, 4);
    return out;
}

}  // namespace demlight
