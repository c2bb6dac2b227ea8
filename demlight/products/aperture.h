// Ambient aperture per cell (Oat & Sander 2007): the visible solid angle, the spherical cap of
// the same area and its axis, the bent normal.
#pragma once

#include "demlight/products/product.h"
#include "demlight/products/tiles.h"

#include <optional>

namespace demlight {

struct ApertureRequest {
    /// Horizon directions integrated; none = the scene plan's.
    std::optional<std::size_t> directions;
    SearchRequest search;
};

struct ApertureResult : ProductResult {
    std::size_t directions = 0;
    double maxDistanceM = 0;
};

/// Bands: bent_normal_east, bent_normal_north, bent_normal_up (ENU unit vector),
/// aperture_radius_deg, visible_solid_angle_sr.
/// Bands of an aperture output.
inline constexpr std::size_t kApertureBands = 5;
/// Memory of a tile (demlight/products/tiles.h): the aperture computes its window's cells only.
TileBytes apertureTileBytes();

/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t apertureHaloCells(const DemSource& source, const ApertureRequest& request);

ApertureResult apertureProduct(const DemSource& source, const CellWindow& window, const ApertureRequest& request,
                               const ProgressFn& progress = {});

}  // namespace demlight
