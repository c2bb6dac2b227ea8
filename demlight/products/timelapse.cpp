#include "demlight/core/parallel.h"
#include "demlight/products/timelapse.h"

#include "demlight/core/timing.h"

#include "demlight/geo/solar_position.h"
#include "demlight/lighting/canopy.h"
#include "demlight/lighting/sequence_fit.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/sunhours.h"
#include "demlight/lighting/surface.h"
#include "demlight/products/sun.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace demlight {
namespace {

using Clock = std::chrono::steady_clock;

/// IEEE 754 binary32: stored significand bits, and the exponent bias plus those bits (a
/// significand read as an integer).
constexpr int kFloatMantissaBits = 23, kFloatExponentBias = 127 + kFloatMantissaBits;

constexpr std::size_t kMinStackDirections = 4, kMaxStackDirections = 720;


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

/// The sky term's sweeps; with a stack, the stack's, which also give every frame's sun horizon.
HorizonParams skyTermParams(const Terrain& t, const ScenePlan& plan, const TimelapseRequest& r,
                            std::size_t skyDirections) {
    if (r.stackDirections == 0) return integralParams(r.search, plan, t, skyDirections);
    return stackHorizonParams(r.search, plan, t, r.sunDiameterDeg);
}

/// The sky term once; with a stack, the stack too (it gives every frame's sun horizon).
struct SkyTerm {
    Grid<float> skyK;
    HorizonStack stack;
    HorizonParams params;
};

SkyTerm skyTerm(const Terrain& t, const Normals& normals, const ScenePlan& plan, const TimelapseRequest& r,
                std::size_t skyDirections, const CanopyTerrain* canopy, ProgressCounter& counter) {
    SkyTerm out;
    out.params = skyTermParams(t, plan, r, skyDirections);
    if (r.stackDirections == 0) {
        out.skyK = canopy ? canopySkyK(t, *canopy, normals, skyDirections, out.params, r.canopy.transmissivity, &counter)
                          : skyLightK(t, normals, skyDirections, out.params, &counter);
        return out;
    }
    out.stack = computeHorizonStack(t, r.stackDirections, out.params, &counter);
    SkyAccumulator acc(normals.east, normals.north, normals.up, r.stackDirections, {});
    for (std::size_t i = 0; i < r.stackDirections; ++i) acc.addDirection(i, out.stack.angleDeg[i]);
    out.skyK = std::move(acc).finish(0.0).skyK;
    return out;
}

/// Directions of the sky term: the stack's, or the request's or the plan's.
std::size_t timelapseSkyDirections(const TimelapseRequest& r, const ScenePlan& plan) {
    return r.stackDirections > 0 ? r.stackDirections
                                 : r.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));
}

/// Search distance (metres) around a window: the sky term's, and the longest any frame's sun
/// needs on the whole DEM (with a stack, the stack's serves every sun).
double reachM(const DemSource& source, const ScenePlan& plan, const TimelapseRequest& r, std::size_t skyDirections) {
    const Terrain& whole = source.geometry().terrain;
    double reach = skyTermParams(whole, plan, r, skyDirections).maxDistanceM;
    if (r.stackDirections == 0)
        for (UtcInstant when : r.frames.instants)
            reach = std::max(reach, sunFrameDistanceM(r.search, r.sunDiameterDeg, plan, whole,
                                                      sunFieldFor(source, when, Atmosphere{}, plan)));
    return reach;
}

/// The fit of a window's cells onto `out` (on the window's georeference, no bands yet);
/// `heightsM` are the window's (nodata cells have no residual to count).
ProductResult fitResult(ProductResult out, const ScenePlan& plan, const SequenceFitter& fitter,
                        const Grid<float>& heightsM, const std::vector<UtcInstant>& instants, TimelapseResult& stats) {
    SequenceFit fit = fitter.finish();
    for (std::size_t i = 0; i < fit.rmsError.size(); ++i) {
        const float e = fit.rmsError.data()[i];
        if (std::isnan(e) || std::isnan(heightsM.data()[i])) continue;
        stats.fitStats.add(e);
    }
    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_FIT_DEGREE", std::to_string(fit.degree)},
        {"DEMLIGHT_FIT_BASIS", "Legendre P_j(x), x = 2 (t - t0) / (t1 - t0) - 1"},
        {"DEMLIGHT_FIT_T0_UTC", formatInstant(instants.front(), std::string())},
        {"DEMLIGHT_FIT_T1_UTC", formatInstant(instants.back(), std::string())},
        {"DEMLIGHT_FIT_FRAMES", std::to_string(instants.size())},
    });
    meta.merge(stats.fitStats.metadata());
    for (const auto& [key, value] : meta) out.metadata[key] = value;
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

namespace {

/// The frames of `window`, computed on `dem` (the window grown by its halo, `read`; the whole
/// DEM when the window is).
TimelapseResult computeTimelapse(const DemSource& source, const Dem& dem, const CellWindow& read,
                                 const CellWindow& window, const ScenePlan& plan, std::size_t skyDirections,
                                 const TimelapseRequest& request, const Grid<float>& wholeCanopy,
                                 const TimelapseSink& sink, const ProgressFn& progress) {
    const auto& instants = request.frames.instants;
    const Terrain& t = dem.terrain;
    std::optional<CanopyTerrain> canopy;
    if (request.canopy.any()) canopy = canopyTerrain(t, wholeCanopy);
    // With a canopy the lit surface is the ground and buildings under it (demlight/lighting/canopy.h).
    const Terrain& lit = canopy ? canopy->ground : t;
    const bool whole = source.isWhole(window);
    // Onto the window's cells and georeference (a no-op for the whole DEM).
    const CellWindow local{window.col0 - read.col0, window.row0 - read.row0, window.col1 - read.col0,
                           window.row1 - read.row0};
    const auto toWindow = [&](ProductResult& r) {
        if (!whole) cropResult(r, read, window);
    };
    const std::vector<Grid<float>> albedo =
        request.previews ? loadPictureAlbedo(source, request.picture) : std::vector<Grid<float>>{};

    // One camera for every frame: the surface, its pyramid and the ground's albedo set up once
    // (and a camera under the terrain refused before any work).
    std::optional<ViewStage> stage;
    if (request.previews && request.view) stage.emplace(source, *request.view);

    const auto tStart = Clock::now();
    const std::size_t n = instants.size();
    ProgressCounter counter(progress, "timelapse", t.heightsM.size() * (skyDirections + n) * (canopy ? 2 : 1));
    const Normals normals = computeNormals(lit);
    const SkyTerm sky = skyTerm(t, normals, plan, request, skyDirections, canopy ? &*canopy : nullptr, counter);

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
        meta.merge(canopyMetadata(request.canopy));
        ProductResult skyResult = makeResult(dem, "timelapse sky", meta);
        skyResult.bands.push_back({"sky_k", "normalised sky irradiance K under a unit uniform sky (0-1)", sky.skyK, {}});
        toWindow(skyResult);
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
        fitter.emplace(times, request.fitDegree, window.col1 - window.col0, window.row1 - window.row0);
    }
    const std::string method =
        request.stackDirections > 0 ? "sweep, interpolated:" + std::to_string(request.stackDirections) : "sweep";
    SweepBuffers buffers;  // the frames' sweeps' scratch and valid-cell bitmap
    // The last night picture drawn (below), while the frames stay dark.
    struct NightPicture {
        DarkCells visibility;
        double skyScale;
        Image8 picture;
    };
    std::optional<NightPicture> night;
    for (std::size_t i = 0; i < n; ++i) {
        const UtcInstant when = instants[i];
        // The whole DEM's sun, read by this window (SunField::onTile): the same bits on its cells.
        const SunField wholeField = sunFieldFor(source, when, Atmosphere{}, plan);
        const SunField field = t.frame ? sunFieldOnTile(wholeField, dem, source) : wholeField;
        SunFrame frame;
        TimelapseFrame out;
        if (request.stackDirections > 0) {
            frame.light = sunLightFromStack(t, normals, sky.stack, field, request.sunDiameterDeg);
            frame.maxDistanceM = sky.stack.maxDistanceM;
            counter.advance(t.heightsM.size());
            out.sunUp = field.elevationRange().second > -request.sunDiameterDeg / 2;
        } else {
            frame = computeSunFrame(t, normals, field, sp, &counter, &buffers);
            out.sunUp = frame.sweepRegions > 0;
            if (canopy)
                blendCanopySun(frame, computeSunFrame(lit, normals, field, sp, &counter, &buffers), canopy->underCrown,
                               request.canopy.transmissivity);
        }
        counter.throwIfCancelled();
        result.sunUp.push_back(out.sunUp);
        out.index = i;
        out.time = when;
        out.localTime = formatInstant(when, request.frames.zone);
        out.centreAzimuthDeg = field.centreAzimuthDeg;
        out.centreElevationDeg = field.centreElevationDeg;
        if (stage) {
            const std::array<Grid<float>, 3> light = stage->light(frame.light.irradiance, sky.skyK);
            out.preview = stage->render({&light[0], &light[1], &light[2]}, field.centreAzimuthDeg,
                                        field.centreElevationDeg).image;
        } else if (request.previews) {
            // A night picture: with every valid cell's visibility +0 the key light is 0 (each
            // penumbra exponent is positive), and below kBounceLowDeg so is the bounce, whatever
            // the sun's direction; what is left depends on the sky scale alone. A frame with the
            // previous night picture's visibility cells and sky scale gets that picture.
            const double elevation = field.centreElevationDeg;
            const bool noKeyNoBounce = bounceScale(elevation) == 0.0 && pp.penumbraExponent.r > 0.0 &&
                                       pp.penumbraExponent.g > 0.0 && pp.penumbraExponent.b > 0.0;
            std::optional<DarkCells> dark;
            if (noKeyNoBounce) dark = darkCells(frame.light.visibility.data(), frame.light.visibility.size());
            const double skyScale = twilightSkyScale(elevation);
            if (dark && night && night->visibility == *dark && night->skyScale == skyScale) {
                out.preview = night->picture;
                out.previewRepeats = true;
            } else {
                out.preview = renderPreview(normals, frame.light.visibility, sky.skyK, albedo, field.centreAzimuthDeg,
                                            elevation, pp);
                if (request.picture.pixels == PixelGeometry::Ground) out.preview = toGroundPixels(out.preview, t);
                if (dark) {
                    night = NightPicture{std::move(*dark), skyScale, out.preview};
                } else {
                    night.reset();
                }
            }
        }
        if (request.previews) {
            out.preview.text = {{"Creation Time", out.localTime},
                                {"Comment", "demlight time-lapse frame " + std::to_string(i) + ", " + out.localTime +
                                                " (UTC " + formatInstant(when, std::string()) + "), sun at the DEM centre: azimuth " +
                                                formatNumber(field.centreAzimuthDeg) + " deg, elevation " +
                                                formatNumber(field.centreElevationDeg) + " deg"}};
        }
        if (fitter) fitter->addFrame(i, whole ? frame.light.irradiance : cropGrid(frame.light.irradiance, local));
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
            meta.merge(canopyMetadata(request.canopy));
            out.lightmap = makeResult(dem, "timelapse frame", meta);
            // The same band order as the sun product: visibility, then irradiance.
            out.lightmap.bands = movedBands(
                ProductBand{"sun_visibility", "fraction of sun disk (0-1)", std::move(frame.light.visibility), {}},
                ProductBand{"sun_irradiance", "normalised irradiance (1 = unit-radiance zenith sun on flat ground)",
                 std::move(frame.light.irradiance), {}});
            toWindow(out.lightmap);
        }
        if (sink.frame) sink.frame(std::move(out));
    }
    if (fitter) {
        ProductResult fit = makeResult(dem, "sequence fit");
        toWindow(fit);  // no bands yet: the window's georeference
        result.fit = fitResult(fit, plan, *fitter, whole ? t.heightsM : cropGrid(t.heightsM, local), instants, result);
    }
    return result;
}

}  // namespace

std::size_t timelapseHaloCells(const DemSource& source, const TimelapseRequest& request) {
    const ScenePlan plan = planFor(request.search, source.geometry().terrain);
    return haloCellsFor(source.geometry().terrain,
                        reachM(source, plan, request, timelapseSkyDirections(request, plan)));
}

TimelapseResult timelapseProduct(const DemSource& source, const CellWindow& window, const TimelapseRequest& request,
                                 const TimelapseSink& sink, const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        const auto& instants = request.frames.instants;
        if (instants.empty()) throw Error("frames: the sequence has no instants");
        if (request.stackDirections != 0 &&
            (request.stackDirections < kMinStackDirections || request.stackDirections > kMaxStackDirections))
            throw FieldError("stackDirections", " " + std::to_string(request.stackDirections) + ": must be 0 or in 4..720");
        validatePicture(request.picture);
        validateSun(request.sunDiameterDeg, Atmosphere{});
        validateCanopy(request.canopy);
        if (request.canopy.any() && request.stackDirections != 0)
            throw FieldError("canopy", ": needs exact horizons (a sweep per frame on each surface), not interpolated ones");
        source.checkWindow(window);
        if (request.previews && !source.isWhole(window))
            throw FieldError("previews", ": pictures are of the whole DEM; a window or tile of it gets lightmaps only");
        const ScenePlan plan = planFor(request.search, source.geometry().terrain);
        const std::size_t skyDirections = timelapseSkyDirections(request, plan);
        const Grid<float> canopy = loadCanopy(request.canopy, source);
        if (source.isWhole(window)) {
            const std::shared_ptr<const Dem> dem = source.readWhole();
            return computeTimelapse(source, *dem, window, window, plan, skyDirections, request, canopy, sink, progress);
        }
        const CellWindow read = source.withHalo(window, timelapseHaloCells(source, request));
        return computeTimelapse(source, source.read(read), read, window, plan, skyDirections, request, canopy, sink,
                                progress);
    });
}

std::size_t timelapseGridsPerCell(const TimelapseRequest& request) {
    // sky K, a frame's visibility and irradiance, the stack's angles, and per fitted
    // coefficient a double moment (two grids) plus the finished float coefficient, the sum of
    // squares (a double) and the residual.
    const std::size_t fitGrids =
        request.fitDegree > 0 ? 3 * (static_cast<std::size_t>(request.fitDegree) + 1) + 3 : 0;
    return 1 + 2 + request.stackDirections + fitGrids;
}

void FitStats::add(float rms) {
    // IEEE 754 binary32: a biased exponent e and a 24-bit significand m (hidden bit set unless
    // subnormal) stand for m x 2^(max(e, 1) - 150).
    std::uint32_t bits = 0;
    std::memcpy(&bits, &rms, sizeof bits);
    const std::uint32_t exponent = (bits >> kFloatMantissaBits) & 0xffu;
    const std::uint32_t hidden = exponent > 0 ? 1u << kFloatMantissaBits : 0u;
    rmsMantissas[exponent] += (bits & ((1u << kFloatMantissaBits) - 1)) | hidden;
    ++cells;
    worstRms = std::max<double>(worstRms, rms);
}

void FitStats::merge(const FitStats& other) {
    cells += other.cells;
    worstRms = std::max(worstRms, other.worstRms);
    for (std::size_t e = 0; e < rmsMantissas.size(); ++e) rmsMantissas[e] += other.rmsMantissas[e];
}

double FitStats::meanRms() const {
    if (cells == 0) return 0.0;
    double sum = 0;
    for (std::size_t e = 0; e < rmsMantissas.size(); ++e)
        sum += std::ldexp(static_cast<double>(rmsMantissas[e]), std::max(static_cast<int>(e), 1) - kFloatExponentBias);
    return sum / static_cast<double>(cells);
}

std::map<std::string, std::string> FitStats::metadata() const {
    return {{"DEMLIGHT_FIT_MEAN_RMS", formatNumber(meanRms())}};
}

}  // namespace demlight
