#include "demlight/core/parallel.h"
#include "demlight/products/sun.h"

#include "demlight/lighting/aperture.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"

namespace demlight {

namespace {

/// SPA's stated pressure limit (hPa; Reda & Andreas, Table 1).
constexpr double kMaxPressureHpa = 5000;
/// Largest sun diameter accepted (degrees): soft shadows, still a disk.
constexpr double kMaxSunDiameterDeg = 20;

SunResult horizonSun(const Dem& dem, const Normals& normals, const SunField& field, const SunRequest& request,
                     const ScenePlan& plan, const CanopyTerrain* canopy, ProgressCounter& counter) {
    // auto: the distance this sun needs (sunSearchDistanceM); full: the plan's DEM diagonal.
    const SunFrameParams params = sunFrameParams(request.search, request.sunDiameterDeg, plan);
    SunFrame frame = computeSunFrame(dem.terrain, normals, field, params, &counter);
    if (canopy)
        blendCanopySun(frame, computeSunFrame(canopy->ground, normals, field, params, &counter), canopy->underCrown,
                       request.canopy.transmissivity);
    SunResult out;
    out.bands = movedBands(ProductBand{"sun_visibility", "fraction of sun disk (0-1)", std::move(frame.light.visibility), {}},
                 ProductBand{"sun_irradiance", "normalised irradiance (1 = unit-radiance zenith sun on flat ground)",
                  std::move(frame.light.irradiance), {}});
    out.maxDistanceM = frame.maxDistanceM;
    out.sweepRegions = frame.sweepRegions;
    out.strategy = sunSweepStrategyName(frame.strategy);
    out.sunUp = frame.sweepRegions > 0;
    return out;
}

SunResult apertureSun(const Dem& dem, const Normals& normals, const SunField& field, const SunRequest& request,
                      const ScenePlan& plan, std::size_t directions, ProgressCounter& counter) {
    // The aperture does not depend on the sun: search distance and directions are the sky's.
    const HorizonParams hp = integralParams(request.search, plan, dem.terrain, directions);
    ApertureAccumulator acc(normals.east, normals.north, normals.up, directions);
    sweepDirections(dem.terrain, hp, directions,
                    [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); }, &counter);
    ApertureLightParams lp;
    lp.sunRadiusDeg = 0.5 * request.sunDiameterDeg;
    lp.smoothIntersection = request.model == SunModel::ApertureSmooth;
    ApertureSunMaps m =
        applyApertureSun(acc.finish(), normals.east, normals.north, normals.up, field, lp);
    SunResult out;
    out.bands = movedBands(ProductBand{"sun_visibility", "fraction of the sun cap inside the aperture cap (0-1)", std::move(m.visibility), {}},
                 ProductBand{"sun_irradiance",
                  "normalised irradiance, Lambert integral over the sun cap inside the aperture cap (1 = "
                  "unit-radiance zenith sun on flat ground)",
                  std::move(m.irradiance), {}});
    out.maxDistanceM = hp.maxDistanceM;
    out.directions = directions;
    out.sunUp = field.elevationRange().second > -0.5 * request.sunDiameterDeg;
    return out;
}

SunResult computeSun(const Dem& dem, const ScenePlan& plan, const SunRequest& request, const SunField& field,
                     const Grid<float>& wholeCanopy, const ProgressFn& progress) {
    const Terrain& t = dem.terrain;
    const auto [lowestSun, highestSun] = field.elevationRange();
    const bool horizon = request.model == SunModel::Horizon;
    std::optional<CanopyTerrain> canopy;
    if (request.canopy.any()) canopy = canopyTerrain(t, wholeCanopy);
    // With a canopy the lit surface is the ground and buildings under it.
    const Normals normals = computeNormals(canopy ? canopy->ground : t);
    const std::size_t directions = request.directions.value_or(static_cast<std::size_t>(plan.skyDirections));
    ProgressCounter counter(progress, "sun", t.heightsM.size() * (horizon ? (canopy ? 2 : 1) : directions));
    SunResult out = horizon ? horizonSun(dem, normals, field, request, plan, canopy ? &*canopy : nullptr, counter)
                            : apertureSun(dem, normals, field, request, plan, directions, counter);
    std::vector<ProductBand> bands = std::move(out.bands);
    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.merge(searchMetadata(t, out.maxDistanceM, request.search.refraction));
    meta.insert({
        {"DEMLIGHT_TIME_UTC", formatInstant(request.time.utc, std::string())},
        {"DEMLIGHT_TIME_LOCAL", formatInstant(request.time.utc, request.time.zone)},
        {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
        {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
        {"DEMLIGHT_SUN_ELEVATION_RANGE_DEG", formatNumber(lowestSun) + "," + formatNumber(highestSun)},
        {"DEMLIGHT_SUN_SWEEP_REGIONS", std::to_string(out.sweepRegions)},
        {"DEMLIGHT_SUN_SWEEP_STRATEGY", out.strategy},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(request.sunDiameterDeg)},
        {"DEMLIGHT_MODEL", std::string(sunModelName(request.model))},
        {"DEMLIGHT_METHOD", "sweep"},
        {"DEMLIGHT_DIRECTIONS", horizon ? std::string() : std::to_string(directions)},
    });
    meta.merge(canopyMetadata(request.canopy));
    static_cast<ProductResult&>(out) = makeResult(dem, "sun", meta);
    out.bands = std::move(bands);
    out.centreAzimuthDeg = field.centreAzimuthDeg;
    out.centreElevationDeg = field.centreElevationDeg;
    return out;
}

}  // namespace

void validateSun(double sunDiameterDeg, const Atmosphere& atmosphere) {
    if (!(sunDiameterDeg >= 0 && sunDiameterDeg <= kMaxSunDiameterDeg))
        throw FieldError("sunDiameterDeg", " " + formatNumber(sunDiameterDeg) + ": must be in [0, 20]");
    if (!(atmosphere.pressureHpa >= 0 && atmosphere.pressureHpa <= kMaxPressureHpa))
        throw FieldError("pressureHpa", " " + formatNumber(atmosphere.pressureHpa) + ": must be in [0, 5000]");
    if (!(atmosphere.temperatureC >= -100 && atmosphere.temperatureC <= 100))
        throw FieldError("temperatureC", " " + formatNumber(atmosphere.temperatureC) + ": must be in [-100, 100]");
}

SunField sunFieldOnTile(const SunField& whole, const Dem& tile, const DemSource& source) {
    return whole.onTile(tile.terrain.frameCol0, tile.terrain.frameRow0, source.width());
}

SunField sunFieldFor(const DemSource& source, UtcInstant time, const Atmosphere& atmosphere, const ScenePlan& plan) {
    SolarSite site;
    site.pressureHpa = atmosphere.pressureHpa;
    site.temperatureC = atmosphere.temperatureC;
    return computeSunField(source, time, site, SpaOptions{}, plan.sunLatticeStepCells);
}

namespace {

/// The halo of sunHaloCells for the plan and the sun field the product makes.
std::size_t sunHalo(const Terrain& whole, const SunRequest& request, const ScenePlan& plan, const SunField& field) {
    // The longest search any sun of this instant needs on the whole DEM.
    double distance = sunFrameDistanceM(request.search, request.sunDiameterDeg, plan, whole, field);
    if (request.model != SunModel::Horizon)
        distance = integralParams(request.search, plan, whole,
                                  request.directions.value_or(static_cast<std::size_t>(plan.skyDirections)))
                       .maxDistanceM;
    return haloCellsFor(whole, distance);
}

}  // namespace

std::size_t sunHaloCells(const DemSource& source, const SunRequest& request) {
    const ScenePlan plan = planFor(request.search, source.geometry().terrain);
    return sunHalo(source.geometry().terrain, request, plan,
                   sunFieldFor(source, request.time.utc, request.atmosphere, plan));
}

SunResult sunProduct(const DemSource& source, const CellWindow& window, const SunRequest& request,
                     const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        validateSun(request.sunDiameterDeg, request.atmosphere);
        if (request.directions && *request.directions < 1)
            throw FieldError("directions", " " + std::to_string(*request.directions) + ": must be >= 1");
        validateCanopy(request.canopy);
        if (request.canopy.any() && request.model != SunModel::Horizon)
            throw FieldError("canopy", ": applies to the horizon sun model only");
        const Grid<float> canopy = loadCanopy(request.canopy, source);
        const Dem& whole = source.geometry();
        const ScenePlan plan = planFor(request.search, whole.terrain);
        // The whole DEM's sun, read by each window (SunField::onTile): the same bits on every cell.
        const SunField field = sunFieldFor(source, request.time.utc, request.atmosphere, plan);
        const std::size_t halo = source.isWhole(window) ? 0 : sunHalo(whole.terrain, request, plan, field);
        return onWindow<SunResult>(source, window, halo, [&](const Dem& dem) {
            return computeSun(dem, plan, request, sunFieldOnTile(field, dem, source), canopy, progress);
        });
    });
}

}  // namespace demlight
