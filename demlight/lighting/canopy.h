// Vegetation that lets a share of the light through: the vegetation scheme of SOLWEIG (Lindberg &
// Grimmond 2011, "The influence of vegetation and building morphology on shadow patterns and mean
// radiant temperatures in urban areas: model development and evaluation", Theoretical and Applied
// Climatology 105, 311-323), where a canopy height model (CDSM: vegetation height above ground)
// casts shadows that pass a transmissivity tau of the beam (SOLWEIG's default 3 %).
//
// demlight lights two surfaces: the ground-and-buildings surface G = DSM - canopy, and the full
// surface F = DSM (G + canopy). A quantity Q that is affine in the horizons' shading (the sun's
// visible disk O, O max(0, N.s), the sky factor K, and what irradiance derives from them) is
//     Q = tau Q_G + (1 - tau) Q_F,
// so where F hides the sun but G does not (the line passes through canopy only) the beam is
// scaled by tau, where G hides it (a building or the ground) it is hidden, and where neither does
// it is whole; the sky term does the same for each sector a crown blocks. A cell with canopy is
// lit on the ground under its crown (its height on G): its own crown covers its whole view, so Q_F
// there is Q with everything hidden (O = 0, K = 0). Both surfaces use G's normals. Crowns reach
// down to the ground (no trunk zone); a line through two crowns passes tau once, as in SOLWEIG.
#pragma once

#include "demlight/lighting/sun_frame.h"
#include "demlight/core/grid.h"

#include <cstdint>

namespace demlight {

/// SOLWEIG's default transmissivity of vegetation to the beam (Lindberg & Grimmond 2011).
inline constexpr double kDefaultCanopyTransmissivity = 0.03;

/// The ground-and-buildings heights G = surface - canopy where the canopy is above 0 (metres; the
/// canopy's NaN and values <= 0 leave the surface as it is), and the cells under a crown (1).
struct CanopyGround {
    Grid<float> groundM;
    Grid<std::uint8_t> underCrown;
};
/// Throws Error unless the grids have one shape.
CanopyGround canopyGround(const Grid<float>& surfaceM, const Grid<float>& canopyM);

/// tau * ground + (1 - tau) * surface, in `surface` (Q = tau Q_G + (1 - tau) Q_F). NaN stays NaN.
void blendCanopy(Grid<float>& surface, const Grid<float>& ground, double transmissivity);

/// `hidden` at the valid cells under a crown: 90 degrees in the full surface's horizons (then
/// everything is hidden from them), or the value of a quantity with everything hidden (0 for O).
void hideUnderCrown(Grid<float>& values, const Grid<std::uint8_t>& underCrown, float hidden);

/// A sun frame of the full surface blended with the ground's: visibility and irradiance of
/// `surface` become tau ground + (1 - tau) surface, the surface's hidden (0) under a crown. Both
/// frames must use the ground's normals.
void blendCanopySun(SunFrame& surface, const SunFrame& ground, const Grid<std::uint8_t>& underCrown,
                    double transmissivity);

}  // namespace demlight
