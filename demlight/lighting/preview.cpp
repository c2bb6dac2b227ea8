// Preview rig; see preview.h. Quilez, "Outdoors lighting" (iquilezles.org): lighting equation with
// key, sky and indirect lights, coloured penumbra, gamma at the end.
#include "demlight/lighting/preview.h"

#include "demlight/lighting/sun.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

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
    thresholds_[255] = std::numeric_limits<double>::quiet_NaN();
    const double* t = thresholds_.data();
    const double* tEnd = t + 255;
    // The table needs thresholds that are ordered, non-negative and finite.
    if (!std::is_sorted(t, tEnd) || !(t[0] >= 0.0) || !std::isfinite(t[254])) return;
    const std::uint64_t keyLo = std::bit_cast<std::uint64_t>(t[0]) >> kShift;
    const std::uint64_t keyHi = std::bit_cast<std::uint64_t>(t[254]) >> kShift;
    if (keyHi - keyLo + 1 > kMaxTableSize) return;
    std::vector<std::uint8_t> below(keyHi - keyLo + 1);
    bool twoPerBucket = false;
    for (std::uint64_t key = keyLo; key <= keyHi; ++key) {
        const double start = std::bit_cast<double>(key << kShift), next = std::bit_cast<double>((key + 1) << kShift);
        const auto first = std::lower_bound(t, tEnd, start), end = std::lower_bound(t, tEnd, next);
        if (end - first > 2) return;  // operator() makes at most two compares per bucket
        twoPerBucket = twoPerBucket || end - first == 2;
        below[key - keyLo] = static_cast<std::uint8_t>(first - t);
    }
    below_ = std::move(below);
    twoPerBucket_ = twoPerBucket;
    keyLo_ = keyLo;
}

std::uint8_t DisplayBytes::search(double linear) const {
    // std::upper_bound's answer (the thresholds not above `linear`; all 255 for NaN) without its
    // unpredictable branches: eight halvings of a fixed width, each a compare and an add.
    std::size_t i = 0;
    for (std::size_t step = 128; step > 0; step /= 2) i += linear < thresholds_[i + step - 1] ? 0 : step;
    return static_cast<std::uint8_t>(i);
}

Rgb toDisplay(const Rgb& x, const PreviewParams& p) {
    const double inv = 1.0 / p.gamma;
    auto f = [&](double v) { return std::clamp(std::pow(std::max(0.0, v * p.exposure), inv), 0.0, 1.0); };
    return {f(x.r), f(x.g), f(x.b)};
}

Image8 renderPreview(const Normals& normals, const Grid<float>& sunVisibility,
                     const Grid<float>& skyLight, const std::vector<Grid<float>>& albedoRgb,
                     double sunAzimuthDeg, double sunElevationDeg, const PreviewParams& params) {
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
    parallelFor(0, h, [&](std::size_t row) {
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
            // (The three lookups before any store: a byte store could alias the table.)
            const std::uint8_t r = toDisplayByte(lin.r), g = toDisplayByte(lin.g), b = toDisplayByte(lin.b);
            px[0] = r;
            px[1] = g;
            px[2] = b;
            px[3] = 255;
        }
    });
    return img;
}

namespace {

/// One source column's share of an output column.
struct Tap {
    std::size_t col;
    double weight;
};

/// The taps of every output column (the same for every row), flattened; column j's taps are
/// taps[first[j] .. first[j + 1]), their weights summing to total[j] (added in tap order).
struct ColumnTaps {
    std::vector<Tap> taps;
    std::vector<std::size_t> first;
    std::vector<double> total;
};

ColumnTaps columnTaps(std::size_t inWidth, std::size_t outWidth) {
    ColumnTaps ct;
    ct.first.reserve(outWidth + 1);
    const double scale = static_cast<double>(inWidth) / static_cast<double>(outWidth);  // input px per output px
    auto add = [&](std::size_t col, double weight) {
        if (weight > 0) ct.taps.push_back({col, weight});
    };
    for (std::size_t j = 0; j < outWidth; ++j) {
        ct.first.push_back(ct.taps.size());
        if (outWidth < inWidth) {
            // Shrinking: each input pixel weighted by how much of it the output pixel covers.
            const double a = static_cast<double>(j) * scale, b = static_cast<double>(j + 1) * scale;
            const auto k0 = static_cast<std::size_t>(std::floor(a));
            const auto k1 = std::min(inWidth, static_cast<std::size_t>(std::ceil(b)));
            for (std::size_t k = k0; k < k1; ++k)
                add(k, std::min(static_cast<double>(k + 1), b) - std::max(static_cast<double>(k), a));
        } else {
            // Stretching: linear between the two input pixel centres around the output centre.
            const double x = std::clamp((static_cast<double>(j) + 0.5) * scale - 0.5, 0.0,
                                        static_cast<double>(inWidth - 1));
            const auto k0 = static_cast<std::size_t>(std::floor(x));
            const std::size_t k1 = std::min(k0 + 1, inWidth - 1);
            const double t = x - static_cast<double>(k0);
            add(k0, 1.0 - t);
            if (k1 != k0) add(k1, t);
        }
    }
    ct.first.push_back(ct.taps.size());
    ct.total.assign(outWidth, 0.0);
    for (std::size_t j = 0; j < outWidth; ++j)
        for (std::size_t t = ct.first[j]; t < ct.first[j + 1]; ++t) ct.total[j] += ct.taps[t].weight;
    return ct;
}

/// Four doubles in one vector register, and four bytes (GCC and Clang vector extensions):
/// + - * / act per lane.
using Double4 = double __attribute__((vector_size(32)));
using Byte4 = std::uint8_t __attribute__((vector_size(4)));
using Int4 = std::int32_t __attribute__((vector_size(16)));

}  // namespace

Image8 toGroundPixels(const Image8& image, const Terrain& terrain) {
    const std::size_t cols = terrain.width(), rows = terrain.height();
    if (image.width != cols || image.height != rows || image.rgba.size() != cols * rows * 4 ||
        terrain.cellWidthM.size() != rows || terrain.cellHeightM.size() != rows)
        throw Error("toGroundPixels: the picture (" + std::to_string(image.width) + " x " +
                    std::to_string(image.height) + ") is not one pixel per cell of the terrain (" +
                    std::to_string(cols) + " x " + std::to_string(rows) + ")");
    if (cols == 0 || rows == 0) return image;
    const std::size_t mid = rows / 2;
    const double aspect = terrain.cellWidthM[mid] / terrain.cellHeightM[mid];  // east-west over north-south
    if (!(aspect > 0) || !std::isfinite(aspect))
        throw Error("toGroundPixels: the middle row's cell size (" + std::to_string(terrain.cellWidthM[mid]) +
                    " x " + std::to_string(terrain.cellHeightM[mid]) + " m) is not positive");
    const auto outWidth = static_cast<std::size_t>(
        std::max(1.0, std::round(static_cast<double>(cols) * aspect)));
    if (outWidth == cols) return image;

    const ColumnTaps ct = columnTaps(cols, outWidth);
    Image8 out;
    out.width = outWidth;
    out.height = rows;
    out.rgba.assign(outWidth * rows * 4, 0);
    // (Pointers held in locals: the byte stores could alias the vectors' own fields.)
    const Tap* const taps = ct.taps.data();
    const std::size_t* const first = ct.first.data();
    const double* const total = ct.total.data();
    const std::uint8_t* const src = image.rgba.data();
    std::uint8_t* const dst = out.rgba.data();
    parallelFor(0, rows, [&, taps, first, total, src, dst](std::size_t row) {
        const std::uint8_t* in = src + row * cols * 4;
        std::uint8_t* q = dst + row * outWidth * 4;
        for (std::size_t j = 0; j < outWidth; ++j, q += 4) {
            // R, G, B and alpha as the four lanes of one vector: each lane makes the same
            // operations as a scalar per channel would (a product and a sum per tap, one
            // division), so the bytes are those of a loop over the channels.
            Double4 sum = {0, 0, 0, 0};
            double opaqueWeight = 0;
            const Tap* const end = taps + first[j + 1];
            for (const Tap* tap = taps + first[j]; tap != end; ++tap) {
                const std::uint8_t* p = in + tap->col * 4;
                const double w = tap->weight;
                if (p[3] == 0) continue;  // nodata: no colour, no coverage
                Byte4 bytes;
                std::memcpy(&bytes, p, sizeof bytes);
                sum += w * __builtin_convertvector(__builtin_convertvector(bytes, Int4), Double4);
                opaqueWeight += w;
            }
            if (opaqueWeight == 0) {
                q[0] = q[1] = q[2] = kNodataGrey;
                q[3] = 0;
                continue;
            }
            // Colour over the opaque taps' weight, alpha over all of it.
            const Double4 mean = sum / Double4{opaqueWeight, opaqueWeight, opaqueWeight, total[j]};
            // lround of each lane, clamped to a byte: the means are 0-255, and for v >= 0,
            // trunc(v + 0.49999999999999994) is lround(v) (the sum cannot round up to the next
            // integer unless v's fraction is at least 1/2).
            const Int4 rounded = __builtin_convertvector(mean + 0.49999999999999994, Int4);
            const Byte4 out4 = __builtin_convertvector(rounded < 0 ? 0 : rounded > 255 ? 255 : rounded, Byte4);
            std::memcpy(q, &out4, sizeof out4);
        }
    });
    return out;
}

}  // namespace demlight
