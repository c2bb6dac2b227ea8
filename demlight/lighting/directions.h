// Horizons in D evenly spaced true azimuths (0, 360/D, ...), handed one at a time to a consumer
// (the sky and aperture accumulators), so no more than one horizon grid is held at once.
#pragma once

#include "demlight/lighting/horizon.h"

#include <functional>

namespace demlight {

/// Azimuth of direction `index` of `directions` (degrees).
double directionAzimuthDeg(std::size_t index, std::size_t directions);

/// Sweeps every direction with `params` (its azimuthDeg is ignored) and calls
/// consume(index, horizon) in index order.
void sweepDirections(const Terrain& terrain, HorizonParams params, std::size_t directions,
                     const std::function<void(std::size_t, const HorizonMap&)>& consume,
                     ProgressCounter* progress = nullptr);

}  // namespace demlight
