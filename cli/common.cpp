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

}  // namespace

RunContext runContext(const CliContext& ctx) {
    RunContext run;
    run.commandLine = ctx.commandLine;
    if (!ctx.quiet) run.notes = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
    run.cancelled = [] { return cancelRequested(); };
    return run;
}

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

void addDemArgument(CLI::App* cmd, DemOptions& o) { addDemArgument(cmd, o.path, o.heights); }

void addDemArgument(CLI::App* cmd, std::string& path, HeightOptions& heights) {
    cmd->add_option("DEM", path, "Input DEM: any raster GDAL opens, /vsizip/ and other virtual paths included")
        ->required();
    CLI::Option* zUnit = cmd->add_option("--z-unit", heights.zUnit,
                                         "Vertical unit of the heights instead of the band's own (m, ft, US survey "
                                         "foot, cm, dm, mm, km)");
    CLI::Option* zFactor = cmd->add_option("--z-factor", heights.zFactor,
                                           "Metres per height unit (after the band's scale and offset), instead of "
                                           "converting a unit")
                               ->check(finiteRange(0, kUnbounded, /*lowOpen=*/true));
    zUnit->excludes(zFactor);
}

DemSource openDem(const DemOptions& o, const CliContext& ctx) { return openDem(o.path, o.heights, ctx); }

DemSource openDem(const std::string& path, const HeightOptions& heights, const CliContext& ctx) {
    ProgressBar bar(!ctx.quiet);
    DemSource source = DemSource::open(path, heights, bar.callback());
    bar.finish();
    return source;
}

void addSearchOptions(CLI::App* cmd, SearchOptions& o) { addSearchOptions(cmd, o.request, o.verbose); }

void addSearchOptions(CLI::App* cmd, SearchRequest& r, bool& verbose) {
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
    cmd->add_flag("-v,--verbose", verbose, "Print the modelling choices (the scene plan)");
}

void notePlan(const SearchOptions& o, const Terrain& terrain, const CliContext& ctx) {
    notePlan(o.request, o.verbose, terrain, ctx);
}

void notePlan(const SearchRequest& request, bool verbose, const Terrain& terrain, const CliContext& ctx) {
    const ScenePlan plan = planFor(request, terrain);
    if (plan.quality == Quality::Full && request.toleranceDeg != kDefaultToleranceDeg)
        note(ctx, "note: --tolerance is not used by --quality full (every effect at its finest setting)");
    if (verbose && !ctx.quiet) {
        note(ctx, "scene plan (--quality " + std::string(qualityName(plan.quality)) + "):");
        for (const auto& r : plan.reasons) note(ctx, "  " + r);
        note(ctx, "  expected horizon error: " + describeExpectedError(plan.expectedError));
    }
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

void addColorRasterOptions(CLI::App* cmd, std::string& path, std::string& encoding, const std::string& use) {
    cmd->add_option("--color-raster", path,
                    "Colour raster (R, G, B bands, or one grey band), resampled onto the DEM: " + use);
    cmd->add_option("--color-encoding", encoding,
                    "How --color-raster holds colour: srgb (display-encoded 0-255 or 0-1, decoded with gamma "
                    "2.2), linear (albedo 0-1), or auto (srgb when any value exceeds 1, else linear)")
        ->check(CLI::IsMember({"auto", "srgb", "linear"}))
        ->capture_default_str();
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
