// demlight timelapse DEM -o DIR (--start T --end T --step DURATION | --date D --tz ZONE): a
// frame per instant (demlight/products/timelapse.h). Writes
//   DIR/frame_NNN.tif  lightmaps: sun_visibility, sun_irradiance (Float32, linear)
//   DIR/sky_k.tif      the sky light K every frame shares (written once)
//   DIR/frame_NNN.png  previews with the render rig
//   DIR/frames.csv     frame number -> local time, UTC, the sun at the DEM centre
//   DIR/timelapse.gif  the previews as an animated GIF (longer side at most --gif-size px)
// DIR must be missing or empty, or hold an earlier time-lapse and --overwrite be given (its files
// are removed first, so frames of two runs never mix). A run in tiles (--tile-size, --memory-limit)
// or on a --srcwin window writes the GeoTIFFs and frames.csv only: pictures are of whole frames.
#include "cli/common.h"
#include "cli/declared.h"
#include "cli/progress_bar.h"
#include "cli/view_options.h"
#include "demlight/geo/image_out.h"
#include "demlight/geo/output_file.h"
#include "demlight/products/timelapse.h"
#include "demlight/core/error.h"
#include "demlight/core/process.h"

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
#include <sys/resource.h>

namespace demlight::cli {
namespace {

namespace fs = std::filesystem;

struct TimelapseOptions {
    ParameterSet set{"timelapse", "A lightmap and preview per instant, and an animated GIF"};
    DemOptions dem;
    std::string outDir;
    TilingOptions tiling;
    SearchOptions search;
    std::string start, end, date, tz;
    std::string step = "15m";
    std::string formats = "tif,png,gif";
    std::string horizonMode = "exact";
    int fps = 8;
    std::size_t gifSize = 800;
    std::optional<std::size_t> skyDirections;
    PictureOptions picture;
    bool albedoGiven = false;  ///< --albedo on the command line (--view: else the landscape)
    bool view = false;         ///< previews in an oblique view (--view and the camera options)
    ViewCameraOptions camera;
    double sunDiameterDeg = kSunDiameterDeg;
    int fitDegree = 0;
    CanopyRequest canopy;
    std::size_t maxFrames = 10000;  ///< refuse longer sequences (a typo in --step would write millions)
    bool overwrite = false;         ///< replace the outputs of an earlier time-lapse in the folder
    /// GDAL creation options of every GeoTIFF it writes (--co), over the GTiff defaults.
    std::vector<std::string> creationOptions;
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
    if (out.count("mp4") && !findProgram("ffmpeg"))
        throw Error("--formats mp4 needs the ffmpeg program on PATH (Debian: apt-get install ffmpeg)");
    return out;
}

/// The outputs besides the frames.
const std::string kSkyFile = "sky_k.tif", kIndexFile = "frames.csv", kFitFile = "sequence_fit.tif";

/// Open files a run needs besides its outputs (the DEM, GDAL's, standard streams, probes).
constexpr rlim_t kSpareFiles = 64;

std::string frameName(std::size_t i, std::size_t count, const std::string& ext) {
    // Zero-padded to the digits of the last frame, at least three: names sort in frame order.
    const std::size_t digits = std::max<std::size_t>(3, std::to_string(count - 1).size());
    const std::string number = std::to_string(i);
    return "frame_" + std::string(digits - std::min(digits, number.size()), '0') + number + "." + ext;
}

/// Encodes DIR/frame_*.png into DIR/timelapse.mp4 with ffmpeg (H.264, yuv420p, even size),
/// under a temporary name (so -f mp4) renamed on success. ffmpeg starts from an argument vector:
/// no shell reads the folder's name.
void encodeMp4(const std::string& dir, std::size_t frameCount, int fps) {
    const int digits = std::max(3, static_cast<int>(std::to_string(frameCount - 1).size()));
    TemporaryFile mp4((fs::path(dir) / "timelapse.mp4").string());
    // ffmpeg's image-sequence input reads '%' in its path as a pattern: the folder's are doubled.
    std::string pattern;
    for (char c : fs::absolute(fs::path(dir)).string()) pattern += c == '%' ? std::string("%%") : std::string(1, c);
    pattern += "/frame_%0" + std::to_string(digits) + "d.png";
    const fs::path log = fs::path(mp4.path()).parent_path() / "ffmpeg.log";  // removed with the folder
    const ProgramExit run = runProgram({{"ffmpeg", "-nostdin", "-loglevel", "error", "-y", "-framerate", std::to_string(fps),
                                         "-f", "image2", "-i", pattern, "-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf",
                                         "scale=trunc(iw/2)*2:trunc(ih/2)*2", "-f", "mp4", mp4.path()},
                                        {},
                                        log.string()});
    if (!run.ok()) {
        std::ifstream in(log);
        std::string line, last;
        while (std::getline(in, line))
            if (!line.empty()) last = line;
        throw Error(writeFailureMessage("'" + mp4.finalPath() + "'", mp4.path(),
                                        "ffmpeg could not encode it: " + run.why + (last.empty() ? "" : "; " + last)));
    }
    mp4.commit();
}

/// Whether `name` is a file a time-lapse writes (frameName and FrameWriter's names).
bool isTimelapseOutput(const std::string& name) {
    static const std::set<std::string> fixed = {kSkyFile, kIndexFile, "timelapse.gif", "timelapse.mp4", kFitFile};
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

/// DIR/frames.csv: frame number -> local time, UTC, the sun at the DEM centre; under a temporary
/// name until commit().
class FrameIndex {
public:
    explicit FrameIndex(const std::string& dir)
        : file_((fs::path(dir) / kIndexFile).string()), out_(file_.path()) {
        out_ << "frame,time_local,time_utc,sun_azimuth_deg,sun_elevation_deg\n";
    }
    void add(const TimelapseFrame& f) {
        out_ << f.index << "," << f.localTime << "," << formatInstant(f.time, std::string()) << ","
             << formatNumber(f.centreAzimuthDeg) << "," << formatNumber(f.centreElevationDeg) << "\n";
    }
    void commit() {
        out_.close();
        if (!out_) throw Error(writeFailureMessage("'" + file_.finalPath() + "'", file_.path(), {}));
        file_.commit();
    }

private:
    TemporaryFile file_;
    std::ofstream out_;
};

/// Writes the frames as they come: frame i on a background thread while frame i + 1 computes;
/// waiting for the previous write before handing over the next keeps the files (and the GIF) in
/// order, and rethrows a failed write.
class FrameWriter {
public:
    FrameWriter(const TimelapseOptions& o, const std::set<std::string>& formats, std::size_t frames,
                const CliContext& ctx)
        : o_(o), formats_(formats), n_(frames), ctx_(ctx), index_(o.outDir) {
        if (formats.count("gif")) gif_ = std::make_unique<GifWriter>((fs::path(o.outDir) / "timelapse.gif").string(), o.fps);
    }
    void sky(ProductResult&& r) { write(r, kSkyFile); }
    void frame(TimelapseFrame&& f) {
        index_.add(f);
        wait();
        writing_ = std::async(std::launch::async, [this, f = std::move(f)]() mutable {
            if (formats_.count("tif")) writeFrame(std::move(f.lightmap), frameName(f.index, n_, "tif"));
            // A picture that repeats the previous frame's is compressed and shrunk once.
            if (formats_.count("png") || formats_.count("mp4")) {
                if (!f.previewRepeats || !png_) png_ = encodePng(f.preview);
                writeImage((fs::path(o_.outDir) / frameName(f.index, n_, "png")).string(), *png_, f.preview.text);
            }
            if (gif_) {
                if (!f.previewRepeats || !gifFrame_) gifFrame_ = downsample(f.preview, o_.gifSize);
                gif_->add(*gifFrame_);
            }
        });
    }
    void finish() {
        wait();
        if (gif_) gif_->finish();
        index_.commit();
    }
    void write(const ProductResult& r, const std::string& name) {
        OutputOptions out;
        out.path = (fs::path(o_.outDir) / name).string();
        out.creationOptions = o_.creationOptions;
        writeResult(r, out, runContext(ctx_), o_.dem.path);
    }

private:
    void wait() {
        if (writing_.valid()) writing_.get();
    }
    /// A frame's GeoTIFF. When its cells equal the previous frame's, bit for bit, and both are
    /// dark (every cell +0 or NaN: the sun down at both instants), the previous file is copied
    /// with this frame's metadata instead: encoding the cells again (predicting and compressing
    /// every tile) would be most of a night frame's time.
    void writeFrame(ProductResult&& lightmap, const std::string& name) {
        std::optional<DarkFrame> dark = darkFrame(lightmap, name);
        if (previous_ && dark && *previous_ == *dark) {
            // From the file that was encoded, not from a copy: each copy appends a directory.
            copyRasterWithMetadata((fs::path(o_.outDir) / previous_->name).string(),
                                   (fs::path(o_.outDir) / name).string(), resultMetadata(lightmap, runContext(ctx_)));
            return;
        }
        write(lightmap, name);
        previous_ = std::move(dark);
    }
    /// What decides a dark frame's file but for its metadata values: the layout, the metadata's
    /// keys, and per band its description and DarkCells (a NaN bitmap: about two bits per cell,
    /// where keeping the frame itself to compare would take 64).
    struct DarkFrame {
        std::string name;  ///< its file, in the output folder (not compared)
        std::vector<std::string> keys, bandNames;
        std::vector<DarkCells> cells;
        std::size_t width = 0, height = 0;
        double nodata = 0;
        GeoReference ref;
        bool operator==(const DarkFrame& o) const {
            return keys == o.keys && bandNames == o.bandNames && cells == o.cells && width == o.width &&
                   height == o.height && nodata == o.nodata && ref.geoTransform == o.ref.geoTransform &&
                   ref.crsWkt == o.ref.crsWkt;
        }
    };
    /// The frame as a DarkFrame, or none when a cell holds anything but +0 or NaN (of one bit
    /// pattern per band), or a band is not Float32.
    static std::optional<DarkFrame> darkFrame(const ProductResult& r, const std::string& name) {
        DarkFrame d;
        d.name = name;
        d.nodata = r.nodata;
        d.ref = r.ref;
        if (r.flagNodata || r.bands.empty()) return std::nullopt;
        for (const auto& [key, value] : r.metadata) d.keys.push_back(key);
        d.width = r.bands.front().values.width();  // (the bands share one shape)
        d.height = r.bands.front().values.height();
        for (const ProductBand& b : r.bands) {
            if (b.values.empty()) return std::nullopt;
            std::optional<DarkCells> cells = darkCells(b.values.data(), b.values.size());
            if (!cells) return std::nullopt;
            d.cells.push_back(std::move(*cells));
            d.bandNames.push_back(b.name + "\n" + b.unit + "\n" + std::to_string(static_cast<int>(b.resampling)));
        }
        return d;
    }
    const TimelapseOptions& o_;
    const std::set<std::string>& formats_;
    std::size_t n_;
    const CliContext& ctx_;
    FrameIndex index_;
    std::unique_ptr<GifWriter> gif_;
    std::future<void> writing_;
    /// The last frame GeoTIFF encoded, when dark (the writing thread's); copies leave it.
    std::optional<DarkFrame> previous_;
    /// The last frame's picture as PNG pixel data and as a GIF frame (the writing thread's).
    std::optional<PngPixels> png_;
    std::optional<Image8> gifFrame_;
};

TimelapseRequest timelapseRequest(const TimelapseOptions& o, const std::set<std::string>& formats, const Dem& dem) {
    TimelapseRequest r;
    r.frames = chooseFrames(o, dem);
    r.stackDirections = parseHorizonMode(o.horizonMode, "horizon_mode");
    r.skyDirections = o.skyDirections;
    r.sunDiameterDeg = o.sunDiameterDeg;
    r.lightmaps = formats.count("tif") > 0;
    r.previews = formats.count("png") || formats.count("mp4") || formats.count("gif");
    r.picture = pictureRequest(o.picture);
    r.fitDegree = o.fitDegree;
    r.canopy = o.canopy;
    r.search = o.search.request;
    if (o.view) {
        ViewRequest v;
        applyViewCameraOptions(o.camera, v);
        v.colorRaster = r.picture.colorRaster;
        v.colorEncoding = r.picture.colorEncoding;
        if (o.albedoGiven && v.colorRaster.empty()) v.albedo = r.picture.albedo;
        v.exposure = r.picture.exposure;
        v.sunDiameterDeg = r.sunDiameterDeg;
        v.skyDirections = r.skyDirections;
        v.search = r.search;
        r.view = v;
    }
    return r;
}

void noteTimelapse(const TimelapseOptions& o, const TimelapseRequest& r, const TimelapseResult& res,
                   const std::set<std::string>& formats, std::size_t tiles, double total, const CliContext& ctx) {
    const auto& f = r.frames;
    note(ctx, "frames: " + std::to_string(res.frames) + " (" + f.description + ", " +
                  formatInstant(f.instants.front(), f.zone) + " .. " + formatInstant(f.instants.back(), f.zone) +
                  ", step " + o.step + "), " +
                  std::to_string(std::count(res.sunUp.begin(), res.sunUp.end(), true)) + " with the sun up");
    note(ctx, "time: sky " + formatSeconds(res.skySeconds) +
                  (tiles > 1 ? " once per tile, " + std::to_string(tiles) + " tiles" : std::string(" once")) + " (" +
                  std::to_string(res.skyDirections) +
                  " directions to " + formatDistance(res.skyMaxDistanceM) + ", quality " +
                  std::string(qualityName(res.quality)) +
                  (r.stackDirections > 0 ? ", also the interpolated sun horizons" : "") + "); total " +
                  formatSeconds(total) + ", " + formatSeconds(total / static_cast<double>(res.frames)) +
                  " per frame" + (tiles > 1 ? std::string() : " (writing in the background)"));
    note(ctx, "wrote " + o.outDir + ": frames.csv " +
                  (formats.count("tif") ? "frame_*.tif (sun_visibility, sun_irradiance), sky_k.tif " : "") +
                  (formats.count("png") ? "frame_*.png " : "") + (formats.count("gif") ? "timelapse.gif " : "") +
                  (formats.count("mp4") ? "timelapse.mp4" : "") + (r.fitDegree > 0 ? kFitFile : ""));
    if (r.fitDegree > 0)
        note(ctx, kFitFile + ": sun_irradiance as degree-" + std::to_string(r.fitDegree) + " polynomials, " +
                      std::to_string(r.fitDegree + 1) + " bands for " + std::to_string(res.frames) +
                      " frames; RMS error vs the exact frames: mean " + formatNumber(res.fitStats.meanRms()) +
                      ", worst cell " + formatNumber(res.fitStats.worstRms));
}

/// A tiled run keeps every output GeoTIFF open from the first tile to the end: raises this
/// process's open-file limit to what `outputs` need (up to the hard limit), or refuses before any
/// work.
void ensureOpenFiles(std::size_t outputs) {
    rlimit limit{};
    if (::getrlimit(RLIMIT_NOFILE, &limit) != 0) return;
    const rlim_t need = static_cast<rlim_t>(outputs) + kSpareFiles;
    if (limit.rlim_cur == RLIM_INFINITY || limit.rlim_cur >= need) return;
    if (limit.rlim_max == RLIM_INFINITY || limit.rlim_max >= need) {
        limit.rlim_cur = need;
        if (::setrlimit(RLIMIT_NOFILE, &limit) == 0) return;
    }
    throw Error("timelapse: a tiled run keeps its " + std::to_string(outputs) +
                " GeoTIFFs open until the last tile, more files than this process may open (ulimit -n " +
                std::to_string(limit.rlim_max) + "); use fewer frames (--step, --start/--end) or a --memory-limit "
                "that fits one piece");
}

/// The rasters of a tiled run: sky_k.tif, frame i at 1 + i, then sequence_fit.tif (with a fit).
std::vector<RasterTarget> tiledTargets(const TimelapseOptions& o, const TimelapseRequest& request) {
    const std::size_t n = request.frames.instants.size();
    const auto target = [&](const std::string& name) {
        RasterTarget t;
        t.out.path = (fs::path(o.outDir) / name).string();
        t.out.creationOptions = o.creationOptions;
        return t;
    };
    std::vector<RasterTarget> targets{target(kSkyFile)};
    for (std::size_t i = 0; i < n; ++i) targets.push_back(target(frameName(i, n, "tif")));
    if (request.fitDegree > 0) targets.push_back(target(kFitFile));
    return targets;
}

/// Tiles outer, frames inside: each tile's sky term is computed once and each frame's lightmap
/// tile goes into that frame's streamed GeoTIFF; every output stays under a temporary name until
/// all are renamed together after the last tile (removed on failure or Ctrl-C).
TimelapseResult runTiled(const TimelapseOptions& o, const DemSource& dem, const TimelapseRequest& request,
                         const RasterRun& run, const std::vector<RasterTarget>& targets, const CliContext& ctx) {
    const std::size_t n = request.frames.instants.size();
    const std::size_t fitTarget = 1 + n;
    TiledWriter writer(run, targets, runContext(ctx), o.dem.path);
    FrameIndex index(o.outDir);
    std::optional<TimelapseResult> total;
    runTiles(run, ctx, [&](const CellWindow& tile, const ProgressFn& progress) {
        const TimelapseSink sink{[&](ProductResult&& r) { writer.write(0, tile, r); },
                                 [&](TimelapseFrame&& f) {
                                     if (!total) index.add(f);  // the same row from every tile
                                     writer.write(1 + f.index, tile, f.lightmap);
                                 }};
        TimelapseResult r = timelapseProduct(dem, tile, request, sink, progress);
        if (r.fit) writer.write(fitTarget, tile, *r.fit);
        r.fit.reset();
        if (!total) {
            total = std::move(r);
            return;
        }
        total->skySeconds += r.skySeconds;
        total->fitStats.merge(r.fitStats);
        for (std::size_t i = 0; i < n; ++i) total->sunUp[i] = total->sunUp[i] || r.sunUp[i];
    });
    if (request.fitDegree > 0) writer.setMetadata(fitTarget, total->fitStats.metadata());
    writer.commit();
    try {
        index.commit();
    } catch (const Error&) {
        removeOutputs(targets, targets.size());
        throw;
    }
    return std::move(*total);
}

void runTimelapse(const TimelapseOptions& o, const CliContext& ctx) {
    if (o.outDir.empty()) throw Error("-o: the output folder path is empty");
    // One run at a time in a folder: a folder that is there is held from now on (a second run
    // into it is refused, naming the first), a new one once this run has made it.
    std::error_code ec;
    std::optional<FolderLock> lock;
    if (fs::is_directory(o.outDir, ec)) lock.emplace(o.outDir);
    checkOutputFolder(o.outDir, o.overwrite);
    const std::set<std::string> formats = parseFormats(o.formats);
    checkCreationOptions("GTiff", o.creationOptions);  // before the work, not at the first file
    const DemSource dem = openDem(o.dem, ctx);
    const TimelapseRequest request = timelapseRequest(o, formats, dem.geometry());
    const RasterRun run = planRasterRun(dem, o.tiling, timelapseHaloCells(dem, request),
                                        productTileBytes(timelapseGridsPerCell(request)), runContext(ctx));
    const bool tiled = run.tiles.size() > 1;
    if (request.previews && !dem.isWhole(run.tiles.front()))
        throw Error("--formats " + o.formats + ": png, gif and mp4 are pictures of whole frames of the DEM, and this run is " +
                    (tiled ? "in " + std::to_string(run.tiles.size()) + " tiles (--tile-size, --memory-limit)"
                           : std::string("a --srcwin window")) +
                    "; give --formats tif" + (tiled ? " (or a --memory-limit that fits the DEM in one piece)" : ""));
    const std::vector<RasterTarget> targets = tiled ? tiledTargets(o, request) : std::vector<RasterTarget>{};
    if (tiled) ensureOpenFiles(targets.size());
    const bool folderWasThere = fs::exists(o.outDir, ec);
    fs::create_directories(o.outDir, ec);
    if (!fs::is_directory(o.outDir)) throw Error("-o " + o.outDir + ": cannot create the output folder");
    if (!lock) {
        // Made since the first check, by this run or another: the rule again under the lock.
        lock.emplace(o.outDir);
        checkOutputFolder(o.outDir, o.overwrite);
    }
    // A run that fails (or is cancelled) before writing anything leaves no empty folder it made.
    struct RemoveMadeEmptyFolder {
        std::string dir;
        ~RemoveMadeEmptyFolder() {
            std::error_code e;
            if (!dir.empty() && fs::is_empty(dir, e) && !e) fs::remove(dir, e);
        }
    } const removeIfEmpty{folderWasThere ? std::string() : o.outDir};
    checkOutputPath((fs::path(o.outDir) / "frame_000.tif").string(), o.dem.path);
    if (o.overwrite) removeEarlierOutputs(o.outDir, isTimelapseOutput);
    notePlan(o.search, dem.geometry().terrain, ctx);
    // A run stopped by an error or a signal keeps the frames it finished, each whole, and nothing
    // else: the shared sky term and the fit go with it.
    struct RemoveSharedOnFailure {
        fs::path dir;
        ~RemoveSharedOnFailure() {
            if (std::uncaught_exceptions() == 0) return;
            std::error_code e;
            for (const std::string& name : {kSkyFile, kFitFile}) fs::remove(dir / name, e);
        }
    } const removeShared{o.outDir};

    const auto start = std::chrono::steady_clock::now();
    if (tiled) {
        const TimelapseResult result = runTiled(o, dem, request, run, targets, ctx);
        noteTimelapse(o, request, result, formats, run.tiles.size(), secondsSince(start), ctx);
        return;
    }
    FrameWriter writer(o, formats, request.frames.instants.size(), ctx);
    ProgressBar bar(!ctx.quiet);
    const TimelapseSink sink{[&](ProductResult&& r) { writer.sky(std::move(r)); },
                             [&](TimelapseFrame&& f) { writer.frame(std::move(f)); }};
    const TimelapseResult result = timelapseProduct(dem, run.tiles.front(), request, sink, bar.callback());
    writer.finish();
    bar.finish();
    if (formats.count("mp4")) {
        encodeMp4(o.outDir, result.frames, o.fps);
        if (!formats.count("png"))  // the PNGs were only the video's input
            for (std::size_t i = 0; i < result.frames; ++i) fs::remove(fs::path(o.outDir) / frameName(i, result.frames, "png"));
    }
    if (result.fit) writer.write(*result.fit, kFitFile);
    noteTimelapse(o, request, result, formats, 1, secondsSince(start), ctx);
}

}  // namespace

void registerTimelapse(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<TimelapseOptions>();
    ParameterSet& set = o->set;
    declareDemOptions(set, o->dem);
    set.add("output", o->outDir, "Output folder", "Output folder (created if missing; must be empty unless {overwrite})")
        .flags("-o,--output")
        .type("DIR")
        .mandatory();
    set.add("overwrite", o->overwrite, "Replace an earlier run",
            "Write into a folder that is not empty: the frames, sky_k.tif, frames.csv, timelapse.gif/.mp4 and "
            "sequence_fit.tif of an earlier run there are removed first (other files are left)");
    set.add("start", o->start, "First instant", "First instant (ISO 8601 with offset, or local with {tz})");
    set.add("end", o->end, "Last instant", "Last instant (inclusive when on a step)");
    set.add("date", o->date, "Day", "Local day YYYY-MM-DD: sunrise to sunset at the DEM centre");
    set.add("tz", o->tz, "Time zone",
            "IANA time zone of local times and of {date} (required with {date}; UTC for universal time)")
        .field("zone");
    set.add("step", o->step, "Time step", "Time between frames: 15m, 1h, 90s, 1h30m (a bare number = minutes)");
    set.add("max_frames", o->maxFrames, "Most frames",
            "Refuse a sequence of more frames than this (guards against a mistyped {step})")
        .within(1, 1000000);
    set.add("horizon_mode", o->horizonMode, "Horizon mode",
            "exact (a sweep per frame along its sun azimuth) or interpolated[:N] (N directions swept once, horizons "
            "interpolated in azimuth; N = 64 by default)")
        .field("stackDirections");
    set.add("formats", o->formats, "Outputs", "Outputs: comma list of tif, png, gif, mp4 (mp4 needs ffmpeg on PATH)")
        .field("previews");
    set.add("creation_options", o->creationOptions, "GDAL creation options",
            "GDAL creation option KEY=VALUE of its GeoTIFFs (frames, sky_k.tif, sequence_fit.tif; repeatable), over "
            "the defaults (tiled, ZSTD level 1, PREDICTOR=3): e.g. COMPRESS=DEFLATE for readers without ZSTD, "
            "PREDICTOR=1 for slightly faster frames in larger files")
        .flags("--co")
        .type("KEY=VALUE")
        .forHowItRuns();
    set.add("fps", o->fps, "GIF frames per second", "GIF frames per second").within(1, 100);
    set.add("gif_size", o->gifSize, "GIF size (pixels)", "Longest GIF side (pixels); frames are box-downsampled")
        .within(16, 100000);
    set.add("sky_directions", o->skyDirections, "Sky directions",
            "Horizon directions for the sky term (default: " + std::to_string(kAutoSkyDirections) +
                " with {quality} auto, " + std::to_string(kFullSkyDirections) +
                " with full; {horizon_mode} interpolated:N uses its N)")
        .within(4, 1024);
    declarePictureOptions(set, o->picture);
    set.add("view", o->view, "Oblique previews",
            "Previews (png, gif, mp4) in an oblique view from one camera, as demlight view draws it (camera options "
            "below), instead of top-down");
    const std::size_t firstCamera = set.parameters().size();
    declareViewCameraOptions(set, o->camera);
    // A camera option without view would be ignored: it needs it.
    for (std::size_t i = firstCamera; i < set.parameters().size(); ++i) set.parameters()[i].onlyWith("view");
    set.add("fit_degree", o->fitDegree, "Fit degree",
            "Also store sun_irradiance as per-cell Legendre polynomials of this degree in DIR/sequence_fit.tif (0 = "
            "off); read back with demlight sequence")
        .within(0, 12);
    declareCanopy(set, o->canopy);
    declareSunDiameter(set, o->sunDiameterDeg);
    declareSearchOptions(set, o->search);
    declareTiling(set, o->tiling);
    notInPython(set);
    CLI::App* cmd = addDeclaredCommand(app, set, ctx);
    ctx.outputs[cmd->get_name()].kind = "folder";
    cmd->callback([o, &ctx, cmd] {
        o->albedoGiven = cmd->get_option("--albedo")->count() > 0;
        runTimelapse(*o, ctx);
    });
}

}  // namespace demlight::cli
