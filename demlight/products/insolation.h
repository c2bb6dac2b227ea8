// Solar irradiation totals in kWh m-2 over local days: beam, diffuse, reflected and global on
// each cell's inclined surface, the clear sky and diffuse models of `irradiance`
// (demlight/products/irradiance.h), integrated by binned sun positions (demlight/lighting/insolation.h): one
// horizon sweep per azimuth sector for the whole period instead of one per instant.
#pragma once

#include "demlight/geo/time.h"
#include "demlight/lighting/insolation.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/product.h"

#include <chrono>
#include <optional>
#include <utility>
#include <vector>

namespace demlight {

/// Azimuth sectors of the bins and of the visible sky by default: 5.6 deg sectors
/// (docs/accuracy.md#insolation-accuracy measures them against the per-instant integral).
inline constexpr std::size_t kDefaultInsolationDirections = 64;
/// Elevation band of the bins by default (degrees).
inline constexpr double kDefaultInsolationBandDeg = 2;

struct InsolationRequest {
    std::chrono::sys_days firstDay, lastDay;  ///< local days, inclusive
    TimeZoneSpec zone;                        ///< of the days and of monthly Linke values
    /// An interval instead of whole days: sun positions from its first instant to its second
    /// (firstDay and lastDay are then ignored).
    std::optional<std::pair<UtcInstant, UtcInstant>> interval;
    /// Sun positions every `step` from local midnight of the first day to local midnight after
    /// the last (or over the interval), weighted by the trapezoid rule.
    std::chrono::milliseconds step = std::chrono::minutes(10);
    std::vector<double> linke{kDefaultLinke};  ///< one value, or 12 monthly (each instant's month)
    double albedo = kDefaultAlbedo;
    double coeffBh = 1, coeffDh = 1;
    ClearSkyRasters rasters;  ///< rasters replacing linke, albedo, coeffBh or coeffDh over the DEM
    DiffuseModel diffuseModel = DiffuseModel::VisibleSky;
    double solarConstantWm2 = kSolarConstantWm2;
    /// Azimuth sectors of the bins and of the visible sky (>= 4); none = kDefaultInsolationDirections.
    std::optional<std::size_t> directions;
    double elevationBandDeg = kDefaultInsolationBandDeg;  ///< in (0, 90]
    double sunDiameterDeg = kSunDiameterDeg;
    Atmosphere atmosphere;
    /// Vegetation over the DEM (a DSM) that passes a share of the beam and of the sky it hides.
    CanopyRequest canopy;
    SearchRequest search;
};

struct InsolationResult : ProductResult {
    std::size_t instants = 0;  ///< sun positions of the period
    std::size_t bins = 0;      ///< bins they fell in (sun up)
    std::size_t directions = 0;
};

/// Checks the request's fields; throws FieldError naming the first bad one.
void validateInsolation(const InsolationRequest& request);
/// First and last instant of the period: the interval, or the days from local midnight to midnight.
std::pair<UtcInstant, UtcInstant> insolationPeriod(const InsolationRequest& request);
/// The sun positions' instants: every request.step from the period's start, then its end.
std::vector<UtcInstant> periodInstants(const InsolationRequest& request);
/// Hours from `a` to `b` (the trapezoid weights: half the hours to each neighbour).
double instantHoursBetween(UtcInstant a, UtcInstant b);

/// Bands (Float32): beam, diffuse, reflected, global (kWh m-2), sun_hours (hours of direct sun:
/// the time of each bin times the fraction of the sun's disk the cell sees in it).
/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t insolationHaloCells(const DemSource& source, const InsolationRequest& request);

InsolationResult insolationProduct(const DemSource& source, const CellWindow& window, const InsolationRequest& request,
                                   const ProgressFn& progress = {});

}  // namespace demlight
