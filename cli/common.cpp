#include "cli/common.h"

#include "lighting/directions.h"
#include "lighting/sky.h"
#include "src/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <strings.h>
#include <sstream>
#include <unistd.h>
#include <utility>

namespace demlight::cli {

namespace fs = std::filesystem;

/// Input nodata values at least this large in magnitude are carried into outputs.
constexpr double kCarriedNodataMagnitude = 10000.0;

/// A range check that also rejects NaN and infinities (CLI::Range lets NaN through). lowOpen: lo
/// excluded. An infinite hi is no upper bound: "NUMBER > lo" (CLI::PositiveNumber would print
/// DBL_MAX in full as its upper end).
CLI::Validator finiteRange(double lo, double hi, bool lowOpen) {
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
CLI::Validator positiveNumber() { return finiteRange(0, kUnbounded, /*lowOpen=*/true); }
CLI::Validator nonNegativeNumber() { return finiteRange(0, kUnbounded); }

}  // namespace

void addOutputOptions(CLI::App* cmd, OutputOptions& o) {
    cmd->add_option("-o,--output", o.path, "Output raster path")->required();
    cmd->add_option("--of", o.format, "Output format (also -of): GTiff (tiled, ZSTD level 1, band-interleaved) or COG (DEFLATE)")
        ->transform(
            [](std::string s) -> std::string {
                if (strcasecmp(s.c_str(), "GTiff") == 0) return "GTiff";
                if (strcasecmp(s.c_str(), "COG") == 0) return "COG";
                throw CLI::ValidationError("must be GTiff or COG, got '" + s + "'");
            },
            "{GTiff,COG}");
    cmd->add_option("--co", o.creationOptions,
                    "GDAL creation option KEY=VALUE (also -co; repeatable), e.g. -co COMPRESS=DEFLATE for readers without ZSTD");
}

void addSearchOptions(CLI::App* cmd, SearchOptions& o) {
    cmd->add_option("--max-distance", o.maxDistanceM,
                    "Horizon search distance (metres). Default (--quality auto): relief / tan(2 deg), "
                    "or the whole DEM when that is half its diagonal or more (sky and aperture "
                    "integrals: the whole DEM unless a range limit saves sweep work); full: the whole DEM")
        ->check(positiveNumber());
    cmd->add_option("--refraction", o.refraction,
                    "Refraction coefficient k for terrain sight lines; earth radius R/(1-k); "
                    "0 = pure geometry")
        ->check(finiteRange(0.0, 0.99))
        ->capture_default_str();
    cmd->add_option("--threads", o.threads, "Worker threads (0 = all cores)")
        ->check(nonNegativeNumber())
        ->capture_default_str();
    cmd->add_option("--quality", o.quality,
                    "auto: model only what the scene needs within --tolerance; full: every effect "
                    "at its finest setting")
        ->check(CLI::IsMember({"auto", "full"}))
        ->capture_default_str();
    cmd->add_option("--tolerance", o.toleranceDeg,
                    "Horizon error budget for --quality auto (degrees): decides curvature and the "
                    "scan-direction tolerance; a looser one is added to the stated error")
        ->check(finiteRange(0.001, 10.0))
        ->capture_default_str();
    cmd->add_flag("-v,--verbose", o.verbose, "Print the modelling choices (the scene plan)");
}

ScenePlan planFor(const SearchOptions& o, const Terrain& terrain, double lowestElevationDeg,
                  const CliContext& ctx) {
    QualityBudget budget;
    budget.toleranceDeg = o.toleranceDeg;
    budget.lowestElevationDeg = lowestElevationDeg;
    budget.refraction = o.refraction;
    budget.maxDistanceM = o.maxDistanceM.value_or(0.0);
    const ScenePlan plan = planScene(terrain, parseQuality(o.quality), budget);
    if (plan.quality == Quality::Full && o.toleranceDeg != kDefaultToleranceDeg)
        note(ctx, "note: --tolerance is not used by --quality full (every effect at its finest setting)");
    if (o.verbose && !ctx.quiet) {
        note(ctx, "scene plan (--quality " + o.quality + "):");
        for (const auto& r : plan.reasons) note(ctx, "  " + r);
        note(ctx, "  expected horizon error: " + describeExpectedError(plan.expectedError));
    }
    return plan;
}

HorizonParams horizonParams(const SearchOptions& o, const ScenePlan& plan) {
    return planHorizonParams(plan, o.refraction, o.threads);
}

HorizonParams integralParams(const SearchOptions& o, const ScenePlan& plan, const Terrain& terrain,
                             std::size_t directions) {
    return planIntegralParams(terrain, plan, directions, o.refraction, o.threads);
}

SunFrameParams sunFrameParams(const SearchOptions& o, double sunDiameterDeg) {
    SunFrameParams p;
    p.sunDiameterDeg = sunDiameterDeg;
    p.refraction = o.refraction;
    p.threads = o.threads;
    p.maxDistanceM = o.maxDistanceM.value_or(0.0);
    return p;
}

SunFrameParams sunFrameParams(const SearchOptions& o, double sunDiameterDeg, const ScenePlan& plan) {
    SunFrameParams p = planSunFrameParams(plan, sunDiameterDeg, o.refraction, o.threads);
    if (o.maxDistanceM) p.maxDistanceM = *o.maxDistanceM;
    return p;
}

Grid<float> planSkyLight(const Terrain& terrain, const Normals& normals, std::size_t directions,
                         const HorizonParams& params, ProgressCounter* progress) {
    SkyAccumulator acc(normals.east, normals.north, normals.up, directions, {}, params.threads);
    sweepDirections(terrain, params, directions,
                    [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); }, progress);
    return std::move(acc).finish(0.0).skyK;
}

std::map<std::string, std::string> planMetadata(const ScenePlan& plan) {
    std::string reasons;
    for (const auto& r : plan.reasons) reasons += (reasons.empty() ? "" : "; ") + r;
    return {{"DEMLIGHT_QUALITY", std::string(qualityName(plan.quality))},
            {"DEMLIGHT_PLAN", reasons},
            {"DEMLIGHT_CURVATURE", plan.curvature ? "on" : "off"},
            {"DEMLIGHT_EXPECTED_ERROR_DEG", describeExpectedError(plan.expectedError)}};
}

double outputNodata(const Dem& dem) {
    if (dem.band.nodata) {
        const double v = *dem.band.nodata;
        if (std::isnan(v) ||
            (std::abs(v) >= kCarriedNodataMagnitude && std::abs(v) <= 3.4028235e38))
            return v;
    }
    return std::numeric_limits<double>::quiet_NaN();
}

WriteOptions makeWriteOptions(const OutputOptions& out, const CliContext& ctx, const Dem& dem,
                              const std::map<std::string, std::string>& extra) {
    WriteOptions w;
    w.format = out.format;
    w.creationOptions = out.creationOptions;
    w.nodata = outputNodata(dem);
    w.metadata["DEMLIGHT_VERSION"] = DEMLIGHT_VERSION;
    w.metadata["DEMLIGHT_COMMAND"] = ctx.commandLine;
    w.metadata["DEMLIGHT_INPUT"] = dem.band.path;
    for (const auto& [k, v] : extra) w.metadata[k] = v;
    return w;
}

void checkOutputPath(const std::string& outPath, const std::string& inputPath) {
    std::error_code ec;
    if (fs::exists(outPath, ec) && fs::equivalent(outPath, inputPath, ec))
        throw Error("output '" + outPath + "' would overwrite the input DEM; choose another -o");
    if (fs::is_directory(outPath, ec))
        throw Error("cannot write '" + outPath + "': it is a directory");
    const fs::path parent = fs::absolute(fs::path(outPath)).parent_path();
    if (!fs::is_directory(parent, ec))
        throw Error("cannot write '" + outPath + "': folder '" + parent.string() +
                    "' does not exist");
    // Probe that the folder accepts new files, so a long computation does not end in failure.
    const fs::path probe = parent / (".demlight-probe-" + std::to_string(::getpid()));
    if (std::FILE* f = std::fopen(probe.c_str(), "w")) {
        std::fclose(f);
        fs::remove(probe, ec);
    } else {
        throw Error("cannot write '" + outPath + "': folder '" + parent.string() +
                    "' is not writable");
    }
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string formatSeconds(double seconds) {
    // Below a tenth of a second, milliseconds (small DEMs would print "0 s").
    if (seconds < 0.1) return formatNumber(std::round(seconds * 1e4) / 10) + " ms";
    return formatNumber(std::round(seconds * 100) / 100) + " s";
}

std::string formatDistance(double metres) {
    return std::isfinite(metres) ? formatNumber(std::round(metres)) + " m" : std::string("the whole DEM");
}

std::string metadataDistanceM(const Terrain& terrain, double metres) {
    return formatNumber(std::round(std::isfinite(metres) ? metres : diagonalM(terrain)));
}

std::string formatNumber(double value) {
    std::ostringstream s;
    s.precision(10);
    s << value;
    return s.str();
}

void note(const CliContext& ctx, const std::string& line) {
    if (!ctx.quiet) std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace demlight::cli
