// Ambient aperture (Oat & Sander 2007, "Ambient Aperture Lighting"): per cell the
// visible solid angle A_p, the bent normal (normalised mean visible direction) and the radius
// r_p = arccos(1 - A_p / 2 pi) of the spherical cap of equal area; and the spherical cap-cap
// intersection used to light the aperture with a cap-shaped source (the sun disk).
//
// Visible set: as in Oat & Sander, the visibility function integrated over the hemisphere around
// the surface NORMAL: directions above the horizon h_i of their sector (same D-sector
// convention as sky.h) and above the cell's tangent plane (N.v > 0). Flat open ground: A_p =
// 2 pi sr, r_p = 90 degrees, bent normal = up.
#pragma once

#include "demlight/lighting/sky.h"
#include "demlight/core/grid.h"

#include <cstddef>
#include <span>
#include <vector>

namespace demlight {

/// Aperture of one cell.
struct Aperture {
    double solidAngleSr = 0.0;  ///< A_p (steradians), in [0, 2 pi]
    EnuVector bentNormal;       ///< unit ENU; the surface normal when nothing is visible
    double radiusDeg = 0.0;     ///< r_p = arccos(1 - A_p / 2 pi) (degrees), in [0, 90]
};

/// Aperture from D sector horizons (degrees) and the unit ENU normal. A_p and the mean
/// direction are closed forms per sector, also where the tangent plane clips it (demlight/lighting/
/// aperture.cpp); only sectors of 180 degrees or wider (D <= 2) fall back to 8-point
/// Gauss-Legendre directions on pieces at most 22.5 degrees wide, which a nearly vertical plane's
/// steep rise defeats (errors up to 0.01, tests/aperture_test.cpp).
Aperture aperture(std::span<const float> horizonDeg, const EnuVector& normal);

/// r_p (degrees) of the cap whose area is solidAngleSr: arccos(1 - A / 2 pi).
double apertureRadiusDeg(double solidAngleSr);

// ---- Spherical caps (radians) ----------------------------------------------------------------

/// Area (sr) of a spherical cap of angular radius rRad: 2 pi (1 - cos r).
double capAreaSr(double rRad);

/// Exact area (sr) of the intersection of two caps with angular radii r1Rad, r2Rad in
/// [0, pi] whose centres are dRad apart (Tovchigrechko & Vakser 2001, the form Oat & Sander
/// use): full containment -> area of the smaller cap; disjoint -> 0; otherwise
/// 2 [pi - acos((cos d - cos r1 cos r2) / (sin r1 sin r2))
///        - cos r1 acos((cos r2 - cos d cos r1) / (sin d sin r1))
///        - cos r2 acos((cos r1 - cos d cos r2) / (sin d sin r2))].
double capIntersectionAreaSr(double r1Rad, double r2Rad, double dRad);

/// Oat & Sander's cheaper approximation (Oat & Sander 2007, Sec. 3.2):
/// capArea(min(r1, r2)) * smoothstep(0, 1, 1 - (d - |r1 - r2|) / (r1 + r2 - |r1 - r2|)).
/// Same containment/disjoint cases as the exact form, and exact at both ends of the partial
/// range. Measured error (tests/aperture_test.cpp, radii 0.25..90 degrees, all separations):
/// at most kCapSmoothstepMaxError of the smaller cap's area (worst for caps of similar radius,
/// where the exact area falls linearly from full overlap but smoothstep starts flat); for a
/// sun-sized cap against an aperture of 10..90 degrees at most kCapSmoothstepSunMaxError.
double capIntersectionAreaSmoothSr(double r1Rad, double r2Rad, double dRad);

/// Bounds on |smooth - exact| / capArea(min(r1, r2)) checked by the tests.
inline constexpr double kCapSmoothstepMaxError = 0.17;
inline constexpr double kCapSmoothstepSunMaxError = 0.05;

/// Vector integral of v d(omega) over the intersection of two caps (centres c1, c2 unit ENU,
/// radii in radians): |result| <= area, result / area is the mean direction, and
/// N.result / area is the EXACT mean Lambert term over the intersection whenever it lies above
/// the tangent plane. Closed form by the boundary identity integral_S v dA =
/// 1/2 closed-integral r x dr: each boundary arc (half-angle alpha_i about the direction t_i
/// from c_i towards the other centre) contributes alpha_i sin^2 r_i c_i
/// - sin r_i cos r_i sin alpha_i t_i, with cos alpha_i the ratios of the area formula.
/// Containment: pi sin^2 r c of the smaller cap; disjoint: zero.
EnuVector capIntersectionVector(const EnuVector& c1, double r1Rad, const EnuVector& c2,
                                double r2Rad);

/// Unit direction of capIntersectionVector: the intersection's centroid seen from the cell
/// (Oat & Sander's Lambert direction). Returns `light` when the caps are disjoint.
EnuVector capIntersectionCentroid(const EnuVector& light, double lightRadiusRad,
                                  const EnuVector& aperture, double apertureRadiusRad);

/// Cheap centroid for the smoothstep path: the midpoint of the lens's extent along the great
/// circle through both centres (containment gives the inner centre). For a sun disk cut in
/// half by the aperture rim this puts the centroid at r_l / 2 instead of ~0.42 r_l from the
/// rim (the half-disk centroid 4 r / 3 pi), which matters only with the sun on the horizon.
EnuVector capIntersectionCentroidFast(const EnuVector& light, double lightRadiusRad,
                                      const EnuVector& aperture, double apertureRadiusRad);

// ---- Grid drivers ----------------------------------------------------------------------------

/// Aperture grids; NaN where a horizon or the normal is NaN.
struct ApertureMaps {
    Grid<float> bentEast, bentNorth, bentUp;  ///< bent normal, unit ENU
    Grid<float> radiusDeg;                    ///< r_p (degrees)
    Grid<float> solidAngleSr;                 ///< A_p (steradians)
};

/// Streaming form (one horizon grid at a time); memory 4 doubles per cell. Same contract as
/// SkyAccumulator: every direction exactly once, normals must outlive it, bit-identical for
/// any thread count.
class ApertureAccumulator {
public:
    ApertureAccumulator(const Grid<float>& normalEast, const Grid<float>& normalNorth,
                        const Grid<float>& normalUp, std::size_t directions);
    void addDirection(std::size_t index, const Grid<float>& horizonDeg);
    /// The same with the accumulator's cells at `cells` of a larger horizon grid (a tile's
    /// window inside the grid swept with its halo); `cells` must match the normals' size.
    void addDirection(std::size_t index, const Grid<float>& horizonDeg, const CellWindow& cells);
    ApertureMaps finish() const;
    /// Bytes of sums held per cell.
    static constexpr std::size_t kBytesPerCell = 4 * sizeof(double);

private:
    const Grid<float>& east_;
    const Grid<float>& north_;
    const Grid<float>& up_;
    std::size_t directions_;
    std::vector<bool> added_;
    Grid<double> omega_, ve_, vn_, vu_;
};

/// All D grids at once (horizonsDeg[i] is azimuth i * 360 / D).
ApertureMaps computeAperture(const std::vector<const Grid<float>*>& horizonsDeg,
                             const Grid<float>& normalEast, const Grid<float>& normalNorth,
                             const Grid<float>& normalUp);

}  // namespace demlight
