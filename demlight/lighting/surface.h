// Surface normals of a DEM in the local east-north-up frame, from true metric cell sizes.
#pragma once

#include "demlight/core/grid.h"
#include "demlight/core/terrain.h"

namespace demlight {

/// A unit vector in the local east-north-up frame (components along true east, true north, up).
struct Enu {
    double east = 0.0;
    double north = 0.0;
    double up = 1.0;
};

/// Unit surface normals, one component per grid (true east, true north, up); NaN at nodata.
struct Normals {
    Grid<float> east;
    Grid<float> north;
    Grid<float> up;

    Enu at(std::size_t col, std::size_t row) const {
        return {east(col, row), north(col, row), up(col, row)};
    }
};

/// Normals from central height differences over the true metric distances between cell centres
/// (per-row cell sizes), one-sided at the DEM edge and next to nodata (zero slope along an axis
/// with no valid neighbour). The gradient is taken along the grid axes and rotated by the
/// meridian convergence gamma into true east/north. Parallel over rows (0 = all cores).
Normals computeNormals(const Terrain& terrain);
/// The normals of `cells` of the terrain only (grids of the window's size), with the same bits
/// as computeNormals gives those cells: a tile's window inside the terrain read with its halo.
/// `cells` must lie inside the terrain.
Normals computeNormals(const Terrain& terrain, const CellWindow& cells);

}  // namespace demlight
