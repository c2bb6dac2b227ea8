#include "demlight/core/parallel.h"
#include "demlight/products/insolation.h"

#include "demlight/geo/solar_position.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <cmath>

namespace demlight {
namespace {

constexpr double kWhPerKWh = 1000;
constexpr std::chrono::milliseconds kMinStep = std::chrono::seconds(6), kMaxStep = std::chrono::hours(2);

/// The sun at the DEM centre every `step` over the period, with trapezoid weights (hours); each
/// with its month when the Linke maps are monthly.
std::vector<WeightedSun> sunsOfPeriod(const DemSource& source, const InsolationRequest& r, bool monthlyLinke,
                                      std::size_t& instants) {
    const std::vector<UtcInstant> times = periodInstants(r);
    instants = times.size();
    SolarSite site;
    std::tie(site.latitudeDeg, site.longitudeDeg) = cellLatLon(
        source.geometry(), 0.5 * static_cast<double>(source.width()), 0.5 * static_cast<double>(source.height()));
    const auto [low, high] = std::pair(source.frame()->lowM, source.frame()->highM);
    site.elevationM = 0.5 * (static_cast<double>(low) + static_cast<double>(high));
    site.pressureHpa = r.atmosphere.pressureHpa;
    site.temperatureC = r.atmosphere.temperatureC;
    std::vector<WeightedSun> suns;
    for (std::size_t i = 0; i < times.size(); ++i) {
        const double before = i > 0 ? instantHoursBetween(times[i - 1], times[i]) : 0.0;
        const double after = i + 1 < times.size() ? instantHoursBetween(times[i], times[i + 1]) : 0.0;
        SpaTrace trace{};
        const SolarPosition p = solarPosition(site, times[i], SpaOptions{}, &trace);
        if (!(p.elevationDeg > 0)) continue;
        suns.push_back({0.5 * (before + after), p.azimuthDeg, p.elevationDeg,
                        extraterrestrialIrradiance(trace.earthSunDistanceAu, r.solarConstantWm2),
                        linkeAt(r.linke, times[i], r.zone),
                        monthlyLinke ? static_cast<int>(monthAt(times[i], r.zone)) : -1});
    }
    return suns;
}

/// The binned totals of one surface's horizons (`horizonsOf`, the DEM's terrain or the ground
/// under a canopy), the visible-sky K0 of the same horizons included; the cells of `hidden` see
/// nothing (under a crown, on the full surface).
InsolationMaps insolationTotals(const Terrain& horizonsOf, const Grid<float>& litHeightsM, const Normals& normals,
                                const InsolationRequest& r, const HorizonParams& hp, const std::vector<SunBin>& bins,
                                std::size_t directions, const ClearSkyGrids& grids, const Grid<std::uint8_t>* hidden,
                                ProgressCounter& counter) {
    const bool visibleSky = r.diffuseModel == DiffuseModel::VisibleSky;
    IrradianceParams params;
    params.model = r.diffuseModel;
    params.albedo = r.albedo;
    params.coeffBh = r.coeffBh;
    params.coeffDh = r.coeffDh;
    InsolationAccumulator totals(litHeightsM, normals, bins, directions, params, r.sunDiameterDeg);
    totals.setGrids(grids);
    std::optional<SkyAccumulator> sky;
    if (visibleSky) sky.emplace(normals.east, normals.north, normals.up, directions, SkyPatches{});
    Grid<float> own, raised;
    sweepDirections(horizonsOf, hp, directions, [&](std::size_t i, const HorizonMap& h) {
        const Grid<float>* horizons = &h.angleDeg;
        if (hidden) {
            own = h.angleDeg;
            hideUnderCrown(own, *hidden, 90.0f);
            horizons = &own;
        }
        totals.addDirection(i, *horizons);
        if (!sky) return;
        raiseToHorizontal(*horizons, raised);
        sky->addDirection(i, raised);
    }, &counter);
    const Grid<float> k0 = sky ? std::move(*sky).finish(0.0).skyK : Grid<float>();
    return totals.finish(visibleSky ? &k0 : nullptr);
}

InsolationResult insolationOn(const Dem& dem, const ScenePlan& plan, const InsolationRequest& r,
                              const std::vector<SunBin>& bins, std::size_t directions, std::size_t instants,
                              const ClearSkyRasterGrids& rasters, const Grid<float>& wholeCanopy,
                              const ProgressFn& progress) {
    const Terrain& t = dem.terrain;
    std::optional<CanopyTerrain> canopy;
    if (r.canopy.any()) canopy = canopyTerrain(t, wholeCanopy);
    // With a canopy the lit surface is the ground and buildings under it (demlight/lighting/canopy.h).
    const Terrain& lit = canopy ? canopy->ground : t;
    const Normals normals = computeNormals(lit);
    const HorizonParams hp = horizonParams(r.search, plan);
    ProgressCounter counter(progress, "insolation", t.heightsM.size() * directions * (canopy ? 2 : 1));
    ClearSkyRasterGrids cut;
    const ClearSkyGrids grids = rasters.on(t, cut);
    InsolationMaps totalMaps = insolationTotals(t, lit.heightsM, normals, r, hp, bins, directions, grids,
                                                canopy ? &canopy->underCrown : nullptr, counter);
    if (canopy) {
        InsolationMaps ground = insolationTotals(lit, lit.heightsM, normals, r, hp, bins, directions, grids, nullptr, counter);
        IrradianceMaps& a = totalMaps.irradiation;
        IrradianceMaps& b = ground.irradiation;
        for (auto [full, under] : {std::pair{&a.beam, &b.beam}, std::pair{&a.diffuse, &b.diffuse},
                                   std::pair{&a.reflected, &b.reflected}, std::pair{&a.global, &b.global},
                                   std::pair{&totalMaps.sunHours, &ground.sunHours}})
            blendCanopy(*full, *under, r.canopy.transmissivity);
    }
    IrradianceMaps& maps = totalMaps.irradiation;
    for (Grid<float>* g : {&maps.beam, &maps.diffuse, &maps.reflected, &maps.global})
        for (float& v : g->values()) v = static_cast<float>(v / kWhPerKWh);

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.merge(searchMetadata(t, hp.maxDistanceM, r.search.refraction));
    const auto [start, end] = insolationPeriod(r);
    meta.insert({
        {"DEMLIGHT_START", formatInstant(start, r.zone)},
        {"DEMLIGHT_END", formatInstant(end, r.zone)},
        {"DEMLIGHT_TIME_ZONE", r.zone.describe()},
        {"DEMLIGHT_STEP_S", formatNumber(std::chrono::duration<double>(r.step).count())},
        {"DEMLIGHT_INSTANTS", std::to_string(instants)},
        {"DEMLIGHT_METHOD", "binned sun positions"},
        {"DEMLIGHT_BINS", std::to_string(bins.size())},
        {"DEMLIGHT_DIRECTIONS", std::to_string(directions)},
        {"DEMLIGHT_ELEVATION_BAND_DEG", formatNumber(r.elevationBandDeg)},
        {"DEMLIGHT_MODEL", "esra"},
        {"DEMLIGHT_DIFFUSE_MODEL", std::string(diffuseModelName(r.diffuseModel))},
        {"DEMLIGHT_SOLAR_CONSTANT_WM2", formatNumber(r.solarConstantWm2)},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(r.sunDiameterDeg)},
        {"DEMLIGHT_UNITS", "kWh m-2"},
    });
    meta.merge(clearSkyInputMetadata(formatNumberList(r.linke), r.albedo, r.coeffBh, r.coeffDh, r.rasters));
    meta.merge(canopyMetadata(r.canopy));
    InsolationResult out;
    static_cast<ProductResult&>(out) = makeResult(dem, "insolation", meta);
    out.instants = instants;
    out.bins = bins.size();
    out.directions = directions;
    out.bands = irradianceBands(std::move(maps), "kWh m-2");
    out.bands.push_back({"sun_hours", "hours", std::move(totalMaps.sunHours), {}});
    return out;
}

}  // namespace

void validateInsolation(const InsolationRequest& r) {
    validateClearSky(r.albedo, r.coeffBh, r.coeffDh, r.solarConstantWm2, r.sunDiameterDeg, r.atmosphere);
    linkeAt(r.linke, localDay(r.firstDay, r.zone).startUtc, r.zone);
    validateCanopy(r.canopy);
    if (r.interval && !(r.interval->first < r.interval->second))
        throw FieldError("interval", " " + formatInstant(r.interval->second, r.zone) + ": is not after its start " +
                                         formatInstant(r.interval->first, r.zone));
    if (!r.interval && r.lastDay < r.firstDay)
        throw FieldError("lastDay", " " + formatDate(r.lastDay) + ": is before the first day " + formatDate(r.firstDay));
    if (r.step < kMinStep || r.step > kMaxStep) throw FieldError("step", ": must be from 6 s to 2 h");
    if (r.directions && *r.directions < 4)
        throw FieldError("directions", " " + std::to_string(*r.directions) + ": must be >= 4");
    if (!(r.elevationBandDeg > 0 && r.elevationBandDeg <= 90))
        throw FieldError("elevationBandDeg", " " + formatNumber(r.elevationBandDeg) + ": must be in (0, 90]");
}

double instantHoursBetween(UtcInstant a, UtcInstant b) {
    return std::chrono::duration<double, std::ratio<3600>>(b - a).count();
}

std::pair<UtcInstant, UtcInstant> insolationPeriod(const InsolationRequest& r) {
    if (r.interval) return *r.interval;
    return {localDay(r.firstDay, r.zone).startUtc, localDay(r.lastDay, r.zone).endUtc};
}

std::vector<UtcInstant> periodInstants(const InsolationRequest& r) {
    const auto [start, end] = insolationPeriod(r);
    std::vector<UtcInstant> times;
    for (UtcInstant t = start; t < end; t += r.step) times.push_back(t);
    times.push_back(end);
    return times;
}

std::size_t insolationHaloCells(const DemSource& source, const InsolationRequest& request) {
    const Terrain& whole = source.geometry().terrain;
    return haloCellsFor(whole, horizonParams(request.search, planFor(request.search, whole)).maxDistanceM);
}

InsolationResult insolationProduct(const DemSource& source, const CellWindow& window, const InsolationRequest& request,
                                   const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        validateInsolation(request);
        const Dem& whole = source.geometry();
        const ScenePlan plan = planFor(request.search, whole.terrain);
        const std::size_t directions = request.directions.value_or(kDefaultInsolationDirections);
        // Resampled onto the whole DEM once and cut per window: the same bits on every cell.
        const ClearSkyRasterGrids rasters = loadClearSkyRasters(request.rasters, source);
        const Grid<float> canopy = loadCanopy(request.canopy, source);
        // The whole DEM's bins for every window: the same bits on its cells.
        std::size_t instants = 0;
        const std::vector<SunBin> bins = binSuns(sunsOfPeriod(source, request, rasters.monthlyLinke(), instants),
                                                 directions, request.elevationBandDeg);
        const std::size_t halo = insolationHaloCells(source, request);
        return onWindow<InsolationResult>(source, window, halo, [&](const Dem& dem) {
            return insolationOn(dem, plan, request, bins, directions, instants, rasters, canopy, progress);
        });
    });
}

}  // namespace demlight
