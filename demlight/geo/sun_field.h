// Fills a SunField (demlight/core/sun_field.h) for a DEM with the NREL SPA.
#pragma once

#include "demlight/geo/dem.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/solar_position.h"
#include "demlight/core/sun_field.h"

namespace demlight {

/// Evaluates SPA at lattice nodes of the DEM at instant t. `site` supplies pressure and
/// temperature; latitude, longitude and elevation come from each node (the height from the DEM,
/// the DEM's mean where a node is nodata).
SunField computeSunField(const Dem& dem, UtcInstant t, const SolarSite& site,
                         const SpaOptions& options, std::size_t stepCells = 64);

/// computeSunField of the source's whole DEM, with the same bits, from the heights at the
/// lattice's nodes alone (DemSource::nodeHeights).
SunField computeSunField(const DemSource& source, UtcInstant t, const SolarSite& site,
                         const SpaOptions& options, std::size_t stepCells = 64);

}  // namespace demlight
