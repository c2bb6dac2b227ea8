// A perspective picture of lit terrain: each pixel's ray is cast exactly against the bilinear
// surface (demlight/lighting/max_mipmap.h), takes the linear radiance of the point it meets (the lit
// ground's, interpolated between cell centres), and passes through an atmosphere on its way to
// the eye: aerial perspective (extinction and in-scattering by a haze whose density falls off
// exponentially with height) and, where no terrain is met, a sky with the sun's disk.
//
// Frame: east-north-up metres with the DEM's cell (0, 0) centre at the origin, E along the grid's
// columns and N against its rows (grid north; a projected DEM's grid is turned from true north by
// the meridian convergence, which the caller folds into the directions it gives). Cells are
// cellWidthM x cellHeightM everywhere (a lat/lon DEM: those of its middle row).
// Earth curvature: the surface is lowered by d^2 / (2 R_eff) at ground distance d from the eye,
// so a straight ray meets what a ray bent by refraction k over a round earth meets (docs/design.md,
// the curvature rule, applied once per picture); far ranges sink below the horizon.
#pragma once

#include "demlight/lighting/max_mipmap.h"
#include "demlight/lighting/preview.h"
#include "demlight/core/grid.h"
#include "demlight/core/image.h"

#include <array>
#include <cstddef>
#include <vector>

namespace demlight {

/// A point or direction in the frame above (metres).
struct Enu3 {
    double e = 0, n = 0, u = 0;
};

struct ViewCamera {
    Enu3 eye;
    Enu3 target;
    double fieldOfViewDeg = 45;  ///< horizontal
    std::size_t width = 1280, height = 720;
};

/// The unit direction of pixel (px, py) (centre at + 0.5; row 0 at the top) of a camera with no
/// roll: its right vector is horizontal.
Enu3 pixelDirection(const ViewCamera& camera, double px, double py);
/// Where a point projects on the picture (pixel coordinates, centre of pixel (0, 0) at (0.5,
/// 0.5)); behind the camera gives {NaN, NaN}.
std::array<double, 2> projectPoint(const ViewCamera& camera, const Enu3& point);

struct ViewAtmosphere {
    bool haze = true;  ///< aerial perspective on the terrain
    bool sky = true;   ///< sky and sun disk behind the terrain (else black, alpha 0)
    /// Meteorological visibility at sea level (km, Koschmieder: extinction 3.912 / V at 550 nm).
    double visibilityKm = 120;
    /// Height over which the haze thins by e (metres): aerosol scale height.
    double scaleHeightM = 1500;
};

struct ViewLight {
    double sunAzimuthDeg = 0;    ///< true azimuth of the sun at the scene
    double sunElevationDeg = 0;  ///< apparent elevation
    double gridConvergenceDeg = 0;  ///< gamma: grid north's true azimuth (frame directions are grid)
    double sunDiameterDeg = 0.53;
    Rgb sunColor = PreviewParams{}.sunColor;
    Rgb skyColor = PreviewParams{}.skyColor;
};

/// The terrain as the view sees it.
struct ViewScene {
    const Grid<float>* heightsM = nullptr;      ///< the surface's heights (exaggerated, curvature applied: viewHeights)
    /// The ground's linear albedo and the light on it per cell (R, G, B): the radiance leaving a
    /// cell is their product, taken at the four cells around the point a ray meets.
    std::array<const Grid<float>*, 3> albedo{}, light{};
    /// The DEM's own heights: a NaN cell is sea (with `sea`, radiance seaRadiance), else a hole.
    const Grid<float>* groundHeightsM = nullptr;
    bool sea = false;
    Rgb seaRadiance;
    double cellWidthM = 1, cellHeightM = 1;
    /// Heights of the haze: a frame height z stands for the altitude z / exaggeration + d^2 / (2 R_eff)
    /// (d from the eye), so the haze thins with the true altitude, not the exaggerated one.
    double exaggeration = 1;
    double effectiveRadiusM = 0;  ///< R / (1 - k); 0: flat earth
};

/// Heights as the view casts rays against them: exaggeration * h - d^2 / (2 R_eff), d the ground
/// distance from the eye (effectiveRadiusM 0: no curvature). NaN stays NaN.
Grid<float> viewHeights(const Grid<float>& heightsM, double cellWidthM, double cellHeightM, double exaggeration,
                        const Enu3& eye, double effectiveRadiusM);

/// The haze between a point and the eye: transmittance per channel (R, G, B) along a segment of
/// `lengthM` from altitude z0 to z1 (metres), through extinction 3.912 / V scaled per channel
/// and thinning as exp(-z / H). Decreases with length; 1 at length 0 or with haze off.
Rgb hazeTransmittance(const ViewAtmosphere& atmosphere, double lengthM, double z0M, double z1M);

/// Radiance the haze scatters towards the eye looking along `direction` (unit, frame): sky light
/// plus sunlight, forward scattered (Henyey-Greenstein) towards the sun.
Rgb hazeInscatter(const ViewLight& light, const Enu3& direction);
/// Radiance of the sky along `direction`: the haze's colour at the horizon, deepening to blue
/// towards the zenith, the sun's glow and its disk.
Rgb skyRadiance(const ViewLight& light, const Enu3& direction);

struct ViewImage {
    Image8 image;
    std::vector<float> linear;  ///< R, G, B per pixel, row-major, before exposure and gamma
    std::vector<float> distanceM;  ///< distance to the terrain per pixel; +inf where none is met
};

/// Renders the scene (parallel over rows; the same bits on any number of threads). Pixels whose
/// ray meets no terrain show the sky (or are transparent black without it).
ViewImage renderView(const ViewScene& scene, const MaxMipmap& surface, const ViewCamera& camera, const ViewLight& light,
                     const ViewAtmosphere& atmosphere, const PreviewParams& display);

}  // namespace demlight
