// Running a raster product for a front end: the run planned on a DEM (the extent, its tiles, the
// memory budget), each tile computed, the results written (in one piece, or tile by tile through
// the streaming writer) and committed, all of a command's rasters or none. The command line and
// the Python module both run products through it.
#pragma once

#include "demlight/core/error.h"
#include "demlight/core/parallel.h"
#include "demlight/core/progress.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/raster.h"
#include "demlight/products/product.h"
#include "demlight/products/tiles.h"

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demlight {

/// Where and how an output raster is written (-o, -of, -co on the command line).
struct OutputOptions {
    std::string path;
    std::string format = "GTiff";
    std::vector<std::string> creationOptions;
    /// Float32 bands stored as 16-bit fixed point instead.
    std::optional<FixedPoint16> fixedPoint;
};

/// How a raster product's extent is cut into tiles.
struct TilingOptions {
    std::string tileSize = "auto";       ///< cells per tile side, or "auto"
    double memoryLimitMB = 0;            ///< 0 = half of this machine's memory
    std::vector<std::size_t> srcwin;     ///< XOFF YOFF XSIZE YSIZE (gdal_translate's order), or empty
};

/// What a run reports besides its results: the command that made it (recorded in each output's
/// DEMLIGHT_COMMAND), notes for a person (the tiles chosen) through `notes` when set, and whether
/// to stop writing (asked between strips of a write; a terminal's Ctrl-C).
struct RunContext {
    std::string commandLine;
    std::function<void(const std::string&)> notes;
    std::function<bool()> cancelled;
    void note(const std::string& line) const {
        if (notes) notes(line);
    }
};

/// One raster a product writes: where, and metadata items added to the result's.
struct RasterTarget {
    OutputOptions out;
    std::map<std::string, std::string> extra;
};

/// The windows a raster product runs on: the extent (the whole DEM or a source window) in tiles.
struct RasterRun {
    CellWindow extent;
    GeoReference ref;  ///< of the extent
    std::vector<CellWindow> tiles;
    /// Cells the product reads around each tile (its xxxHaloCells), which the tiles are sized for.
    std::size_t haloCells = 0;
};

/// Chooses the tiles: a tile size of N cells, or auto (one piece unless extent + halo exceeds the
/// memory limit for a tile holding `bytes` and reading `haloCells` around it: the product's own
/// halo). Throws Error naming the option on bad values.
RasterRun planRasterRun(const DemSource& dem, const TilingOptions& tiling, std::size_t haloCells,
                        const TileBytes& bytes, const RunContext& ctx);

/// The metadata a written result carries: its own items, DEMLIGHT_COMMAND and `extra`.
std::map<std::string, std::string> resultMetadata(const ProductResult& result, const RunContext& ctx,
                                                  const std::map<std::string, std::string>& extra = {});

/// Writes a product result to `out` (atomically), with DEMLIGHT_COMMAND added; `extra` items
/// are added to its metadata. Refuses to overwrite `inputPath`.
void writeResult(const ProductResult& result, const OutputOptions& out, const RunContext& ctx,
                 const std::string& inputPath, const std::map<std::string, std::string>& extra = {});

/// Removes the first `count` targets' files (written before a later one failed).
void removeOutputs(const std::vector<RasterTarget>& targets, std::size_t count);

/// Writes `rasters[k]` to `targets[k]` with writeResult: all or none (a failure removes the ones
/// written before it).
void writeResults(const std::vector<const ProductResult*>& rasters, const std::vector<RasterTarget>& targets,
                  const RunContext& ctx, const std::string& inputPath);

/// Fails early (before any work) if the output cannot be written or would replace the input.
void checkOutputPath(const std::string& outPath, const std::string& inputPath);
/// As above for a raster output, which must also be named as a GeoTIFF (checkRasterPath).
void checkOutputPath(const OutputOptions& out, const std::string& inputPath);

/// Streamed outputs of a tiled run: one sink per target, opened at the first tile.
class TiledWriter {
public:
    TiledWriter(const RasterRun& run, std::vector<RasterTarget> targets, RunContext ctx, std::string inputPath);
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
    RunContext ctx_;
    std::string inputPath_;
    std::vector<std::unique_ptr<RasterSink>> sinks_;
};

/// A raster command's work on any DEM source, built once from the command's parameters
/// (demlight/run/raster_commands.h) for every front end: what the tiles are planned from, the
/// product on one window, and the rasters it writes for one output path.
template <class Result>
struct ProductWork {
    std::string command;
    HeightOptions heights;  ///< how the DEM is to be opened
    TilingOptions tiling;
    /// Worker threads of the run (SearchRequest::threads; 0 = all cores): runRaster and
    /// computeRaster enter them once for every tile.
    int threads = 0;
    /// The cells the product reads around a window of a DEM (the product's xxxHaloCells): what
    /// the tiles are planned with.
    std::function<std::size_t(const DemSource&)> halo;
    TileBytes tileBytes;    ///< of planRasterRun
    /// The product on one window of a source.
    std::function<Result(const DemSource&, const CellWindow&, const ProgressFn&)> compute;
    /// The rasters of a result, one per target, in the order of `targets`.
    std::function<std::vector<const ProductResult*>(const Result&)> parts;
    /// The rasters the command writes for one output (horizon: two).
    std::function<std::vector<RasterTarget>(const OutputOptions&)> targets;

    RasterRun plan(const DemSource& dem, const RunContext& ctx) const {
        return planRasterRun(dem, tiling, halo(dem), tileBytes, ctx);
    }
};

/// A work with its result as the list of its rasters, for a front end that handles every
/// command alike (the Python module).
using RasterWork = ProductWork<std::vector<ProductResult>>;

/// `work` with its result as its rasters.
template <class Result>
RasterWork rasterWork(const ProductWork<Result>& work) {
    RasterWork out;
    out.command = work.command;
    out.heights = work.heights;
    out.tiling = work.tiling;
    out.threads = work.threads;
    out.halo = work.halo;
    out.tileBytes = work.tileBytes;
    out.compute = [compute = work.compute, parts = work.parts](const DemSource& dem, const CellWindow& w,
                                                               const ProgressFn& p) {
        Result r = compute(dem, w, p);
        std::vector<ProductResult> rasters;
        // The parts are members of r, which is this call's own: moved out, not copied.
        for (const ProductResult* part : parts(r)) rasters.push_back(std::move(const_cast<ProductResult&>(*part)));
        return rasters;
    };
    out.parts = [](const std::vector<ProductResult>& rasters) {
        std::vector<const ProductResult*> pointers;
        for (const ProductResult& r : rasters) pointers.push_back(&r);
        return pointers;
    };
    out.targets = work.targets;
    return out;
}

/// A work whose result is one raster written to the output as it is.
template <class Result>
ProductWork<Result> singleRasterWork(std::string command, const HeightOptions& heights, const TilingOptions& tiling,
                                     int threads, std::function<std::size_t(const DemSource&)> halo,
                                     const TileBytes& tileBytes,
                                     std::function<Result(const DemSource&, const CellWindow&, const ProgressFn&)> compute) {
    ProductWork<Result> work;
    work.command = std::move(command);
    work.heights = heights;
    work.tiling = tiling;
    work.threads = threads;
    work.halo = std::move(halo);
    work.tileBytes = tileBytes;
    work.compute = std::move(compute);
    work.parts = [](const Result& r) { return std::vector<const ProductResult*>{&r}; };
    work.targets = [](const OutputOptions& out) { return std::vector<RasterTarget>{{out, {}}}; };
    return work;
}

/// Runs step(tile, progress) on each tile of `run` in order, each tile's progress its share of
/// `progress`: the tiled half of runRaster, and the driver of products that write several rasters
/// while they compute a tile (time-lapse frames through a TiledWriter).
template <class Step>
void runTiles(const RasterRun& run, const ProgressFn& progress, Step&& step) {
    for (std::size_t i = 0; i < run.tiles.size(); ++i)
        step(run.tiles[i], tileProgress(progress, i, run.tiles.size()));
}

/// runRaster on the threads of the run it is called in.
template <class Result>
Result runRasterOnThreads(const ProductWork<Result>& work, const DemSource& dem, const RasterRun& run,
                          const std::vector<RasterTarget>& targets, const RunContext& ctx, const std::string& inputPath,
                          const ProgressFn& progress, const std::function<void()>& computed) {
    if (run.tiles.size() == 1) {
        Result r = work.compute(dem, run.tiles.front(), progress);
        if (computed) computed();
        writeResults(work.parts(r), targets, ctx, inputPath);
        return r;
    }
    TiledWriter writer(run, targets, ctx, inputPath);
    std::optional<Result> first;
    runTiles(run, progress, [&](const CellWindow& tile, const ProgressFn& tileFn) {
        Result r = work.compute(dem, tile, tileFn);
        writer.write(tile, work.parts(r));
        if (!first) first = std::move(r);
    });
    if (computed) computed();
    writer.commit();
    return std::move(*first);
}

/// Runs `work` on each window of `run` with `progress` for the whole job and writes its rasters
/// to `targets`: in one piece as writeResult does, in tiles through a TiledWriter; `computed` is
/// called once every tile is computed, before the last write. Returns the first window's result,
/// for the command's notes.
template <class Result>
Result runRaster(const ProductWork<Result>& work, const DemSource& dem, const RasterRun& run,
                 const std::vector<RasterTarget>& targets, const RunContext& ctx, const std::string& inputPath,
                 const ProgressFn& progress, const std::function<void()>& computed = {}) {
    // The run's threads, entered once: every tile's product and loop runs on them.
    return withThreads(work.threads, [&] {
        return runRasterOnThreads(work, dem, run, targets, ctx, inputPath, progress, computed);
    });
}

/// Every band of `part` pasted into `into` at (col0, row0) (cells of `into`).
void pasteResult(ProductResult& into, const ProductResult& part, std::size_t col0, std::size_t row0);

/// `work` on its extent in the tiles `run` plans, pasted into one result per output raster:
/// what the command writes, held in memory.
std::vector<ProductResult> computeRaster(const RasterWork& work, const DemSource& dem, const RasterRun& run,
                                         const ProgressFn& progress);

/// What `demlight info --json` prints of `source` opened from `path`: one JSON object, as text
/// (indented by `indent` spaces; -1: on one line).
std::string infoJson(const std::string& path, const DemSource& source, int indent = -1);

}  // namespace demlight
