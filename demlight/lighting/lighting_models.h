// Lighting models that turn per-cell geometry (normals, horizons, apertures, sky factors) into
// normalised irradiance (irradiance / pi for unit source radiance; docs/design.md §3): a flat,
// unshadowed cell under a unit zenith sun, or under a unit uniform sky, gets 1.0.
//
//   horizon          sun visibility from the horizon angle in the sun's azimuth (Hoffman &
//                    Mitchell Eq. 5-7) times max(0, N.s); computed by demlight/lighting/sun.h, not here
//   aperture         Oat & Sander ambient aperture, exact cap-cap intersection
//   aperture-smooth  the same with the smoothstep approximation of the intersection
// and the sky models: stewart-langer (demlight/lighting/sky.h) and Hargreaves hemisphere lighting (a
// sky-only model, no shadows).
#pragma once

#include "demlight/lighting/aperture.h"
#include "demlight/lighting/sky.h"
#include "demlight/core/grid.h"
#include "demlight/core/sun_field.h"

#include <string_view>

namespace demlight {

/// How the direct sun is modelled.
enum class SunModel { Horizon, Aperture, ApertureSmooth };
/// "horizon", "aperture" or "aperture-smooth"; throws Error naming the choices.
SunModel parseSunModel(std::string_view name);
std::string_view sunModelName(SunModel model);

/// How the sky term is modelled: Stewart & Langer's horizon-based K and f_sky, Hargreaves'
/// hemisphere (no occlusion), or no sky.
enum class SkyModel { StewartLanger, Hemisphere, None };
/// "stewart-langer", "hemisphere" or "none"; throws Error naming the choices.
SkyModel parseSkyModel(std::string_view name);
std::string_view skyModelName(SkyModel model);

// ---- Ambient aperture (Oat & Sander 2007, Sec. 3) ---------------------------------------------

/// Sun angular radius (degrees): half of kSunDiameterDeg (demlight/lighting/sun.h).
inline constexpr double kSunRadiusDeg = 0.5 * kSunDiameterDeg;

struct ApertureLightParams {
    double sunRadiusDeg = kSunRadiusDeg;  ///< light cap radius (degrees); larger = softer shadows
    double sunRadiance = 1.0;    ///< normalised: a fully visible zenith sun on flat ground gives this
    double ambientRadiance = 1.0;  ///< uniform sky radiance used for the ambient fill
    bool smoothIntersection = false;  ///< true: smoothstep approximation (aperture-smooth)
};

/// The two terms of the aperture model for one cell (normalised irradiance).
struct ApertureLight {
    double sun = 0.0;      ///< sunRadiance * integral over the intersection of N.v / (pi sin^2 r_l)
    double ambient = 0.0;  ///< ambientRadiance * sin^2(r_p) max(0, N.V_p) * (1 - A_int / A_p)
    double sunVisible = 0.0;  ///< A_int / A_sun: covered fraction of the sun cap, in [0, 1]
    double total() const { return sun + ambient; }
};

/// Direct term: the sun cap (centre sunDirection, radius sunRadiusDeg) intersected with the
/// aperture cap (centre bent normal, radius r_p), normalised so that a fully visible sun gives
/// max(0, N.s) exactly (Hoffman & Mitchell Eq. 3 with O = 1).
///   aperture:        max(0, N . capIntersectionVector) / (pi sin^2 r_l) -- the intersection
///                    centroid times its area, which is the exact Lambert integral over the
///                    intersection while it lies above the tangent plane (pi sin^2 r_l is
///                    that integral for the whole disk at normal incidence);
///   aperture-smooth: smoothstep area / A_sun * max(0, N . capIntersectionCentroidFast).
/// Ambient fill: Oat & Sander fill the part of the aperture the sun does not cover with sky
/// light; we weight it with the exact Lambert integral of a uniform cap that does not cross
/// the tangent plane, (1/pi) integral_cap N.v d(omega) = sin^2(r_p) N.V_p, so a flat open cell
/// under a unit sky gets 1 - A_int / A_p ~ 1.
ApertureLight apertureLight(const EnuVector& normal, const Aperture& aperture,
                            const EnuVector& sunDirection, const ApertureLightParams& params);

/// Grids of the two aperture terms; NaN where any input is NaN.
struct ApertureLightMaps {
    Grid<float> sun;
    Grid<float> ambient;
};

/// Applies apertureLight to every cell for one sun direction (true ENU unit vector).
ApertureLightMaps applyApertureLight(const ApertureMaps& aperture, const Grid<float>& normalEast,
                                     const Grid<float>& normalNorth, const Grid<float>& normalUp,
                                     const EnuVector& sunDirection,
                                     const ApertureLightParams& params);

/// Sun through the aperture for a whole DEM at one instant (`demlight sun --model aperture`,
/// `aperture-smooth`): every cell with its own sun position from `field` (bilinear at the cell
/// centre), so the result matches the horizon model's per-cell sun.
///   visibility = ApertureLight::sunVisible, the covered fraction of the sun cap (the aperture
///                model's counterpart of the horizon model's visible fraction of the disk);
///   irradiance = ApertureLight::sun, the direct term (max(0, N.s) for a fully covered sun).
/// The ambient fill is not included: it is sky light (see `demlight sky`). NaN where any input
/// is NaN.
struct ApertureSunMaps {
    Grid<float> visibility;
    Grid<float> irradiance;
};
ApertureSunMaps applyApertureSun(const ApertureMaps& aperture, const Grid<float>& normalEast,
                                 const Grid<float>& normalNorth, const Grid<float>& normalUp,
                                 const SunField& field, const ApertureLightParams& params);

// ---- Hemisphere lighting (Hargreaves 2003) ---------------------------------------------------

/// sky * (1 + N_up) / 2 + ground * (1 - N_up) / 2, normalUp in [-1, 1].
double hemisphereLight(double normalUp, double skyRadiance, double groundRadiance);

struct HemisphereParams {
    double skyRadiance = 1.0;        ///< normalised sky radiance
    double groundIrradiance = 1.0;   ///< light falling on the surrounding ground (normalised)
    double albedo = 0.2;             ///< ground albedo when no albedo raster is given
};

/// Per-cell hemisphere lighting; ground radiance = albedo * groundIrradiance with the albedo
/// from `albedo` (same size as normalUp) or params.albedo. NaN normal or albedo gives NaN.
Grid<float> applyHemisphereLight(const Grid<float>& normalUp, const HemisphereParams& params,
                                 const Grid<float>* albedo = nullptr);

}  // namespace demlight
