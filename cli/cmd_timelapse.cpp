// demlight timelapse DEM -o DIR (--start T --end T --step DURATION | --date D [--tz ZONE]):
// a frame per instant. Per frame the sun is placed per region and swept exactly along its own
// azimuth (lighting/sun_frame.h); the sky light K is computed once. Writes
//   DIR/frame_NNN.tif  lightmaps: sun_irradiance, sun_visibility (Float32, linear)
//   DIR/sky_k.tif      the sky light K every frame shares (written once)
//   DIR/frame_NNN.png  previews with the render rig (lighting/preview.h)
//   DIR/timelapse.gif  the previews as an animated GIF (longer side at most --gif-size px)
// The scene plan (--quality, lighting/quality.h) sets the sun-position lattice, the sun's search
// distance (full: the DEM diagonal) and the sky's directions, distance, curvature and
// scan-direction tolerance; frames record it in their metadata.
#include "cli/common.h"
#include "cli/image_out.h"
#include "cli/progress_bar.h"
#include "geo/solar_position.h"
#include "geo/sun_field.h"
#include "geo/time.h"
#include "lighting/preview.h"
#include "lighting/sequence_fit.h"
#include "lighting/sky.h"
#include "lighting/sun_frame.h"
#include "lighting/sunhours.h"
#include "src/error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

namespace demlight::cli {
namespace {

namespace fs = std::filesystem;

struct TimelapseOptions {
    std::string demPath;
    std::string outDir;
    SearchOptions search;
    std::string start, end, date, tz;
    std::string step = "15m";
    std::string formats = "tif,png,gif";
    std::string horizonMode = "exact";
    int fps = 8;
    std::size_t gifSize = 800;
    std::optional<std::size_t> skyDirections;  ///< default: the scene plan's
    double exposure = 1.0;
    double albedo = PreviewParams{}.albedo;
    std::string colorRaster;
    double sunDiameterDeg = kSunDiameterDeg;
    int fitDegree = 0;  ///< > 0: also store the sun_irradiance sequence as a polynomial fit
    std::size_t maxFrames = 10000;  ///< refuse longer sequences (a typo in --step would write millions)
};

/// Seconds since the Unix epoch, the clock the sequence fit's times use.
double unixSeconds(UtcInstant t) {
    return std::chrono::duration<double>(t.time_since_epoch()).count();
}

/// "15m", "1h", "90s", "1h30m", or a plain number of minutes. Throws Error naming --step.
std::chrono::milliseconds parseStep(const std::string& text) {
    using namespace std::chrono;
    auto bad = [&] {
        return Error("--step '" + text + "': expected a duration like 15m, 1h, 90s or 1h30m");
    };
    if (text.empty()) throw bad();
    double totalMs = 0;
    std::size_t i = 0;
    while (i < text.size()) {
        std::size_t used = 0;
        double v;
        try {
            v = std::stod(text.substr(i), &used);
        } catch (const std::exception&) {
            throw bad();
        }
        i += used;
        char unit = i < text.size() ? text[i] : 'm';
        if (i < text.size()) ++i;
        const double scale = unit == 'h' ? 3.6e6 : unit == 'm' ? 6e4 : unit == 's' ? 1e3 : -1;
        if (scale < 0 || !(v >= 0)) throw bad();
        totalMs += v * scale;
    }
    if (!(totalMs >= 1000)) throw Error("--step '" + text + "': must be at least 1 s");
    return milliseconds(static_cast<long long>(std::llround(totalMs)));
}

/// "exact" -> 0; "interpolated" -> 64; "interpolated:N" -> N (4..720). Throws naming the option.
std::size_t parseHorizonMode(const std::string& text) {
    if (text == "exact") return 0;
    if (text == "interpolated") return 64;
    const std::string prefix = "interpolated:";
    if (text.rfind(prefix, 0) == 0) {
        std::size_t used = 0;
        long n = -1;
        try {
            n = std::stol(text.substr(prefix.size()), &used);
        } catch (const std::exception&) {
        }
        if (used == text.size() - prefix.size() && n >= 4 && n <= 720) return static_cast<std::size_t>(n);
    }
    throw Error("--horizon-mode '" + text + "': expected exact, interpolated or interpolated:N (N in 4..720)");
}

std::set<std::string> parseFormats(const std::string& text) {
    std::set<std::string> out;
    std::stringstream ss(text);
    std::string f;
    while (std::getline(ss, f, ',')) {
        if (f != "tif" && f != "png" && f != "gif" && f != "mp4")
            throw Error("--formats: unknown format '" + f + "'; expected a list of tif, png, gif, mp4");
        out.insert(f);
    }
    if (out.empty()) throw Error("--formats: give at least one of tif, png, gif, mp4");
    if (out.count("mp4") && std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
        throw Error("--formats mp4 needs the ffmpeg program on PATH (Debian: apt-get install ffmpeg)");
    return out;
}

/// Encodes DIR/frame_*.png into DIR/timelapse.mp4 with ffmpeg (H.264, yuv420p, even size).
void encodeMp4(const std::string& dir, std::size_t frameCount, int fps) {
    const int digits = std::max(3, static_cast<int>(std::to_string(frameCount - 1).size()));
    const fs::path mp4 = fs::path(dir) / "timelapse.mp4";
    const std::string cmd = "ffmpeg -loglevel error -y -framerate " + std::to_string(fps) + " -i '" +
                            (fs::path(dir) / ("frame_%0" + std::to_string(digits) + "d.png")).string() +
                            "' -c:v libx264 -pix_fmt yuv420p -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' '" +
                            mp4.string() + "'";
    if (std::system(cmd.c_str()) != 0) {
        std::error_code ec;
        fs::remove(mp4, ec);
        throw Error("ffmpeg could not encode " + mp4.string());
    }
}

std::string frameName(std::size_t i, std::size_t count, const std::string& ext) {
    const int digits = std::max(3, static_cast<int>(std::to_string(count - 1).size()));
    char buf[32];
    std::snprintf(buf, sizeof buf, "frame_%0*zu.", digits, i);
    return buf + ext;
}

struct Frames {
    std::vector<UtcInstant> instants;
    TimeZoneSpec zone;
    std::string description;  // how the sequence was chosen
};

Frames chooseFrames(const TimelapseOptions& o, const Dem& dem) {
    const auto step = parseStep(o.step);
    Frames f;
    UtcInstant t0, t1;
    if (!o.date.empty()) {
        if (!o.start.empty() || !o.end.empty())
            throw Error("timelapse: give either --date or --start/--end, not both");
        f.zone = TimeZoneSpec::fromName(o.tz);
        const LocalDay day = localDay(parseDate(o.date), f.zone);
        // Sunrise to sunset at the DEM centre (SPA A.2); the whole day on polar day.
        const auto [lat, lon] = cellLatLon(dem, dem.terrain.width() / 2.0, dem.terrain.height() / 2.0);
        SolarSite site;
        site.latitudeDeg = lat;
        site.longitudeDeg = lon;
        const SunEvents ev = sunEvents(site, day.startUtc);
        if (ev.kind == DayKind::PolarNight)
            throw Error("--date " + o.date + ": the sun does not rise at the DEM centre (polar night); use --start/--end");
        // Whole seconds: frame times read cleanly and the sun is up by then.
        t0 = std::chrono::ceil<std::chrono::seconds>(ev.sunrise.value_or(day.startUtc));
        t1 = std::chrono::floor<std::chrono::seconds>(ev.sunset.value_or(day.endUtc));
        f.description = ev.kind == DayKind::PolarDay ? "local day (polar day)" : "sunrise to sunset";
        if (ev.sunrise && ev.sunset && *ev.sunset < *ev.sunrise) {
            // --tz is far from the DEM's own zone (e.g. UTC for a DEM at 122 W): the day's sunset
            // falls after the zone's midnight, and the one in this day is the previous evening's.
            // Film the daylight that starts at this sunrise, to its sunset in the next window.
            const SunEvents next = sunEvents(site, day.startUtc + std::chrono::hours(24));
            if (next.sunset && *next.sunset > *ev.sunrise) {
                t1 = std::chrono::floor<std::chrono::seconds>(*next.sunset);
            } else {
                t1 = std::chrono::floor<std::chrono::seconds>(day.endUtc);
            }
            f.description = "sunrise to sunset (the sun sets after midnight in " + f.zone.describe() +
                            "; --tz for the DEM's own zone gives its local day)";
        }
    } else {
        if (o.start.empty() || o.end.empty())
            throw Error("timelapse: give --start T and --end T (with --step), or --date D");
        const ZonedInstant a = parseZonedInstant(o.start, o.tz);
        const ZonedInstant b = parseZonedInstant(o.end, o.tz);
        if (b.utc < a.utc) throw Error("timelapse: --end is before --start");
        f.zone = a.zone;
        t0 = a.utc;
        t1 = b.utc;
        f.description = "start to end";
    }
    if (t1 < t0) throw Error("timelapse: the sequence ends before it starts");
    const auto count = static_cast<std::size_t>((t1 - t0) / step) + 1;
    if (count > o.maxFrames)
        throw Error("timelapse: " + std::to_string(count) + " frames at --step " + o.step + ", more than --max-frames " +
                    std::to_string(o.maxFrames) + "; use a longer --step or raise --max-frames");
    for (UtcInstant t = t0; t <= t1; t += step) f.instants.push_back(t);
    return f;
}

/// Writes DIR/sequence_fit.tif: the Legendre coefficients of sun_irradiance over the frame span
/// and the per-cell RMS residual; `demlight sequence` reconstructs any instant from it.
void writeSequenceFit(const SequenceFitter& fitter, const std::vector<UtcInstant>& instants,
                      const Dem& dem, const TimelapseOptions& o, const ScenePlan& plan, const CliContext& ctx) {
    const SequenceFit fit = fitter.finish();
    std::vector<OutputBand> bands;
    for (int j = 0; j <= fit.degree; ++j)
        bands.push_back({&fit.coefficients[static_cast<std::size_t>(j)], nullptr,
                         "sun_irradiance_legendre_" + std::to_string(j), "normalised irradiance"});
    bands.push_back({&fit.rmsError, nullptr, "rms_error", "normalised irradiance"});
    double sum = 0, worst = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < fit.rmsError.size(); ++i) {
        const float e = fit.rmsError.data()[i];
        if (std::isnan(e) || std::isnan(dem.terrain.heightsM.data()[i])) continue;
        sum += e, worst = std::max<double>(worst, e), ++n;
    }
    const double meanRms = n ? sum / static_cast<double>(n) : 0.0;
    OutputOptions out;
    out.path = (std::filesystem::path(o.outDir) / "sequence_fit.tif").string();
    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_PRODUCT", "sequence fit"},
        {"DEMLIGHT_FIT_DEGREE", std::to_string(fit.degree)},
        {"DEMLIGHT_FIT_BASIS", "Legendre P_j(x), x = 2 (t - t0) / (t1 - t0) - 1"},
        {"DEMLIGHT_FIT_T0_UTC", formatInstant(instants.front(), std::string())},
        {"DEMLIGHT_FIT_T1_UTC", formatInstant(instants.back(), std::string())},
        {"DEMLIGHT_FIT_FRAMES", std::to_string(instants.size())},
        {"DEMLIGHT_FIT_MEAN_RMS", formatNumber(meanRms)},
    });
    writeRaster(out.path, bands, dem.band.ref, makeWriteOptions(out, ctx, dem, meta), o.demPath);
    note(ctx, "wrote " + out.path + ": sun_irradiance as degree-" + std::to_string(fit.degree) +
                  " polynomials, " + std::to_string(fit.degree + 1) + " bands for " +
                  std::to_string(instants.size()) + " frames (size ratio " +
                  formatNumber(static_cast<double>(fit.degree + 1) / static_cast<double>(instants.size())) +
                  "); RMS error vs the exact frames: mean " + formatNumber(meanRms) + ", worst cell " +
                  formatNumber(worst));
}

void runTimelapse(const TimelapseOptions& o, const CliContext& ctx) {
    const std::set<std::string> formats = parseFormats(o.formats);
    const std::size_t stackDirections = parseHorizonMode(o.horizonMode);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;
    const Frames frames = chooseFrames(o, dem);
    std::error_code ec;
    fs::create_directories(o.outDir, ec);
    if (!fs::is_directory(o.outDir))
        throw Error("-o " + o.outDir + ": cannot create the output folder");
    checkOutputPath((fs::path(o.outDir) / "frame_000.tif").string(), o.demPath);
    std::vector<Grid<float>> albedo;
    if (!o.colorRaster.empty()) albedo = loadAlbedoRaster(o.colorRaster, dem, "--color-raster");

    using clock = std::chrono::steady_clock;
    const auto seconds = [](clock::duration d) { return std::chrono::duration<double>(d).count(); };
    const auto tStart = clock::now();
    const ScenePlan plan = planFor(o.search, t, kDefaultLowestElevationDeg, ctx);
    const std::size_t skyDirections =
        stackDirections > 0 ? stackDirections : o.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));
    // The interpolated stack also gives every frame's sun horizon: the plan's own direction
    // tolerance, not the integrals' (planIntegralParams).
    HorizonParams skyParams = stackDirections > 0 ? planHorizonParams(plan, o.search.refraction, o.search.threads)
                                                  : integralParams(o.search, plan, t, skyDirections);
    const std::size_t n = frames.instants.size();
    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), "timelapse", t.heightsM.size() * (skyDirections + n));

    // Sky once; with interpolated horizons, from the same precomputed directions.
    const Normals normals = computeNormals(t, o.search.threads);
    HorizonStack stack;
    Grid<float> sky;
    if (stackDirections > 0) {
        // One stack serves every sun: out to the lowest sun's shadows (auto) or the plan's
        // distance (full).
        if (!o.search.maxDistanceM)
            skyParams.maxDistanceM = plan.quality == Quality::Full ? plan.maxDistanceM
                                                                   : sunSearchDistanceM(t, 0.0, o.sunDiameterDeg);
        // The stack also gives every frame's sun horizon: two scan lines per cell.
        HorizonParams stackParams = skyParams;
        stackParams.nearestLine = false;
        stack = computeHorizonStack(t, stackDirections, stackParams, &counter);
        SkyAccumulator acc(normals.east, normals.north, normals.up, stackDirections, {}, o.search.threads);
        for (std::size_t i = 0; i < stackDirections; ++i) acc.addDirection(i, stack.angleDeg[i]);
        sky = std::move(acc).finish(0.0).skyK;
    } else {
        sky = planSkyLight(t, normals, skyDirections, skyParams, &counter);
    }
    const double skySeconds = seconds(clock::now() - tStart);

    const SunFrameParams sp = sunFrameParams(o.search, o.sunDiameterDeg, plan);
    PreviewParams pp;
    pp.albedo = o.albedo;
    pp.exposure = o.exposure;
    std::unique_ptr<GifWriter> gif;
    if (formats.count("gif"))
        gif = std::make_unique<GifWriter>((fs::path(o.outDir) / "timelapse.gif").string(), o.fps);

    double computeS = 0, writeS = 0;
    if (formats.count("tif")) {
        // The sky term is the same in every frame: written once, next to the frames.
        const auto w0 = clock::now();
        std::map<std::string, std::string> meta = planMetadata(plan);
        meta.insert({
            {"DEMLIGHT_PRODUCT", "timelapse sky"},
            {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(skyDirections)},
            {"DEMLIGHT_SKY_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, skyParams.maxDistanceM)},
            {"DEMLIGHT_REFRACTION", formatNumber(skyParams.refraction)},
        });
        OutputOptions out;
        out.path = (fs::path(o.outDir) / "sky_k.tif").string();
        writeRaster(out.path,
                    {{&sky, nullptr, "sky_k", "normalised sky irradiance K under a unit uniform sky (0-1)"}},
                    dem.band.ref, makeWriteOptions(out, ctx, dem, meta), o.demPath);
        writeS += seconds(clock::now() - w0);
    }
    std::size_t sunUp = 0;
    std::unique_ptr<SequenceFitter> fitter;
    if (o.fitDegree > 0) {
        std::vector<double> times;
        for (UtcInstant when : frames.instants) times.push_back(unixSeconds(when));
        fitter = std::make_unique<SequenceFitter>(times, o.fitDegree, t.width(), t.height());
    }
    // Frame i is written on a background thread while frame i + 1 computes; waiting for the
    // previous write before handing over the next keeps the files (and the GIF) in order, and
    // rethrows a failed write.
    std::future<void> writing;
    const auto waitForWriting = [&] {
        if (writing.valid()) writing.get();
    };
    for (std::size_t i = 0; i < n; ++i) {
        const UtcInstant when = frames.instants[i];
        const auto c0 = clock::now();
        const SunField field = computeSunField(dem, when, SolarSite{}, SpaOptions{}, plan.sunLatticeStepCells);
        SunFrame frame;
        if (stackDirections > 0) {
            frame.light = sunLightFromStack(t, normals, stack, field, o.sunDiameterDeg, o.search.threads);
            frame.maxDistanceM = stack.maxDistanceM;
            counter.advance(t.heightsM.size());
            if (field.elevationRange().second > -o.sunDiameterDeg / 2) ++sunUp;
        } else {
            frame = computeSunFrame(t, normals, field, sp, &counter);
            if (frame.sweepRegions > 0) ++sunUp;
        }
        Image8 preview;
        if (formats.count("png") || formats.count("mp4") || gif)
            preview = renderPreview(normals, frame.light.visibility, sky, albedo,
                                    field.centreAzimuthDeg, field.centreElevationDeg, pp,
                                    o.search.threads);
        if (fitter) fitter->addFrame(i, frame.light.irradiance);
        std::map<std::string, std::string> meta;
        if (formats.count("tif")) {
            // The horizons of this frame resolve what its own search distance reaches.
            ScenePlan framePlan = plan;
            framePlan.expectedError.aboveElevationDeg =
                std::max(plan.expectedError.aboveElevationDeg, resolvedElevationDeg(t, frame.maxDistanceM));
            meta = planMetadata(framePlan);
            meta.insert({
                {"DEMLIGHT_PRODUCT", "timelapse frame"},
                {"DEMLIGHT_FRAME", std::to_string(i)},
                {"DEMLIGHT_TIME_UTC", formatInstant(when, std::string())},
                {"DEMLIGHT_TIME_LOCAL", formatInstant(when, frames.zone)},
                {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
                {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
                {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(o.sunDiameterDeg)},
                {"DEMLIGHT_METHOD", stackDirections > 0 ? "sweep, interpolated:" + std::to_string(stackDirections) : "sweep"},
                {"DEMLIGHT_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, frame.maxDistanceM)},
                {"DEMLIGHT_SUN_SWEEP_REGIONS", std::to_string(frame.sweepRegions)},
                {"DEMLIGHT_SUN_SWEEP_STRATEGY", stackDirections > 0 ? "interpolated stack" : sunSweepStrategyName(frame.strategy)},
                {"DEMLIGHT_REFRACTION", formatNumber(sp.refraction)},
                {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(skyDirections)},
                {"DEMLIGHT_SKY_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, skyParams.maxDistanceM)},
            });
        }
        computeS += seconds(clock::now() - c0);
        waitForWriting();
        counter.throwIfCancelled();
        writing = std::async(std::launch::async, [&, i, light = std::move(frame.light), preview = std::move(preview),
                                                  meta = std::move(meta)] {
            const auto w0 = clock::now();
            if (formats.count("tif")) {
                OutputOptions out;
                out.path = (fs::path(o.outDir) / frameName(i, n, "tif")).string();
                writeRaster(out.path,
                            {{&light.irradiance, nullptr, "sun_irradiance",
                              "normalised irradiance (1 = unit-radiance zenith sun on flat ground)"},
                             {&light.visibility, nullptr, "sun_visibility", "fraction of sun disk (0-1)"}},
                            dem.band.ref, makeWriteOptions(out, ctx, dem, meta), o.demPath);
            }
            if (formats.count("png") || formats.count("mp4"))
                writeImage((fs::path(o.outDir) / frameName(i, n, "png")).string(), preview);
            if (gif) gif->add(downsample(preview, o.gifSize));
            writeS += seconds(clock::now() - w0);
        });
    }
    waitForWriting();
    if (gif) gif->finish();
    bar.finish();
    if (formats.count("mp4")) {
        encodeMp4(o.outDir, n, o.fps);
        if (!formats.count("png"))  // the PNGs were only the video's input
            for (std::size_t i = 0; i < n; ++i) fs::remove(fs::path(o.outDir) / frameName(i, n, "png"));
    }
    if (fitter) writeSequenceFit(*fitter, frames.instants, dem, o, plan, ctx);
    const double total = seconds(clock::now() - tStart);
    note(ctx, "frames: " + std::to_string(n) + " (" + frames.description + ", " +
                  formatInstant(frames.instants.front(), frames.zone) + " .. " +
                  formatInstant(frames.instants.back(), frames.zone) + ", step " + o.step +
                  "), " + std::to_string(sunUp) + " with the sun up");
    note(ctx, "time: sky " + formatNumber(std::round(skySeconds * 1000)) + " ms once (" +
                  std::to_string(skyDirections) + " directions to " +
                  formatDistance(skyParams.maxDistanceM) + ", quality " +
                  std::string(qualityName(plan.quality)) +
                  (stackDirections > 0 ? ", also the interpolated sun horizons" : "") +
                  "); per frame " +
                  formatNumber(std::round(computeS * 1000 / n)) + " ms compute + " +
                  formatNumber(std::round(writeS * 1000 / n)) +
                  " ms writing (in the background, while the next frame computes); total " +
                  formatNumber(std::round(total * 100) / 100) + " s, " +
                  formatNumber(std::round(total * 1000 / n)) + " ms per frame");
    note(ctx, "wrote " + o.outDir + ": " +
                  (formats.count("tif") ? "frame_*.tif (sun_irradiance, sun_visibility), sky_k.tif " : "") +
                  (formats.count("png") ? "frame_*.png " : "") + (gif ? "timelapse.gif " : "") +
                  (formats.count("mp4") ? "timelapse.mp4" : ""));
}

}  // namespace

void registerTimelapse(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<TimelapseOptions>();
    CLI::App* cmd = app.add_subcommand(
        "timelapse", "A lightmap and preview per instant, and an animated GIF");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", o->outDir, "Output folder (created if missing)")->required();
    cmd->add_option("--start", o->start, "First instant (ISO 8601 with offset, or local with --tz)");
    cmd->add_option("--end", o->end, "Last instant (inclusive when on a step)");
    cmd->add_option("--date", o->date, "Local day YYYY-MM-DD: sunrise to sunset at the DEM centre");
    cmd->add_option("--tz", o->tz, "IANA time zone of local times and of --date (default UTC)");
    cmd->add_option("--step", o->step, "Time between frames: 15m, 1h, 90s, 1h30m (plain number = minutes)")
        ->capture_default_str();
    cmd->add_option("--max-frames", o->maxFrames,
                    "Refuse a sequence of more frames than this (guards against a mistyped --step)")
        ->check(finiteRange(1, 1000000))
        ->capture_default_str();
    cmd->add_option("--horizon-mode", o->horizonMode,
                    "exact (a sweep per frame along its sun azimuth) or interpolated[:N] (N "
                    "directions swept once, horizons interpolated in azimuth; N = 64 by default)")
        ->capture_default_str();
    cmd->add_option("--formats", o->formats, "Outputs: comma list of tif, png, gif, mp4 (mp4 needs ffmpeg on PATH)")
        ->capture_default_str();
    cmd->add_option("--fps", o->fps, "GIF frames per second")->check(finiteRange(1, 100))->capture_default_str();
    cmd->add_option("--gif-size", o->gifSize, "Longest GIF side (pixels); frames are box-downsampled")
        ->check(finiteRange(16, 100000))
        ->capture_default_str();
    cmd->add_option("--sky-directions", o->skyDirections,
                    "Horizon directions for the sky term (default: " + std::to_string(kAutoSkyDirections) +
                        " with --quality auto, " + std::to_string(kFullSkyDirections) +
                        " with full; --horizon-mode interpolated:N uses its N)")
        ->check(finiteRange(4, 1024));
    cmd->add_option("--color-raster", o->colorRaster, "RGB raster used as preview albedo")
        ->check(CLI::ExistingFile);
    cmd->add_option("--albedo", o->albedo, "Linear preview albedo without a colour raster")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--exposure", o->exposure, "Preview exposure (multiplies linear light)")
        ->check(finiteRange(0.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("--fit-degree", o->fitDegree,
                    "Also store sun_irradiance as per-cell Legendre polynomials of this degree in "
                    "DIR/sequence_fit.tif (0 = off); read back with demlight sequence")
        ->check(finiteRange(0, 12));
    cmd->add_option("--sun-diameter", o->sunDiameterDeg, "Angular diameter of the sun disk (degrees)")
        ->check(finiteRange(0.0, 20.0))
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runTimelapse(*o, ctx); });
}

}  // namespace demlight::cli
