// demlight horizon DEM -o OUT.tif (--azimuth DEG... | --directions N): horizon angle maps.
//
// Output: one Float32 band per azimuth, the horizon elevation angle in degrees, described as
// "horizon_azimuth=<deg>". The truncation mask goes to a sidecar GeoTIFF next to the output,
// OUT.truncated.tif: one Byte band per azimuth ("truncated_azimuth=<deg>"), 1 where the search
// reached the DEM edge before --max-distance.
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "lighting/horizon.h"
#include "src/angles.h"
#include "src/error.h"

#include <chrono>
#include <filesystem>

namespace demlight::cli {
namespace {

/// Truncation mask value at DEM voids (declared as the mask's nodata).
constexpr std::uint8_t kMaskNodata = 255;

struct HorizonOptions {
    std::string demPath;
    OutputOptions out;
    SearchOptions search;
    std::vector<double> azimuthsDeg;
    int directions = 0;
    std::string method = "sweep";
};

std::string truncationPath(const std::string& outPath) {
    std::filesystem::path p(outPath);
    return (p.parent_path() / (p.stem().string() + ".truncated.tif")).string();
}

void runHorizon(const HorizonOptions& o, const CliContext& ctx) {
    if (o.azimuthsDeg.empty() == (o.directions == 0))
        throw Error("give either --azimuth DEG [DEG ...] or --directions N");
    checkOutputPath(o.out.path, o.demPath);
    const Dem dem = loadDem(o.demPath);

    std::vector<double> azimuths = o.azimuthsDeg;
    for (int i = 0; i < o.directions; ++i) azimuths.push_back(360.0 * i / o.directions);

    const ScenePlan plan = planFor(o.search, dem.terrain, kDefaultLowestElevationDeg, ctx);
    HorizonParams params = horizonParams(o.search, plan);
    const bool reference = o.method == "reference";

    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), reference ? "horizon (reference)" : "horizon (sweep)",
                            azimuths.size() * dem.terrain.heightsM.size());
    const auto start = std::chrono::steady_clock::now();
    std::vector<HorizonMap> maps;
    for (double az : azimuths) {
        params.azimuthDeg = az;
        maps.push_back(reference ? referenceHorizon(dem.terrain, params, &counter)
                                 : sweepHorizon(dem.terrain, params, &counter));
    }
    bar.finish();
    const double seconds = secondsSince(start);

    std::vector<OutputBand> bands, masks;
    std::string azimuthList;
    for (std::size_t i = 0; i < azimuths.size(); ++i) {
        const std::string az = formatNumber(wrapAzimuthDeg(azimuths[i]));
        bands.push_back({&maps[i].angleDeg, nullptr, "horizon_azimuth=" + az, "deg"});
        masks.push_back({nullptr, &maps[i].truncated, "truncated_azimuth=" + az, ""});
        azimuthList += (i ? "," : "") + az;
    }
    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_PRODUCT", "horizon"},
        {"DEMLIGHT_METHOD", o.method},
        {"DEMLIGHT_AZIMUTHS_DEG", azimuthList},
        {"DEMLIGHT_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, params.maxDistanceM)},
        {"DEMLIGHT_REFRACTION", formatNumber(params.refraction)},
        {"DEMLIGHT_TRUNCATION_MASK", truncationPath(o.out.path)},
    });
    WriteOptions wo = makeWriteOptions(o.out, ctx, dem, meta);
    writeRaster(o.out.path, bands, dem.band.ref, wo, o.demPath);
    // The mask says nothing at DEM voids: 255 there, declared as its nodata value.
    WriteOptions maskOptions = wo;
    maskOptions.format = "GTiff";
    maskOptions.nodata = kMaskNodata;
    for (HorizonMap& m : maps) {
        const float* h = dem.terrain.heightsM.data();
        std::uint8_t* flag = m.truncated.data();
        for (std::size_t k = 0; k < m.truncated.size(); ++k)
            if (std::isnan(h[k])) flag[k] = kMaskNodata;
    }
    writeRaster(truncationPath(o.out.path), masks, dem.band.ref, maskOptions, o.demPath);

    const double nsPerCellDir = seconds * 1e9 / static_cast<double>(dem.terrain.heightsM.size() * azimuths.size());
    note(ctx, "wrote " + o.out.path + " (" + std::to_string(azimuths.size()) +
                  (azimuths.size() == 1 ? " horizon band" : " horizon bands") + ", degrees) and " +
                  truncationPath(o.out.path) + " (truncation mask); max distance " +
                  formatDistance(params.maxDistanceM) + "; " + formatSeconds(seconds) + " compute, " + formatNumber(std::round(nsPerCellDir * 10) / 10) +
                  " ns per cell per direction");
}

}  // namespace

void registerHorizon(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<HorizonOptions>();
    CLI::App* cmd = app.add_subcommand("horizon", "Horizon elevation angle maps along true azimuths");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    addOutputOptions(cmd, o->out);
    auto* az = cmd->add_option("--azimuth", o->azimuthsDeg,
                               "True azimuth(s), degrees clockwise from north (repeatable)")
                   ->expected(1, -1);
    auto* dirs = cmd->add_option("--directions", o->directions,
                                 "N azimuths evenly spaced from 0 (0, 360/N, ...)")
                     ->check(finiteRange(1, 4096));
    az->excludes(dirs);
    addSearchOptions(cmd, o->search);
    cmd->add_option("--method", o->method, "sweep (fast, default) or reference (brute-force ray march)")
        ->check(CLI::IsMember({"sweep", "reference"}))
        ->capture_default_str();
    cmd->callback([o, &ctx] { runHorizon(*o, ctx); });
}

}  // namespace demlight::cli
