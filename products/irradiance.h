// Solar irradiance in W m-2 at one instant on each cell's inclined surface: beam, diffuse,
// ground-reflected and global, from the ESRA clear sky as r.sun implements it (lighting/esra.h)
// through demlight's sun-disk visibility and, for the visible-sky diffuse model, the sky the
// horizons leave (lighting/irradiance.h).
#pragma once

#include "geo/time.h"
#include "lighting/irradiance.h"
#include "products/product.h"
#include "products/sky.h"
#include "products/sun.h"

#include <optional>
#include <vector>

namespace demlight {

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
    DiffuseModel diffuseModel = DiffuseModel::VisibleSky;
    /// Solar constant I0 (W m-2) of the extraterrestrial irradiance I0 / R^2.
    double solarConstantWm2 = kSolarConstantWm2;
    /// Horizon directions of the visible sky; none = the scene plan's. Unused by the rsun model.
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
    Atmosphere atmosphere;
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
/// Numbers as formatNumber writes them, comma-separated ("1.5,1.6").
std::string formatNumberList(const std::vector<double>& values);
/// linkeAt for the request's instant and zone.
double linkeFor(const IrradianceRequest& request);
/// Checks the fields irradiance and insolation share (albedo, coeffBh, coeffDh, solarConstantWm2,
/// sunDiameterDeg, the atmosphere); throws FieldError naming them.
void validateClearSky(double albedo, double coeffBh, double coeffDh, double solarConstantWm2,
                      double sunDiameterDeg, const Atmosphere& atmosphere);

/// The four bands of irradiance and insolation, in their order: beam, diffuse, reflected, global.
std::vector<ProductBand> irradianceBands(IrradianceMaps maps, const std::string& unit);

/// Bands (W m-2, Float32): beam, diffuse, reflected, global.
IrradianceResult irradianceProduct(const DemSource& source, const CellWindow& window,
                                   const IrradianceRequest& request, const ProgressFn& progress = {});

}  // namespace demlight
