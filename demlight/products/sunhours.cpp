#include "demlight/core/parallel.h"
#include "demlight/products/sunhours.h"

#include "demlight/geo/solar_position.h"
#include "demlight/geo/sun_field.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/sunhours.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"

#include <cmath>
#include <optional>

namespace demlight {
namespace {

/// Shortest and longest integration step accepted.
constexpr std::chrono::seconds kMinStep{6}, kMaxStep{2 * 3600};

struct Sequence {
    std::vector<SunInstant> instants;
    std::vector<UtcInstant> utc;
};

/// How many instants makeSequence lays: start, start + step, ... before the last day's end, and
/// that end itself.
std::size_t sequenceLength(const LocalDay& first, const LocalDay& last, std::chrono::milliseconds step) {
    const auto span = last.endUtc - first.startUtc;
    return static_cast<std::size_t>((span + step - std::chrono::milliseconds(1)) / step) + 1;
}

/// Instants every step from the start of the first local day to the end of the last one.
Sequence makeSequence(const LocalDay& first, const LocalDay& last, const TimeZoneSpec& zone,
                      std::chrono::milliseconds step) {
    using namespace std::chrono;
    Sequence s;
    auto add = [&](UtcInstant t, bool isEnd) {
        // Clock time within the local day the instant belongs to (24.0 for the final midnight).
        const LocalDay d = localDayOf(isEnd ? t - milliseconds(1) : t, zone);
        const auto local = t + zone.offsetAt(t);
        const double clock = duration<double, std::ratio<3600>>(local - UtcInstant(d.date)).count();
        const double hours = duration<double, std::ratio<3600>>(t - first.startUtc).count();
        s.utc.push_back(t);
        s.instants.push_back({hours, clock});
    };
    const std::size_t n = sequenceLength(first, last, step);
    s.utc.reserve(n);
    s.instants.reserve(n);
    for (std::size_t i = 0; i + 1 < n; ++i) add(first.startUtc + static_cast<long>(i) * step, false);
    add(last.endUtc, true);
    return s;
}

SunhoursResult computeSunhours(const DemSource& source, const Dem& dem, const ScenePlan& plan,
                               const SunhoursRequest& r, std::size_t stackDirections, const Grid<float>& wholeCanopy,
                               const ProgressFn& progress) {
    const Terrain& t = dem.terrain;
    std::optional<CanopyTerrain> canopy;
    if (r.canopy.any()) canopy = canopyTerrain(t, wholeCanopy);
    // Each instant's sun on the whole DEM, read by this window (the same bits on its cells).
    const auto fieldAt = [&](UtcInstant when, const SolarSite& site) {
        const SunField field = computeSunField(source, when, site, SpaOptions{}, plan.sunLatticeStepCells);
        return t.frame ? sunFieldOnTile(field, dem, source) : field;
    };
    const Sequence seq = makeSequence(localDay(r.firstDay, r.zone), localDay(r.lastDay, r.zone), r.zone, r.step);
    SunHoursParams params;
    // auto: each instant's sun sets its own distance (sunSearchDistanceM); full: the DEM diagonal.
    params.frame = sunFrameParams(r.search, r.sunDiameterDeg, plan);
    const SolarSite site;  // default pressure and temperature; position from each lattice node
    // With a canopy the lit surface is the ground and buildings under it (demlight/lighting/canopy.h).
    const Normals normals = computeNormals(canopy ? canopy->ground : t);
    if (canopy) {
        params.canopyGround = &canopy->ground;
        params.underCrown = &canopy->underCrown;
        params.transmissivity = r.canopy.transmissivity;
    }

    // Sky term once: it does not depend on the sun's position. With a stack, from the stack's
    // directions (which also give every instant's sun horizons), as the time-lapse does.
    const std::size_t skyDirections =
        stackDirections > 0 ? stackDirections : r.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));
    const HorizonParams hp = stackDirections > 0 ? stackHorizonParams(r.search, plan, t, r.sunDiameterDeg)
                                                 : integralParams(r.search, plan, t, skyDirections);
    SkyAccumulator skyAcc(normals.east, normals.north, normals.up, skyDirections, SkyPatches{});
    ProgressCounter skyCounter(progress, stackDirections > 0 ? "horizons" : "sky", t.heightsM.size() * skyDirections);
    HorizonStack stack;
    if (stackDirections > 0) {
        stack = computeHorizonStack(t, stackDirections, hp, &skyCounter);
        for (std::size_t i = 0; i < stackDirections; ++i) skyAcc.addDirection(i, stack.angleDeg[i]);
        params.stack = &stack;
    } else if (!canopy) {
        sweepDirections(t, hp, skyDirections,
                        [&](std::size_t i, const HorizonMap& h) { skyAcc.addDirection(i, h.angleDeg); }, &skyCounter);
    }
    Grid<float> skyFactor;
    if (!canopy) {
        skyFactor = std::move(skyAcc).finish(r.albedo).skyFactor;
    } else {
        // K of each surface (the full one hidden under the crowns), blended, then f_sky from it.
        skyFactor = skyFactorOf(
            canopySkyK(t, *canopy, normals, skyDirections, hp, r.canopy.transmissivity, &skyCounter), nullptr,
            r.albedo);
    }

    ProgressCounter counter(progress, "sunhours", seq.instants.size());
    SunHoursMaps maps = integrateSunHours(
        t, normals, seq.instants,
        [&](std::size_t i) { return fieldAt(seq.utc[i], site); },
        params, &counter);
    // Daylight from the sun's geometric elevation (no refraction: pressure 0), SPA's sunrise/sunset.
    SolarSite geometric = site;
    geometric.pressureHpa = 0;
    const Grid<float> daylight = integrateDaylight(
        t, seq.instants,
        [&](std::size_t i) { return fieldAt(seq.utc[i], geometric); });
    Grid<float> skyIrr = skyIrradiation(skyFactor, daylight);

    // Never lit: -1, not NaN, which would be written as the DEM's nodata value (a void).
    for (Grid<float>* clock : {&maps.firstLitClock, &maps.lastLitClock}) {
        const float* h = t.heightsM.data();
        float* v = clock->data();
        for (std::size_t i = 0; i < clock->size(); ++i)
            if (std::isnan(v[i]) && !std::isnan(h[i])) v[i] = kNeverLitClock;
    }
    const double stepMin = std::chrono::duration<double, std::ratio<60>>(r.step).count();
    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_NEVER_LIT", formatNumber(kNeverLitClock) + " in first_lit and last_lit"},
        {"DEMLIGHT_FIRST_DATE", formatDate(r.firstDay)},
        {"DEMLIGHT_LAST_DATE", formatDate(r.lastDay)},
        {"DEMLIGHT_TIME_ZONE", r.zone.describe()},
        {"DEMLIGHT_START_UTC", formatInstant(seq.utc.front(), std::string())},
        {"DEMLIGHT_END_UTC", formatInstant(seq.utc.back(), std::string())},
        {"DEMLIGHT_STEP_MIN", formatNumber(stepMin)},
        {"DEMLIGHT_INTEGRATION", "trapezoid"},
        {"DEMLIGHT_INSTANTS", std::to_string(seq.instants.size())},
        {"DEMLIGHT_INSTANTS_SWEPT", std::to_string(maps.instantsSwept)},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(r.sunDiameterDeg)},
        {"DEMLIGHT_LIT_VISIBILITY", formatNumber(kLitVisibility)},
        {"DEMLIGHT_METHOD", "sweep"},
        {"DEMLIGHT_HORIZON_MODE", stackDirections > 0 ? "interpolated:" + std::to_string(stackDirections) : "exact"},
        {"DEMLIGHT_HORIZON_MODE_CHOICE", r.stackDirections ? std::string("given")
                                         : "auto (interpolated on terrain under quality auto from " +
                                               std::to_string(kAutoStackMinInstants) + " instants; " +
                                               std::to_string(seq.instants.size()) + " here)"},
        {"DEMLIGHT_REFRACTION", formatNumber(params.frame.refraction)},
        {"DEMLIGHT_SKY_MODEL", "stewart-langer"},
        {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(skyDirections)},
        {"DEMLIGHT_SKY_MAX_DISTANCE_M", metadataDistanceM(t, hp.maxDistanceM)},
        {"DEMLIGHT_ALBEDO", formatNumber(r.albedo)},
        {"DEMLIGHT_DAYLIGHT", "SPA sunrise to sunset at the cell, no terrain (geometric elevation of the "
                              "sun's centre > " + formatNumber(kSunriseGeometricElevationDeg) + " deg)"},
    });
    meta.merge(canopyMetadata(r.canopy));
    SunhoursResult out;
    static_cast<ProductResult&>(out) = makeResult(dem, "sunhours", meta);
    out.instants = seq.instants.size();
    out.instantsSwept = maps.instantsSwept;
    out.stackDirections = stackDirections;
    const std::string zone = r.zone.describe();
    out.bands = movedBands(
        ProductBand{"sun_hours", "hours of direct sun weighted by visibility (h)", std::move(maps.sunHours), {}},
        ProductBand{"sun_irradiation", "normalised irradiance x hours (1 h of unit zenith sun on flat ground = 1)",
         std::move(maps.sunIrradiation), {}},
        ProductBand{"sky_irradiation",
         "f_sky x daylight hours: a unit uniform sky from sunrise to sunset at the cell "
         "(1 h of unit sky on open flat ground = 1)",
         std::move(skyIrr), {}},
        // Nearest: kNeverLitClock (-1) sits beside clock hours, and a mean of the two (a cell
        // "first lit" at 2 a.m.) is a time no cell has.
        ProductBand{"first_lit", "local clock hours (" + zone + ") when half the sun first shows; -1 = never",
         std::move(maps.firstLitClock), {}, Resampling::Nearest},
        ProductBand{"last_lit", "local clock hours (" + zone + ") when half the sun last shows; -1 = never",
         std::move(maps.lastLitClock), {}, Resampling::Nearest});
    return out;
}

}  // namespace

std::size_t sunhoursInstantCount(const SunhoursRequest& r) {
    return sequenceLength(localDay(r.firstDay, r.zone), localDay(r.lastDay, r.zone), r.step);
}

std::size_t sunhoursStackDirectionsAtMost(const SunhoursRequest& r) {
    if (r.stackDirections) return *r.stackDirections;
    const bool longPeriod = r.search.quality == Quality::Auto && sunhoursInstantCount(r) >= kAutoStackMinInstants;
    return longPeriod ? kDefaultStackDirections : 0;
}

std::size_t sunhoursStackDirections(const SunhoursRequest& r, const ScenePlan& plan) {
    const bool autoOnTerrain = plan.quality == Quality::Auto && !plan.surfaceModel && !r.canopy.any();
    return r.stackDirections || autoOnTerrain ? sunhoursStackDirectionsAtMost(r) : 0;
}

std::size_t sunhoursHaloCells(const DemSource& source, const SunhoursRequest& request) {
    const Terrain& whole = source.geometry().terrain;
    const ScenePlan plan = planFor(request.search, whole);
    // Every sun of the days down to the horizon (the distance a stack of horizons serving every
    // sun searches), or the sky's.
    const double sunDistance = stackHorizonParams(request.search, plan, whole, request.sunDiameterDeg).maxDistanceM;
    const double skyDistance =
        integralParams(request.search, plan, whole,
                       request.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections)))
            .maxDistanceM;
    return haloCellsFor(whole, std::max(sunDistance, skyDistance));
}

SunhoursResult sunhoursProduct(const DemSource& source, const CellWindow& window, const SunhoursRequest& request,
                               const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        if (request.lastDay < request.firstDay)
            throw FieldError("lastDay", " " + formatDate(request.lastDay) + " is before firstDay " + formatDate(request.firstDay));
        if (request.step < kMinStep || request.step > kMaxStep)
            throw FieldError("step", " " + formatNumber(std::chrono::duration<double>(request.step).count()) +
                        " s: must be from 6 s to 2 h");
        validateSun(request.sunDiameterDeg, Atmosphere{});
        checkSpaValidity(localDay(request.firstDay, request.zone).startUtc);
        checkSpaValidity(localDay(request.lastDay, request.zone).endUtc - std::chrono::milliseconds(1));
        if (!(request.albedo >= 0 && request.albedo <= 1))
            throw FieldError("albedo", " " + formatNumber(request.albedo) + ": must be in [0, 1]");
        if (request.stackDirections && *request.stackDirections != 0 &&
            (*request.stackDirections < 4 || *request.stackDirections > 720))
            throw FieldError("stackDirections", " " + std::to_string(*request.stackDirections) + ": must be 0 or 4..720");
        validateCanopy(request.canopy);
        if (request.canopy.any() && request.stackDirections && *request.stackDirections != 0)
            throw FieldError("stackDirections", ": interpolated horizons do not model a canopy; use exact horizons");
        const Grid<float> canopy = loadCanopy(request.canopy, source);
        const Terrain& whole = source.geometry().terrain;
        const ScenePlan plan = planFor(request.search, whole);
        const std::size_t stackDirections = sunhoursStackDirections(request, plan);
        const std::size_t halo = source.isWhole(window) ? 0 : sunhoursHaloCells(source, request);
        return onWindow<SunhoursResult>(source, window, halo,
                                        [&](const Dem& dem) {
                                            return computeSunhours(source, dem, plan, request, stackDirections, canopy,
                                                                   progress);
                                        });
    });
}

}  // namespace demlight
