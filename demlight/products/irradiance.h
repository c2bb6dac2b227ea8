// Solar irradiance in W m-2 at one instant on each cell's inclined surface: beam, diffuse,
// ground-reflected and global, from the ESRA clear sky as r.sun implements it (demlight/lighting/esra.h)
// through demlight's sun-disk visibility and, for the visible-sky diffuse model, the sky the
// horizons leave (demlight/lighting/irradiance.h).
#pragma once

#include "demlight/geo/time.h"
#include "demlight/lighting/irradiance.h"
#include "demlight/products/product.h"
#include "demlight/products/sky.h"
#include "demlight/products/sun.h"

#include <optional>
#include <vector>

namespace demlight {

/// Rasters (paths GDAL opens) of the clear-sky inputs that vary over the DEM, as r.sun's linke,
/// albedo, coeff_bh and coeff_dh maps: resampled bilinearly onto the DEM's grid once
/// (loadAuxiliaryRaster) and cut per window, so tiles give the one-piece bits. Empty = the
/// request's constant. Where a raster has no data the outputs are nodata.
struct ClearSkyRasters {
    /// Linke turbidity, 1-10: none; one path, of one band (the whole period) or of twelve (band m
    /// = month m, January first, as the SoDa monthly climatology); or twelve one-band paths,
    /// January first. Monthly maps give each instant its month's map (the month on the clocks of
    /// the request's zone).
    std::vector<std::string> linke;
    std::string albedo;   ///< ground albedo, 0-1 (band 1)
    std::string coeffBh;  ///< real-sky beam index, 0-1 (band 1)
    std::string coeffDh;  ///< real-sky diffuse index, 0-1 (band 1)
    bool any() const { return !linke.empty() || !albedo.empty() || !coeffBh.empty() || !coeffDh.empty(); }
};

/// Months of a year: the count of monthly Linke values and maps.
inline constexpr std::size_t kMonths = 12;

/// The rasters on the whole DEM's grid (empty grids for those not given).
struct ClearSkyRasterGrids {
    std::vector<Grid<float>> linke;  ///< none, one (the whole period) or twelve (January first)
    Grid<float> albedo, coeffBh, coeffDh;
    bool monthlyLinke() const { return linke.size() == kMonths; }
    /// The grids of a window's terrain (cut from these when it is a tile) as ClearSkyGrids;
    /// `cut` holds the cut grids while the result is used. Monthly Linke maps: `month` (0 =
    /// January) picks one as ClearSkyGrids::linke (an instant's); without it all twelve go to
    /// ClearSkyGrids::linkeByMonth (a period's).
    ClearSkyGrids on(const Terrain& terrain, ClearSkyRasterGrids& cut, std::optional<std::size_t> month = {}) const;
};
/// Loads the rasters of `rasters` for `source`; throws FieldError naming linkeRaster, albedoRaster,
/// coeffBhRaster or coeffDhRaster (unreadable, out of range, covering no cell; a Linke raster of
/// neither 1 nor 12 bands, or a count of Linke paths other than 1 and 12).
ClearSkyRasterGrids loadClearSkyRasters(const ClearSkyRasters& rasters, const DemSource& source);
/// The values of the rasters at one cell of `source` (NaN where a raster has no data), for point
/// queries: each raster resampled bilinearly onto that cell alone. `linkeByMonth` receives the
/// twelve Linke values of monthly maps (empty otherwise; `linke` is then January's).
IrradianceParams clearSkyAtCell(const ClearSkyRasters& rasters, const DemSource& source, CellIndex cell,
                                IrradianceParams constants, std::vector<double>* linkeByMonth = nullptr);
/// The metadata of the clear-sky inputs: DEMLIGHT_LINKE (`linke`, or the raster's path),
/// DEMLIGHT_ALBEDO, DEMLIGHT_COEFF_BH and DEMLIGHT_COEFF_DH (the constant or the raster's path).
std::map<std::string, std::string> clearSkyInputMetadata(const std::string& linke, double albedo, double coeffBh,
                                                         double coeffDh, const ClearSkyRasters& rasters);

struct IrradianceRequest {
    /// The instant, and the zone its civil time is shown in (DEMLIGHT_TIME_LOCAL) and whose
    /// calendar month picks a monthly Linke value.
    ZonedInstant time;
    /// Linke turbidity factor (air mass 2), each in [1, 10]: one value, or 12 monthly values
    /// (January first) of which the instant's month in `time.zone` is used.
    std::vector<double> linke{kDefaultLinke};
    /// Ground albedo (0-1) of the reflected component.
    double albedo = kDefaultAlbedo;
    /// Real-sky indices: the fractions (0-1) of clear-sky beam and diffuse that reach the ground.
    double coeffBh = 1, coeffDh = 1;
    /// Rasters replacing linke, albedo, coeffBh or coeffDh over the DEM.
    ClearSkyRasters rasters;
    DiffuseModel diffuseModel = DiffuseModel::VisibleSky;
    /// Solar constant I0 (W m-2) of the extraterrestrial irradiance I0 / R^2.
    double solarConstantWm2 = kSolarConstantWm2;
    /// Horizon directions of the visible sky; none = the scene plan's. Unused by the rsun model.
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
    Atmosphere atmosphere;
    /// Vegetation over the DEM (a DSM) that passes a share of the beam and of the sky it hides.
    CanopyRequest canopy;
    SearchRequest search;
};

struct IrradianceResult : ProductResult {
    double centreAzimuthDeg = 0, centreElevationDeg = 0;  ///< the sun at the DEM centre
    double linke = 0;                 ///< the Linke factor used
    double extraterrestrialWm2 = 0;   ///< G0 at the instant
};

/// The Linke factor of `linke` (one value, or 12 monthly) at instant `t`: the value of the
/// month on the clocks of `zone`. Throws FieldError "linke" unless there are 1 or 12 values,
/// each in [1, 10].
double linkeAt(const std::vector<double>& linke, UtcInstant t, const TimeZoneSpec& zone);
/// The calendar month (0 = January) of instant `t` on the clocks of `zone`.
std::size_t monthAt(UtcInstant t, const TimeZoneSpec& zone);
/// Numbers as formatNumber writes them, comma-separated ("1.5,1.6").
std::string formatNumberList(const std::vector<double>& values);
/// Checks the request's fields; throws FieldError naming the first bad one.
void validateIrradiance(const IrradianceRequest& request);
/// linkeAt for the request's instant and zone.
double linkeFor(const IrradianceRequest& request);
/// Checks the fields irradiance and insolation share (albedo, coeffBh, coeffDh, solarConstantWm2,
/// sunDiameterDeg, the atmosphere); throws FieldError naming them.
void validateClearSky(double albedo, double coeffBh, double coeffDh, double solarConstantWm2,
                      double sunDiameterDeg, const Atmosphere& atmosphere);

/// The four bands of irradiance and insolation, in their order: beam, diffuse, reflected, global.
std::vector<ProductBand> irradianceBands(IrradianceMaps maps, const std::string& unit);

/// Bands (W m-2, Float32): beam, diffuse, reflected, global.
/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t irradianceHaloCells(const DemSource& source, const IrradianceRequest& request);

IrradianceResult irradianceProduct(const DemSource& source, const CellWindow& window,
                                   const IrradianceRequest& request, const ProgressFn& progress = {});

}  // namespace demlight
