// Integrals of direct sun over a sequence of instants (docs/design.md §6.6):
// hours of direct sun, normalised sun irradiation, and the first and last time each cell is lit;
// and the hours of daylight, from which the sky irradiation follows.
//
// Quadrature: the trapezoid rule over the given instants (any spacing), so a quantity that is
// constant over [t0, tN] integrates to exactly its value times (tN - t0). Instants where the
// sun's upper limb is below the horizon everywhere (field elevation < kSunDownElevationDeg) are
// not swept: every valid cell gets visibility 0 there.
//
// Sky irradiation: the sky is a uniform sky of unit radiance (docs/design.md §3: a flat open cell
// gets 1) while the sun is up, and dark otherwise. The sky term does not depend on the sun's
// position, so its integral is the cell's sky term (computed once: K, or f_sky) times the cell's
// hours of daylight (skyIrradiation). Daylight is SPA's sunrise-to-sunset at the cell, with no
// terrain: the GEOMETRIC elevation of the sun's centre above kSunriseGeometricElevationDeg. It is
// interpolated linearly between instants and each crossing integrated exactly (geometric, not
// apparent, elevation: SPA switches refraction on at that elevation, so the apparent elevation
// jumps by ~0.6 deg there and cannot be interpolated across). Neither the sun's elevation nor
// the atmosphere modulates the sky (no diffuse-share model): scale by a measured diffuse
// radiation for absolute units.
#pragma once

#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/grid.h"
#include "demlight/core/progress.h"
#include "demlight/core/sun_field.h"
#include "demlight/core/terrain.h"

#include <functional>
#include <span>

namespace demlight {

/// Below this sun elevation everywhere (degrees) an instant is dark without any sweep.
/// computeSunFrame already treats the sun as set once its upper limb is below the level horizon
/// everywhere (elevation < -0.27°), so this cut-off loses nothing it would have computed; it only
/// saves the frame set-up. (A cell on a steep slope at a summit could in reality see a sun a
/// little below level; neither driver models that.)
inline constexpr double kSunDownElevationDeg = -1.0;

/// Geometric (unrefracted) elevation of the sun's centre at sunrise and sunset (degrees): the
/// upper limb on the horizon under the standard 0.5667 deg of refraction, SPA's convention
/// (Reda & Andreas A.2: -(0.26667 + 0.5667)).
inline constexpr double kSunriseGeometricElevationDeg = -0.8333;

/// Visibility at which a cell counts as lit for first_lit / last_lit: half the sun's disk above
/// the cell's horizon (the cell's own sunrise / sunset, as SPA's is for the sun's centre).
inline constexpr double kLitVisibility = 0.5;

/// One instant of the sequence.
struct SunInstant {
    double hours = 0;       ///< time of the instant (hours from any fixed origin), increasing
    double clockHours = 0;  ///< local clock time of the instant (hours, e.g. 6.25 = 06:15)
};

struct HorizonStack;

struct SunHoursParams {
    SunFrameParams frame;  ///< sun disk, search distance, refraction
    /// Set: each instant's sun horizons are interpolated from this stack (sunLightFromStack, the
    /// `interpolated:N` horizon mode) instead of an exact sweep along its azimuth.
    const HorizonStack* stack = nullptr;
    /// Set (exact sweeps only, no stack): vegetation over the terrain (demlight/lighting/canopy.h); each
    /// instant's frame is blended with the frame of this ground-and-buildings terrain.
    const Terrain* canopyGround = nullptr;
    const Grid<std::uint8_t>* underCrown = nullptr;  ///< with canopyGround: the cells under a crown
    double transmissivity = 0;                       ///< with canopyGround: tau
};

struct SunHoursMaps {
    Grid<float> sunHours;        ///< ∫ visibility dt (hours); NaN at nodata
    Grid<float> sunIrradiation;  ///< ∫ normalised irradiance dt (normalised irradiance × hours)
    Grid<float> firstLitClock;   ///< local clock hours when visibility first reaches 0.5; NaN if never
    Grid<float> lastLitClock;    ///< local clock hours when visibility last drops below 0.5; NaN if never
    std::size_t instantsSwept = 0;  ///< instants with the sun up somewhere (each costs a sweep)
};

/// Directions of a stack when none are given (`interpolated` alone, and sunhours' auto choice).
inline constexpr std::size_t kDefaultStackDirections = 64;

/// Horizon maps at N equally spaced true azimuths (direction i at i * 360 / N degrees), swept
/// once for a whole sequence: the `interpolated:N` horizon mode of time-lapses. Memory: N floats
/// per cell.
struct HorizonStack {
    std::vector<Grid<float>> angleDeg;  ///< NaN at nodata
    double maxDistanceM = 0;
};

/// Sweeps the N directions (params.azimuthDeg is ignored). Progress counts cells swept.
HorizonStack computeHorizonStack(const Terrain& terrain, std::size_t directions,
                                 const HorizonParams& params, ProgressCounter* progress = nullptr);

/// Sun light at one instant from a stack instead of an exact sweep: each cell's horizon is
/// interpolated linearly in azimuth between the two directions bracketing its own sun azimuth,
/// then visibility and irradiance as computeSunFrame (Hoffman & Mitchell 2001b, Eq. 3, 5-7). All
/// zero (NaN at nodata) when the sun's upper limb is below the horizon everywhere.
SunLight sunLightFromStack(const Terrain& terrain, const Normals& normals,
                           const HorizonStack& stack, const SunField& field,
                           double sunDiameterDeg);

/// Returns the sun across the DEM at instant i of the sequence.
using SunFieldAt = std::function<SunField(std::size_t instantIndex)>;

/// Hours of daylight of every valid cell over `instants` (at least 2, strictly increasing; NaN at
/// nodata): the time the sun's geometric elevation, interpolated linearly between instants, is
/// above kSunriseGeometricElevationDeg. `geometricFieldAt(i)` must give the sun at instant i
/// WITHOUT refraction (elevationDeg geometric). Deterministic for any thread count.
Grid<float> integrateDaylight(const Terrain& terrain, std::span<const SunInstant> instants,
                              const SunFieldAt& geometricFieldAt);

/// Sky irradiation: skyTerm × daylightHours per cell, in the units of
/// SunHoursMaps::sunIrradiation (1 h of a unit sky on open flat ground = 1). `skyTerm` is the
/// sky's normalised irradiance under a unit uniform sky (K, or f_sky with interreflection).
/// NaN where either is NaN. Throws Error on different shapes.
Grid<float> skyIrradiation(const Grid<float>& skyTerm, const Grid<float>& daylightHours);

/// Integrates direct sun over `instants` (at least 2). first/last lit are interpolated linearly
/// between samples where visibility crosses kLitVisibility; a cell lit at the first (last)
/// instant gets that instant's clock time. Progress counts instants. Deterministic for any
/// thread count.
SunHoursMaps integrateSunHours(const Terrain& terrain, const Normals& normals,
                               std::span<const SunInstant> instants, const SunFieldAt& fieldAt,
                               const SunHoursParams& params, ProgressCounter* progress = nullptr);

}  // namespace demlight
