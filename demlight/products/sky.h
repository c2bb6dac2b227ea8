// Sky-view factors and skylight (Hoffman & Mitchell 2001b, Eq. 8-12, after Stewart & Langer 1997)
// from horizons in evenly spaced azimuths; or Hargreaves' hemisphere lighting (no horizons).
#pragma once

#include "demlight/lighting/lighting_models.h"
#include "demlight/lighting/sky.h"
#include "demlight/products/product.h"
#include "demlight/products/tiles.h"

#include <optional>
#include <string>

namespace demlight {

/// Ground albedo C of the interreflection approximation f_sky = K / (1 - C (1 - K)) by default.
inline constexpr double kDefaultAlbedo = 0.2;

struct SkyRequest {
    /// StewartLanger or Hemisphere (None makes no sky product).
    SkyModel model = SkyModel::StewartLanger;
    /// Horizon directions (sectors); none = the scene plan's.
    std::optional<std::size_t> directions;
    /// Constant ground albedo C in [0, 1], unless albedoRaster is given.
    double albedo = kDefaultAlbedo;
    /// Per-cell albedo raster (band 1, 0-1), resampled onto the DEM; empty = `albedo`.
    std::string albedoRaster;
    /// Sky patches (parseSkyPatches), one sky_K band each; StewartLanger only.
    SkyPatches patches;
    SearchRequest search;
};

struct SkyResult : ProductResult {
    std::size_t directions = 0;  ///< sectors integrated (0 for the hemisphere model)
    double maxDistanceM = 0;     ///< search distance of the sweeps
    double directionToleranceDeg = 0;
};

/// Bands: svf_horizontal, sky_fraction, sky_K, sky_factor, then sky_K_patch=<name> per patch;
/// the hemisphere model: sky_hemisphere.
/// Bands of a sky output: svf_horizontal, sky_fraction, sky_K, f_sky and one per sky patch.
std::size_t skyBands(const SkyRequest& request);
/// Memory of a tile (demlight/products/tiles.h): the sky computes its window's cells only.
TileBytes skyTileBytes(const SkyRequest& request);

/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t skyHaloCells(const DemSource& source, const SkyRequest& request);

SkyResult skyProduct(const DemSource& source, const CellWindow& window, const SkyRequest& request,
                     const ProgressFn& progress = {});

}  // namespace demlight
