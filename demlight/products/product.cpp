#include "demlight/products/product.h"

#include "demlight/lighting/directions.h"
#include "demlight/lighting/sky.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace demlight {
namespace {

/// Input nodata values at least this large in magnitude are carried into outputs.
constexpr double kCarriedNodataMagnitude = 10000.0;
/// Largest finite Float32 magnitude: a nodata value beyond it cannot be written as Float32.
constexpr double kMaxFloat32 = 3.4028235e38;
/// Gamma of display-encoded colour rasters (decoded to linear albedo).
constexpr double kDisplayGamma = 2.2;
/// Largest 8-bit display value.
constexpr double kMaxByte = 255.0;

}  // namespace

const ProductBand& ProductResult::band(const std::string& name) const {
    for (const ProductBand& b : bands)
        if (b.name == name) return b;
    throw Error("the result has no band '" + name + "'");
}

ScenePlan planFor(const SearchRequest& search, const Terrain& terrain) {
    if (search.maxDistanceM && !(*search.maxDistanceM > 0))
        throw FieldError("maxDistanceM", " " + formatNumber(*search.maxDistanceM) + ": must be > 0");
    if (!(search.refraction >= 0 && search.refraction < 1))
        throw FieldError("refraction", " " + formatNumber(search.refraction) + ": must be in [0, 1)");
    if (!(search.toleranceDeg > 0) || !std::isfinite(search.toleranceDeg))
        throw FieldError("toleranceDeg", " " + formatNumber(search.toleranceDeg) + ": must be a number > 0");
    if (search.threads < 0 || search.threads > kMaxThreads)
        throw FieldError("threads", " " + std::to_string(search.threads) + ": must be in [0, " +
                                        std::to_string(kMaxThreads) + "] (0 = all cores)");
    QualityBudget budget;
    budget.toleranceDeg = search.toleranceDeg;
    budget.lowestElevationDeg = kDefaultLowestElevationDeg;
    budget.refraction = search.refraction;
    budget.maxDistanceM = search.maxDistanceM;
    if (search.nearFieldSteps) {
        if (*search.nearFieldSteps < 0 || *search.nearFieldSteps > kMaxNearFieldSteps)
            throw FieldError("nearFieldSteps", " " + std::to_string(*search.nearFieldSteps) + ": must be in [0, " +
                                                   std::to_string(kMaxNearFieldSteps) + "]");
        budget.nearFieldSteps = *search.nearFieldSteps;
    }
    return planScene(terrain, search.quality, budget);
}

HorizonParams horizonParams(const SearchRequest& search, const ScenePlan& plan) {
    return planHorizonParams(plan, search.refraction);
}

HorizonParams stackHorizonParams(const SearchRequest& search, const ScenePlan& plan, const Terrain& terrain,
                                 double sunDiameterDeg) {
    // The stack gives every instant's sun horizon: the plan's own direction tolerance, not the
    // integrals' (planIntegralParams), and two scan lines per cell.
    HorizonParams p = horizonParams(search, plan);
    p.nearestLine = false;
    // One stack serves every sun: out to the lowest sun's shadows (auto) or the plan's distance (full).
    if (!search.maxDistanceM)
        p.maxDistanceM = plan.quality == Quality::Full ? plan.maxDistanceM : sunSearchDistanceM(terrain, 0.0, sunDiameterDeg);
    return p;
}

HorizonParams integralParams(const SearchRequest& search, const ScenePlan& plan, const Terrain& terrain,
                             std::size_t directions) {
    return planIntegralParams(terrain, plan, directions, search.refraction);
}

SunFrameParams sunFrameParams(const SearchRequest& search, double sunDiameterDeg, const ScenePlan& plan) {
    SunFrameParams p = planSunFrameParams(plan, sunDiameterDeg, search.refraction);
    if (search.maxDistanceM) p.maxDistanceM = *search.maxDistanceM;
    return p;
}

double sunFrameDistanceM(const SearchRequest& search, double sunDiameterDeg, const ScenePlan& plan,
                         const Terrain& terrain, const SunField& field) {
    return sunFrameSearchDistanceM(terrain, field, sunFrameParams(search, sunDiameterDeg, plan));
}

Grid<float> skyLightK(const Terrain& terrain, const Normals& normals, std::size_t directions,
                      const HorizonParams& params, ProgressCounter* progress) {
    SkyAccumulator acc(normals.east, normals.north, normals.up, directions, {});
    sweepDirections(terrain, params, directions,
                    [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); }, progress);
    return std::move(acc).finish(0.0).skyK;
}

std::size_t haloCellsFor(const Terrain& terrain, double maxDistanceM) {
    const FullGridRef g = fullGrid(terrain);
    const std::size_t whole = std::max(g.width, g.height);
    if (!std::isfinite(maxDistanceM)) return whole;
    const double cell = g.minCellM();
    if (!(cell > 0) || !std::isfinite(cell)) return whole;
    const double cells = std::ceil(maxDistanceM / cell) + 1;
    return cells >= static_cast<double>(whole) ? whole : static_cast<std::size_t>(cells);
}

std::string formatNumber(double value) {
    std::ostringstream s;
    s.precision(10);
    s << value;
    return s.str();
}

std::string metadataDistanceM(const Terrain& terrain, double metres) {
    return formatNumber(std::round(std::isfinite(metres) ? metres : diagonalM(fullGrid(terrain))));
}

std::map<std::string, std::string> planMetadata(const ScenePlan& plan) {
    std::string reasons;
    for (const auto& r : plan.reasons) reasons += (reasons.empty() ? "" : "; ") + r;
    return {{"DEMLIGHT_QUALITY", std::string(qualityName(plan.quality))},
            {"DEMLIGHT_PLAN", reasons},
            {"DEMLIGHT_CURVATURE", plan.curvature ? "on" : "off"},
            {"DEMLIGHT_EXPECTED_ERROR_DEG", describeExpectedError(plan.expectedError)}};
}

std::map<std::string, std::string> productMetadata(const Dem& dem, const std::string& product) {
    return {{"DEMLIGHT_VERSION", DEMLIGHT_VERSION}, {"DEMLIGHT_INPUT", dem.band.path}, {"DEMLIGHT_PRODUCT", product}};
}

std::map<std::string, std::string> searchMetadata(const Terrain& terrain, double maxDistanceM, double refraction) {
    return {{"DEMLIGHT_MAX_DISTANCE_M", metadataDistanceM(terrain, maxDistanceM)},
            {"DEMLIGHT_REFRACTION", formatNumber(refraction)}};
}

double outputNodata(const Dem& dem) {
    if (dem.band.nodata) {
        const double v = *dem.band.nodata;
        if (std::isnan(v) || (std::abs(v) >= kCarriedNodataMagnitude && std::abs(v) <= kMaxFloat32)) return v;
    }
    return std::numeric_limits<double>::quiet_NaN();
}

ProductResult makeResult(const Dem& dem, const std::string& product, const std::map<std::string, std::string>& extra) {
    ProductResult r;
    r.ref = dem.band.ref;
    r.nodata = outputNodata(dem);
    r.metadata = productMetadata(dem, product);
    for (const auto& [k, v] : extra) r.metadata[k] = v;
    return r;
}

CellWindow cellsWithin(const CellWindow& read, const CellWindow& window) {
    return {window.col0 - read.col0, window.row0 - read.row0, window.col1 - read.col0, window.row1 - read.row0};
}

std::optional<CellWindow> sweepWindowOf(const Terrain& terrain, const CellWindow& cells) {
    if (cells.col0 == 0 && cells.row0 == 0 && cells.col1 == terrain.width() && cells.row1 == terrain.height())
        return std::nullopt;
    return cells;
}

void cropResult(ProductResult& result, const CellWindow& read, const CellWindow& window) {
    const CellWindow cells = cellsWithin(read, window);
    for (ProductBand& b : result.bands) {
        if (!b.values.empty()) b.values = cropGrid(b.values, cells);
        if (!b.flags.empty()) b.flags = cropGrid(b.flags, cells);
    }
    moveReference(result, read, window);
}

void moveReference(ProductResult& result, const CellWindow& read, const CellWindow& window) {
    const CellWindow cells = cellsWithin(read, window);
    auto& gt = result.ref.geoTransform;
    gt[0] += static_cast<double>(cells.col0) * gt[1];
    gt[3] += static_cast<double>(cells.row0) * gt[5];
}

ColorEncoding parseColorEncoding(const std::string& name, const std::string& field) {
    if (name == "auto") return ColorEncoding::Auto;
    if (name == "srgb") return ColorEncoding::Srgb;
    if (name == "linear") return ColorEncoding::Linear;
    throw FieldError(field, " '" + name + "': expected auto, srgb or linear");
}

namespace {

std::vector<Grid<float>> readAuxiliaryRaster(const std::string& path, const DemSource& source, const AuxiliarySpec& spec) {
    const std::string what = " " + path;
    std::vector<Grid<float>> bands;
    try {
        bands = readRasterResampled(path, source.geometry().band.ref, source.width(), source.height());
    } catch (const Error& e) {
        throw FieldError(spec.field, what + ": " + e.what());
    }
    if (bands.empty()) throw FieldError(spec.field, what + ": the raster has no bands");
    if (spec.bands == 3 && spec.greyToRgb && bands.size() == 1) bands = {bands[0], bands[0], bands[0]};
    if (bands.size() < spec.bands)
        throw FieldError(spec.field, what + ": expected " + std::to_string(spec.bands) + " bands (R, G, B) or one grey band, found " +
                    std::to_string(bands.size()));
    bands.resize(spec.bands);

    // Coverage: a raster that misses every valid cell of the DEM is a wrong file, not "no data".
    bool covers = false;
    for (std::size_t row0 = 0; row0 < source.height() && !covers; row0 += source.stripRows()) {
        const CellWindow strip{0, row0, source.width(), std::min(source.height(), row0 + source.stripRows())};
        const Grid<float> h = source.heightsM(strip);
        for (std::size_t r = 0; r < h.height() && !covers; ++r)
            for (std::size_t col = 0; col < h.width() && !covers; ++col)
                covers = !std::isnan(h(col, r)) && !std::isnan(bands[0](col, row0 + r));
    }
    if (!covers) throw FieldError(spec.field, what + ": covers no cell of the DEM (check its extent and CRS against the DEM's)");

    if (spec.color) {
        float maxValue = 0;
        for (const auto& b : bands)
            for (float v : b.values())
                if (!std::isnan(v)) maxValue = std::max(maxValue, v);
        const bool srgb = spec.encoding == ColorEncoding::Srgb || (spec.encoding == ColorEncoding::Auto && maxValue > 1.0f);
        if (srgb) {
            if (maxValue > kMaxByte)
                throw FieldError(spec.field, what + ": holds " + formatNumber(maxValue) +
                            "; display-encoded colour must be 0-255 (or 0-1); scale it to 8 bits first, "
                            "e.g. gdal_translate -ot Byte -scale");
            const double scale = maxValue > 1.0f ? 1.0 / kMaxByte : 1.0;
            for (auto& b : bands)
                for (float& v : b.values())
                    if (!std::isnan(v)) v = static_cast<float>(std::pow(std::clamp(v * scale, 0.0, 1.0), kDisplayGamma));
        }
    }
    for (std::size_t b = 0; b < bands.size(); ++b)
        for (float v : bands[b].values())
            if (!std::isnan(v) && !(v >= spec.minValue && v <= spec.maxValue))
                throw FieldError(spec.field, what + ": band " + std::to_string(b + 1) + " holds " + formatNumber(v) + "; expected " +
                            (spec.color ? "linear albedo " : "values ") + formatNumber(spec.minValue) + "-" +
                            formatNumber(spec.maxValue) +
                            (spec.color ? " (an 8-bit picture is decoded with encoding srgb or auto)" : ""));
    return bands;
}

}  // namespace

std::vector<Grid<float>> loadAuxiliaryRaster(const std::string& path, const DemSource& source, const AuxiliarySpec& spec) {
    // Every window of a job reads the same raster: resampled once per source while it fits.
    std::ostringstream key;
    key.precision(17);
    key << "auxiliary " << spec.field << " " << spec.bands << " " << spec.greyToRgb << " " << spec.minValue << " "
        << spec.maxValue << " " << spec.color << " " << static_cast<int>(spec.encoding) << " " << path;
    const std::size_t bytes = spec.bands * source.width() * source.height() * sizeof(float);
    return *source.derived<std::vector<Grid<float>>>(key.str(), bytes,
                                                     [&] { return readAuxiliaryRaster(path, source, spec); });
}

}  // namespace demlight
