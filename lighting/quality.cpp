#include "lighting/quality.h"

#include "src/angles.h"
#include "src/error.h"

#include <cmath>
#include <sstream>

namespace demlight {
namespace {

constexpr double kFullDirectionToleranceDeg = 0.01;
constexpr std::size_t kAutoSunLatticeCells = 64;
constexpr std::size_t kFullSunLatticeCells = 16;
/// Curvature is dropped only when its largest effect is below this share of the tolerance.
constexpr double kCurvatureShareOfTolerance = 0.1;

std::string describe(const std::string& name, double value, const std::string& why) {
    std::ostringstream s;
    s.precision(6);
    s << name << "=" << value << " (" << why << ")";
    return s.str();
}

double diagonalM(const Terrain& t) {
    double heightM = 0, widthM = 0;
    for (std::size_t r = 0; r < t.height(); ++r) {
        heightM += t.cellHeightM[r];
        widthM = std::max(widthM, t.cellWidthM[r] * static_cast<double>(t.width()));
    }
    return std::hypot(widthM, heightM);
}

}  // namespace

Quality parseQuality(std::string_view name) {
    if (name == "auto") return Quality::Auto;
    if (name == "full") return Quality::Full;
    throw Error("--quality must be auto or full, got '" + std::string(name) + "'");
}

std::string_view qualityName(Quality q) { return q == Quality::Auto ? "auto" : "full"; }

ScenePlan planScene(const Terrain& terrain, Quality quality, const QualityBudget& budget) {
    if (!(budget.toleranceDeg > 0)) throw Error("--tolerance must be a positive number of degrees");
    if (!(budget.lowestElevationDeg > 0 && budget.lowestElevationDeg < 90))
        throw Error("the lowest relevant elevation must be in (0, 90) degrees");
    ScenePlan plan;
    plan.quality = quality;
    const double diagonal = diagonalM(terrain);
    const double minCell = std::min(terrain.cellWidthM[terrain.height() / 2], terrain.cellHeightM[terrain.height() / 2]);
    const double rEff = kEarthRadiusM / (1.0 - budget.refraction);

    if (quality == Quality::Full) {
        plan.maxDistanceM = std::max(diagonal, minCell);
        plan.curvature = true;
        plan.directionToleranceDeg = kFullDirectionToleranceDeg;
        plan.skyDirections = kFullSkyDirections;
        plan.sunLatticeStepCells = kFullSunLatticeCells;
        plan.reasons = {describe("max_distance_m", plan.maxDistanceM, "full: DEM diagonal"),
                        "curvature=on (full)",
                        describe("direction_tolerance_deg", plan.directionToleranceDeg, "full"),
                        describe("sky_directions", plan.skyDirections, "full"),
                        describe("sun_lattice_cells", static_cast<double>(plan.sunLatticeStepCells), "full")};
        return plan;
    }

    const auto [lo, hi] = heightRangeM(terrain.heightsM);
    const double relief = std::isfinite(lo) ? static_cast<double>(hi - lo) : 0.0;
    const double byRelief = relief / std::tan(budget.lowestElevationDeg * kDegToRad);
    plan.maxDistanceM = std::max(minCell, std::min(byRelief, diagonal));
    const double curvatureDeg = plan.maxDistanceM / (2 * rEff) * kRadToDeg;
    plan.curvature = curvatureDeg >= kCurvatureShareOfTolerance * budget.toleranceDeg;
    plan.directionToleranceDeg = 0;  // the sweep's automatic rule
    plan.skyDirections = kAutoSkyDirections;
    plan.sunLatticeStepCells = kAutoSunLatticeCells;
    std::ostringstream why;
    why << "relief " << relief << " m / tan " << budget.lowestElevationDeg << " deg, capped by the diagonal "
        << diagonal << " m";
    std::ostringstream curv;
    curv << "curvature=" << (plan.curvature ? "on" : "off") << " (drop over the search distance "
         << curvatureDeg << " deg vs tolerance " << budget.toleranceDeg << " deg)";
    plan.reasons = {describe("max_distance_m", plan.maxDistanceM, why.str()), curv.str(),
                    "direction_tolerance_deg=auto (one cell of sideways drift at the search distance)",
                    describe("sky_directions", plan.skyDirections, "measured sky error budget"),
                    describe("sun_lattice_cells", static_cast<double>(plan.sunLatticeStepCells),
                             "sun direction changes by < 0.01 deg over 64 cells of 30 m")};
    return plan;
}

}  // namespace demlight
