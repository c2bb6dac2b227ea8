// The walk of a block of scan lines along a grid axis through the gather-free hull kernel
// (demlight/lighting/hull_lanes.h): where lines run through cell centres, each cell's horizon
// is its own sample's tangent to the hull of the samples before it, which is what the kernel
// computes for every sample of sixteen lines at once.
#pragma once

#include "demlight/lighting/sweep/line_geometry.h"

namespace demlight::sweep {

/// Whether walkAxisBlock serves a region's lines: lines along a grid axis (slope 0: cells served
/// as the walk reaches them, no crossing points).
bool axisKernelServes(const LineGeometry& geo);

/// Lines [kBegin, kEnd) of a region that axisKernelServes, walked to the nearest window cell:
/// every window cell they pass gets its sample's slope to the hull (curvature included) in
/// planeA, -inf where no earlier sample has data; nodata cells are not written. Lines along
/// columns are read in place, lines along rows through a transposed copy.
/// Without a range limit (`limited` false, as walkLineBlock decides it) the walk starts at the
/// far edge and the hull holds every sample before the cell. With one, the kernel restarts at
/// every chunk of maxDistanceM (anchored to the full grid's far edge, as the walk of lines one
/// by one cuts them), and the previous chunk's samples within range are added in double, from
/// a hull grown from that chunk's near end: both parts see the same samples in a tile as in its
/// DEM, so they give the same bits.
void walkAxisBlock(const Terrain& t, const LineGeometry& geo, double invR, double maxDistanceM, bool limited,
                   long kBegin, long kEnd, float* planeA);

}  // namespace demlight::sweep
