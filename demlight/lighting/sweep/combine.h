// The combine of a sweep: the tangents the lines served (two planes) and the near field's into
// horizon angles, and the truncation flags.
#pragma once

#include "demlight/lighting/sweep/line_geometry.h"

#include <cstddef>
#include <cstdint>

namespace demlight::sweep {

/// Angles (and truncation flags, when `truncated` is not null) of full-grid row `row` of window
/// `w` (see combine.cpp).
void combineRow(const LineGeometry& geo, const Terrain& terrain, const FullGridRef& g, double maxDistanceM,
                double invR, std::size_t row, const CellWindow& w, const CellWindow& terrainCells, float* planeA,
                const float* planeB, std::uint8_t* truncated);

}  // namespace demlight::sweep
