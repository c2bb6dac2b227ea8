// The regions of a sweep: the output split into parts each swept along one straight grid
// direction, laid on the full grid a terrain was cut from (sweepRegions in
// demlight/lighting/horizon.h).
#pragma once

#include "demlight/lighting/horizon.h"

#include <vector>

namespace demlight::sweep {

/// The regions of the params' output window (all of the terrain without one), in full-grid
/// coordinates; validates the params first.
std::vector<SweepRegion> fullGridRegions(const Terrain& terrain, const HorizonParams& params);

}  // namespace demlight::sweep
