#include "cli/common.h"

#include "cli/progress_bar.h"
#include "demlight/geo/output_file.h"
#include "demlight/geo/time.h"
#include "demlight/core/error.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <strings.h>
#include <unistd.h>

namespace demlight::cli {

namespace fs = std::filesystem;

CLI::Validator finiteRange(double lo, double hi, bool lowOpen) {
    // An infinite hi is no upper bound: "NUMBER > lo" (CLI::PositiveNumber would print DBL_MAX).
    const bool bounded = std::isfinite(hi);
    const std::string description =
        bounded ? std::string(lowOpen ? "(" : "[") + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]"
                : std::string(lowOpen ? "NUMBER > " : "NUMBER >= ") + CLI::detail::to_string(lo);
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            double v = 0;
            if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v))
                return "expected a finite number, got '" + text + "'";
            if (!(v < lo || v > hi || (lowOpen && v == lo))) return {};
            return bounded ? "value " + text + " is outside " + description
                           : std::string("must be ") + (lowOpen ? "> " : ">= ") + CLI::detail::to_string(lo) +
                                 ", got " + text;
        },
        description);
}

namespace {

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

/// Megabytes as a whole number (rounded up: a limit named must be enough).
std::string wholeMegabytes(double megabytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", std::ceil(megabytes));
    return text;
}

}  // namespace

void addOutputOptions(CLI::App* cmd, OutputOptions& o) {
    cmd->add_option("-o,--output", o.path, "Output raster path")->required()->type_name("OUT.tif");
    cmd->add_option("--of", o.format, "Output format (also -of): GTiff (tiled, ZSTD level 1, band-interleaved) or COG (DEFLATE)")
        ->transform(
            [](std::string s) -> std::string {
                if (strcasecmp(s.c_str(), "GTiff") == 0) return "GTiff";
                if (strcasecmp(s.c_str(), "COG") == 0) return "COG";
                throw CLI::ValidationError("must be GTiff or COG, got '" + s + "'");
            },
            "{GTiff,COG}");
    cmd->add_option("--co", o.creationOptions,
                    "GDAL creation option KEY=VALUE (also -co; repeatable), e.g. -co COMPRESS=DEFLATE for readers "
                    "without ZSTD; block sides (BLOCKXSIZE, BLOCKYSIZE, BLOCKSIZE) 1 to " +
                        std::to_string(kMaxBlockSideCells) + " cells")
        ->check(CLI::Validator(
            [](std::string& option) { return blockSizeProblem(option); }, "KEY=VALUE"));
}

void addDemArgument(CLI::App* cmd, DemOptions& o) {
    cmd->add_option("DEM", o.path, "Input DEM: any raster GDAL opens, /vsizip/ and other virtual paths included")
        ->required();
    CLI::Option* zUnit = cmd->add_option("--z-unit", o.heights.zUnit,
                                         "Vertical unit of the heights instead of the band's own (m, ft, US survey "
                                         "foot, cm, dm, mm, km)");
    CLI::Option* zFactor = cmd->add_option("--z-factor", o.heights.zFactor,
                                           "Metres per height unit (after the band's scale and offset), instead of "
                                           "converting a unit")
                               ->check(finiteRange(0, kUnbounded, /*lowOpen=*/true));
    zUnit->excludes(zFactor);
}

DemSource openDem(const DemOptions& o, const CliContext& ctx) {
    try {
        ProgressBar bar(!ctx.quiet);
        DemSource source = DemSource::open(o.path, o.heights, bar.callback());
        bar.finish();
        return source;
    } catch (const Cancelled&) {
        throw;
    } catch (const Error& e) {
        throw Error(renameHeightFields(e.what(), "--z-unit", "--z-factor"));  // the user typed flags
    }
}

std::string renameHeightFields(std::string message, const std::string& zUnit, const std::string& zFactor) {
    const std::pair<std::string, const std::string&> renames[] = {{"HeightOptions::zUnit", zUnit},
                                                                  {"HeightOptions::zFactor", zFactor}};
    for (const auto& [field, name] : renames)
        for (auto at = message.find(field); at != std::string::npos; at = message.find(field, at + name.size()))
            message.replace(at, field.size(), name);
    return message;
}

void addSearchOptions(CLI::App* cmd, SearchOptions& o) {
    SearchRequest& r = o.request;
    cmd->add_option("--max-distance", r.maxDistanceM,
                    "Horizon search distance (metres). Default (--quality auto): relief / tan(2 deg), "
                    "or the whole DEM when that is half its diagonal or more (sky and aperture "
                    "integrals: the whole DEM unless a range limit saves sweep work); full: the whole DEM")
        ->check(finiteRange(0, kUnbounded, /*lowOpen=*/true));
    cmd->add_option("--refraction", r.refraction,
                    "Refraction coefficient k for terrain sight lines; earth radius R/(1-k); "
                    "0 = pure geometry")
        ->check(finiteRange(0.0, 0.99))
        ->capture_default_str();
    cmd->add_option("--threads", r.threads, "Worker threads (0 = all cores; at most the cores are used)")
        ->check(finiteRange(0, kUnbounded))
        ->capture_default_str();
    cmd->add_option_function<std::string>(
           "--quality", [&r](const std::string& name) { r.quality = parseQuality(name); },
           "auto: model only what the scene needs within --tolerance; full: every effect at its finest setting")
        ->check(CLI::IsMember({"auto", "full"}))
        ->default_str("auto");
    cmd->add_option("--tolerance", r.toleranceDeg,
                    "Horizon error budget for --quality auto (degrees): decides curvature and the "
                    "scan-direction tolerance; a looser one is added to the stated error")
        ->check(finiteRange(0.001, 10.0))
        ->capture_default_str();
    cmd->add_option("--near-field", r.nearFieldSteps,
                    "Horizon near field (line steps, 0-32): terrain this close is sampled on the ray from "
                    "each cell's own centre, farther terrain by scan lines. Default: 16 on surface models "
                    "(buildings, trees: 5 % or more of neighbour steps steeper than 45 deg), 4 on terrain; 0 = scan lines only (the model of earlier releases)")
        ->check(finiteRange(0, kMaxNearFieldSteps));
    cmd->add_flag("-v,--verbose", o.verbose, "Print the modelling choices (the scene plan)");
}

void notePlan(const SearchOptions& o, const Terrain& terrain, const CliContext& ctx) {
    const ScenePlan plan = planFor(o.request, terrain);
    if (plan.quality == Quality::Full && o.request.toleranceDeg != kDefaultToleranceDeg)
        note(ctx, "note: --tolerance is not used by --quality full (every effect at its finest setting)");
    if (o.verbose && !ctx.quiet) {
        note(ctx, "scene plan (--quality " + std::string(qualityName(plan.quality)) + "):");
        for (const auto& r : plan.reasons) note(ctx, "  " + r);
        note(ctx, "  expected horizon error: " + describeExpectedError(plan.expectedError));
    }
}

std::map<std::string, std::string> resultMetadata(const ProductResult& result, const CliContext& ctx,
                                                  const std::map<std::string, std::string>& extra) {
    std::map<std::string, std::string> metadata = result.metadata;
    metadata["DEMLIGHT_COMMAND"] = ctx.commandLine;
    for (const auto& [k, v] : extra) metadata[k] = v;
    return metadata;
}

void writeResult(const ProductResult& result, const OutputOptions& out, const CliContext& ctx,
                 const std::string& inputPath, const std::map<std::string, std::string>& extra) {
    WriteOptions w;
    w.format = out.format;
    w.creationOptions = out.creationOptions;
    w.fixedPoint = out.fixedPoint;
    w.nodata = result.flagNodata.value_or(result.nodata);
    w.metadata = resultMetadata(result, ctx, extra);
    // Ctrl-C while writing stops the write (its temporary file removed) like any other work;
    // nothing is drawn, so the notes stay as they are.
    w.progress = [](double, const std::string&) { return !cancelRequested(); };
    std::vector<OutputBand> bands;
    for (const ProductBand& b : result.bands)
        bands.push_back({b.values.empty() ? nullptr : &b.values, b.values.empty() ? &b.flags : nullptr, b.name, b.unit,
                         b.resampling});
    writeRaster(out.path, bands, result.ref, w, inputPath);
}

void addTilingOptions(CLI::App* cmd, TilingOptions& o) {
    cmd->add_option("--tile-size", o.tileSize,
                    "Compute in tiles of N x N cells, each with the halo its search needs, writing each as it "
                    "completes; the output is bit for bit the one-piece output. auto: one piece unless that "
                    "exceeds --memory-limit")
        ->capture_default_str();
    cmd->add_option("--memory-limit", o.memoryLimitMB,
                    "Peak memory (MB) of the whole process that --tile-size auto plans for: the program, the pass "
                    "over the DEM's heights and each tile must fit; a run that cannot is refused, naming the "
                    "smallest limit that fits (default: half of this machine's memory)")
        ->check(finiteRange(16, 1e9));
    cmd->add_option("--srcwin", o.srcwin,
                    "Compute only the window XOFF YOFF XSIZE YSIZE (cells, as gdal_translate -srcwin), reading the "
                    "halo it needs; its output has the window's georeference, and windows mosaicked with "
                    "gdalbuildvrt equal the one-piece output bit for bit")
        ->expected(4)
        ->check(finiteRange(0, kUnbounded));  // before the conversion: "-5" would wrap to 2^64 - 5
}

RasterRun planRasterRun(const DemSource& dem, const TilingOptions& tiling, const SearchRequest& search,
                        const TileBytes& bytes, const CliContext& ctx) {
    RasterRun run;
    run.extent = dem.whole();
    if (!tiling.srcwin.empty()) {
        const auto& s = tiling.srcwin;
        if (s[2] == 0 || s[3] == 0 || s[0] >= dem.width() || s[1] >= dem.height() || s[2] > dem.width() - s[0] ||
            s[3] > dem.height() - s[1])
            throw Error("--srcwin " + std::to_string(s[0]) + " " + std::to_string(s[1]) + " " + std::to_string(s[2]) +
                        " " + std::to_string(s[3]) + ": the window must be non-empty and inside the " +
                        std::to_string(dem.width()) + " x " + std::to_string(dem.height()) + " DEM");
        run.extent = {s[0], s[1], s[0] + s[2], s[1] + s[3]};
    }
    TileShape tile;
    const std::size_t halo = haloCellsFor(dem.geometry().terrain, planFor(search, dem.geometry().terrain).maxDistanceM);
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
                                          ? "--memory-limit " + CLI::detail::to_string(tiling.memoryLimitMB) + " MB"
                                          : "the default --memory-limit (half of this machine's memory, " +
                                                wholeMegabytes(limit / 1e6) + " MB)";
            throw Error(given + " is less than this command needs on this " + std::to_string(dem.width()) + " x " +
                        std::to_string(dem.height()) + " DEM: at least " + need +
                        " MB (the program, its pass over the DEM's heights, GDAL's block cache, and the smallest "
                        "tile with its halo of " +
                        std::to_string(halo) + " cells); give --memory-limit " + need +
                        " or more, or a shorter --max-distance");
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
            throw Error("--tile-size '" + tiling.tileSize + "': expected auto or a whole number of cells from 16 to 1000000");
        tile = {static_cast<std::size_t>(n), static_cast<std::size_t>(n)};
    }
    run.ref = dem.geometry().band.ref;
    run.ref.geoTransform[0] += static_cast<double>(run.extent.col0) * run.ref.geoTransform[1];
    run.ref.geoTransform[3] += static_cast<double>(run.extent.row0) * run.ref.geoTransform[5];
    run.tiles = tilesOf(run.extent, tile);
    if (run.tiles.size() > 1) {
        note(ctx, "computing in " + std::to_string(run.tiles.size()) + " tiles of up to " + std::to_string(tile.cols) +
                      " x " + std::to_string(tile.rows) + " cells, each with a halo of " + std::to_string(halo) + " cells");
        if (halo >= std::max(dem.width(), dem.height()))
            note(ctx, "note: the search reaches across the whole DEM, so every tile reads and sweeps all of it: tiles "
                      "then bound the output's memory only and multiply the time; a --max-distance shorter than the "
                      "DEM makes tiles cheap");
    }
    return run;
}

TiledWriter::TiledWriter(const RasterRun& run, std::vector<RasterTarget> targets, const CliContext& ctx,
                         std::string inputPath)
    : run_(run), targets_(std::move(targets)), ctx_(ctx), inputPath_(std::move(inputPath)) {}

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

std::string flagForField(const std::string& field) {
    // One meaning per option name across commands, so one table for all of them.
    static const std::map<std::string, std::string> flags = {
        {"albedo", "--albedo"},           {"albedoRaster", "--albedo-raster"},   {"azimuthsDeg", "--azimuth"},
        {"cloudShadow", "--cloud-shadow"}, {"coeffBh", "--coeff-bh"},                {"coeffDh", "--coeff-dh"},
        {"coeffBhRaster", "--coeff-bh-raster"}, {"coeffDhRaster", "--coeff-dh-raster"},
        {"colorEncoding", "--color-encoding"}, {"colorRaster", "--color-raster"}, {"diffuseModel", "--diffuse-model"},
        {"directions", "--sky-directions"}, {"exposure", "--exposure"},          {"lastDay", "--end"},
        {"elevationBandDeg", "--elevation-band"}, {"firstDay", "--start"},
        {"linke", "--linke"},             {"linkeRaster", "--linke-raster"},     {"solarConstantWm2", "--solar-constant"},
        {"maxDistanceM", "--max-distance"}, {"maxFrames", "--max-frames"},       {"pressureHpa", "--pressure"},
        {"nearFieldSteps", "--near-field"},
        {"patches", "--patches"},         {"point", "--at"},                     {"quality", "--quality"},
        {"refraction", "--refraction"},   {"skyColor", "--sky-color"},           {"skyDirections", "--sky-directions"},
        {"stackDirections", "--horizon-mode"}, {"step", "--step"},               {"sunColor", "--sun-color"},
        {"sunDiameterDeg", "--sun-diameter"}, {"temperatureC", "--temperature"}, {"threads", "--threads"},
        {"time", "--time"},               {"toleranceDeg", "--tolerance"},       {"overwrite", "--overwrite"},
        {"zone", "--tz"},                 {"canopy", "--canopy"},                {"canopyRaster", "--canopy"},
        {"transmissivity", "--transmissivity"},
    };
    const auto it = flags.find(field);
    return it == flags.end() ? field : it->second;
}

void checkOutputPath(const std::string& outPath, const std::string& inputPath) {
    if (outPath.empty()) throw Error("-o: the output path is empty");
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

std::array<double, 3> parseColor(const std::string& text, const std::string& option) {
    const auto bad = [&] { return Error(option + " '" + text + "': expected three linear values >= 0 like 1,0.9,0.8"); };
    std::array<double, 3> c{};
    std::stringstream ss(text);
    std::string part;
    std::size_t n = 0;
    while (std::getline(ss, part, ',')) {
        const std::optional<double> v = parseFiniteNumber(part);
        if (n >= 3 || !v || !(*v >= 0)) throw bad();
        c[n++] = *v;
    }
    if (n != 3) throw bad();
    return c;
}

std::chrono::milliseconds parseStepOption(const std::string& text, std::chrono::milliseconds bareUnit) {
    try {
        return parseDurationOr(text, "step", bareUnit);
    } catch (const Error& e) {
        throw Error("--" + std::string(e.what()));
    }
}

void addColorRasterOptions(CLI::App* cmd, std::string& path, std::string& encoding, const std::string& use) {
    cmd->add_option("--color-raster", path,
                    "Colour raster (R, G, B bands, or one grey band), resampled onto the DEM: " + use);
    cmd->add_option("--color-encoding", encoding,
                    "How --color-raster holds colour: srgb (display-encoded 0-255 or 0-1, decoded with gamma "
                    "2.2), linear (albedo 0-1), or auto (srgb when any value exceeds 1, else linear)")
        ->check(CLI::IsMember({"auto", "srgb", "linear"}))
        ->capture_default_str();
}

ZonedInstant parseTimeOptions(const std::string& time, const std::string& tz) {
    try {
        return parseZonedInstant(time, tz);
    } catch (const Error& e) {
        std::string m = e.what();
        for (const auto& [from, to] : {std::pair<std::string, std::string>{"or give a time zone", "or give --tz ZONE"},
                                       {"drop the offset or the zone", "drop the offset or the --tz"}})
            if (const auto at = m.find(from); at != std::string::npos) m.replace(at, from.size(), to);
        throw Error(m);
    }
}

void addTimeOptions(CLI::App* cmd, std::string& time, std::string& tz) {
    cmd->add_option("--time", time,
                    "Instant: ISO 8601 with offset or Z (2024-06-21T05:30:00+02:00), or local time with --tz")
        ->required()
        ->type_name("TIME");
    cmd->add_option("--tz", tz, "IANA time zone for a local --time (e.g. Europe/Zurich)");
}

void addDayOptions(CLI::App* cmd, DayOptions& o, const std::string& tzHelp) {
    cmd->add_option("--date", o.date, "Local day YYYY-MM-DD (midnight to midnight in --tz)");
    if (o.periods) {
        cmd->add_option("--start", o.startDate,
                        "Start of a range: a first local day YYYY-MM-DD, or a local time YYYY-MM-DDTHH:MM[:SS]");
        cmd->add_option("--end", o.endDate,
                        "End of a range: a last local day YYYY-MM-DD (inclusive), or a local time YYYY-MM-DDTHH:MM[:SS]");
        cmd->add_option("--month", o.month, "Local calendar month YYYY-MM");
        cmd->add_option("--year", o.year, "Local calendar year YYYY");
    } else {
        cmd->add_option("--start", o.startDate, "First local day YYYY-MM-DD of a range");
        cmd->add_option("--end", o.endDate, "Last local day YYYY-MM-DD of a range (inclusive)");
    }
    cmd->add_option("--tz", o.tz, tzHelp);
}

LocalDays parseDayOptions(const DayOptions& o, const std::string& command) {
    LocalDays days{{}, {}, zoneOfDays(o.tz), std::nullopt};
    const bool range = !o.startDate.empty() || !o.endDate.empty();
    const int given = int(!o.date.empty()) + int(range) + int(!o.month.empty()) + int(!o.year.empty());
    const std::string choices = o.periods ? "--date D, --start D --end D, --month YYYY-MM or --year YYYY"
                                          : "--date D, or both --start D and --end D";
    if (given > 1) throw Error(command + ": give one of " + choices + ", not several");
    if (!o.date.empty()) {
        days.first = days.last = parseDate(o.date);
    } else if (!o.month.empty()) {
        const DateRange month = parseMonth(o.month);
        days.first = month.first;
        days.last = month.last;
    } else if (!o.year.empty()) {
        const DateRange year = parseYear(o.year);
        days.first = year.first;
        days.last = year.last;
    } else if (o.startDate.empty() || o.endDate.empty()) {
        throw Error(command + ": give " + choices);
    } else if (o.periods && (o.startDate.find('T') != std::string::npos || o.endDate.find('T') != std::string::npos)) {
        const UtcInstant start = parseTimeOptions(o.startDate, o.tz).utc, end = parseTimeOptions(o.endDate, o.tz).utc;
        if (end <= start) throw Error(command + ": --end " + o.endDate + " is not after --start " + o.startDate);
        days.interval = std::pair(start, end);
        days.first = localDayOf(start, days.zone).date;
        days.last = localDayOf(end, days.zone).date;
    } else {
        days.first = parseDate(o.startDate);
        days.last = parseDate(o.endDate);
        if (days.last < days.first) throw Error(command + ": --end " + o.endDate + " is before --start " + o.startDate);
    }
    return days;
}

void addSunDiameterOption(CLI::App* cmd, double& diameterDeg) {
    cmd->add_option("--sun-diameter", diameterDeg, "Angular diameter of the sun disk (degrees); larger = softer shadows")
        ->check(finiteRange(0.0, 20.0))
        ->capture_default_str();
}

void addCanopyOptions(CLI::App* cmd, CanopyRequest& canopy) {
    cmd->add_option("--canopy", canopy.raster,
                    "Vegetation height above ground (metres, 0-150) on the DEM, a surface model with the trees on "
                    "it: where the sun's line passes only through crowns, --transmissivity of the beam gets "
                    "through (and of the sky they hide); cells under a crown are lit on the ground below it (any "
                    "raster GDAL opens, band 1, resampled bilinearly; nodata = no vegetation)")
        ->type_name("PATH");
    cmd->add_option("--transmissivity", canopy.transmissivity,
                    "Share of the light that passes through the crowns of --canopy (0-1; SOLWEIG's default)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
}

void addPictureOptions(CLI::App* cmd, PictureOptions& o) {
    addColorRasterOptions(cmd, o.colorRaster, o.colorEncoding, "the albedo of the picture");
    cmd->add_option("--albedo", o.albedo, "Linear albedo without a colour raster")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--exposure", o.exposure, "Multiplies linear light before gamma")
        ->check(finiteRange(0.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("--pixels", o.pixels,
                    "ground: square ground pixels (lat/lon DEMs are resampled east-west); cell: one pixel per DEM cell")
        ->check(CLI::IsMember({"ground", "cell"}))
        ->capture_default_str();
}

PictureRequest pictureRequest(const PictureOptions& o) {
    PictureRequest r;
    r.colorRaster = o.colorRaster;
    r.colorEncoding = parseColorEncoding(o.colorEncoding, "--color-encoding");
    r.albedo = o.albedo;
    r.exposure = o.exposure;
    r.pixels = o.pixels == "cell" ? PixelGeometry::Cell : PixelGeometry::Ground;
    return r;
}

std::optional<double> parseFiniteNumber(const std::string& text, bool trailingSpaces) {
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    while (trailingSpaces && used < text.size() && text[used] == ' ') ++used;
    if (used == 0 || used != text.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::string formatSeconds(double seconds) {
    // Below a tenth of a second, milliseconds (small DEMs would print "0 s").
    if (seconds < 0.1) return formatNumber(std::round(seconds * 1e4) / 10) + " ms";
    return formatNumber(std::round(seconds * 100) / 100) + " s";
}

std::string formatDistance(double metres) {
    return std::isfinite(metres) ? formatNumber(std::round(metres)) + " m" : std::string("the whole DEM");
}

void note(const CliContext& ctx, const std::string& line) {
    if (!ctx.quiet) std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace demlight::cli
