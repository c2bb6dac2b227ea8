// "Model no more than a scene needs" (docs/design.md §6.11): from the scene and an error budget,
// choose the search distance, curvature, scan-direction tolerance, number of sky directions and
// sun-position granularity. `auto` spends only what the budget needs; `full` turns every effect on
// at its finest setting. The plan is recorded in output metadata and printed with --verbose.
#pragma once

#include "demlight/lighting/horizon.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/core/terrain.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace demlight {

enum class Quality { Auto, Full };

/// "auto" or "full"; throws Error naming the option otherwise.
Quality parseQuality(std::string_view name);
std::string_view qualityName(Quality q);

/// A scene with at least this share of steep neighbour steps (SteepSteps: slopes over 45 deg
/// between adjacent cells) is a surface model: walls and roof edges, not terrain. The project's
/// terrain DEMs measure 0–1.6 %, its surface models 11–32 %.
inline constexpr double kSurfaceModelSteepShare = 0.05;
/// Near field of the sweeps on terrain and on surface models (line steps): each is the smallest
/// that meets the horizon targets on its kind of scene, measured against the reference
/// (docs/accuracy.md, "Surface models").
inline constexpr int kTerrainNearFieldSteps = 4;
inline constexpr int kSurfaceNearFieldSteps = 16;
/// Below this share of steep neighbour steps the far field's grid-line crossings
/// (HorizonParams::farFieldCrossings) are left out: they sample edges that are steep between two
/// line steps (wall top edges, cliffs), and off the grid axes they cost a third of the sweep.
/// Set where leaving them out still keeps auto within its tolerance of full (measured: docs/
/// accuracy.md, "How the horizon is computed, and how accurate it is", after the terrain table).
inline constexpr double kFarFieldCrossingsSteepShare = 0.01;

/// Sky and aperture directions used by `auto`: the measured default (demlight/lighting/sky.h); on
/// surface models kFullSkyDirections (the sky budget needs them there: docs/accuracy.md).
inline constexpr int kAutoSkyDirections = static_cast<int>(kDefaultSkyDirections);
/// Directions used by `full`.
inline constexpr int kFullSkyDirections = 64;
/// Largest direction-tolerance floor auto takes from a loose --tolerance (degrees).
inline constexpr double kMaxDirectionFloorDeg = 0.5;

/// The default horizon error budget of --quality auto (degrees); the expected errors of
/// ExpectedError were measured with it.
inline constexpr double kDefaultToleranceDeg = 0.1;

struct QualityBudget {
    /// Horizon angle error the user accepts from modelling choices (degrees).
    double toleranceDeg = kDefaultToleranceDeg;
    /// Lowest sun (or sky) elevation whose shadows matter (degrees); sets the search distance.
    double lowestElevationDeg = 2.0;
    /// Effective-radius refraction coefficient k the user asked for.
    double refraction = kDefaultRefraction;
    /// The search distance the user gave, used as is (the other choices, curvature and the
    /// expected error's scope, follow from it); none: the plan's.
    SearchDistanceM maxDistanceM;
    /// >= 0: the near field the user gave (HorizonParams::nearFieldSteps), used as is.
    int nearFieldSteps = -1;
};

/// The horizon error a plan states (DEMLIGHT_EXPECTED_ERROR_DEG): the sweep's measured |error|
/// against the full-physics reference (ray march, curvature on, whole DEM), over cells and
/// azimuths of real DEMs where both meet terrain (a horizon of kNoHorizonDeg, no terrain before
/// the DEM edge, says nothing about accuracy). Only horizons at or above `aboveElevationDeg` are
/// in scope: a cell's error is |max(h, e) - max(h_ref, e)|, i.e. the horizon as seen by a sun or
/// sky patch at elevation e or higher. For auto e is the lowest relevant elevation of the budget
/// (its search distance resolves everything above it); for full e = -90 (every horizon).
struct ExpectedError {
    double medianDeg = 0;  ///< median |error| (degrees)
    double p99Deg = 0;     ///< 99th percentile of |error| (degrees)
    double aboveElevationDeg = -90;  ///< -90 = every horizon is bounded
    std::string source;    ///< where the figures were measured
};

/// "median M, p99 P deg[ for horizons at or above E deg] (source)".
std::string describeExpectedError(const ExpectedError& e);

/// Elevation (degrees) above which a search distance sees every occluder: atan(relief / d).
/// Terrain farther than d cannot rise above it. -90 when d covers the DEM diagonal.
double resolvedElevationDeg(const Terrain& terrain, double maxDistanceM);

struct ScenePlan {
    Quality quality = Quality::Auto;
    double maxDistanceM = 0;          ///< horizon search distance (metres)
    bool curvature = true;            ///< earth curvature and refraction in sight lines
    double directionToleranceDeg = 0; ///< sweep region split tolerance (0 = the sweep's automatic rule)
    /// auto: the automatic rule's tolerance is at least this (HorizonParams::
    /// directionToleranceFloorDeg): the budget's tolerance, at most kMaxDirectionFloorDeg.
    double directionToleranceFloorDeg = 0;
    int skyDirections = kAutoSkyDirections;           ///< sectors for sky and aperture integrals
    /// Sky and aperture integrals sweep with HorizonParams::nearestLine (one scan line per cell):
    /// auto, where the integral's error budget holds with it; full interpolates two lines.
    /// Horizon maps and sun frames always use two lines.
    bool integralNearestLine = true;
    /// The search distance was given by the user (--max-distance), not chosen by the plan.
    bool userDistance = false;
    /// The DEM is a surface model (buildings, trees): at least kSurfaceModelSteepShare of its
    /// neighbour steps are steeper than 45 deg.
    bool surfaceModel = false;
    /// HorizonParams::nearFieldSteps of every sweep: kSurfaceNearFieldSteps on surface models
    /// (SteepSteps share at least kSurfaceModelSteepShare), else kTerrainNearFieldSteps (auto
    /// and full alike).
    int nearFieldSteps = 0;
    /// HorizonParams::farFieldCrossings of every sweep: on where the SteepSteps share is at least
    /// kFarFieldCrossingsSteepShare (surface models, cliffy terrain), off on smoother terrain
    /// (off the grid axes they nearly double the sweep's hull vertices); auto and full alike,
    /// with a given near field too.
    bool farFieldCrossings = true;
    std::size_t sunLatticeStepCells = 64;  ///< SPA evaluated every this many cells
    ExpectedError expectedError;           ///< what the horizons of this plan are within
    /// One line per choice, "name=value (why)", for metadata and --verbose.
    std::vector<std::string> reasons;
};

/// Chooses the plan. Rules for `auto`:
///  - search distance: relief / tan(lowestElevation): terrain farther away cannot rise above
///    that elevation; the whole DEM (its diagonal) when that is half the diagonal or more, where
///    a range limit saves no sweep work;
///  - curvature: on unless the drop over the whole search distance, d / (2 R_eff), is below a
///    tenth of the tolerance (it costs nothing in the sweep, so only tiny scenes turn it off);
///  - direction tolerance: the sweep's automatic rule (one cell of sideways drift at the search
///    distance), but at least the budget's tolerance (at most kMaxDirectionFloorDeg): a scan
///    direction off by theta sees the horizon of azimuth A + theta, an error of about
///    theta |dh/dA| at any distance, so on large DEMs the cell rule asks for far more regions
///    than the angle budget needs
///    (docs/measurements.md#lightingqualityh-planscene-direction-tolerance);
///  - sky directions: kAutoSkyDirections; sun lattice: 64 cells (the sun moves 0.004 deg per km).
/// `full`: the DEM diagonal as distance, curvature on, 0.01 deg direction tolerance,
/// kFullSkyDirections, a 16-cell sun lattice.
/// Budget: with these rules the modelling choices of `auto` add at most budget.toleranceDeg to
/// the median and the 99th percentile of the horizon error of `full` (both measured against the
/// full-physics reference, horizons clamped at budget.lowestElevationDeg), and both stay within
/// expectedError (tests/quality_realdem_test.cpp checks this on real DEMs).
ScenePlan planScene(const Terrain& terrain, Quality quality, const QualityBudget& budget);

/// HorizonParams of the plan's sweeps: its search distance, curvature and direction tolerance,
/// with the given refraction coefficient (azimuthDeg left at 0), two scan lines per
/// cell.
HorizonParams planHorizonParams(const ScenePlan& plan, double refraction);

/// SunFrameParams of the plan: its curvature and direction tolerance; the search distance is
/// the plan's (full) or left to the sun (auto: sunSearchDistanceM for the frame's lowest sun).
SunFrameParams planSunFrameParams(const ScenePlan& plan, double sunDiameterDeg, double refraction);

/// Under auto, the scan direction of a sky or aperture integral may deviate from its sector's
/// centre azimuth by this share of the sector width (360 / directions degrees): 0.70 deg at 32
/// directions, 1.4 deg at 16. The D-sector quadrature samples each sector's horizon once, at its
/// centre; moving that sample by 1/16 of the sector is far inside the quadrature's own error,
/// and changes the sky by a small fraction of kSkyBudgetMae (the measured figures:
/// docs/measurements.md#lightingqualityh-kintegraltoleranceshareofsector); the test
/// Quality.IntegralToleranceKeepsTheSkyOnARealTile checks it.
inline constexpr double kIntegralToleranceShareOfSector = 1.0 / 16.0;

/// planHorizonParams() for the sweeps of a sky or aperture integral over `directions` sectors:
/// nearestLine as the plan says. Under auto the direction tolerance is the larger of the sweep's
/// automatic rule and kIntegralToleranceShareOfSector of the sector width, and (unless the user
/// set the distance) the whole DEM is searched where the range limit does not pay over the
/// directions' sweeps (estimateSweepSteps, kRangeLimitStepCost): with few regions the lines
/// walk the whole DEM anyway, and the whole DEM is the exact answer. Full: the plan's settings.
HorizonParams planIntegralParams(const Terrain& terrain, const ScenePlan& plan, std::size_t directions,
                                 double refraction);

/// Deterministic estimate of the work of one sweepHorizon(terrain, params) call, in line steps
/// (one step = one interpolated line sample fed to a hull), plus one per output cell for the
/// combine pass. Follows the sweep's documented geometry (demlight/lighting/horizon.h): the regions of
/// sweepRegions(), lines one cell apart along the minor axis, each walked from the cells it
/// serves in its region to maxDistanceM beyond them (clipped to the grid). Used to compare the
/// cost of plans without timing. It leaves out the range-limit pass, which makes a step up to
/// kRangeLimitStepCost times as dear when maxDistanceM is a small fraction of the line length (see
/// kWholeDemShareOfDiagonal in quality.cpp); `demlight_tradeoff_bench --auto-vs-full` prints it
/// beside measured times. Estimated on the terrain's full grid (params.window, when set, in
/// full-grid coordinates), so every tile of a DEM gets the same estimate and plan.
double estimateSweepSteps(const Terrain& terrain, const HorizonParams& params);

/// Cost of one line step of a range-limited sweep relative to an unlimited one (the chunked
/// hulls and the exact range pass): the worst measured, on one-region DEMs
/// (docs/measurements.md#lightingqualitycpp-kwholedemshareofdiagonal). A range limit pays only
/// where it cuts the steps by more than this.
inline constexpr double kRangeLimitStepCost = 1.8;

/// True when sweeping with `params` as given is expected to cost less than sweeping the whole
/// DEM (maxDistanceM = infinity), by estimateSweepSteps and kRangeLimitStepCost. Both find the
/// same horizons above the elevation the limit resolves, so callers that only need those (sun
/// frames) take whichever is cheaper.
bool rangeLimitPays(const Terrain& terrain, const HorizonParams& params);

/// estimateSweepSteps summed over `directions` evenly spaced azimuths (0, 360/directions, ...)
/// with the plan's integral parameters (planIntegralParams): the cost of a sky or aperture integral.
double estimateSweepWork(const Terrain& terrain, const ScenePlan& plan, std::size_t directions,
                         double refraction);

}  // namespace demlight
