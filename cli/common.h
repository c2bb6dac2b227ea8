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
#include "demlight/run/common_parameters.h"
#include "demlight/run/options.h"
#include "demlight/run/runner.h"
#include "demlight/core/error.h"
#include "demlight/core/process.h"

#include <array>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demlight::cli {

/// The DEM argument and how its heights are read (--z-unit, --z-factor).
struct DemOptions {
    std::string path;
    HeightOptions heights;  ///< --z-unit, --z-factor
};
/// The DEM and its heights (demlight/run/common_parameters.h) into DemOptions.
void declareDemOptions(ParameterSet& set, DemOptions& o);
DemSource openDem(const DemOptions& o, const CliContext& ctx);
DemSource openDem(const std::string& path, const HeightOptions& heights, const CliContext& ctx);

/// --max-distance, --refraction, --threads, --quality, --tolerance and -v into a SearchRequest.
struct SearchOptions {
    SearchRequest request;
    bool verbose = false;
};
void declareSearchOptions(ParameterSet& set, SearchOptions& o);

/// Notes about the plan the product will make: unused options, and with -v the plan itself.
void notePlan(const SearchOptions& o, const Terrain& terrain, const CliContext& ctx);
void notePlan(const SearchRequest& request, bool verbose, const Terrain& terrain, const CliContext& ctx);

/// The run context of a command: its command line, notes on stderr unless quiet, and Ctrl-C
/// stopping a write.
RunContext runContext(const CliContext& ctx);

/// Runs step(tile, progress) on each tile of `run` with one progress bar for the whole job.
template <class Step>
void runTiles(const RasterRun& run, const CliContext& ctx, Step&& step);

/// Plans `work`'s run on `dem`, runs it with one progress bar for the whole job and writes its
/// rasters to `targets` (demlight::runRaster). Returns the first window's result, for the
/// command's notes.
template <class Result>
Result runWork(const ProductWork<Result>& work, const DemSource& dem, const std::vector<RasterTarget>& targets,
               const CliContext& ctx, const std::string& inputPath);

/// What a raster command's run gives its closing note.
template <class Result>
struct RasterOutcome {
    Result result;            ///< of the first window
    std::size_t demCells = 0;  ///< of the whole DEM
    double readSeconds = 0;    ///< opening the DEM
    double seconds = 0;        ///< computing and writing
};

/// A raster command run from its work: the outputs checked before any work (the first a raster,
/// the others its companions, named after it), the DEM opened with `heights`, the scene plan of
/// `search` noted (unless null), the work run and its rasters written to `targets`.
template <class Result>
RasterOutcome<Result> runRasterCommand(const ProductWork<Result>& work, const std::string& demPath,
                                       const std::vector<RasterTarget>& targets, const SearchRequest* search,
                                       bool verbose, const CliContext& ctx);

/// The parameters of a command the Python package does not offer (pictures, time-lapses): shown
/// by the command line and QGIS.
void notInPython(ParameterSet& set);
/// The parameters of a command only the command line offers.
void commandLineOnly(ParameterSet& set);

/// --color-raster, --color-encoding, --albedo, --exposure and --pixels of pictures.
struct PictureOptions {
    std::string colorRaster, colorEncoding = "auto";
    double albedo = PreviewParams{}.albedo;
    double exposure = 1.0;
    std::string pixels = "ground";
};
void declarePictureOptions(ParameterSet& set, PictureOptions& o);
/// -o OUT.png of the picture commands; `extensions` lists the formats they write (".png, .jpg").
void declarePictureOutput(ParameterSet& set, std::string& path, const std::string& extensions);
PictureRequest pictureRequest(const PictureOptions& o);

/// A search distance for notes: "N m" (rounded), or "the whole DEM" when infinite.
std::string formatDistance(double metres);
/// A duration for notes, rounded to hundredths of a second ("1.23 s").
std::string formatSeconds(double seconds);
/// Prints a line to stderr unless quiet.
void note(const CliContext& ctx, const std::string& line);

template <class Step>
void runTiles(const RasterRun& run, const CliContext& ctx, Step&& step) {
    ProgressBar bar(!ctx.quiet);
    demlight::runTiles(run, bar.callback(), step);
    bar.finish();
}

template <class Result>
Result runWork(const ProductWork<Result>& work, const DemSource& dem, const std::vector<RasterTarget>& targets,
               const CliContext& ctx, const std::string& inputPath) {
    const RunContext run = runContext(ctx);
    const RasterRun tiles = work.plan(dem, run);
    ProgressBar bar(!ctx.quiet);
    return runRaster(work, dem, tiles, targets, run, inputPath, bar.callback(), [&bar] { bar.finish(); });
}

template <class Result>
RasterOutcome<Result> runRasterCommand(const ProductWork<Result>& work, const std::string& demPath,
                                       const std::vector<RasterTarget>& targets, const SearchRequest* search,
                                       bool verbose, const CliContext& ctx) {
    for (std::size_t k = 0; k < targets.size(); ++k) {
        if (k == 0)
            checkOutputPath(targets[k].out, demPath);
        else
            checkOutputPath(targets[k].out.path, demPath);
    }
    const auto readStart = std::chrono::steady_clock::now();
    const DemSource dem = openDem(demPath, work.heights, ctx);
    const double readSeconds = secondsSince(readStart);
    if (search) notePlan(*search, verbose, dem.geometry().terrain, ctx);
    const auto start = std::chrono::steady_clock::now();
    Result result = runWork(work, dem, targets, ctx, demPath);
    const double seconds = secondsSince(start);
    if (verbose) note(ctx, "peak memory: " + formatNumber(std::round(peakResidentBytes() / 1e5) / 10) + " MB");
    return {std::move(result), dem.width() * dem.height(), readSeconds, seconds};
}

}  // namespace demlight::cli
