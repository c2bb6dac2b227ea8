// Sun visibility and direct-sun irradiance at one instant. Sun position per cell: SPA on a
// lattice (demlight/geo/sun_field.h), interpolated. SunModel::Horizon: one sweep whose regions follow the
// sun's azimuth across the DEM (demlight/lighting/sun_frame.h). Aperture models: the ambient aperture of
// every cell from `directions` sweeps, then the sun cap intersected with it per cell
// (demlight/lighting/lighting_models.h applyApertureSun).
#pragma once

#include "demlight/geo/sun_field.h"
#include "demlight/geo/time.h"
#include "demlight/lighting/lighting_models.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/products/canopy.h"
#include "demlight/products/product.h"

#include <optional>

namespace demlight {

/// Air pressure and temperature of the solar refraction model (SPA defaults).
struct Atmosphere {
    double pressureHpa = 1013.25;  ///< 0 = no atmospheric refraction of the sun
    double temperatureC = 15;
};

struct SunRequest {
    /// The instant, and the zone results are shown in (DEMLIGHT_TIME_LOCAL).
    ZonedInstant time;
    SunModel model = SunModel::Horizon;
    /// Angular diameter of the sun's disk (degrees); larger = softer shadows.
    double sunDiameterDeg = kSunDiameterDeg;
    Atmosphere atmosphere;
    /// Aperture models: horizon directions of the aperture; none = the scene plan's.
    std::optional<std::size_t> directions;
    /// Vegetation over the DEM (a DSM) that passes a share of the beam; horizon model only.
    CanopyRequest canopy;
    SearchRequest search;
};

struct SunResult : ProductResult {
    double centreAzimuthDeg = 0, centreElevationDeg = 0;  ///< the sun at the DEM centre
    bool sunUp = false;            ///< the sun's disk is above the horizon somewhere
    double maxDistanceM = 0;       ///< search distance used
    std::size_t sweepRegions = 0;  ///< horizon model: regions of the sun sweep
    std::string strategy;          ///< horizon model: the sun sweep's strategy
    std::size_t directions = 0;    ///< aperture models: directions of the aperture
};

/// The sun of `time` on the DEM's lattice (every plan.sunLatticeStepCells cells).
SunField sunFieldFor(const DemSource& source, UtcInstant time, const Atmosphere& atmosphere, const ScenePlan& plan);
/// The whole DEM's field as a window of it (read from `source`) sees it: SunField::onTile at the
/// window's corner, so the window's cells get the whole DEM's sun bit for bit.
SunField sunFieldOnTile(const SunField& whole, const Dem& tile, const DemSource& source);

/// Bands: sun_visibility (fraction of the disk, 0-1), sun_irradiance (normalised).
/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t sunHaloCells(const DemSource& source, const SunRequest& request);

SunResult sunProduct(const DemSource& source, const CellWindow& window, const SunRequest& request,
                     const ProgressFn& progress = {});

/// Checks the fields common to sun requests (diameter, atmosphere); throws Error naming them.
void validateSun(double sunDiameterDeg, const Atmosphere& atmosphere);

}  // namespace demlight
