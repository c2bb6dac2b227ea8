// Options and helpers shared by the commands: they parse into product requests, call one product
// and write its result.
#pragma once

#include "demlight/core/timing.h"  // secondsSince, for the time notes of the commands

#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/time.h"
#include "demlight/geo/raster.h"
#include "demlight/products/canopy.h"
#include "demlight/products/product.h"
#include "demlight/products/render.h"
#include "demlight/products/tiles.h"
#include "demlight/core/error.h"

#include <array>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demlight::cli {

/// -o, -of, -co: where and how an output raster is written.
struct OutputOptions {
    std::string path;
    std::string format = "GTiff";
    std::vector<std::string> creationOptions;
    /// Float32 bands stored as 16-bit fixed point instead (a command's --ot Int16).
    std::optional<FixedPoint16> fixedPoint;
};
void addOutputOptions(CLI::App* cmd, OutputOptions& o);

/// The DEM argument and how its heights are read (--z-unit, --z-factor).
struct DemOptions {
    std::string path;
    HeightOptions heights;  ///< --z-unit, --z-factor
};
void addDemArgument(CLI::App* cmd, DemOptions& o);
DemSource openDem(const DemOptions& o, const CliContext& ctx);

/// --max-distance, --refraction, --threads, --quality, --tolerance and -v into a SearchRequest.
struct SearchOptions {
    SearchRequest request;
    bool verbose = false;
};
void addSearchOptions(CLI::App* cmd, SearchOptions& o);

/// Notes about the plan the product will make: unused options, and with -v the plan itself.
void notePlan(const SearchOptions& o, const Terrain& terrain, const CliContext& ctx);

/// The metadata writeResult gives a product result's file: its own items, DEMLIGHT_COMMAND and
/// `extra`.
std::map<std::string, std::string> resultMetadata(const ProductResult& result, const CliContext& ctx,
                                                  const std::map<std::string, std::string>& extra = {});

/// Writes a product result to `out` (atomically), with DEMLIGHT_COMMAND added; `extra` items
/// are added to its metadata. Refuses to overwrite `inputPath`.
void writeResult(const ProductResult& result, const OutputOptions& out, const CliContext& ctx,
                 const std::string& inputPath, const std::map<std::string, std::string>& extra = {});

/// --tile-size, --memory-limit and --srcwin of the raster products.
struct TilingOptions {
    std::string tileSize = "auto";       ///< cells per tile side, or "auto"
    double memoryLimitMB = 0;            ///< 0 = half of this machine's memory
    std::vector<std::size_t> srcwin;     ///< XOFF YOFF XSIZE YSIZE (gdal_translate's order), or empty
};
void addTilingOptions(CLI::App* cmd, TilingOptions& o);

/// One raster a product writes: where, and metadata items added to the result's.
struct RasterTarget {
    OutputOptions out;
    std::map<std::string, std::string> extra;
};

/// The windows a raster product runs on: the extent (the whole DEM or --srcwin) in tiles.
struct RasterRun {
    CellWindow extent;
    GeoReference ref;  ///< of the extent
    std::vector<CellWindow> tiles;
};
/// Chooses the tiles: --tile-size N, or auto (one piece unless extent + halo exceeds
/// --memory-limit for a tile holding `bytes`). Throws Error naming the option on bad values.
RasterRun planRasterRun(const DemSource& dem, const TilingOptions& tiling, const SearchRequest& search,
                        const TileBytes& bytes, const CliContext& ctx);

/// Streamed outputs of a tiled run: one sink per target, opened at the first tile.
class TiledWriter {
public:
    TiledWriter(const RasterRun& run, std::vector<RasterTarget> targets, const CliContext& ctx, std::string inputPath);
    ~TiledWriter();
    /// Writes the parts of one tile's result, part k to target k.
    void write(const CellWindow& tile, const std::vector<const ProductResult*>& parts);
    /// Writes one tile of target k alone (products that stream several rasters per tile).
    void write(std::size_t target, const CellWindow& tile, const ProductResult& part);
    /// Sets metadata items of target k known only once every tile is written (a mean over the
    /// raster); the target must have been written.
    void setMetadata(std::size_t target, const std::map<std::string, std::string>& items);
    /// Renames every output to its name.
    void commit();

private:
    RasterRun run_;
    std::vector<RasterTarget> targets_;
    const CliContext& ctx_;
    std::string inputPath_;
    std::vector<std::unique_ptr<RasterSink>> sinks_;
};

/// A raster command's parsed options as a call on any DEM source, for a caller that brings its own
/// DEM and writes the results itself (CliContext::takeCall): the requests are the command's own,
/// so names, defaults, checks and messages are the command line's.
struct RasterCall {
    std::string command;
    HeightOptions heights;  ///< --z-unit, --z-factor: how the DEM argument is to be opened
    TilingOptions tiling;
    SearchRequest search;         ///< what the halo and the tiles are planned from (planRasterRun)
    TileBytes tileBytes;          ///< of planRasterRun
    /// The product on one window of a source: one result per output raster (rasterTargets).
    std::function<std::vector<ProductResult>(const DemSource&, const CellWindow&, const ProgressFn&)> run;
    /// The rasters the command writes for -o, in the order of run's results.
    std::function<std::vector<RasterTarget>(const OutputOptions&)> targets;
};

/// What `demlight info --json` prints of `source` opened from `path`: one JSON object, as text.
std::string infoJson(const std::string& path, const DemSource& source);

/// A RasterCall of a command that writes one raster: `product(source, window, progress)`.
template <class Product>
RasterCall singleRasterCall(std::string command, const DemOptions& dem, const TilingOptions& tiling,
                            const SearchRequest& search, const TileBytes& tileBytes, Product product) {
    RasterCall call;
    call.command = std::move(command);
    call.heights = dem.heights;
    call.tiling = tiling;
    call.search = search;
    call.tileBytes = tileBytes;
    call.run = [product](const DemSource& source, const CellWindow& w, const ProgressFn& p) {
        return std::vector<ProductResult>{product(source, w, p)};
    };
    call.targets = [](const OutputOptions& out) { return std::vector<RasterTarget>{{out, {}}}; };
    return call;
}

/// Removes the first `count` targets' files (written before a later one failed).
void removeOutputs(const std::vector<RasterTarget>& targets, std::size_t count);

/// Runs step(tile, progress) on each tile of `run` in order, with one progress bar for the whole
/// job: the tiled half of runRaster, and the driver of products that write several rasters while
/// they compute a tile (time-lapse frames through a TiledWriter).
template <class Step>
void runTiles(const RasterRun& run, const CliContext& ctx, Step&& step);

/// Runs a raster product on each window of `run` (product(window, progress) -> Result; parts(r)
/// lists its rasters, one per target) with one progress bar for the whole job, and writes them:
/// in one piece as writeResult does, in tiles through a TiledWriter. Returns the first window's
/// result, for the command's notes.
template <class Result, class Product, class Parts>
Result runRaster(const RasterRun& run, const std::vector<RasterTarget>& targets, const CliContext& ctx,
                 const std::string& inputPath, Product&& product, Parts&& parts);

/// The flag that sets a request field (FieldError::field), e.g. "maxDistanceM" -> "--max-distance";
/// the field itself when no flag sets it.
std::string flagForField(const std::string& field);
/// `message` with the HeightOptions fields the library names in its DEM-opening messages
/// (HeightOptions::zUnit, ::zFactor) as the user spells them: flags, or Python keywords.
std::string renameHeightFields(std::string message, const std::string& zUnit, const std::string& zFactor);

/// Fails early (before any work) if the output cannot be written or would replace the input.
void checkOutputPath(const std::string& outPath, const std::string& inputPath);
/// As above for a raster output, which must also be named as a GeoTIFF (checkRasterPath).
void checkOutputPath(const OutputOptions& out, const std::string& inputPath);

/// "R,G,B" linear, each >= 0; throws Error naming the option.
std::array<double, 3> parseColor(const std::string& text, const std::string& option);

/// A duration option (--step): 10m, 1h30m, 90s; a bare number counts `bareUnit`s.
std::chrono::milliseconds parseStepOption(const std::string& text, std::chrono::milliseconds bareUnit);

/// A range check that also rejects NaN and infinities (CLI::Range lets NaN through). lowOpen:
/// lo excluded.
CLI::Validator finiteRange(double lo, double hi, bool lowOpen = false);
/// The --color-raster and --color-encoding options of pictures and light.
void addColorRasterOptions(CLI::App* cmd, std::string& path, std::string& encoding, const std::string& use);

/// SPA's stated pressure limit (hPa; Reda & Andreas, Table 1); 0 = no atmospheric refraction.
inline constexpr double kMaxPressureHpa = 5000;

/// --time with --tz: parseZonedInstant, its messages naming the flags.
ZonedInstant parseTimeOptions(const std::string& time, const std::string& tz);
/// --time and --tz of every command at one instant.
void addTimeOptions(CLI::App* cmd, std::string& time, std::string& tz);
/// --date D, or --start D --end D, and --tz of the commands over local days; with periods also
/// --month YYYY-MM, --year YYYY, and --start/--end as local times (an interval within days).
struct DayOptions {
    std::string date, startDate, endDate, month, year, tz;
    bool periods = false;  ///< --month, --year and local times in --start/--end are offered
};
/// Adds them (--month and --year when o.periods); `tzHelp` says what --tz is the zone of.
void addDayOptions(CLI::App* cmd, DayOptions& o, const std::string& tzHelp);
/// The local days (inclusive) of the options; `command` names the command in errors.
struct LocalDays {
    std::chrono::sys_days first, last;
    TimeZoneSpec zone;
    /// --start/--end given as local times: the interval itself (first and last are its days).
    std::optional<std::pair<UtcInstant, UtcInstant>> interval;
};
LocalDays parseDayOptions(const DayOptions& o, const std::string& command);

/// --sun-diameter (degrees).
void addSunDiameterOption(CLI::App* cmd, double& diameterDeg);
/// --canopy RASTER and --transmissivity (demlight/products/canopy.h).
void addCanopyOptions(CLI::App* cmd, CanopyRequest& canopy);

/// --color-raster, --color-encoding, --albedo, --exposure and --pixels of pictures.
struct PictureOptions {
    std::string colorRaster, colorEncoding = "auto";
    double albedo = PreviewParams{}.albedo;
    double exposure = 1.0;
    std::string pixels = "ground";
};
void addPictureOptions(CLI::App* cmd, PictureOptions& o);
PictureRequest pictureRequest(const PictureOptions& o);

/// A search distance for notes: "N m" (rounded), or "the whole DEM" when infinite.
std::string formatDistance(double metres);
/// `text` as one finite number (trailing spaces allowed when `trailingSpaces`); nullopt when it
/// is not exactly that. The option parsers' number rule.
std::optional<double> parseFiniteNumber(const std::string& text, bool trailingSpaces = false);
/// A duration for notes, rounded to hundredths of a second ("1.23 s").
std::string formatSeconds(double seconds);
/// Prints a line to stderr unless quiet.
void note(const CliContext& ctx, const std::string& line);

template <class Step>
void runTiles(const RasterRun& run, const CliContext& ctx, Step&& step) {
    ProgressBar bar(!ctx.quiet);
    for (std::size_t i = 0; i < run.tiles.size(); ++i)
        step(run.tiles[i], tileProgress(bar.callback(), i, run.tiles.size()));
    bar.finish();
}

template <class Result, class Product, class Parts>
Result runRaster(const RasterRun& run, const std::vector<RasterTarget>& targets, const CliContext& ctx,
                 const std::string& inputPath, Product&& product, Parts&& parts) {
    if (run.tiles.size() == 1) {
        ProgressBar bar(!ctx.quiet);
        Result r = product(run.tiles.front(), bar.callback());
        bar.finish();
        const std::vector<const ProductResult*> rasters = parts(r);
        for (std::size_t k = 0; k < targets.size(); ++k) {
            try {
                writeResult(*rasters[k], targets[k].out, ctx, inputPath, targets[k].extra);
            } catch (const Error&) {
                removeOutputs(targets, k);  // a product's rasters are all written or none
                throw;
            }
        }
        return r;
    }
    TiledWriter writer(run, targets, ctx, inputPath);
    std::optional<Result> first;
    runTiles(run, ctx, [&](const CellWindow& tile, const ProgressFn& progress) {
        Result r = product(tile, progress);
        writer.write(tile, parts(r));
        if (!first) first = std::move(r);
    });
    writer.commit();
    return std::move(*first);
}

}  // namespace demlight::cli
