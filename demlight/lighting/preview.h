// The preview rig: how demlight shows a person a lit DEM (docs/design.md §6.5, after Quilez,
// "Outdoors lighting"). Three lights in linear space on an albedo of about 0.2:
//   key    sun · max(0, N·s) · visibility^(1, 1.2, 1.5)   (coloured penumbra; no occlusion)
//   fill   sky colour · sky light (Lambert-weighted visible sky K, demlight/lighting/sky.h)
//   bounce bounce colour · max(0, N·b) · sky light, b = horizontal direction opposite the sun
// and gamma 1/2.2 only at the very end. Below the horizon the key and bounce fade out and the
// sky fill dims to a twilight floor, so a night picture still shows the relief, never black.
#pragma once

#include "demlight/lighting/surface.h"
#include "demlight/core/grid.h"
#include "demlight/core/image.h"
#include "demlight/core/terrain.h"

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace demlight {

/// Linear RGB.
struct Rgb {
    double r = 0, g = 0, b = 0;
};

/// Sky fill at night as a fraction of the daytime fill: keeps the relief readable.
inline constexpr double kNightSkyFloor = 0.25;
/// Sun elevations (degrees) between which the sky fill fades from night floor to full day
/// (civil-to-nautical twilight).
inline constexpr double kTwilightLowDeg = -12.0, kTwilightHighDeg = 0.0;
/// Sun elevations (degrees) between which the bounce light fades in (it is lit terrain's glow).
inline constexpr double kBounceLowDeg = -1.0, kBounceHighDeg = 3.0;

struct PreviewParams {
    Rgb sunColor{1.64, 1.27, 0.99};     ///< key light (Quilez)
    Rgb skyColor{0.16, 0.20, 0.28};     ///< sky fill (Quilez)
    Rgb bounceColor{0.40, 0.28, 0.20};  ///< bounce fill (Quilez)
    Rgb penumbraExponent{1.0, 1.2, 1.5};  ///< coloured penumbra: visibility^e per channel
    double albedo = 0.2;      ///< linear albedo when no colour raster is given
    double exposure = 1.0;    ///< multiplies linear radiance before gamma
    double gamma = 2.2;       ///< display gamma (the output is linear^(1/gamma))
};

/// Scale of the sky fill for a sun elevation (degrees): kNightSkyFloor at or below
/// kTwilightLowDeg, 1 at or above kTwilightHighDeg, smoothstep in between.
double twilightSkyScale(double sunElevationDeg);
/// Scale of the bounce light for a sun elevation (degrees), smoothstep 0..1.
double bounceScale(double sunElevationDeg);

/// Linear radiance of one cell. normal: unit ENU; albedo: linear; sunVisibility in [0, 1];
/// sun at azimuth/elevation (degrees); skyLight: K in [0, 1] (or (1 + N_up)/2 without horizons).
Rgb previewRadiance(const Enu& normal, const Rgb& albedo, double sunVisibility,
                    double sunAzimuthDeg, double sunElevationDeg, double skyLight,
                    const PreviewParams& params);

/// Display value of a linear radiance: clamp((exposure · x)^(1/gamma), 0, 1) per channel.
Rgb toDisplay(const Rgb& linear, const PreviewParams& params);

/// The 8-bit display value of one linear channel, lround(255 · toDisplay), without a pow per
/// pixel: the byte is the number of thresholds ((k + 1/2) / 255)^gamma / exposure, k = 0..254,
/// at or below the value (where the rounding steps), as std::upper_bound over them gives.
/// renderPreview uses it for every pixel, so the count is read from a table: a non-negative
/// double's bits order it like its value, so its top bits (exponent and kTableMantissaBits of
/// mantissa) name a bucket, the table holds the count below each bucket's first double, and one
/// or two compares with the thresholds add those within the bucket (one where no bucket holds
/// two, as with the default gamma). Where thresholds crowd more than
/// two to a bucket or span too many buckets (extreme gamma or exposure), and for negative values,
/// a binary search over the thresholds answers instead.
class DisplayBytes {
public:
    explicit DisplayBytes(const PreviewParams& params);
    std::uint8_t operator()(double linear) const;  // (inline below: renderPreview calls it per pixel)

    static constexpr int kTableMantissaBits = 9;
    static constexpr std::size_t kMaxTableSize = std::size_t{1} << 16;

private:
    std::uint8_t search(double linear) const;

    static constexpr int kShift = 52 - kTableMantissaBits;
    /// The 255 thresholds, then NaN: a compare past the last one never counts.
    std::array<double, 256> thresholds_{};
    /// Per bucket (key - keyLo_), the thresholds below its first double; empty: no table.
    std::vector<std::uint8_t> below_;
    std::uint64_t keyLo_ = 0;
    bool twoPerBucket_ = false;  ///< some bucket holds two thresholds: a second compare
};

inline std::uint8_t DisplayBytes::operator()(double linear) const {
    const auto bits = std::bit_cast<std::uint64_t>(linear);
    if (below_.empty() || (bits >> 63) != 0) return search(linear);
    // (Below the first bucket the key wraps around: both ends are outside the table.)
    const std::uint64_t bucket = (bits >> kShift) - keyLo_;
    if (bucket >= below_.size()) return (bits >> kShift) < keyLo_ ? 0 : 255;  // under t[0]; over t[254] or NaN
    std::size_t i = below_[bucket];
    i += linear >= thresholds_[i] ? 1 : 0;
    if (twoPerBucket_) i += linear >= thresholds_[i] ? 1 : 0;
    return static_cast<std::uint8_t>(i);
}

/// Renders every cell (one pixel per cell). sunVisibility and skyLight have the normals' shape;
/// albedoRgb is empty (use params.albedo) or three linear grids of that shape. Nodata cells
/// (NaN normal or visibility) get kNodataGrey with alpha 0; NaN albedo falls back to
/// params.albedo. Parallel over rows; deterministic.
Image8 renderPreview(const Normals& normals, const Grid<float>& sunVisibility,
                     const Grid<float>& skyLight, const std::vector<Grid<float>>& albedoRgb,
                     double sunAzimuthDeg, double sunElevationDeg, const PreviewParams& params);

/// Pixel geometry of a picture of a DEM.
enum class PixelGeometry {
    Cell,    ///< one pixel per cell (a lat/lon DEM looks stretched east-west away from the equator)
    Ground,  ///< square ground pixels (toGroundPixels)
};

/// Resamples a picture of `terrain` (one pixel per cell, as renderPreview draws it) so each pixel
/// covers a square of ground: the height stays the number of rows and the width becomes
/// max(1, round(cols * cellWidthM / cellHeightM)) with the cell size of the middle row (row index
/// height / 2), so a DEM spanning many degrees of latitude is square at its middle. Only columns
/// are resampled: by area (box) averaging where the picture shrinks, linear interpolation between
/// pixel centres where it stretches. Transparent pixels (alpha 0, nodata) are left out of the
/// colour average and alpha becomes the covered share of the weights, as the time-lapse GIF's
/// downsampling does; a pixel with no opaque contribution is kNodataGrey with alpha 0. Returns
/// the image unchanged (same bytes) when the width equals the column count (projected grids with
/// square cells). Deterministic. Throws Error when the image and the terrain differ in size.
Image8 toGroundPixels(const Image8& image, const Terrain& terrain);

}  // namespace demlight
