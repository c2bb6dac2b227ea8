#include "demlight/run/runner.h"

#include "demlight/geo/output_file.h"
#include "demlight/products/info.h"
#include "demlight/core/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace demlight {

namespace fs = std::filesystem;

namespace {

/// Megabytes as a whole number (rounded up: a limit named must be enough).
std::string wholeMegabytes(double megabytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", std::ceil(megabytes));
    return text;
}

/// A number as a stream prints it (six significant digits), as the option was echoed.
std::string streamed(double value) {
    std::ostringstream s;
    s << value;
    return s.str();
}

}  // namespace

std::map<std::string, std::string> resultMetadata(const ProductResult& result, const RunContext& ctx,
                                                  const std::map<std::string, std::string>& extra) {
    std::map<std::string, std::string> metadata = result.metadata;
    metadata["DEMLIGHT_COMMAND"] = ctx.commandLine;
    for (const auto& [k, v] : extra) metadata[k] = v;
    return metadata;
}

void writeResult(const ProductResult& result, const OutputOptions& out, const RunContext& ctx,
                 const std::string& inputPath, const std::map<std::string, std::string>& extra) {
    WriteOptions w;
    w.format = out.format;
    w.creationOptions = out.creationOptions;
    w.fixedPoint = out.fixedPoint;
    w.nodata = result.flagNodata.value_or(result.nodata);
    w.metadata = resultMetadata(result, ctx, extra);
    // Ctrl-C while writing stops the write (its temporary file removed) like any other work;
    // nothing is drawn, so the notes stay as they are.
    w.progress = [&ctx](double, const std::string&) { return !(ctx.cancelled && ctx.cancelled()); };
    std::vector<OutputBand> bands;
    for (const ProductBand& b : result.bands)
        bands.push_back({b.values.empty() ? nullptr : &b.values, b.values.empty() ? &b.flags : nullptr, b.name, b.unit,
                         b.resampling});
    writeRaster(out.path, bands, result.ref, w, inputPath);
}

RasterRun planRasterRun(const DemSource& dem, const TilingOptions& tiling, std::size_t halo,
                        const TileBytes& bytes, const RunContext& ctx) {
    RasterRun run;
    run.extent = dem.whole();
    if (!tiling.srcwin.empty()) {
        const auto& s = tiling.srcwin;
        if (s[2] == 0 || s[3] == 0 || s[0] >= dem.width() || s[1] >= dem.height() || s[2] > dem.width() - s[0] ||
            s[3] > dem.height() - s[1])
            throw ParameterError("{srcwin} " + std::to_string(s[0]) + " " + std::to_string(s[1]) + " " + std::to_string(s[2]) +
                        " " + std::to_string(s[3]) + ": the window must be non-empty and inside the " +
                        std::to_string(dem.width()) + " x " + std::to_string(dem.height()) + " DEM");
        run.extent = {s[0], s[1], s[0] + s[2], s[1] + s[3]};
    }
    TileShape tile;
    run.haloCells = halo;
    const double limit = tiling.memoryLimitMB > 0 ? tiling.memoryLimitMB * 1e6 : defaultMemoryLimitBytes();
    setRasterCacheBytes(rasterCacheBytes(limit));  // streamed outputs' blocks count in the budget
    if (tiling.tileSize == "auto") {
        const TilePlan plan = automaticTiles(run.extent, dem.width(), dem.height(), halo, bytes, tileMemoryBytes(limit));
        // The limit is the process's peak: the opening pass (done by now) and the tiles must
        // each fit. Holding it being impossible, say which limit would do rather than exceed it.
        const double openingBytes = kProcessBytes + dem.passBytes();
        if (plan.shape.cols == 0 || limit < openingBytes) {
            const std::string need =
                wholeMegabytes(std::max(openingBytes, memoryBudgetFor(plan.smallestTileBytes)) / 1e6);
            const std::string given = tiling.memoryLimitMB > 0
                                          ? "{memory_limit} " + streamed(tiling.memoryLimitMB) + " MB"
                                          : "the default {memory_limit} (half of this machine's memory, " +
                                                wholeMegabytes(limit / 1e6) + " MB)";
            throw ParameterError(given + " is less than this command needs on this " + std::to_string(dem.width()) + " x " +
                        std::to_string(dem.height()) + " DEM: at least " + need +
                        " MB (the program, its pass over the DEM's heights, GDAL's block cache, and the smallest "
                        "tile with its halo of " +
                        std::to_string(halo) + " cells); give {memory_limit} " + need +
                        " or more, or a shorter {max_distance}");
        }
        tile = plan.shape;
    } else {
        std::size_t used = 0;
        unsigned long long n = 0;
        try {
            n = std::stoull(tiling.tileSize, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != tiling.tileSize.size() || n < 16 || n > 1000000)
            throw ParameterError("{tile_size} '" + tiling.tileSize + "': expected auto or a whole number of cells from 16 to 1000000");
        tile = {static_cast<std::size_t>(n), static_cast<std::size_t>(n)};
    }
    run.ref = dem.geometry().band.ref;
    run.ref.geoTransform[0] += static_cast<double>(run.extent.col0) * run.ref.geoTransform[1];
    run.ref.geoTransform[3] += static_cast<double>(run.extent.row0) * run.ref.geoTransform[5];
    run.tiles = tilesOf(run.extent, tile);
    if (run.tiles.size() > 1) {
        ctx.note("computing in " + std::to_string(run.tiles.size()) + " tiles of up to " + std::to_string(tile.cols) +
                      " x " + std::to_string(tile.rows) + " cells, each with a halo of " + std::to_string(halo) + " cells");
        if (halo >= std::max(dem.width(), dem.height()))
            ctx.note("note: the search reaches across the whole DEM, so every tile reads and sweeps all of it: tiles "
                      "then bound the output's memory only and multiply the time; a shorter search distance than the "
                      "DEM makes tiles cheap");
    }
    return run;
}

TiledWriter::TiledWriter(const RasterRun& run, std::vector<RasterTarget> targets, RunContext ctx,
                         std::string inputPath)
    : run_(run), targets_(std::move(targets)), ctx_(std::move(ctx)), inputPath_(std::move(inputPath)) {}

TiledWriter::~TiledWriter() = default;

void TiledWriter::write(const CellWindow& tile, const std::vector<const ProductResult*>& parts) {
    for (std::size_t k = 0; k < targets_.size(); ++k) write(k, tile, *parts[k]);
}

void TiledWriter::write(std::size_t target, const CellWindow& tile, const ProductResult& part) {
    sinks_.resize(targets_.size());
    std::unique_ptr<RasterSink>& sink = sinks_[target];
    if (!sink) {
        WriteOptions w;
        w.format = targets_[target].out.format;
        w.creationOptions = targets_[target].out.creationOptions;
        w.fixedPoint = targets_[target].out.fixedPoint;
        w.nodata = part.flagNodata.value_or(part.nodata);
        w.metadata = resultMetadata(part, ctx_, targets_[target].extra);
        sink = std::make_unique<RasterSink>(targets_[target].out.path, run_.extent.col1 - run_.extent.col0,
                                            run_.extent.row1 - run_.extent.row0, run_.ref, w, inputPath_);
    }
    const CellWindow at{tile.col0 - run_.extent.col0, tile.row0 - run_.extent.row0, tile.col1 - run_.extent.col0,
                        tile.row1 - run_.extent.row0};
    std::vector<OutputBand> bands;
    for (const ProductBand& b : part.bands)
        bands.push_back({b.values.empty() ? nullptr : &b.values, b.values.empty() ? &b.flags : nullptr, b.name, b.unit,
                         b.resampling});
    sink->write(at, bands);
}

void TiledWriter::setMetadata(std::size_t target, const std::map<std::string, std::string>& items) {
    if (target >= sinks_.size() || !sinks_[target]) throw Error("internal: metadata for an output not yet written");
    for (const auto& [key, value] : items) sinks_[target]->setMetadata(key, value);
}

void TiledWriter::commit() {
    for (std::size_t k = 0; k < sinks_.size(); ++k) {
        try {
            if (!sinks_[k]) throw Error("internal: nothing was written to '" + targets_[k].out.path + "'");
            sinks_[k]->commit();
        } catch (const Error&) {
            removeOutputs(targets_, k);  // a product's rasters are all written or none
            throw;
        }
    }
}

void removeOutputs(const std::vector<RasterTarget>& targets, std::size_t count) {
    std::error_code ec;
    for (std::size_t k = 0; k < count && k < targets.size(); ++k) std::filesystem::remove(targets[k].out.path, ec);
}

void writeResults(const std::vector<const ProductResult*>& rasters, const std::vector<RasterTarget>& targets,
                  const RunContext& ctx, const std::string& inputPath) {
    if (rasters.size() != targets.size())
        throw Error("the result has " + std::to_string(rasters.size()) + " rasters, the command writes " +
                    std::to_string(targets.size()));
    for (std::size_t k = 0; k < targets.size(); ++k) {
        try {
            writeResult(*rasters[k], targets[k].out, ctx, inputPath, targets[k].extra);
        } catch (const Error&) {
            removeOutputs(targets, k);  // a product's rasters are all written or none
            throw;
        }
    }
}

void checkOutputPath(const std::string& outPath, const std::string& inputPath) {
    if (outPath.empty()) throw ParameterError("{output}: the output path is empty");
    // Before anything touches the folder: a device's folder (/dev) gets no probe file either.
    checkOutputFile(outPath);
    checkNotInput(outPath, inputPath);
    // Probe that the folder accepts new files, so a long computation does not end in failure.
    checkFolderAcceptsFiles(fs::absolute(fs::path(outPath)).parent_path().string(), outPath);
}

void checkOutputPath(const OutputOptions& out, const std::string& inputPath) {
    checkOutputPath(out.path, inputPath);
    checkRasterPath(out.path);
}

void pasteResult(ProductResult& into, const ProductResult& part, std::size_t col0, std::size_t row0) {
    for (std::size_t k = 0; k < part.bands.size(); ++k) {
        const ProductBand& from = part.bands[k];
        ProductBand& to = into.bands[k];
        const std::size_t cols = from.values.empty() ? from.flags.width() : from.values.width();
        const std::size_t rows = from.values.empty() ? from.flags.height() : from.values.height();
        for (std::size_t r = 0; r < rows; ++r) {
            if (from.values.empty())
                std::copy_n(&from.flags(0, r), cols, &to.flags(col0, row0 + r));
            else
                std::copy_n(&from.values(0, r), cols, &to.values(col0, row0 + r));
        }
    }
}

namespace {

std::vector<ProductResult> computeRasterOnThreads(const RasterWork& work, const DemSource& dem, const RasterRun& run,
                                                  const ProgressFn& progress) {
    if (run.tiles.size() == 1) return work.compute(dem, run.tiles.front(), progress);
    std::vector<ProductResult> out;
    runTiles(run, progress, [&](const CellWindow& tile, const ProgressFn& tileFn) {
        std::vector<ProductResult> parts = work.compute(dem, tile, tileFn);
        if (out.empty()) {
            const std::size_t cols = run.extent.col1 - run.extent.col0, rows = run.extent.row1 - run.extent.row0;
            for (const ProductResult& part : parts) {
                ProductResult whole = part;
                whole.ref = run.ref;
                for (ProductBand& b : whole.bands) {
                    if (b.values.empty())
                        b.flags = Grid<std::uint8_t>(cols, rows);
                    else
                        b.values = Grid<float>(cols, rows);
                }
                out.push_back(std::move(whole));
            }
        }
        for (std::size_t k = 0; k < parts.size(); ++k)
            pasteResult(out[k], parts[k], tile.col0 - run.extent.col0, tile.row0 - run.extent.row0);
    });
    return out;
}

}  // namespace

std::vector<ProductResult> computeRaster(const RasterWork& work, const DemSource& dem, const RasterRun& run,
                                         const ProgressFn& progress) {
    // The run's threads, entered once for every tile.
    return withThreads(work.threads, [&] { return computeRasterOnThreads(work, dem, run, progress); });
}

namespace {

nlohmann::json infoObject(const std::string& path, const Dem& dem, const DemInfo& d) {
    const HeightTransform& z = dem.heights;
    nlohmann::json j;
    j["path"] = path;
    j["width"] = d.width;
    j["height"] = d.height;
    j["crs_name"] = dem.crs.name;
    j["epsg"] = dem.crs.epsg ? nlohmann::json(*dem.crs.epsg) : nlohmann::json(nullptr);
    j["geographic"] = dem.crs.geographic;
    j["extent"] = {{"lat_min", d.latMinDeg}, {"lat_max", d.latMaxDeg}, {"lon_min", d.lonMinDeg}, {"lon_max", d.lonMaxDeg}};
    nlohmann::json cells = nlohmann::json::object();
    for (const auto& r : d.rows)
        cells[r.name] = {{"row", r.row}, {"latitude_deg", r.latitudeDeg}, {"x_m", r.cellWidthM}, {"y_m", r.cellHeightM}};
    j["cell_size_m"] = cells;
    j["elevation_min_m"] = d.elevationMinM;
    j["elevation_max_m"] = d.elevationMaxM;
    j["relief_m"] = d.reliefM;
    j["nodata_fraction"] = d.nodataFraction;
    j["nodata_value"] = dem.band.nodata ? nlohmann::json(*dem.band.nodata) : nlohmann::json(nullptr);
    j["height_scale"] = z.scale;
    j["height_offset"] = z.offset;
    j["height_unit"] = z.unit;
    j["height_to_metres"] = z.toMetres;
    j["height_source"] = z.source;
    j["convergence_deg"] = d.convergenceDeg
                               ? nlohmann::json{{"min", d.convergenceDeg->first}, {"max", d.convergenceDeg->second}}
                               : nlohmann::json(nullptr);
    j["longest_shadow_m_at_5deg"] = d.longestShadowM;
    return j;
}

}  // namespace

std::string infoJson(const std::string& path, const DemSource& source, int indent) {
    return infoObject(path, source.geometry(), describeDem(source)).dump(indent);
}

}  // namespace demlight
