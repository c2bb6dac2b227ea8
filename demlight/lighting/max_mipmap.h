// Exact ray casting of a height field with a maximum mipmap: Tevs, Ihrke & Seidel 2008, "Maximum
// mipmaps for fast, accurate, and scalable dynamic height field rendering" (I3D '08), section 3.
// The surface is the one demlight lights everywhere: bilinear between cell centres (vertex
// (i, j) = cell (col i, row j)), so patch (i, j) spans [i, i + 1] x [j, j + 1] and the ray meets
// it where a quadratic in the ray parameter has its first root (Tevs et al. 3.3). Level 0 of the
// pyramid holds each patch's highest corner; level k + 1 the highest of 2 x 2 nodes of level k.
// A ray descends into a node only where it passes below the node's maximum, and climbs a level
// after leaving one (Tevs et al. 3.2), so a ray over open country crosses it in large steps.
#pragma once

#include "demlight/core/grid.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace demlight {

/// A ray in grid coordinates: x along columns, y along rows (in cells; cell centres at integer
/// values), z in the height field's unit. Points are origin + t * direction for t >= 0.
struct GridRay {
    double x = 0, y = 0, z = 0;
    double dx = 0, dy = 0, dz = 0;
};

/// Where a ray first meets the surface: its parameter and the point (grid coordinates, height).
struct GridHit {
    double t = 0;
    double x = 0, y = 0, z = 0;
};

/// The pyramid of patch maxima of a height field (NaN cells are holes: a patch with a NaN
/// corner is not there and its maximum is -inf).
class MaxMipmap {
public:
    /// Builds the levels (parallel over rows). Needs at least 2 x 2 cells.
    explicit MaxMipmap(const Grid<float>& heights);

    /// First intersection of `ray` with the surface at t in [0, tMax], or none.
    std::optional<GridHit> cast(const GridRay& ray, double tMax) const;

    const Grid<float>& heights() const { return *heights_; }
    std::size_t levels() const { return levels_.size(); }
    /// The highest point of the surface (-inf when every patch is a hole).
    float top() const { return levels_.back()(0, 0); }

private:
    const Grid<float>* heights_;
    std::vector<Grid<float>> levels_;  ///< levels_[0]: (W - 1) x (H - 1) patch maxima
};

/// First root s in [s0, s1] of the ray with patch (i, j) of `heights` (the patch's corners must
/// be finite), or none: Tevs et al. 3.3, the bilinear patch along a line is a quadratic in s. A
/// ray already under the patch at s0 (come through a hole or the field's side) gets none: the
/// surface is met from above only, so holes and the field's edges have no walls.
std::optional<double> intersectPatch(const Grid<float>& heights, std::size_t i, std::size_t j, const GridRay& ray,
                                     double s0, double s1);

/// The same intersection found without the pyramid, by visiting every patch the ray crosses in
/// turn (a 2-D grid walk): the reference the pyramid's answer is tested against.
std::optional<GridHit> castRayThroughEveryPatch(const Grid<float>& heights, const GridRay& ray, double tMax);

}  // namespace demlight
