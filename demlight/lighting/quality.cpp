#include "demlight/lighting/quality.h"

#include "demlight/lighting/directions.h"
#include "demlight/lighting/sweep/row_steps.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace demlight {
namespace {

constexpr double kFullDirectionToleranceDeg = 0.01;
constexpr std::size_t kAutoSunLatticeCells = 64;
constexpr std::size_t kFullSunLatticeCells = 16;
/// How fast the sun's direction changes with the observer's position: one degree of arc on the
/// earth per 111 km.
constexpr double kSunDirectionDegPerKm = 1.0 / 111.2;
/// Curvature is dropped only when its largest effect is below this share of the tolerance.
constexpr double kCurvatureShareOfTolerance = 0.1;
/// When relief / tan(lowest elevation) reaches this share of the DEM diagonal, auto searches the
/// whole DEM: limits of half a diagonal or more take the same time as none, and shorter limits
/// save time only on DEMs swept in many regions and take up to kRangeLimitStepCost times as long
/// on one-region DEMs (docs/measurements.md#lightingqualitycpp-kwholedemshareofdiagonal).
// (kWholeDemShareOfDiagonal = 0.5, demlight/lighting/horizon.h.)
/// Line slopes below this are grid-aligned directions off by rounding (the sweep snaps them too).
constexpr double kSlopeSnap = 1e-12;
/// A DEM of more cells than this is computed in tiles (it passes the default memory budget of a
/// few GB at ~60 bytes a cell), and a search of the whole DEM would have every tile read and
/// sweep all of it: a finite range limit is kept there whatever the step counts say.
constexpr double kLargestWholeSearchCells = 64.0 * 1024 * 1024;

/// The full grid of `terrain` has more than kLargestWholeSearchCells cells.
bool tooLargeToSearchWhole(const Terrain& terrain) {
    const FullGridRef g = fullGrid(terrain);
    return static_cast<double>(g.width) * static_cast<double>(g.height) > kLargestWholeSearchCells;
}

/// The sweep's horizon error against the full-physics reference (the statistic of ExpectedError),
/// the largest measured over real DEMs, azimuths and both plans (median and 99th percentile;
/// the measured figures and their sources:
/// docs/measurements.md#lightingqualitycpp-ksweepmedianerrordeg-ksweepp99errordeg).
constexpr double kSweepMedianErrorDeg = 0.072;
constexpr double kSweepP99ErrorDeg = 6.8;
constexpr const char* kSweepErrorSource =
    "sweep vs whole-DEM reference on real DEMs, docs/bench/whole_dem_errors.csv";
/// Cells longer than wide (or wider than long) by this ratio or more have a larger sweep error:
/// the figures are those of the 4.8:1 cells of 1" lat/lon data at 78 deg N over 12 azimuths
/// (docs/stability.md rows "78 N lat/lon cells", which tests/stability_test.cpp enforces at these
/// values), rounded up with a margin.
constexpr double kAnisotropicCellRatio = 3.0;
constexpr double kAnisotropicMedianErrorDeg = 0.26;
constexpr double kAnisotropicP99ErrorDeg = 10.0;
constexpr const char* kAnisotropicErrorSource =
    "sweep vs reference on 4.8:1 lat/lon cells at 78 N, docs/stability.md";

std::string describeNumber(double value) {
    std::ostringstream s;
    s.precision(6);
    s << value;
    return s.str();
}

std::string describe(const std::string& name, double value, const std::string& why) {
    return name + "=" + describeNumber(value) + " (" + why + ")";
}

/// Largest ratio of the longer to the shorter cell side over the rows of the full grid.
double cellAspectRatio(const Terrain& t) {
    const FullGridRef g = fullGrid(t);
    double ratio = 1;
    for (std::size_t r = 0; r < g.height; ++r) {
        const double w = g.cellWidthM[r], h = g.cellHeightM[r];
        if (w > 0 && h > 0) ratio = std::max(ratio, std::max(w / h, h / w));
    }
    return ratio;
}

/// Surface models (SteepSteps share >= kSurfaceModelSteepShare) with the surface near field:
/// what one azimuth's band holds, which tests/urban_test.cpp enforces on the shared surface
/// models azimuth by azimuth (measured there over the horizons the statement covers: worst
/// median 0.098 deg, at 123.4 deg on Manhattan; worst p99 on the diagonals; on the grid axes
/// medians of 0.006-0.024 deg; docs/accuracy.md "Surface models"). Pooled over seven azimuths,
/// as the surface-model targets were set, every horizon: median 0.030-0.035, p99 2.58-2.63 deg.
constexpr double kSurfaceMedianErrorDeg = 0.15;
constexpr double kSurfaceP99ErrorDeg = 5.0;
constexpr const char* kSurfaceErrorSource =
    "sweep vs whole-DEM reference at each of 9 azimuths on two city and dune-edge surface models, "
    "tests/urban_test.cpp";

ExpectedError sweepExpectedError(const Terrain& t, double aboveElevationDeg) {
    const bool anisotropic = cellAspectRatio(t) >= kAnisotropicCellRatio;
    if (!anisotropic && fullGrid(t).steepStepShare() >= kSurfaceModelSteepShare) {
        return ExpectedError{kSurfaceMedianErrorDeg, kSurfaceP99ErrorDeg, aboveElevationDeg, kSurfaceErrorSource};
    }
    ExpectedError e;
    e.medianDeg = anisotropic ? kAnisotropicMedianErrorDeg : kSweepMedianErrorDeg;
    e.p99Deg = anisotropic ? kAnisotropicP99ErrorDeg : kSweepP99ErrorDeg;
    e.source = anisotropic ? kAnisotropicErrorSource : kSweepErrorSource;
    e.aboveElevationDeg = aboveElevationDeg;
    return e;
}

}  // namespace

std::string describeExpectedError(const ExpectedError& e) {
    std::ostringstream s;
    s.precision(3);
    s << "median " << e.medianDeg << ", p99 " << e.p99Deg << " deg";
    if (e.aboveElevationDeg > -90) s << " for horizons at or above " << e.aboveElevationDeg << " deg";
    s << " (" << e.source << ")";
    return s.str();
}

double resolvedElevationDeg(const Terrain& terrain, double maxDistanceM) {
    const FullGridRef g = fullGrid(terrain);
    if (maxDistanceM >= diagonalM(g)) return -90;
    const auto [lo, hi] = g.heightRangeM();
    const double relief = std::isfinite(lo) ? static_cast<double>(hi - lo) : 0.0;
    return std::atan(relief / maxDistanceM) * kRadToDeg;
}

Quality parseQuality(std::string_view name) {
    if (name == "auto") return Quality::Auto;
    if (name == "full") return Quality::Full;
    throw FieldError("quality", " must be auto or full, got '" + std::string(name) + "'");
}

std::string_view qualityName(Quality q) { return q == Quality::Auto ? "auto" : "full"; }

namespace {

/// estimateSweepSteps summed over `directions` evenly spaced azimuths (params.azimuthDeg ignored).
double stepsOverDirections(const Terrain& terrain, HorizonParams params, std::size_t directions) {
    double steps = 0;
    for (std::size_t i = 0; i < directions; ++i) {
        params.azimuthDeg = directionAzimuthDeg(i, directions);
        steps += estimateSweepSteps(terrain, params);
    }
    return steps;
}

/// A distance in the budget replaces the plan's, and the expected error covers only the horizons
/// that distance resolves.
void applyUserDistance(const Terrain& terrain, const QualityBudget& budget, ScenePlan& plan) {
    if (!budget.maxDistanceM) return;
    plan.maxDistanceM = *budget.maxDistanceM;
    plan.userDistance = true;
    std::ostringstream why;
    why << "max_distance_m=" << *budget.maxDistanceM << " (given)";
    plan.reasons[0] = why.str();
    plan.expectedError.aboveElevationDeg =
        std::max(plan.expectedError.aboveElevationDeg, resolvedElevationDeg(terrain, *budget.maxDistanceM));
}

}  // namespace

ScenePlan planScene(const Terrain& terrain, Quality quality, const QualityBudget& budget) {
    if (!(budget.toleranceDeg > 0))
        throw FieldError("toleranceDeg", " " + describeNumber(budget.toleranceDeg) + ": must be a positive number of degrees");
    if (!(budget.lowestElevationDeg > 0 && budget.lowestElevationDeg < 90))
        throw Error("the lowest relevant elevation must be in (0, 90) degrees");
    ScenePlan plan;
    plan.quality = quality;
    // Of the full grid: the plan of a DEM is the same whichever window of it is at hand.
    const FullGridRef g = fullGrid(terrain);
    const double diagonal = diagonalM(g);
    const double minCell = std::min(g.cellWidthM[g.height / 2], g.cellHeightM[g.height / 2]);
    const double rEff = kEarthRadiusM / (1.0 - budget.refraction);

    const double steepShare = g.steepStepShare();
    const bool surfaceModel = steepShare >= kSurfaceModelSteepShare;
    plan.surfaceModel = surfaceModel;
    // The same rule under full: its claim is that auto adds at most the tolerance to full's
    // error, and a longer near field on terrain alone moves full's p99 by more than that.
    plan.nearFieldSteps = surfaceModel ? kSurfaceNearFieldSteps : kTerrainNearFieldSteps;
    std::ostringstream nearWhy;
    nearWhy.precision(3);
    if (budget.nearFieldSteps >= 0) {
        plan.nearFieldSteps = budget.nearFieldSteps;
        nearWhy << "near_field_steps=" << plan.nearFieldSteps << " (given)";
    } else {
        nearWhy << "near_field_steps=" << plan.nearFieldSteps << " (" << 100 * steepShare
                << " % of neighbour steps steeper than 45 deg: " << (surfaceModel ? "a surface model" : "terrain")
                << "; horizons over the nearest steps from each cell's own centre)";
    }
    plan.farFieldCrossings = steepShare >= kFarFieldCrossingsSteepShare;
    std::ostringstream crossWhy;
    crossWhy << "far_field_crossings=" << (plan.farFieldCrossings ? "on" : "off") << " ("
             << (plan.farFieldCrossings ? "at least " : "under ") << 100 * kFarFieldCrossingsSteepShare
             << " % of neighbour steps steeper than 45 deg: edges between scan steps "
             << (plan.farFieldCrossings ? "sampled where the lines cross grid lines)" : "need no extra samples)");
    if (quality == Quality::Full) {
        plan.maxDistanceM = std::max(diagonal, minCell);
        plan.curvature = true;
        plan.directionToleranceDeg = kFullDirectionToleranceDeg;
        plan.skyDirections = kFullSkyDirections;
        plan.integralNearestLine = false;
        plan.sunLatticeStepCells = kFullSunLatticeCells;
        plan.reasons = {describe("max_distance_m", plan.maxDistanceM, "full: DEM diagonal"),
                        "curvature=on (full)",
                        describe("direction_tolerance_deg", plan.directionToleranceDeg, "full"),
                        describe("sky_directions", plan.skyDirections, "full"),
                        "sky_scan_lines=two (full: each cell between its two bracketing lines)",
                        describe("sun_lattice_cells", static_cast<double>(plan.sunLatticeStepCells), "full"),
                        nearWhy.str(), crossWhy.str()};
        plan.expectedError = sweepExpectedError(terrain, -90);
        applyUserDistance(terrain, budget, plan);
        return plan;
    }

    const ReliefSearch search = reliefSearch(terrain, budget.lowestElevationDeg);
    const double relief = search.reliefM, byRelief = search.byReliefM;
    const bool wholeDem = search.wholeDem;
    plan.maxDistanceM = budget.maxDistanceM.value_or(search.distanceM);
    const double curvatureDeg = plan.maxDistanceM / (2 * rEff) * kRadToDeg;
    plan.curvature = curvatureDeg >= kCurvatureShareOfTolerance * budget.toleranceDeg;
    plan.directionToleranceDeg = 0;  // the sweep's automatic rule ...
    plan.directionToleranceFloorDeg = std::min(budget.toleranceDeg, kMaxDirectionFloorDeg);  // ... or the budget
    // Surface models: walls make the horizon change fast with azimuth, and 16 sectors miss
    // it (sky_K off by 0.009 even from reference horizons); 64 meet the sky budget there.
    plan.skyDirections = surfaceModel ? kFullSkyDirections : kAutoSkyDirections;
    plan.integralNearestLine = true;
    plan.sunLatticeStepCells = kAutoSunLatticeCells;
    std::ostringstream why;
    why << "relief " << relief << " m / tan " << budget.lowestElevationDeg << " deg = " << byRelief << " m"
        << (wholeDem ? ", at least half the DEM diagonal: the whole DEM" : "");
    std::ostringstream curv;
    curv << "curvature=" << (plan.curvature ? "on" : "off") << " (drop over the search distance "
         << curvatureDeg << " deg vs tolerance " << budget.toleranceDeg << " deg)";
    std::ostringstream lattice;
    lattice.precision(3);
    const double latticeKm = static_cast<double>(plan.sunLatticeStepCells) * minCell / 1000;
    lattice << "SPA every " << plan.sunLatticeStepCells << " cells (" << latticeKm
            << " km here), bilinear between; the sun's direction changes smoothly, by ~"
            << kSunDirectionDegPerKm * latticeKm << " deg over that span";
    plan.reasons = {describe("max_distance_m", plan.maxDistanceM, why.str()), curv.str(),
                    "direction_tolerance_deg=auto (one cell of sideways drift at the search distance, but at "
                    "least " + describeNumber(plan.directionToleranceFloorDeg) + " deg, the tolerance: a scan "
                    "direction off by theta changes a horizon by about theta |dh/dA| at any distance; "
                    "sky and aperture integrals: at least 1/16 of their sector width, over the whole DEM "
                    "unless a range limit saves sweep work)",
                    describe("sky_directions", plan.skyDirections,
                             surfaceModel ? "measured sky error budget on surface models"
                                          : "measured sky error budget"),
                    "sky_scan_lines=nearest (sky and aperture integrals: one scan line per cell; their "
                    "error stays within the sky error budget)",
                    describe("sun_lattice_cells", static_cast<double>(plan.sunLatticeStepCells), lattice.str()),
                    nearWhy.str(), crossWhy.str()};
    plan.expectedError = sweepExpectedError(terrain, budget.lowestElevationDeg);
    if (budget.toleranceDeg > kDefaultToleranceDeg) {
        // Measured at the default budget. A looser one lets auto add up to the tolerance to
        // full's error (the budget's own bound), and full's is within the measured figures.
        plan.expectedError.medianDeg += budget.toleranceDeg;
        plan.expectedError.p99Deg += budget.toleranceDeg;
        std::ostringstream src;
        src << "; plus the tolerance " << budget.toleranceDeg << " deg, which auto may add to full's error";
        plan.expectedError.source += src.str();
    }
    applyUserDistance(terrain, budget, plan);
    return plan;
}

HorizonParams planHorizonParams(const ScenePlan& plan, double refraction) {
    HorizonParams p;
    p.maxDistanceM = plan.maxDistanceM;
    p.curvature = plan.curvature;
    p.refraction = refraction;
    p.directionToleranceDeg = plan.directionToleranceDeg;
    p.directionToleranceFloorDeg = plan.directionToleranceFloorDeg;
    p.nearFieldSteps = plan.nearFieldSteps;
    p.farFieldCrossings = plan.farFieldCrossings;
    return p;
}

SunFrameParams planSunFrameParams(const ScenePlan& plan, double sunDiameterDeg, double refraction) {
    SunFrameParams p;
    p.sunDiameterDeg = sunDiameterDeg;
    p.refraction = refraction;
    p.curvature = plan.curvature;
    p.directionToleranceDeg = plan.directionToleranceDeg;
    p.directionToleranceFloorDeg = plan.directionToleranceFloorDeg;
    if (plan.quality == Quality::Full) p.maxDistanceM = plan.maxDistanceM;  // else each sun's own
    p.nearFieldSteps = plan.nearFieldSteps;
    p.farFieldCrossings = plan.farFieldCrossings;
    return p;
}

HorizonParams planIntegralParams(const Terrain& terrain, const ScenePlan& plan, std::size_t directions,
                                 double refraction) {
    if (directions == 0) throw Error("the number of directions must be at least 1");
    HorizonParams p = planHorizonParams(plan, refraction);
    p.nearestLine = plan.integralNearestLine;
    p.truncationFlags = false;  // integrals never read them
    if (plan.quality == Quality::Full) return p;
    const double sectorDeg = 360.0 / static_cast<double>(directions);
    p.directionToleranceDeg =
        std::max(effectiveDirectionToleranceDeg(terrain, p), kIntegralToleranceShareOfSector * sectorDeg);
    if (plan.userDistance || !std::isfinite(p.maxDistanceM) || tooLargeToSearchWhole(terrain)) return p;
    HorizonParams whole = p;
    whole.maxDistanceM = std::numeric_limits<double>::infinity();
    return kRangeLimitStepCost * stepsOverDirections(terrain, p, directions) <
                   stepsOverDirections(terrain, whole, directions)
               ? p
               : whole;
}

double estimateSweepSteps(const Terrain& terrain, const HorizonParams& params) {
    // On the full grid, so that every tile of a DEM makes the same choices from it.
    const FullGridRef g = fullGrid(terrain);
    const CellWindow window = params.window ? *params.window : CellWindow{0, 0, g.width, g.height};
    const RowStepBounds steps(g.cellWidthM, g.cellHeightM);
    double total = 0;
    for (const SweepRegion& region : sweepRegionsOnFullGrid(terrain, params, window)) {
        const CellWindow& w = region.window;
        total += static_cast<double>((w.col1 - w.col0) * (w.row1 - w.row0));  // combine pass
        // Line geometry: one step per cell along the major axis; a line k lies at minor
        // coordinate k + slope * m.
        const bool xMajor = std::abs(region.dirCol) >= std::abs(region.dirRow);
        const double major = xMajor ? region.dirCol : region.dirRow;
        double slope = (xMajor ? region.dirRow : region.dirCol) / major;
        if (std::abs(slope) < kSlopeSnap) slope = 0;  // on-axis, as the sweep snaps it
        const int farSign = major >= 0 ? 1 : -1;
        const double majorSize = static_cast<double>(xMajor ? g.width : g.height);
        const double minorSize = static_cast<double>(xMajor ? g.height : g.width);
        const double a0 = static_cast<double>(xMajor ? w.col0 : w.row0);
        const double a1 = static_cast<double>(xMajor ? w.col1 : w.row1) - 1;
        const double b0 = static_cast<double>(xMajor ? w.row0 : w.col0);
        const double b1 = static_cast<double>(xMajor ? w.row1 : w.col1) - 1;
        const double minStepM = steps.range(xMajor ? 1.0 : slope, xMajor ? slope : 1.0).first;
        const double extension = std::isfinite(params.maxDistanceM)
                                     ? std::min(majorSize, std::ceil(params.maxDistanceM / minStepM) + 1)
                                     : majorSize;
        // The major interval on which a line's minor coordinate k + slope * m lies in (lo, hi]
        // (a line at x uses cells floor(x) and floor(x) + 1, the second only when x is not whole).
        const auto within = [&](double k, double lo, double hi, double& m0, double& m1) {
            if (slope == 0) {
                m0 = -std::numeric_limits<double>::infinity();
                m1 = (k > lo && k <= hi) ? -m0 : m0;
                return;
            }
            const double u = (lo - k) / slope, v = (hi - k) / slope;
            m0 = std::min(u, v), m1 = std::max(u, v);
        };
        const double kFirst = std::floor(b0 - std::max(slope * a0, slope * a1)) - 1;
        const double kLast = std::ceil(b1 - std::min(slope * a0, slope * a1)) + 1;
        for (double k = kFirst; k <= kLast; ++k) {
            // Steps where the line serves a window cell.
            double s0, s1;
            within(k, b0 - 1, b1, s0, s1);
            s0 = std::max(std::ceil(s0), a0), s1 = std::min(std::floor(s1), a1);
            if (s0 > s1) continue;
            // Walked from maxDistanceM beyond the farthest served step to the nearest one ...
            double m0 = farSign > 0 ? s0 : s0 - extension;
            double m1 = farSign > 0 ? s1 + extension : s1;
            // ... on the grid only.
            double g0, g1;
            within(k, -1, minorSize - 1, g0, g1);
            m0 = std::max({m0, std::ceil(g0), 0.0});
            m1 = std::min({m1, std::floor(g1), majorSize - 1});
            if (m1 >= m0) total += m1 - m0 + 1;
        }
    }
    return total;
}

bool rangeLimitPays(const Terrain& terrain, const HorizonParams& params) {
    if (!std::isfinite(params.maxDistanceM)) return false;
    if (tooLargeToSearchWhole(terrain)) return true;
    HorizonParams whole = params;
    whole.maxDistanceM = std::numeric_limits<double>::infinity();
    return kRangeLimitStepCost * estimateSweepSteps(terrain, params) < estimateSweepSteps(terrain, whole);
}

double estimateSweepWork(const Terrain& terrain, const ScenePlan& plan, std::size_t directions,
                         double refraction) {
    return stepsOverDirections(terrain, planIntegralParams(terrain, plan, directions, refraction), directions);
}

}  // namespace demlight
