// Horizon angle in one true azimuth for every cell of a DEM (docs/design.md §6.1, the core kernel),
// and the brute-force reference it is measured against.
//
// Definitions (docs/design.md §3–4):
//  - The horizon of cell p in azimuth A is the largest elevation angle (degrees above p's local
//    horizontal plane) of any valid terrain point on the line leaving p in TRUE azimuth A, within
//    maxDistanceM of p, on a curved earth of effective radius R/(1-k): a point at distance d and
//    height difference dh is seen at atan((dh - d²/(2 R_eff)) / d).
//  - "The line in azimuth A" follows the local grid direction: at every point its grid azimuth is
//    A - gamma (meridian convergence) and its metric steps use that row's cell sizes. In a
//    projected CRS that is a straight grid line (a geodesic to first order); in a geographic CRS
//    it is a rhumb line, which departs from the great circle by about d²·tan(lat)/(2R) sideways
//    (≈ 200 m at 50 km, 45° N) — a known approximation of both methods.
//  - Cells whose line meets no valid terrain within range get kNoHorizonDeg (-90°).
//  - Nodata cells get NaN; they neither occlude nor receive.
//  - truncated = 1 where the line reaches the DEM edge before maxDistanceM (beyond the DEM nothing
//    is known, so the horizon may be too low there).
#pragma once

#include "demlight/core/grid.h"
#include "demlight/core/progress.h"
#include "demlight/core/terrain.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace demlight {

/// Horizon angle given to a cell that sees no terrain in range (degrees).
inline constexpr double kNoHorizonDeg = -90.0;

/// The reference's ray-march step as a share of the smaller side of the start cell; the sweep's
/// near field samples the same points.
inline constexpr double kReferenceStepOfCell = 0.25;

/// Largest HorizonParams::nearFieldSteps (the near field's cost grows with it, its benefit
/// flattens out well before: docs/accuracy.md).
inline constexpr int kMaxNearFieldSteps = 32;

/// A horizon search distance as every layer holds it, from a product's request to a sweep:
/// metres along the ground, infinity = the whole DEM. Where one may be left to the scene plan
/// (SearchRequest, QualityBudget) or to each sun (SunFrameParams), it is optional and none means
/// so; a sweep (HorizonParams::maxDistanceM) always has one.
using SearchDistanceM = std::optional<double>;

struct HorizonParams {
    /// True azimuth of the search (degrees clockwise from true north); any finite value, reduced
    /// to [0, 360) by wrapAzimuthDeg so 0 and 360 give identical bits.
    double azimuthDeg = 0.0;
    /// Occluders farther than this (metres, along the line) are ignored. Must be > 0.
    double maxDistanceM = std::numeric_limits<double>::infinity();
    /// Refraction coefficient k in [0, 1): effective earth radius kEarthRadiusM / (1 - k).
    double refraction = kDefaultRefraction;
    /// false = flat earth (no curvature drop, refraction unused).
    bool curvature = true;
    /// Compute only these output cells (others are left NaN / 0); occluders come from anywhere.
    /// In the terrain's own coordinates.
    std::optional<CellWindow> window;
    /// Sweep only: largest allowed error (degrees) of the scan direction against the local true
    /// azimuth; 0 = automatic (see effectiveDirectionToleranceDeg()). The grid is split into regions, each
    /// swept with its own straight direction, until every cell's error is below this (see
    /// sweepRegions). Must be >= 0.
    double directionToleranceDeg = 0.0;
    /// Sweep only, with directionToleranceDeg = 0: the automatic tolerance is at least this
    /// (degrees). A scan direction off by theta sees the horizon of azimuth A + theta, an error
    /// of about theta |dh/dA| whatever the distance, so an angle budget allows theta up to about
    /// that budget however long the search (the scene plan sets it from --tolerance). Must be >= 0.
    double directionToleranceFloorDeg = 0.0;
    /// Sweep only: serve each cell from the one scan line nearest to it instead of interpolating
    /// the tangents of the two lines bracketing it. Off the grid axes that halves the hull
    /// queries (about a third less time per sweep) at a larger per-cell error (the README's
    /// horizon accuracy table has both); sky and aperture integrals, which average many
    /// directions, use it.
    bool nearestLine = false;
    /// Sweep only: the exact near field, in line steps (one cell along the scan direction's
    /// major axis). Terrain nearer than this is sampled on the ray from the cell's own centre,
    /// at the reference's quarter-cell steps on the bilinear surface; the scan lines' hulls then
    /// answer only for terrain at least this many steps away, queried with the cell's own
    /// height. Walls, roof edges and cliffs next to a cell are where interpolating two scan lines
    /// half a cell beside it fails (a street cell takes part of the roof's horizon), so surface
    /// models need more steps than terrain (docs/accuracy.md). 0 = the line-interpolated model of
    /// earlier versions: no near field, the query height interpolated from the lines. Must be
    /// <= kMaxNearFieldSteps.
    int nearFieldSteps = 0;
    /// Sweep only, with nearFieldSteps > 0: the far field's lines also take a point wherever they
    /// cross a grid line of the minor axis between two steps (the bilinear surface is linear
    /// there, and a wall's top edge along the major axis is such a line), so wall top edges beyond
    /// the near field are sampled exactly. Off the grid axes that nearly doubles the hulls'
    /// vertices; terrain has no such edges and the scene plan turns it off there
    /// (docs/accuracy.md).
    bool farFieldCrossings = true;
    /// Sweep only: the true azimuth (degrees, unwrapped values allowed) wanted at the centre of
    /// cell (col, row) when it varies over the grid, as the sun's does across a large DEM; empty
    /// = azimuthDeg everywhere. Regions are then split until each region's straight direction is
    /// within the direction tolerance of this azimuth at its samples (sweepRegions), so one sweep
    /// serves every cell at its own azimuth. The field must be smooth over a region (the split
    /// samples corners, edge midpoints and centre). The reference marches each cell's ray along
    /// the field's azimuth at that cell. (col, row) are on the terrain's full grid
    /// (Terrain::frame; the terrain's own coordinates when it has no frame).
    std::function<double(double col, double row)> azimuthAtDeg;
    /// Sweep only: false leaves HorizonMap::truncated empty (integrals that never read it skip
    /// its grid and the per-cell edge test).
    bool truncationFlags = true;
};

struct HorizonMap {
    /// Horizon elevation angle (degrees); NaN at nodata cells (and outside the window).
    Grid<float> angleDeg;
    /// 1 where the search reached the DEM edge before maxDistanceM, else 0 (empty when the sweep
    /// ran with HorizonParams::truncationFlags = false).
    Grid<std::uint8_t> truncated;
};

/// The one rule for a search distance from the terrain: every occluder seen above elevationDeg
/// lies within relief / tan(elevationDeg) (byReliefM); when that is kWholeDemShareOfDiagonal of
/// the DEM diagonal or more the whole DEM is searched (a range limit that long saves no sweep
/// work, and the whole DEM is exact); and at least the smallest cell side, so that flat DEMs
/// still see their neighbours. A DEM without valid heights has relief 0.
struct ReliefSearch {
    double reliefM = 0;    ///< highest minus lowest valid height (metres)
    double byReliefM = 0;  ///< relief / tan(elevation) (metres)
    bool wholeDem = false;
    double distanceM = 0;  ///< the search distance (metres)
};
ReliefSearch reliefSearch(const Terrain& terrain, double elevationDeg);

/// Default search distance (metres): reliefSearch at kDefaultLowestElevationDeg (2°).
/// Terrain farther than relief/tan(2°) can only be seen below 2° elevation (curvature lowers it
/// further), and a sun that low contributes little and is rarely of interest; below that the
/// horizon saturates. At least one cell size so that flat DEMs still see their neighbours.
double defaultMaxDistanceM(const Terrain& terrain);

/// A search distance of at least this share of the DEM diagonal is replaced by the whole DEM:
/// lines walk the whole DEM anyway, so the range limit saves no sweep work and only adds its
/// range pass (docs/measurements.md#lightingqualitycpp-kwholedemshareofdiagonal). Used by the
/// scene plan and sun frames.
inline constexpr double kWholeDemShareOfDiagonal = 0.5;

/// Elevation of the lowest sun that defaultMaxDistanceM() resolves (degrees).
inline constexpr double kDefaultLowestElevationDeg = 2.0;

/// The direction tolerance used by the sweep (degrees): params.directionToleranceDeg if > 0, else
/// atan(1 cell / reach), reach = min(maxDistanceM, DEM diagonal), clamped to [0.01°, 0.5°]: the
/// swept line then stays within a cell of the true line over the whole search distance (0.05°
/// for 30 m cells and 34 km); and at least params.directionToleranceFloorDeg. Each extra region
/// costs a sweep of its own (see sweepRegions).
double effectiveDirectionToleranceDeg(const Terrain& terrain, const HorizonParams& params);

/// A region of the output swept with one straight grid direction.
struct SweepRegion {
    CellWindow window;
    /// Grid direction in cells toward the azimuth: +col = east, +row = south.
    double dirCol = 0.0, dirRow = 0.0;
};

/// Splits the output window into regions, each swept along one straight grid direction taken at
/// the region centre (from that row's cell sizes and the convergence there). Rule: a region is
/// halved (along the axis whose ends disagree most) while the true azimuth that its direction
/// represents, evaluated at its corners, edge midpoints and centre with the local cell sizes and
/// gamma, differs from `azimuthDeg` by more than effectiveDirectionToleranceDeg(). Both sources of error
/// are smooth (gamma ≈ Δlon·sin(lat); the cell aspect ratio of geographic grids varies with
/// cos(lat)), so these nine samples bound it. With params.azimuthAtDeg, each region's direction
/// is taken for the field's azimuth at its centre and compared with the field's azimuth at each
/// sample instead of `azimuthDeg`. Regions are not split below 8 cells a side. Each
/// region's lines start up to maxDistanceM beyond it, so many small regions cost extra time.
std::vector<SweepRegion> sweepRegions(const Terrain& terrain, const HorizonParams& params);

/// The regions of a terrain's full grid (Terrain::frame, or the terrain itself): the full grid
/// split as a whole (so that every tile cut from it gives each cell the same direction) and
/// clipped to `window`, all in full-grid coordinates. Only the parts of the split that meet
/// `window` are split further, so a window's regions cost its own extent, not the full grid's
/// (`examined`, when given, receives the number of regions whose error was evaluated).
/// sweepRegions() is this for the output window, moved to the terrain's coordinates; the sweep
/// runs on these. Plans that must not depend on the tile (estimateSweepSteps) use it directly.
std::vector<SweepRegion> sweepRegionsOnFullGrid(const Terrain& terrain, const HorizonParams& params,
                                                const CellWindow& window, std::size_t* examined = nullptr);

/// The fast method: upper-convex-hull sweeps along lines parallel to the azimuth (Dozier 1981;
/// Timonen & Westerholm 2010), O(cells) per region.
///
/// Lines step one cell along the major grid axis of the direction and lie one cell apart along
/// the minor axis; a line sample is linearly interpolated between the two cells bracketing it
/// (one of them if the other is nodata; both nodata = a gap). Each line is walked from its far end
/// toward the observer side keeping the upper hull of g(s) = h(s) - s²/(2 R_eff) (docs/design.md
/// §4), so the curved-earth slope is (g_q - g_p)/(s_q - s_p) + s_p/R_eff. A cell is served by the
/// two lines bracketing it at its major index: each line's hull is queried with the cell's own
/// height (tangent search starting from the line sample's tangent), and the two tangents (slopes)
/// are interpolated by the cross-line weight. Distances s accumulate per-row metric step lengths.
///
/// maxDistanceM is exact: each line is cut into chunks of maxDistanceM with a fresh hull each, and
/// a cell also takes the tangent to the previous chunk's hull when its vertex is in range; the
/// few cells whose steepest previous-chunk point is out of range get an exact O(n log n) pass.
/// Each block of lines is walked only from maxDistanceM beyond the cells it serves in a region.
HorizonMap sweepHorizon(const Terrain& terrain, const HorizonParams& params,
                        ProgressCounter* progress = nullptr);

/// Scratch grids a sweep needs besides its output, kept between sweeps by callers that run
/// many (sky and aperture directions, sun frames) so each sweep refills memory already mapped.
struct SweepBuffers {
    Grid<float> planeB;
    /// A bitmap of the terrain's valid cells for one scan orientation (X-major or Y-major lines),
    /// built by the first sweep that needs it and kept for the next sweeps of the same heights
    /// grid (the same data, width and height): callers that share buffers between sweeps must
    /// not change the heights in between.
    struct ValidBits {
        const float* heights = nullptr;
        std::size_t width = 0, height = 0;
        std::vector<std::uint64_t> words;  // empty where few cells are nodata (not worth a bitmap)
    };
    ValidBits validBits[2];  // [0]: X-major lines, [1]: Y-major
};

/// sweepHorizon() writing into `out` (resized to the terrain if its shape differs) and reusing
/// `buffers`; the result is identical. Returns the number of regions swept (sweepRegions).
std::size_t sweepHorizonInto(const Terrain& terrain, const HorizonParams& params, HorizonMap& out,
                             SweepBuffers& buffers, ProgressCounter* progress = nullptr);

/// The reference method: a ray march from every cell centre in steps of a quarter of the smaller
/// cell side, bilinear heights (nodata corners dropped and weights renormalised), re-evaluating
/// the grid direction from the local gamma and cell sizes at every step, up to maxDistanceM or the
/// DEM edge; in params.azimuthAtDeg's azimuth at the cell when that is set. Slow
/// (O(cells × distance)); used to measure the sweep. Parallel over rows.
HorizonMap referenceHorizon(const Terrain& terrain, const HorizonParams& params,
                            ProgressCounter* progress = nullptr);

/// Reference horizon of selected cells only (params.window is ignored).
struct HorizonSample {
    float angleDeg = 0.0f;       ///< as HorizonMap::angleDeg
    std::uint8_t truncated = 0;  ///< as HorizonMap::truncated
};
std::vector<HorizonSample> referenceHorizonAt(const Terrain& terrain, const HorizonParams& params,
                                              std::span<const CellIndex> cells,
                                              ProgressCounter* progress = nullptr);

/// The cells accuracy measurements hand to referenceHorizonAt: every valid cell at least
/// edgeMarginM from each DEM edge (converted to cells with the middle row's sizes, plus two;
/// 0 = no margin), in row-major order shuffled by std::mt19937_64(seed), the first `count` kept.
/// The same arguments always give the same cells.
std::vector<CellIndex> sampleValidCells(const Terrain& terrain, std::size_t count, std::uint64_t seed,
                                        double edgeMarginM = 0);

/// Validates params (finite azimuth, maxDistanceM > 0, 0 <= refraction < 1, tolerance >= 0, a
/// window inside the grid) and throws Error naming the bad option.
void validateHorizonParams(const Terrain& terrain, const HorizonParams& params);

/// 1 / R_eff (1/metres) for the params; 0 when curvature is off.
double inverseEffectiveRadius(const HorizonParams& params);

}  // namespace demlight
