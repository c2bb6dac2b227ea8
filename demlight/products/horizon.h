// Horizon angle maps along true azimuths: one band per azimuth, and the truncation mask.
#pragma once

#include "demlight/products/product.h"

#include <vector>

namespace demlight {

enum class HorizonMethod {
    Sweep,      ///< upper-convex-hull sweeps (demlight/lighting/horizon.h sweepHorizon)
    Reference,  ///< brute-force ray march (referenceHorizon)
};
/// "sweep" or "reference"; throws Error naming the choices.
HorizonMethod parseHorizonMethod(const std::string& name);
const char* horizonMethodName(HorizonMethod method);

struct HorizonRequest {
    /// True azimuths (degrees clockwise from north), one band each; at least one.
    std::vector<double> azimuthsDeg;
    HorizonMethod method = HorizonMethod::Sweep;
    SearchRequest search;
};

/// `directions` azimuths evenly spaced from 0 (0, 360/N, ...).
std::vector<double> evenAzimuthsDeg(std::size_t directions);

struct HorizonResult {
    /// Bands "horizon_azimuth=<deg>" (degrees); metadata DEMLIGHT_AZIMUTHS_DEG and the plan.
    ProductResult horizons;
    /// Byte bands "truncated_azimuth=<deg>": 1 where the search reached the DEM edge before the
    /// search distance, 0 elsewhere, kTruncationMaskNodata at DEM voids (its nodata value).
    ProductResult truncation;
    double maxDistanceM = 0;  ///< the search distance used (infinite = the whole DEM)
};

/// 16-bit storage of horizon angles (the compact horizon maps of Hoffman & Mitchell 2001a, in a
/// signed range so that downhill horizons survive): -90..90 deg over +-32767, a step of 90 / 32767
/// = 0.00275 deg, so a stored angle is within 0.0014 deg of the Float32 one; nodata -32768.
inline FixedPoint16 horizonFixedPoint() { return {90.0 / kFixedPoint16Max, 0.0, FixedPoint16{}.nodata}; }

/// Crops both results to `window` (onWindow).
void cropResult(HorizonResult& result, const CellWindow& read, const CellWindow& window);

/// Truncation mask value at DEM voids (declared as the mask's nodata).
inline constexpr std::uint8_t kTruncationMaskNodata = 255;

/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t horizonHaloCells(const DemSource& source, const HorizonRequest& request);

HorizonResult horizonProduct(const DemSource& source, const CellWindow& window, const HorizonRequest& request,
                             const ProgressFn& progress = {});

}  // namespace demlight
