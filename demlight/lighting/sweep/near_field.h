// The exact near field of a sweep: terrain within a few line steps of a cell sampled on the ray
// from the cell's own centre at the reference's quarter-cell steps, on the bilinear surface.
#pragma once

#include "demlight/lighting/sweep/line_geometry.h"
#include "demlight/core/grid.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace demlight::sweep {

/// One point of the near field's stencil: the ray from a cell centre, `dc` columns and `dr` rows
/// away, at distance d; its bilinear taps (offsets from the cell, weights > 0, padded to four
/// with zero-weight copies of the first so every point costs the same).
struct NearPoint {
    double dc, dr;
    float invDistance, drop;  // 1/d (1/metres) and d/(2 R_eff): slope = (h - h0)/d - d/(2 R_eff)
    long tapCol[4], tapRow[4];
    float weight[4];
    int taps;  // 2 when the point lies on a grid line (weights 2 and 3 zero), else 4
};

/// The near field's points for cells of full-grid row `row` (see near_field.cpp).
void nearStencil(const LineGeometry& geo, const FullGridRef& g, std::size_t row, double maxDistanceM, double invR,
                 std::vector<NearPoint>& out);

/// The near-field slopes of the cells of full-grid row `row` in window `w` (see near_field.cpp).
void nearFieldRow(const Terrain& t, const FullGridRef& g, const CellWindow& cells, std::size_t row,
                  const CellWindow& w, RowSpan heights, const std::vector<NearPoint>& stencil,
                  std::vector<float>& out, std::vector<std::uint8_t>& bad);

}  // namespace demlight::sweep
