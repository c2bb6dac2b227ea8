// The combined lightmap at one instant, sun + sky, Float32 linear (Hoffman & Mitchell 2001b:
// lightmap = sun term + sky term, times colour; the normalisation of docs/design.md §3):
//   light   = sunColor · sun term · cloud + skyColor · sky term                   (one band, or R, G, B)
//   light_c = albedo_c · (sunColor_c · sun term · cloud + skyColor_c · sky term_c)  (colour raster)
// The sun term is the sun product's irradiance (SunModel), the sky term (SkyModel) f_sky =
// K / (1 − C(1 − K)) from direction sweeps, Hargreaves' (1 + N_up)/2 + C (1 − N_up)/2, or 0, with
// C the albedo (constant, raster, or per channel the colour raster). The aperture and the sky
// share one pass of direction sweeps.
#pragma once

#include "demlight/geo/time.h"
#include "demlight/lighting/lighting_models.h"
#include "demlight/products/product.h"
#include "demlight/products/sun.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace demlight {

/// Linear RGB radiance, each >= 0.
using LinearRgb = std::array<double, 3>;

struct LightRequest {
    ZonedInstant time;
    SunModel model = SunModel::Horizon;
    SkyModel skyModel = SkyModel::StewartLanger;
    /// Linear sun and sky radiance per channel; either set gives three bands.
    std::optional<LinearRgb> sunColor, skyColor;
    /// Ground albedo C of the sky term (0-1); none = kDefaultAlbedo. Excludes the rasters.
    std::optional<double> albedo;
    /// Per-cell albedo (band 1, 0-1). Excludes albedo and colorRaster.
    std::string albedoRaster;
    /// Per-channel albedo (3 bands R, G, B, or one grey band): the sky term's C per channel, and
    /// the output is albedo x light in three bands reflected_r/g/b.
    std::string colorRaster;
    ColorEncoding colorEncoding = ColorEncoding::Auto;
    /// Raster multiplying the sun term (band 1, 0-1); NaN cells leave the sun as it is.
    std::string cloudShadow;
    /// Directions of the stewart-langer sky and the aperture models; none = the plan's.
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
    Atmosphere atmosphere;
    /// Vegetation that passes a share of the light (demlight/lighting/canopy.h): the sun and the
    /// sky are blended from the ground-and-buildings surface and the full one, the sky's K before
    /// the interreflection. The horizon sun model and the stewart-langer sky only.
    CanopyRequest canopy;
    SearchRequest search;
};

/// The terms combineLight() puts together (every grid of the DEM's shape).
struct LightTerms {
    const Grid<float>* heightsM = nullptr;    ///< NaN = nodata (stays NaN)
    const Grid<float>* sunIrradiance = nullptr;
    const Grid<float>* cloud = nullptr;       ///< or null; NaN cells multiply by 1
    std::vector<const Grid<float>*> sky;      ///< none, one, or one per channel
    std::vector<const Grid<float>*> reflectance;  ///< none, or three (R, G, B albedo)
    LinearRgb sunColor{1, 1, 1}, skyColor{1, 1, 1};
    std::size_t channels = 1;                 ///< 1 or 3
};

/// The combination above, per cell, in double: one grid per channel; NaN at nodata.
std::vector<Grid<float>> combineLight(const LightTerms& terms);

struct LightResult : ProductResult {
    double centreAzimuthDeg = 0, centreElevationDeg = 0;
};

/// Bands: light, or light_r/g/b (a colour), or reflected_r/g/b (a colour raster).
/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t lightHaloCells(const DemSource& source, const LightRequest& request);

LightResult lightProduct(const DemSource& source, const CellWindow& window, const LightRequest& request,
                         const ProgressFn& progress = {});

}  // namespace demlight
