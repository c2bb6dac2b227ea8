// Options and helpers shared by the raster-producing subcommands.
#pragma once

#include "cli/commands.h"
#include "geo/dem.h"
#include "geo/raster.h"
#include "lighting/horizon.h"
#include "lighting/quality.h"
#include "lighting/sun_frame.h"
#include "lighting/surface.h"

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace demlight::cli {

/// -o, -of, -co: where and how an output raster is written.
struct OutputOptions {
    std::string path;
    std::string format = "GTiff";
    std::vector<std::string> creationOptions;
};
void addOutputOptions(CLI::App* cmd, OutputOptions& o);

/// Search options shared by everything that computes horizons.
struct SearchOptions {
    std::optional<double> maxDistanceM;
    double refraction = 0.13;
    int threads = 0;
    std::string quality = "auto";
    double toleranceDeg = kDefaultToleranceDeg;
    bool verbose = false;
};
void addSearchOptions(CLI::App* cmd, SearchOptions& o);

/// The scene plan (lighting/quality.h) for these options, with the user's explicit
/// --max-distance taking precedence; printed with --verbose. `lowestElevationDeg` is the lowest
/// sun or sky elevation whose shadows matter for the command.
ScenePlan planFor(const SearchOptions& o, const Terrain& terrain, double lowestElevationDeg,
                  const CliContext& ctx);

/// HorizonParams from a plan: distance, curvature, refraction, direction tolerance, threads.
HorizonParams horizonParams(const SearchOptions& o, const ScenePlan& plan);
/// horizonParams() for the sweeps of sky and aperture integrals (planIntegralParams).
HorizonParams integralParams(const SearchOptions& o, const ScenePlan& plan, const Terrain& terrain,
                             std::size_t directions);

/// Parameters of a sun frame (lighting/sun_frame.h) from the search options: --max-distance
/// when given, else 0 (the distance this sun needs).
SunFrameParams sunFrameParams(const SearchOptions& o, double sunDiameterDeg);

/// The same with the plan's distance: --max-distance when given; with --quality full the plan's
/// (the DEM diagonal); with auto 0, the distance this sun needs (sunSearchDistanceM).
SunFrameParams sunFrameParams(const SearchOptions& o, double sunDiameterDeg, const ScenePlan& plan);

/// Sky light K of the preview rig (lighting/preview.h) from `directions` evenly spaced sweeps
/// with `params` (the plan's distance, curvature and direction tolerance). NaN at nodata.
Grid<float> planSkyLight(const Terrain& terrain, const Normals& normals, std::size_t directions,
                         const HorizonParams& params, ProgressCounter* progress);

/// Metadata items recording the plan (DEMLIGHT_QUALITY, DEMLIGHT_PLAN, DEMLIGHT_CURVATURE) and
/// its expected horizon error against the reference (DEMLIGHT_EXPECTED_ERROR_DEG, measured
/// figures cited in lighting/quality.cpp).
std::map<std::string, std::string> planMetadata(const ScenePlan& plan);

/// The nodata value written for nodata cells of Float32 outputs: the input's own value when it
/// cannot be mistaken for a result (NaN, or magnitude >= 10000, e.g. -32768, 65535, -3.4e38),
/// otherwise NaN (an input nodata of 0 would collide with a visibility of 0).
double outputNodata(const Dem& dem);

/// Dataset metadata every output carries: version, command line, input, plus `extra`.
WriteOptions makeWriteOptions(const OutputOptions& out, const CliContext& ctx, const Dem& dem,
                              const std::map<std::string, std::string>& extra);

/// Fails early (before any work) if the output cannot be written or would replace the input.
void checkOutputPath(const std::string& outPath, const std::string& inputPath);

/// Shortest decimal form of a number for metadata and band names ("37.5", "0.13").
std::string formatNumber(double value);

/// A search distance for notes: "N m" (rounded), or "the whole DEM" when infinite.
std::string formatDistance(double metres);
/// A range check that also rejects NaN and infinities (CLI::Range lets NaN through). lowOpen:
/// lo excluded.
CLI::Validator finiteRange(double lo, double hi, bool lowOpen = false);
/// SPA's stated pressure limit (hPa; Reda & Andreas, Table 1); 0 = no atmospheric refraction.
inline constexpr double kMaxPressureHpa = 5000;
/// A search distance for metadata, always a number (metres): the DEM diagonal for the whole
/// DEM (an infinite distance), which is the same search.
std::string metadataDistanceM(const Terrain& terrain, double metres);

/// Seconds elapsed since `start` (steady clock), for the time notes of the commands.
double secondsSince(std::chrono::steady_clock::time_point start);

/// A duration for notes, rounded to hundredths of a second ("1.23 s").
std::string formatSeconds(double seconds);

/// Prints a line to stderr unless quiet.
void note(const CliContext& ctx, const std::string& line);

}  // namespace demlight::cli
