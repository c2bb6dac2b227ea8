// The walk of a block of scan lines far to near: hulls pushed and popped (hull.h, or eight lines
// at once on the AVX-512 path), and cells served from the lines beside them into two planes of
// tangents that combine.h turns into angles.
#pragma once

#include "demlight/lighting/sweep/line_geometry.h"
#include "demlight/lighting/sweep/valid_cells.h"

#include <cstddef>

namespace demlight::sweep {

/// Lines processed in lock-step by one task: adjacent lines touch adjacent cells at each step,
/// so a block reads and writes a few cache lines per step whatever the direction.
inline constexpr std::size_t kLinesPerBlock = 16;

/// Walks lines [kBegin, kEnd) of a region (at most kLinesPerBlock) and serves the cells they
/// reach into planeA (and planeB where two lines serve a cell), the terrain's cells' grids.
/// Blocks along a grid axis over the whole DEM go through walkAxisBlock (axis_walk.h).
/// eightAtOnce: the AVX-512 path's lanes where they apply.
void walkLineBlock(const Terrain& t, const LineGeometry& geo, double invR, double maxDistanceM, long kBegin,
                   long kEnd, float* planeA, float* planeB, const ValidCells& valid, bool eightAtOnce);

}  // namespace demlight::sweep
