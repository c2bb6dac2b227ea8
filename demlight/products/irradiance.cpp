#include "demlight/core/parallel.h"
#include "demlight/products/irradiance.h"

#include "demlight/geo/solar_position.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace demlight {
namespace {

/// Linke factors accepted: 1 is a clean dry (Rayleigh) atmosphere by definition; ESRA's fits are
/// not meant for turbidities beyond 10.
constexpr double kMinLinke = 1, kMaxLinke = 10;
/// Solar constants accepted (W m-2): the measured values lie near 1361-1367.
constexpr double kMinSolarConstantWm2 = 1000, kMaxSolarConstantWm2 = 1500;

}  // namespace

void validateIrradiance(const IrradianceRequest& r) {
    validateClearSky(r.albedo, r.coeffBh, r.coeffDh, r.solarConstantWm2, r.sunDiameterDeg, r.atmosphere);
    linkeFor(r);
    validateCanopy(r.canopy);
    if (r.skyDirections && *r.skyDirections < 1)
        throw FieldError("skyDirections", " " + std::to_string(*r.skyDirections) + ": must be >= 1");
}

namespace {

/// K0: the sky K of the horizons raised to the horizontal (demlight/lighting/irradiance.h); the cells of
/// `hidden` (under a crown, on the full surface of a canopy) see none of it.
Grid<float> skyAboveHorizontal(const Terrain& t, const Normals& normals, std::size_t directions,
                               const HorizonParams& params, ProgressCounter& counter,
                               const Grid<std::uint8_t>* hidden = nullptr) {
    SkyAccumulator sky(normals.east, normals.north, normals.up, directions, SkyPatches{});
    Grid<float> raised;
    sweepDirections(t, params, directions, [&](std::size_t i, const HorizonMap& h) {
        raiseToHorizontal(h.angleDeg, raised);
        if (hidden) hideUnderCrown(raised, *hidden, 90.0f);
        sky.addDirection(i, raised);
    }, &counter);
    return std::move(sky).finish(0.0).skyK;
}

IrradianceResult irradianceOn(const Dem& dem, const ScenePlan& plan, const IrradianceRequest& r,
                             const SunField& field, double g0, double linke, const ClearSkyRasterGrids& rasters,
                             const Grid<float>& wholeCanopy, const ProgressFn& progress) {
    const Terrain& t = dem.terrain;
    const bool visibleSky = r.diffuseModel == DiffuseModel::VisibleSky;
    std::optional<CanopyTerrain> canopy;
    if (r.canopy.any()) canopy = canopyTerrain(t, wholeCanopy);
    // With a canopy the lit surface is the ground and buildings under it (demlight/lighting/canopy.h).
    const Terrain& lit = canopy ? canopy->ground : t;
    const Normals normals = computeNormals(lit);
    const std::size_t directions = r.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));
    const HorizonParams hp = integralParams(r.search, plan, t, directions);
    ProgressCounter counter(progress, "irradiance",
                            t.heightsM.size() * ((visibleSky ? directions : 0) + 1) * (canopy ? 2 : 1));

    Grid<float> k0;
    if (visibleSky) {
        k0 = skyAboveHorizontal(t, normals, directions, hp, counter,
                                canopy ? &canopy->underCrown : nullptr);
        if (canopy)
            blendCanopy(k0, skyAboveHorizontal(lit, normals, directions, hp, counter),
                        r.canopy.transmissivity);
    }
    const SunFrameParams sp = sunFrameParams(r.search, r.sunDiameterDeg, plan);
    SunFrame frame = computeSunFrame(t, normals, field, sp, &counter);
    if (canopy)
        blendCanopySun(frame, computeSunFrame(lit, normals, field, sp, &counter), canopy->underCrown,
                       r.canopy.transmissivity);

    IrradianceParams params;
    params.model = r.diffuseModel;
    params.linke = linke;
    params.albedo = r.albedo;
    params.coeffBh = r.coeffBh;
    params.coeffDh = r.coeffDh;
    params.extraterrestrialWm2 = g0;
    IrradianceInputs inputs;
    inputs.heightsM = &lit.heightsM;
    inputs.normals = &normals;
    inputs.sun = &field;
    inputs.sunVisibility = &frame.light.visibility;
    inputs.sunIrradiance = &frame.light.irradiance;
    inputs.skyK0 = visibleSky ? &k0 : nullptr;
    ClearSkyRasterGrids cut;
    inputs.grids = rasters.on(t, cut, monthAt(r.time.utc, r.time.zone));
    IrradianceMaps maps = computeIrradiance(inputs, params);

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.merge(searchMetadata(t, frame.maxDistanceM, r.search.refraction));
    meta.insert({
        {"DEMLIGHT_TIME_UTC", formatInstant(r.time.utc, std::string())},
        {"DEMLIGHT_TIME_LOCAL", formatInstant(r.time.utc, r.time.zone)},
        {"DEMLIGHT_TIME_ZONE", r.time.zone.describe()},
        {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
        {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(r.sunDiameterDeg)},
        {"DEMLIGHT_SUN_SWEEP_REGIONS", std::to_string(frame.sweepRegions)},
        {"DEMLIGHT_MODEL", "esra"},
        {"DEMLIGHT_DIFFUSE_MODEL", std::string(diffuseModelName(r.diffuseModel))},
        {"DEMLIGHT_LINKE_MONTHLY",
         r.linke.size() == kMonths && r.rasters.linke.empty() ? formatNumberList(r.linke) : std::string()},
        {"DEMLIGHT_SOLAR_CONSTANT_WM2", formatNumber(r.solarConstantWm2)},
        {"DEMLIGHT_EXTRATERRESTRIAL_WM2", formatNumber(g0)},
        {"DEMLIGHT_UNITS", "W m-2"},
        {"DEMLIGHT_SKY_DIRECTIONS", visibleSky ? std::to_string(directions) : std::string()},
        {"DEMLIGHT_SKY_MAX_DISTANCE_M", visibleSky ? metadataDistanceM(t, hp.maxDistanceM) : std::string()},
    });
    meta.merge(clearSkyInputMetadata(formatNumber(linke), r.albedo, r.coeffBh, r.coeffDh, r.rasters));
    meta.merge(canopyMetadata(r.canopy));
    IrradianceResult out;
    static_cast<ProductResult&>(out) = makeResult(dem, "irradiance", meta);
    out.centreAzimuthDeg = field.centreAzimuthDeg;
    out.centreElevationDeg = field.centreElevationDeg;
    out.linke = linke;
    out.extraterrestrialWm2 = g0;
    out.bands = irradianceBands(std::move(maps), "W m-2");
    return out;
}

}  // namespace

ClearSkyGrids ClearSkyRasterGrids::on(const Terrain& terrain, ClearSkyRasterGrids& cut,
                                      std::optional<std::size_t> month) const {
    const auto one = [&](const Grid<float>& whole, Grid<float>& part) -> const Grid<float>* {
        if (whole.empty()) return nullptr;
        if (!terrain.frame) return &whole;
        part = cropGrid(whole, cellsOnFullGrid(terrain));
        return &part;
    };
    ClearSkyGrids out{nullptr, {}, one(albedo, cut.albedo), one(coeffBh, cut.coeffBh), one(coeffDh, cut.coeffDh)};
    cut.linke.resize(linke.size());
    if (linke.size() == 1) {
        out.linke = one(linke[0], cut.linke[0]);
    } else if (monthlyLinke() && month) {
        out.linke = one(linke.at(*month), cut.linke[*month]);
    } else if (monthlyLinke()) {
        for (std::size_t m = 0; m < kMonths; ++m) out.linkeByMonth[m] = one(linke[m], cut.linke[m]);
    }
    return out;
}

namespace {

/// Linke factors accepted in rasters: as the constants.
const AuxiliarySpec kLinkeRasterSpec{"linkeRaster", 1, false, kMinLinke, kMaxLinke, false, {}};

/// The one-band auxiliary rasters of the clear sky: request field and valid range.
struct ClearSkyRasterSpec {
    const std::string ClearSkyRasters::*path;
    Grid<float> ClearSkyRasterGrids::*grid;
    double IrradianceParams::*value;
    AuxiliarySpec spec;
};
const ClearSkyRasterSpec kClearSkyRasterSpecs[] = {
    {&ClearSkyRasters::albedo, &ClearSkyRasterGrids::albedo, &IrradianceParams::albedo,
     {"albedoRaster", 1, false, 0, 1, false, {}}},
    {&ClearSkyRasters::coeffBh, &ClearSkyRasterGrids::coeffBh, &IrradianceParams::coeffBh,
     {"coeffBhRaster", 1, false, 0, 1, false, {}}},
    {&ClearSkyRasters::coeffDh, &ClearSkyRasterGrids::coeffDh, &IrradianceParams::coeffDh,
     {"coeffDhRaster", 1, false, 0, 1, false, {}}},
};

/// The band count of a raster, or a FieldError naming `field` when GDAL cannot open it.
std::size_t bandsOf(const std::string& path, const std::string& field) {
    try {
        return inspectRaster(path).dataTypes.size();
    } catch (const Error& e) {
        throw FieldError(field, " " + path + ": " + e.what());
    }
}

/// The Linke maps of `paths`: one of one band; one of twelve bands (monthly); or twelve of one band.
/// `read(path, bands)` reads `bands` bands of a path.
template <class Read>
std::vector<Grid<float>> linkeMaps(const std::vector<std::string>& paths, const Read& read) {
    const std::string& field = kLinkeRasterSpec.field;
    if (paths.empty()) return {};
    if (paths.size() == kMonths) {
        std::vector<Grid<float>> maps;
        for (const std::string& path : paths) {
            if (const std::size_t n = bandsOf(path, field); n != 1)
                throw FieldError(field, " " + path + ": has " + std::to_string(n) +
                                            " bands; twelve monthly Linke rasters must have one band each");
            maps.push_back(std::move(read(path, 1)[0]));
        }
        return maps;
    }
    if (paths.size() != 1)
        throw FieldError(field, ": " + std::to_string(paths.size()) +
                                    " paths; expected one raster (of one band, or of 12 monthly bands) or 12 one-band "
                                    "rasters, January first");
    const std::size_t n = bandsOf(paths[0], field);
    if (n != 1 && n != kMonths)
        throw FieldError(field, " " + paths[0] + ": has " + std::to_string(n) +
                                    " bands; expected 1 (the whole period) or 12 (band m = month m, January first)");
    return read(paths[0], n);
}

}  // namespace

ClearSkyRasterGrids loadClearSkyRasters(const ClearSkyRasters& rasters, const DemSource& source) {
    ClearSkyRasterGrids out;
    out.linke = linkeMaps(rasters.linke, [&](const std::string& path, std::size_t bands) {
        AuxiliarySpec spec = kLinkeRasterSpec;
        spec.bands = bands;
        return loadAuxiliaryRaster(path, source, spec);
    });
    for (const ClearSkyRasterSpec& r : kClearSkyRasterSpecs)
        if (!(rasters.*r.path).empty()) out.*r.grid = std::move(loadAuxiliaryRaster(rasters.*r.path, source, r.spec)[0]);
    return out;
}

IrradianceParams clearSkyAtCell(const ClearSkyRasters& rasters, const DemSource& source, CellIndex cell,
                                IrradianceParams constants, std::vector<double>* linkeByMonth) {
    GeoReference ref = source.geometry().band.ref;
    ref.geoTransform[0] += static_cast<double>(cell.col) * ref.geoTransform[1];
    ref.geoTransform[3] += static_cast<double>(cell.row) * ref.geoTransform[5];
    // The bands of a raster at the cell, each checked against the spec's range.
    const auto atCell = [&](const std::string& path, const AuxiliarySpec& spec, std::size_t count) {
        std::vector<Grid<float>> bands;
        try {
            bands = readRasterResampled(path, ref, 1, 1);
        } catch (const Error& e) {
            throw FieldError(spec.field, " " + path + ": " + e.what());
        }
        if (bands.size() < count) throw FieldError(spec.field, " " + path + ": the raster has too few bands");
        std::vector<double> values;
        for (std::size_t b = 0; b < count; ++b) {
            const float v = bands[b](0, 0);
            if (!std::isnan(v) && !(v >= spec.minValue && v <= spec.maxValue))
                throw FieldError(spec.field, " " + path + ": holds " + formatNumber(v) + " at the point; expected values " +
                                                 formatNumber(spec.minValue) + "-" + formatNumber(spec.maxValue));
            values.push_back(v);
        }
        return values;
    };
    std::vector<double> linke;
    for (const Grid<float>& g : linkeMaps(rasters.linke, [&](const std::string& path, std::size_t bands) {
             std::vector<Grid<float>> out;
             for (double v : atCell(path, kLinkeRasterSpec, bands)) out.emplace_back(1, 1, static_cast<float>(v));
             return out;
         }))
        linke.push_back(g(0, 0));
    if (!linke.empty()) constants.linke = linke[0];
    if (linkeByMonth) *linkeByMonth = linke.size() == kMonths ? linke : std::vector<double>{};
    for (const ClearSkyRasterSpec& r : kClearSkyRasterSpecs) {
        const std::string& path = rasters.*r.path;
        if (!path.empty()) constants.*r.value = atCell(path, r.spec, 1)[0];
    }
    return constants;
}

std::map<std::string, std::string> clearSkyInputMetadata(const std::string& linke, double albedo, double coeffBh,
                                                         double coeffDh, const ClearSkyRasters& rasters) {
    const auto valueOr = [](const std::string& path, const std::string& value) { return path.empty() ? value : path; };
    std::string linkePaths;
    for (const std::string& path : rasters.linke) linkePaths += (linkePaths.empty() ? "" : ",") + path;
    return {{"DEMLIGHT_LINKE", valueOr(linkePaths, linke)},
            {"DEMLIGHT_ALBEDO", valueOr(rasters.albedo, formatNumber(albedo))},
            {"DEMLIGHT_COEFF_BH", valueOr(rasters.coeffBh, formatNumber(coeffBh))},
            {"DEMLIGHT_COEFF_DH", valueOr(rasters.coeffDh, formatNumber(coeffDh))}};
}

std::vector<ProductBand> irradianceBands(IrradianceMaps maps, const std::string& unit) {
    return {{"beam", unit, std::move(maps.beam), {}},
            {"diffuse", unit, std::move(maps.diffuse), {}},
            {"reflected", unit, std::move(maps.reflected), {}},
            {"global", unit, std::move(maps.global), {}}};
}

void validateClearSky(double albedo, double coeffBh, double coeffDh, double solarConstantWm2, double sunDiameterDeg,
                      const Atmosphere& atmosphere) {
    validateSun(sunDiameterDeg, atmosphere);
    for (const auto& [field, value] :
         {std::pair<const char*, double>{"albedo", albedo}, {"coeffBh", coeffBh}, {"coeffDh", coeffDh}})
        if (!(value >= 0 && value <= 1)) throw FieldError(field, " " + formatNumber(value) + ": must be in [0, 1]");
    if (!(solarConstantWm2 >= kMinSolarConstantWm2 && solarConstantWm2 <= kMaxSolarConstantWm2))
        throw FieldError("solarConstantWm2", " " + formatNumber(solarConstantWm2) + ": must be in [1000, 1500]");
}

std::string formatNumberList(const std::vector<double>& values) {
    std::string out;
    for (double v : values) {
        if (!out.empty()) out += ',';
        out += formatNumber(v);
    }
    return out;
}

double linkeAt(const std::vector<double>& linke, UtcInstant t, const TimeZoneSpec& zone) {
    if (linke.size() != 1 && linke.size() != 12)
        throw FieldError("linke", " " + formatNumberList(linke) + ": expected one value or 12 monthly values");
    for (double v : linke)
        if (!(v >= kMinLinke && v <= kMaxLinke)) throw FieldError("linke", " " + formatNumber(v) + ": must be in [1, 10]");
    if (linke.size() == 1) return linke[0];
    return linke[monthAt(t, zone)];
}

std::size_t monthAt(UtcInstant t, const TimeZoneSpec& zone) {
    const std::chrono::year_month_day date{localDayOf(t, zone).date};
    return static_cast<unsigned>(date.month()) - 1;
}

double linkeFor(const IrradianceRequest& r) { return linkeAt(r.linke, r.time.utc, r.time.zone); }

namespace {

/// The halo of irradianceHaloCells for the plan and the sun field the product makes.
std::size_t irradianceHalo(const Terrain& whole, const IrradianceRequest& request, const ScenePlan& plan,
                           const SunField& field) {
    double distance = sunFrameDistanceM(request.search, request.sunDiameterDeg, plan, whole, field);
    if (request.diffuseModel == DiffuseModel::VisibleSky)
        distance = std::max(distance, integralParams(request.search, plan, whole,
                                                     request.skyDirections.value_or(
                                                         static_cast<std::size_t>(plan.skyDirections)))
                                          .maxDistanceM);
    return haloCellsFor(whole, distance);
}

}  // namespace

std::size_t irradianceHaloCells(const DemSource& source, const IrradianceRequest& request) {
    const ScenePlan plan = planFor(request.search, source.geometry().terrain);
    return irradianceHalo(source.geometry().terrain, request, plan,
                          sunFieldFor(source, request.time.utc, request.atmosphere, plan));
}

IrradianceResult irradianceProduct(const DemSource& source, const CellWindow& window, const IrradianceRequest& request,
                                   const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        validateIrradiance(request);
        const double linke = linkeFor(request);
        // R is heliocentric: any site gives it.
        SpaTrace trace{};
        solarPosition(SolarSite{}, request.time.utc, SpaOptions{}, &trace);
        const double g0 = extraterrestrialIrradiance(trace.earthSunDistanceAu, request.solarConstantWm2);
        const Dem& whole = source.geometry();
        const ScenePlan plan = planFor(request.search, whole.terrain);
        // The whole DEM's sun, read by each window: the same bits on its cells.
        const SunField field = sunFieldFor(source, request.time.utc, request.atmosphere, plan);
        const std::size_t halo = source.isWhole(window) ? 0 : irradianceHalo(whole.terrain, request, plan, field);
        // Resampled onto the whole DEM once and cut per window: the same bits on every cell.
        const ClearSkyRasterGrids rasters = loadClearSkyRasters(request.rasters, source);
        const Grid<float> canopy = loadCanopy(request.canopy, source);
        return onWindow<IrradianceResult>(source, window, halo, [&](const Dem& dem) {
            if (!dem.terrain.frame) return irradianceOn(dem, plan, request, field, g0, linke, rasters, canopy, progress);
            return irradianceOn(dem, plan, request, sunFieldOnTile(field, dem, source), g0, linke, rasters, canopy,
                                progress);
        });
    });
}

}  // namespace demlight
