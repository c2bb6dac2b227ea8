// A canopy height raster over a surface model (demlight/lighting/canopy.h): vegetation that passes a share
// of the light, for sun, irradiance and insolation.
#pragma once

#include "demlight/geo/dem_source.h"
#include "demlight/lighting/canopy.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/progress.h"
#include "demlight/core/terrain.h"

#include <cstddef>
#include <map>
#include <string>

namespace demlight {

/// Tallest vegetation accepted in a canopy raster (metres): the tallest trees measured are ~116 m.
inline constexpr double kMaxCanopyHeightM = 150;

struct CanopyRequest {
    /// Vegetation height above ground (metres, 0-150; 0 or nodata = none), band 1 of any raster
    /// GDAL opens, resampled bilinearly onto the DEM's grid; the DEM is then the surface with the
    /// vegetation on it (a DSM). Empty = no canopy.
    std::string raster;
    /// Share of the beam (and of the sky a crown hides) that passes a crown, 0-1.
    double transmissivity = kDefaultCanopyTransmissivity;
    bool any() const { return !raster.empty(); }
};

/// Throws FieldError "transmissivity" outside [0, 1].
void validateCanopy(const CanopyRequest& request);

/// The canopy heights on the whole DEM's grid (empty without a raster; NaN where it has no data),
/// loaded once per source. Throws FieldError "canopyRaster" (unreadable, out of range, covering
/// no cell of the DEM).
Grid<float> loadCanopy(const CanopyRequest& request, const DemSource& source);

/// A window's ground-and-buildings terrain (the window's terrain minus the canopy cut from the
/// whole DEM's) and its cells under a crown.
struct CanopyTerrain {
    Terrain ground;
    Grid<std::uint8_t> underCrown;
};
CanopyTerrain canopyTerrain(const Terrain& surface, const Grid<float>& wholeCanopy);

/// The sky light K of a surface under a canopy (Q = tau Q_G + (1 - tau) Q_F): the sky K of the
/// full surface, its horizons raised to hide everything under a crown, blended with the ground's
/// (skyLightK on each; `normals` are the ground's). Twice the sweeps of one sky.
Grid<float> canopySkyK(const Terrain& surface, const CanopyTerrain& canopy, const Normals& normals,
                       std::size_t directions, const HorizonParams& params, double transmissivity,
                       ProgressCounter* progress);

/// DEMLIGHT_CANOPY (the raster) and DEMLIGHT_CANOPY_TRANSMISSIVITY; empty without a canopy.
std::map<std::string, std::string> canopyMetadata(const CanopyRequest& request);

}  // namespace demlight
