// The walk of a block of scan lines along a grid axis through the gather-free hull kernel
// (demlight/lighting/hull_lanes.h): where lines run through cell centres, each cell's horizon
// is its own sample's tangent to the hull of the samples before it, which is what the kernel
// computes for every sample of sixteen lines at once.
#pragma once

#include "demlight/lighting/sweep/line_geometry.h"

namespace demlight::sweep {

/// Whether walkAxisBlock serves a region's lines: lines along a grid axis (slope 0: cells served
/// as the walk reaches them, no crossing points) searched over the whole DEM (no range limit;
/// `limited` as walkLineBlock decides it).
bool axisKernelServes(const LineGeometry& geo, bool limited);

/// Lines [kBegin, kEnd) of a region that axisKernelServes, walked from the far edge to the
/// nearest window cell: every window cell they pass gets its sample's slope to the hull (curvature
/// included) in planeA, -inf where no earlier sample has data; nodata cells are not written.
/// Lines along columns are read in place, lines along rows through a transposed copy.
void walkAxisBlock(const Terrain& t, const LineGeometry& geo, double invR, long kBegin, long kEnd, float* planeA);

}  // namespace demlight::sweep
