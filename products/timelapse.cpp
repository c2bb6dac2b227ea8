#include "products/timelapse.h"

#include "geo/solar_position.h"
#include "lighting/sequence_fit.h"
#include "lighting/sky.h"
#include "lighting/sun_frame.h"
#include "lighting/sunhours.h"
#include "lighting/surface.h"
#include "products/sun.h"
#include "src/error.h"

#include <algorithm>
#include <cmath>

namespace demlight {
namespace {

using Clock = std::chrono::steady_clock;

/// Horizon directions of the interpolated mode when no N is given.
constexpr std::size_t kDefaultStackDirections = 64;
constexpr std::size_t kMinStackDirections = 4, kMaxStackDirections = 720;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// Seconds since the Unix epoch, the clock the sequence fit's times use.
double unixSeconds(UtcInstant t) { return std::chrono::duration<double>(t.time_since_epoch()).count(); }

void fillInstants(TimelapseInstants& f, UtcInstant t0, UtcInstant t1, std::chrono::milliseconds step,
                  std::size_t maxFrames) {
    if (step < std::chrono::seconds(1)) throw FieldError("step", ": must be at least 1 s");
    if (t1 < t0) throw Error("the sequence ends before it starts");
    const auto count = static_cast<std::size_t>((t1 - t0) / step) + 1;
    if (count > maxFrames)
        throw FieldError("maxFrames", " " + std::to_string(maxFrames) + ": the sequence would have " +
                                          std::to_string(count) + " frames at a step of " +
                                          formatNumber(std::chrono::duration<double>(step).count()) +
                                          " s; use a longer step or allow more frames");
    for (UtcInstant t = t0; t <= t1; t += step) f.instants.push_back(t);
}

/// The sky term once; with a stack, the stack too (it gives every frame's sun horizon).
struct SkyTerm {
    Grid<float> skyK;
    HorizonStack stack;
    HorizonParams params;
};

SkyTerm skyTerm(const Terrain& t, const Normals& normals, const ScenePlan& plan, const TimelapseRequest& r,
                std::size_t skyDirections, ProgressCounter& counter) {
    SkyTerm out;
    // The interpolated stack also gives every frame's sun horizon: the plan's own direction
    // tolerance, not the integrals' (planIntegralParams).
    out.params = r.stackDirections > 0 ? horizonParams(r.search, plan) : integralParams(r.search, plan, t, skyDirections);
    if (r.stackDirections == 0) {
        out.skyK = skyLightK(t, normals, skyDirections, out.params, &counter);
        return out;
    }
    // One stack serves every sun: out to the lowest sun's shadows (auto) or the plan's distance (full).
    if (!r.search.maxDistanceM)
        out.params.maxDistanceM = plan.quality == Quality::Full ? plan.maxDistanceM
                                                                : sunSearchDistanceM(t, 0.0, r.sunDiameterDeg);
    // The stack also gives every frame's sun horizon: two scan lines per cell.
    HorizonParams stackParams = out.params;
    stackParams.nearestLine = false;
    out.stack = computeHorizonStack(t, r.stackDirections, stackParams, &counter);
    SkyAccumulator acc(normals.east, normals.north, normals.up, r.stackDirections, {}, r.search.threads);
    for (std::size_t i = 0; i < r.stackDirections; ++i) acc.addDirection(i, out.stack.angleDeg[i]);
    out.skyK = std::move(acc).finish(0.0).skyK;
    return out;
}

ProductResult fitResult(const Dem& dem, const ScenePlan& plan, const SequenceFitter& fitter,
                        const std::vector<UtcInstant>& instants, TimelapseResult& stats) {
    SequenceFit fit = fitter.finish();
    double sum = 0, worst = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < fit.rmsError.size(); ++i) {
        const float e = fit.rmsError.data()[i];
        if (std::isnan(e) || std::isnan(dem.terrain.heightsM.data()[i])) continue;
        sum += e, worst = std::max<double>(worst, e), ++n;
    }
    stats.fitMeanRms = n ? sum / static_cast<double>(n) : 0.0;
    stats.fitWorstRms = worst;
    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_FIT_DEGREE", std::to_string(fit.degree)},
        {"DEMLIGHT_FIT_BASIS", "Legendre P_j(x), x = 2 (t - t0) / (t1 - t0) - 1"},
        {"DEMLIGHT_FIT_T0_UTC", formatInstant(instants.front(), std::string())},
        {"DEMLIGHT_FIT_T1_UTC", formatInstant(instants.back(), std::string())},
        {"DEMLIGHT_FIT_FRAMES", std::to_string(instants.size())},
        {"DEMLIGHT_FIT_MEAN_RMS", formatNumber(stats.fitMeanRms)},
    });
    ProductResult out = makeResult(dem, "sequence fit", meta);
    for (int j = 0; j <= fit.degree; ++j)
        out.bands.push_back({"sun_irradiance_legendre_" + std::to_string(j), "normalised irradiance",
                             std::move(fit.coefficients[static_cast<std::size_t>(j)]), {}});
    out.bands.push_back({"rms_error", "normalised irradiance", std::move(fit.rmsError), {}});
    return out;
}

}  // namespace

TimelapseInstants instantsBetween(const ZonedInstant& start, const ZonedInstant& end, std::chrono::milliseconds step,
                                  std::size_t maxFrames) {
    if (end.utc < start.utc) throw Error("the end instant is before the start");
    checkSpaValidity(start.utc);
    checkSpaValidity(end.utc);
    TimelapseInstants f;
    f.zone = start.zone;
    f.description = "start to end";
    fillInstants(f, start.utc, end.utc, step, maxFrames);
    return f;
}

TimelapseInstants instantsOfDay(const Dem& dem, std::chrono::sys_days date, const TimeZoneSpec& zone,
                                std::chrono::milliseconds step, std::size_t maxFrames) {
    TimelapseInstants f;
    f.zone = zone;
    const LocalDay day = localDay(date, zone);
    // Sunrise to sunset at the DEM centre (SPA A.2); the whole day on polar day.
    const auto [lat, lon] = cellLatLon(dem, static_cast<double>(dem.band.width) / 2.0, static_cast<double>(dem.band.height) / 2.0);
    SolarSite site;
    site.latitudeDeg = lat;
    site.longitudeDeg = lon;
    const SunEvents ev = sunEvents(site, day.startUtc);
    if (ev.kind == DayKind::PolarNight)
        throw Error("date " + formatDate(date) + ": the sun does not rise at the DEM centre (polar night); give a start and end instead");
    // Whole seconds: frame times read cleanly and the sun is up by then.
    UtcInstant t0 = std::chrono::ceil<std::chrono::seconds>(ev.sunrise.value_or(day.startUtc));
    UtcInstant t1 = std::chrono::floor<std::chrono::seconds>(ev.sunset.value_or(day.endUtc));
    f.description = ev.kind == DayKind::PolarDay ? "local day (polar day)" : "sunrise to sunset";
    if (ev.sunrise && ev.sunset && *ev.sunset < *ev.sunrise) {
        // The zone is far from the DEM's own (e.g. UTC for a DEM at 122 W): the day's sunset
        // falls after the zone's midnight, and the one in this day is the previous evening's.
        // Film the daylight that starts at this sunrise, to its sunset in the next window.
        const SunEvents next = sunEvents(site, day.startUtc + std::chrono::hours(24));
        t1 = std::chrono::floor<std::chrono::seconds>(next.sunset && *next.sunset > *ev.sunrise ? *next.sunset
                                                                                                 : day.endUtc);
        f.description = "sunrise to sunset (the sun sets after midnight in " + zone.describe() +
                        "; the DEM's own time zone gives its local day)";
    }
    fillInstants(f, t0, t1, step, maxFrames);
    return f;
}

std::size_t parseHorizonMode(const std::string& text, const std::string& field) {
    if (text == "exact") return 0;
    if (text == "interpolated") return kDefaultStackDirections;
    const std::string prefix = "interpolated:";
    if (text.rfind(prefix, 0) == 0) {
        std::size_t used = 0;
        long n = -1;
        try {
            n = std::stol(text.substr(prefix.size()), &used);
        } catch (const std::exception&) {
        }
        if (used == text.size() - prefix.size() && n >= static_cast<long>(kMinStackDirections) &&
            n <= static_cast<long>(kMaxStackDirections))
            return static_cast<std::size_t>(n);
    }
    throw FieldError(field, " '" + text + "': expected exact, interpolated or interpolated:N (N in 4..720)");
}

TimelapseResult timelapseProduct(const DemSource& source, const TimelapseRequest& request, const TimelapseSink& sink,
                                 const ProgressFn& progress) {
    const auto& instants = request.frames.instants;
    if (instants.empty()) throw Error("frames: the sequence has no instants");
    if (request.stackDirections != 0 &&
        (request.stackDirections < kMinStackDirections || request.stackDirections > kMaxStackDirections))
        throw FieldError("stackDirections", " " + std::to_string(request.stackDirections) + ": must be 0 or in 4..720");
    validatePicture(request.picture);
    validateSun(request.sunDiameterDeg, Atmosphere{});
    const std::shared_ptr<const Dem> whole = source.readWhole();
    const Dem& dem = *whole;
    const Terrain& t = dem.terrain;
    const std::vector<Grid<float>> albedo = loadPictureAlbedo(source, request.picture);

    const auto tStart = Clock::now();
    const ScenePlan plan = planFor(request.search, t);
    const std::size_t skyDirections = request.stackDirections > 0
                                          ? request.stackDirections
                                          : request.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));
    const std::size_t n = instants.size();
    ProgressCounter counter(progress, "timelapse", t.heightsM.size() * (skyDirections + n));
    const Normals normals = computeNormals(t, request.search.threads);
    const SkyTerm sky = skyTerm(t, normals, plan, request, skyDirections, counter);

    TimelapseResult result;
    result.frames = n;
    result.skyDirections = skyDirections;
    result.skyMaxDistanceM = sky.params.maxDistanceM;
    result.quality = plan.quality;
    result.skySeconds = secondsSince(tStart);
    if (request.lightmaps && sink.sky) {
        std::map<std::string, std::string> meta = planMetadata(plan);
        meta.insert({
            {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(skyDirections)},
            {"DEMLIGHT_SKY_MAX_DISTANCE_M", metadataDistanceM(t, sky.params.maxDistanceM)},
            {"DEMLIGHT_REFRACTION", formatNumber(sky.params.refraction)},
        });
        ProductResult skyResult = makeResult(dem, "timelapse sky", meta);
        skyResult.bands.push_back({"sky_k", "normalised sky irradiance K under a unit uniform sky (0-1)", sky.skyK, {}});
        sink.sky(std::move(skyResult));
    }

    const SunFrameParams sp = sunFrameParams(request.search, request.sunDiameterDeg, plan);
    PreviewParams pp;
    pp.albedo = request.picture.albedo;
    pp.exposure = request.picture.exposure;
    std::optional<SequenceFitter> fitter;
    if (request.fitDegree > 0) {
        std::vector<double> times;
        for (UtcInstant when : instants) times.push_back(unixSeconds(when));
        fitter.emplace(times, request.fitDegree, t.width(), t.height());
    }
    const std::string method =
        request.stackDirections > 0 ? "sweep, interpolated:" + std::to_string(request.stackDirections) : "sweep";
    for (std::size_t i = 0; i < n; ++i) {
        const UtcInstant when = instants[i];
        const SunField field = sunFieldFor(source, when, Atmosphere{}, plan);
        SunFrame frame;
        TimelapseFrame out;
        if (request.stackDirections > 0) {
            frame.light = sunLightFromStack(t, normals, sky.stack, field, request.sunDiameterDeg, request.search.threads);
            frame.maxDistanceM = sky.stack.maxDistanceM;
            counter.advance(t.heightsM.size());
            out.sunUp = field.elevationRange().second > -request.sunDiameterDeg / 2;
        } else {
            frame = computeSunFrame(t, normals, field, sp, &counter);
            out.sunUp = frame.sweepRegions > 0;
        }
        counter.throwIfCancelled();
        result.sunUpFrames += out.sunUp ? 1 : 0;
        out.index = i;
        out.time = when;
        out.localTime = formatInstant(when, request.frames.zone);
        out.centreAzimuthDeg = field.centreAzimuthDeg;
        out.centreElevationDeg = field.centreElevationDeg;
        if (request.previews) {
            out.preview = renderPreview(normals, frame.light.visibility, sky.skyK, albedo, field.centreAzimuthDeg,
                                        field.centreElevationDeg, pp, request.search.threads);
            if (request.picture.pixels == PixelGeometry::Ground) out.preview = toGroundPixels(out.preview, t);
            out.preview.text = {{"Creation Time", out.localTime},
                                {"Comment", "demlight time-lapse frame " + std::to_string(i) + ", " + out.localTime +
                                                " (UTC " + formatInstant(when, std::string()) + "), sun at the DEM centre: azimuth " +
                                                formatNumber(field.centreAzimuthDeg) + " deg, elevation " +
                                                formatNumber(field.centreElevationDeg) + " deg"}};
        }
        if (fitter) fitter->addFrame(i, frame.light.irradiance);
        if (request.lightmaps) {
            // The horizons of this frame resolve what its own search distance reaches.
            ScenePlan framePlan = plan;
            framePlan.expectedError.aboveElevationDeg =
                std::max(plan.expectedError.aboveElevationDeg, resolvedElevationDeg(t, frame.maxDistanceM));
            std::map<std::string, std::string> meta = planMetadata(framePlan);
            meta.merge(searchMetadata(t, frame.maxDistanceM, sp.refraction));
            meta.insert({
                {"DEMLIGHT_FRAME", std::to_string(i)},
                {"DEMLIGHT_TIME_UTC", formatInstant(when, std::string())},
                {"DEMLIGHT_TIME_LOCAL", out.localTime},
                {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
                {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
                {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(request.sunDiameterDeg)},
                {"DEMLIGHT_METHOD", method},
                {"DEMLIGHT_SUN_SWEEP_REGIONS", std::to_string(frame.sweepRegions)},
                {"DEMLIGHT_SUN_SWEEP_STRATEGY",
                 request.stackDirections > 0 ? "interpolated stack" : sunSweepStrategyName(frame.strategy)},
                {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(skyDirections)},
                {"DEMLIGHT_SKY_MAX_DISTANCE_M", metadataDistanceM(t, sky.params.maxDistanceM)},
            });
            out.lightmap = makeResult(dem, "timelapse frame", meta);
            // The same band order as the sun product: visibility, then irradiance.
            out.lightmap.bands = {
                {"sun_visibility", "fraction of sun disk (0-1)", std::move(frame.light.visibility), {}},
                {"sun_irradiance", "normalised irradiance (1 = unit-radiance zenith sun on flat ground)",
                 std::move(frame.light.irradiance), {}}};
        }
        if (sink.frame) sink.frame(std::move(out));
    }
    if (fitter) result.fit = fitResult(dem, plan, *fitter, instants, result);
    return result;
}

}  // namespace demlight
