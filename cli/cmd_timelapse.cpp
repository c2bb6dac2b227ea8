// demlight timelapse DEM -o DIR (--start T --end T --step DURATION | --date D --tz ZONE): a
// frame per instant (products/timelapse.h). Writes
//   DIR/frame_NNN.tif  lightmaps: sun_visibility, sun_irradiance (Float32, linear)
//   DIR/sky_k.tif      the sky light K every frame shares (written once)
//   DIR/frame_NNN.png  previews with the render rig
//   DIR/frames.csv     frame number -> local time, UTC, the sun at the DEM centre
//   DIR/timelapse.gif  the previews as an animated GIF (longer side at most --gif-size px)
// DIR must be missing or empty, or hold an earlier time-lapse and --overwrite be given (its files
// are removed first, so frames of two runs never mix).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/image_out.h"
#include "geo/output_file.h"
#include "products/timelapse.h"
#include "src/error.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <optional>
#include <set>
#include <sstream>

namespace demlight::cli {
namespace {

namespace fs = std::filesystem;

struct TimelapseOptions {
    DemOptions dem;
    std::string outDir;
    SearchOptions search;
    std::string start, end, date, tz;
    std::string step = "15m";
    std::string formats = "tif,png,gif";
    std::string horizonMode = "exact";
    int fps = 8;
    std::size_t gifSize = 800;
    std::optional<std::size_t> skyDirections;
    PictureOptions picture;
    double sunDiameterDeg = kSunDiameterDeg;
    int fitDegree = 0;
    std::size_t maxFrames = 10000;  ///< refuse longer sequences (a typo in --step would write millions)
    bool overwrite = false;         ///< replace the outputs of an earlier time-lapse in the folder
};

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

std::string frameName(std::size_t i, std::size_t count, const std::string& ext) {
    const int digits = std::max(3, static_cast<int>(std::to_string(count - 1).size()));
    char buf[32];
    std::snprintf(buf, sizeof buf, "frame_%0*zu.", digits, i);
    return buf + ext;
}

/// Encodes DIR/frame_*.png into DIR/timelapse.mp4 with ffmpeg (H.264, yuv420p, even size),
/// under a temporary name (so -f mp4) renamed on success.
void encodeMp4(const std::string& dir, std::size_t frameCount, int fps) {
    const int digits = std::max(3, static_cast<int>(std::to_string(frameCount - 1).size()));
    TemporaryFile mp4((fs::path(dir) / "timelapse.mp4").string(), TemporaryNaming::Hidden);
    const std::string cmd = "ffmpeg -loglevel error -y -framerate " + std::to_string(fps) + " -i '" +
                            (fs::path(dir) / ("frame_%0" + std::to_string(digits) + "d.png")).string() +
                            "' -c:v libx264 -pix_fmt yuv420p -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -f mp4 '" +
                            mp4.path() + "'";
    if (std::system(cmd.c_str()) != 0) throw Error("ffmpeg could not encode " + mp4.finalPath());
    mp4.commit();
}

/// Whether `name` is a file a time-lapse writes (frameName and FrameWriter's names).
bool isTimelapseOutput(const std::string& name) {
    static const std::set<std::string> fixed = {"sky_k.tif", "frames.csv", "timelapse.gif", "timelapse.mp4",
                                                "sequence_fit.tif"};
    if (fixed.count(name)) return true;
    // frame_<digits>.tif or .png
    constexpr std::size_t kDigitsAt = 6;
    const std::size_t dot = name.rfind('.');
    if (!name.starts_with("frame_") || dot == std::string::npos || dot <= kDigitsAt) return false;
    const std::string ext = name.substr(dot + 1);
    return (ext == "tif" || ext == "png") && std::all_of(name.begin() + kDigitsAt, name.begin() + static_cast<std::ptrdiff_t>(dot),
                                                         [](unsigned char c) { return std::isdigit(c); });
}

TimelapseInstants chooseFrames(const TimelapseOptions& o, const Dem& dem) {
    const auto step = parseStepOption(o.step, std::chrono::minutes(1));
    try {
        if (!o.date.empty()) {
            if (!o.start.empty() || !o.end.empty()) throw Error("give either --date or --start/--end, not both");
            return instantsOfDay(dem, parseDate(o.date), zoneOfDays(o.tz), step, o.maxFrames);
        }
        if (o.start.empty() || o.end.empty()) throw Error("give --start T and --end T (with --step), or --date D");
        return instantsBetween(parseTimeOptions(o.start, o.tz), parseTimeOptions(o.end, o.tz), step, o.maxFrames);
    } catch (const FieldError&) {
        throw;
    } catch (const Error& e) {
        throw Error(std::string("timelapse: ") + e.what());
    }
}

/// Writes the frames as they come: frame i on a background thread while frame i + 1 computes;
/// waiting for the previous write before handing over the next keeps the files (and the GIF) in
/// order, and rethrows a failed write.
class FrameWriter {
public:
    FrameWriter(const TimelapseOptions& o, const std::set<std::string>& formats, std::size_t frames,
                const CliContext& ctx)
        : o_(o), formats_(formats), n_(frames), ctx_(ctx),
          indexFile_((fs::path(o.outDir) / "frames.csv").string(), TemporaryNaming::Hidden),
          index_(indexFile_.path()) {
        if (formats.count("gif")) gif_ = std::make_unique<GifWriter>((fs::path(o.outDir) / "timelapse.gif").string(), o.fps);
        index_ << "frame,time_local,time_utc,sun_azimuth_deg,sun_elevation_deg\n";
    }
    void sky(ProductResult&& r) { write(r, "sky_k.tif"); }
    void frame(TimelapseFrame&& f) {
        index_ << f.index << "," << f.localTime << "," << formatInstant(f.time, std::string()) << ","
               << formatNumber(f.centreAzimuthDeg) << "," << formatNumber(f.centreElevationDeg) << "\n";
        wait();
        writing_ = std::async(std::launch::async, [this, f = std::move(f)] {
            if (formats_.count("tif")) write(f.lightmap, frameName(f.index, n_, "tif"));
            if (formats_.count("png") || formats_.count("mp4"))
                writeImage((fs::path(o_.outDir) / frameName(f.index, n_, "png")).string(), f.preview);
            if (gif_) gif_->add(downsample(f.preview, o_.gifSize));
        });
    }
    void finish() {
        wait();
        if (gif_) gif_->finish();
        index_.close();
        if (!index_) throw Error(writeFailureMessage("'" + indexFile_.finalPath() + "'", indexFile_.path(), {}));
        indexFile_.commit();
    }
    void write(const ProductResult& r, const std::string& name) {
        OutputOptions out;
        out.path = (fs::path(o_.outDir) / name).string();
        writeResult(r, out, ctx_, o_.dem.path);
    }

private:
    void wait() {
        if (writing_.valid()) writing_.get();
    }
    const TimelapseOptions& o_;
    const std::set<std::string>& formats_;
    std::size_t n_;
    const CliContext& ctx_;
    TemporaryFile indexFile_;  // frames.csv, renamed into place by finish()
    std::ofstream index_;
    std::unique_ptr<GifWriter> gif_;
    std::future<void> writing_;
};

TimelapseRequest timelapseRequest(const TimelapseOptions& o, const std::set<std::string>& formats, const Dem& dem) {
    TimelapseRequest r;
    r.frames = chooseFrames(o, dem);
    r.stackDirections = parseHorizonMode(o.horizonMode, "--horizon-mode");
    r.skyDirections = o.skyDirections;
    r.sunDiameterDeg = o.sunDiameterDeg;
    r.lightmaps = formats.count("tif") > 0;
    r.previews = formats.count("png") || formats.count("mp4") || formats.count("gif");
    r.picture = pictureRequest(o.picture);
    r.fitDegree = o.fitDegree;
    r.search = o.search.request;
    return r;
}

void noteTimelapse(const TimelapseOptions& o, const TimelapseRequest& r, const TimelapseResult& res,
                   const std::set<std::string>& formats, double total, const CliContext& ctx) {
    const auto& f = r.frames;
    note(ctx, "frames: " + std::to_string(res.frames) + " (" + f.description + ", " +
                  formatInstant(f.instants.front(), f.zone) + " .. " + formatInstant(f.instants.back(), f.zone) +
                  ", step " + o.step + "), " + std::to_string(res.sunUpFrames) + " with the sun up");
    note(ctx, "time: sky " + formatSeconds(res.skySeconds) + " once (" + std::to_string(res.skyDirections) +
                  " directions to " + formatDistance(res.skyMaxDistanceM) + ", quality " +
                  std::string(qualityName(res.quality)) +
                  (r.stackDirections > 0 ? ", also the interpolated sun horizons" : "") + "); total " +
                  formatSeconds(total) + ", " + formatSeconds(total / static_cast<double>(res.frames)) +
                  " per frame (writing in the background)");
    note(ctx, "wrote " + o.outDir + ": frames.csv " +
                  (formats.count("tif") ? "frame_*.tif (sun_visibility, sun_irradiance), sky_k.tif " : "") +
                  (formats.count("png") ? "frame_*.png " : "") + (formats.count("gif") ? "timelapse.gif " : "") +
                  (formats.count("mp4") ? "timelapse.mp4" : "") + (res.fit ? "sequence_fit.tif" : ""));
    if (res.fit)
        note(ctx, "sequence_fit.tif: sun_irradiance as degree-" + std::to_string(r.fitDegree) + " polynomials, " +
                      std::to_string(r.fitDegree + 1) + " bands for " + std::to_string(res.frames) +
                      " frames; RMS error vs the exact frames: mean " + formatNumber(res.fitMeanRms) +
                      ", worst cell " + formatNumber(res.fitWorstRms));
}

void runTimelapse(const TimelapseOptions& o, const CliContext& ctx) {
    if (o.outDir.empty()) throw Error("-o: the output folder path is empty");
    checkOutputFolder(o.outDir, o.overwrite);
    const std::set<std::string> formats = parseFormats(o.formats);
    const DemSource dem = openDem(o.dem, ctx);
    const TimelapseRequest request = timelapseRequest(o, formats, dem.geometry());
    std::error_code ec;
    fs::create_directories(o.outDir, ec);
    if (!fs::is_directory(o.outDir)) throw Error("-o " + o.outDir + ": cannot create the output folder");
    checkOutputPath((fs::path(o.outDir) / "frame_000.tif").string(), o.dem.path);
    if (o.overwrite) removeEarlierOutputs(o.outDir, isTimelapseOutput);
    notePlan(o.search, dem.geometry().terrain, ctx);

    const auto start = std::chrono::steady_clock::now();
    FrameWriter writer(o, formats, request.frames.instants.size(), ctx);
    ProgressBar bar(!ctx.quiet);
    const TimelapseSink sink{[&](ProductResult&& r) { writer.sky(std::move(r)); },
                             [&](TimelapseFrame&& f) { writer.frame(std::move(f)); }};
    const TimelapseResult result = timelapseProduct(dem, request, sink, bar.callback());
    writer.finish();
    bar.finish();
    if (formats.count("mp4")) {
        encodeMp4(o.outDir, result.frames, o.fps);
        if (!formats.count("png"))  // the PNGs were only the video's input
            for (std::size_t i = 0; i < result.frames; ++i) fs::remove(fs::path(o.outDir) / frameName(i, result.frames, "png"));
    }
    if (result.fit) writer.write(*result.fit, "sequence_fit.tif");
    noteTimelapse(o, request, result, formats, secondsSince(start), ctx);
}

}  // namespace

void registerTimelapse(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<TimelapseOptions>();
    CLI::App* cmd = app.add_subcommand("timelapse", "A lightmap and preview per instant, and an animated GIF");
    ctx.outputs[cmd->get_name()].kind = "folder";
    addDemArgument(cmd, o->dem);
    cmd->add_option("-o,--output", o->outDir, "Output folder (created if missing; must be empty unless --overwrite)")
        ->required();
    cmd->add_flag("--overwrite", o->overwrite,
                  "Write into a folder that is not empty: the frames, sky_k.tif, frames.csv, timelapse.gif/.mp4 "
                  "and sequence_fit.tif of an earlier run there are removed first (other files are left)");
    cmd->add_option("--start", o->start, "First instant (ISO 8601 with offset, or local with --tz)");
    cmd->add_option("--end", o->end, "Last instant (inclusive when on a step)");
    cmd->add_option("--date", o->date, "Local day YYYY-MM-DD: sunrise to sunset at the DEM centre");
    cmd->add_option("--tz", o->tz, "IANA time zone of local times and of --date (required with --date; UTC for universal time)");
    cmd->add_option("--step", o->step, "Time between frames: 15m, 1h, 90s, 1h30m (a bare number = minutes)")
        ->capture_default_str();
    cmd->add_option("--max-frames", o->maxFrames, "Refuse a sequence of more frames than this (guards against a mistyped --step)")
        ->check(finiteRange(1, 1000000))
        ->capture_default_str();
    cmd->add_option("--horizon-mode", o->horizonMode,
                    "exact (a sweep per frame along its sun azimuth) or interpolated[:N] (N directions swept once, "
                    "horizons interpolated in azimuth; N = 64 by default)")
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
    addPictureOptions(cmd, o->picture);
    cmd->add_option("--fit-degree", o->fitDegree,
                    "Also store sun_irradiance as per-cell Legendre polynomials of this degree in "
                    "DIR/sequence_fit.tif (0 = off); read back with demlight sequence")
        ->check(finiteRange(0, 12));
    addSunDiameterOption(cmd, o->sunDiameterDeg);
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runTimelapse(*o, ctx); });
}

}  // namespace demlight::cli
