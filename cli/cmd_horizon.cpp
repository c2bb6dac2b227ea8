// demlight horizon DEM -o OUT.tif (--azimuth DEG... | --directions N): horizon angle maps, one
// Float32 band per azimuth (demlight/products/horizon.h), and the truncation mask in OUT.truncated.tif.
#include "cli/common.h"
#include "cli/point_options.h"
#include "cli/progress_bar.h"
#include "demlight/products/horizon.h"
#include "demlight/products/point.h"
#include "demlight/core/error.h"

#include <cmath>
#include <filesystem>
#include <iostream>

namespace demlight::cli {
namespace {

struct HorizonOptions {
    DemOptions dem;
    OutputOptions out;
    TilingOptions tiling;
    SearchOptions search;
    PointOptions point;
    std::vector<double> azimuthsDeg;
    int directions = 0;
    std::string method = "sweep";
    std::string dataType = "Float32";  ///< --ot: Float32 or Int16 (fixed point, horizonFixedPoint)
};

/// The output options of the horizons: -o, -of, -co, and --ot Int16 as fixed point.
OutputOptions horizonOutput(const HorizonOptions& o) {
    OutputOptions out = o.out;
    if (o.dataType == "Int16") out.fixedPoint = horizonFixedPoint();
    return out;
}

/// The horizon raster's metadata item that names its truncation mask raster.
constexpr const char* kTruncationMaskKey = "DEMLIGHT_TRUNCATION_MASK";

std::string truncationPath(const std::string& outPath) {
    std::filesystem::path p(outPath);
    return (p.parent_path() / (p.stem().string() + ".truncated.tif")).string();
}

/// Directions of a point query's profile when neither --azimuth nor --directions is given: PVGIS's
/// horizon profile, 48 values every 7.5 deg.
constexpr int kPointProfileDirections = 48;

HorizonRequest horizonRequest(const HorizonOptions& o) {
    if (!o.azimuthsDeg.empty() && o.directions != 0) throw Error("give either --azimuth DEG [DEG ...] or --directions N");
    if (o.azimuthsDeg.empty() && o.directions == 0 && !pointOf(o.point))
        throw Error("give either --azimuth DEG [DEG ...] or --directions N");
    HorizonRequest request;
    request.azimuthsDeg = o.azimuthsDeg;
    const int directions = o.azimuthsDeg.empty() && o.directions == 0 ? kPointProfileDirections : o.directions;
    for (double az : evenAzimuthsDeg(static_cast<std::size_t>(directions))) request.azimuthsDeg.push_back(az);
    request.method = parseHorizonMethod(o.method);
    request.search = o.search.request;
    return request;
}

/// The two rasters of -o OUT: the horizons in OUT, the truncation mask in OUT.truncated.tif (the
/// same format and creation options), each naming the mask's file in its metadata.
std::vector<RasterTarget> horizonTargets(const OutputOptions& out) {
    OutputOptions maskOut = out;
    maskOut.path = truncationPath(out.path);
    maskOut.fixedPoint.reset();  // a Byte mask either way
    return {{out, {{kTruncationMaskKey, maskOut.path}}}, {maskOut, {{kTruncationMaskKey, maskOut.path}}}};
}

/// Memory of a window per cell (for tile sizes): a horizon and a mask band per azimuth.
std::size_t horizonBands(const HorizonRequest& request) { return 2 * request.azimuthsDeg.size(); }

RasterCall horizonCall(const HorizonOptions& o) {
    const HorizonRequest request = horizonRequest(o);
    RasterCall call;
    call.command = "horizon";
    call.heights = o.dem.heights;
    call.tiling = o.tiling;
    call.search = request.search;
    call.tileBytes = productTileBytes(horizonBands(request));
    call.run = [request](const DemSource& dem, const CellWindow& w, const ProgressFn& p) {
        HorizonResult r = horizonProduct(dem, w, request, p);
        return std::vector<ProductResult>{std::move(r.horizons), std::move(r.truncation)};
    };
    call.targets = horizonTargets;
    return call;
}

/// The point formats a horizon profile adds to json and csv: solar tools' horizon files.
constexpr const char* kPvgisFormat = "pvgis";
constexpr const char* kPvlibFormat = "pvlib";

/// PVGIS's user horizon file (the `userhorizon` upload of PVGIS 5): one horizon height (degrees)
/// per line at equidistant azimuths, the first due north, then clockwise (east, south, west).
std::string pvgisUserHorizon(const PointHorizon& h) {
    std::string text;
    for (const HorizonSample& s : h.samples) text += formatNumber(s.angleDeg) + "\n";
    return text;
}

/// pvlib's horizon profile (as pvlib.iotools.get_pvgis_horizon returns it): azimuth in degrees
/// clockwise from north (0 = N, 90 = E), horizon elevation in degrees; a CSV of two columns.
std::string pvlibHorizonTable(const PointHorizon& h) {
    std::string text = "azimuth,elevation\n";
    for (std::size_t i = 0; i < h.samples.size(); ++i)
        text += formatNumber(h.azimuthsDeg[i]) + "," + formatNumber(h.samples[i].angleDeg) + "\n";
    return text;
}

/// --at / --at-xy: the reference horizon of one cell in each azimuth, printed.
void printHorizonAt(const HorizonOptions& o, const PointSpec& spec, const CliContext& ctx) {
    refuseRasterOptions(o.tiling);
    const bool solarFile = o.point.format == kPvgisFormat || o.point.format == kPvlibFormat;
    if (solarFile && !o.azimuthsDeg.empty())
        throw Error("--point-format " + o.point.format +
                    " writes a profile at equidistant azimuths from north: give --directions N (default 48), not "
                    "--azimuth");
    const HorizonRequest request = horizonRequest(o);
    const DemSource dem = openPointDem(o.dem, o.search.request, ctx);
    const PointCell cell = locatePoint(dem, spec);
    const PointHorizon h = pointHorizon(dem, cell, request.azimuthsDeg, request.search);
    if (solarFile) {
        std::size_t truncated = 0;
        for (const HorizonSample& s : h.samples) truncated += s.truncated != 0;
        if (truncated > 0)
            note(ctx, std::to_string(truncated) + " of " + std::to_string(h.samples.size()) +
                          " directions reached the DEM's edge within the search distance: what lies beyond is "
                          "missing from their horizon");
        std::cout << (o.point.format == kPvgisFormat ? pvgisUserHorizon(h) : pvlibHorizonTable(h));
        return;
    }
    nlohmann::ordered_json j;
    j["point"] = pointJson(cell);
    j["method"] = "reference ray march";
    j["max_distance_m"] = h.maxDistanceM;
    j["refraction"] = request.search.refraction;
    j["horizon"] = nlohmann::ordered_json::array();
    std::vector<std::vector<std::string>> rows;
    for (std::size_t i = 0; i < h.samples.size(); ++i) {
        const HorizonSample& s = h.samples[i];
        j["horizon"].push_back({{"azimuth_deg", h.azimuthsDeg[i]},
                                {"elevation_deg", s.angleDeg},
                                {"truncated", s.truncated != 0}});
        rows.push_back({formatNumber(h.azimuthsDeg[i]), formatNumber(s.angleDeg), std::to_string(s.truncated)});
    }
    printPoint(o.point, j, {"azimuth_deg", "horizon_deg", "truncated"}, rows);
}

void runHorizon(const HorizonOptions& o, const CliContext& ctx) {
    if (const auto spec = pointOf(o.point)) return printHorizonAt(o, *spec, ctx);
    requireOutputOrPoint(o.out, o.point);
    const HorizonRequest request = horizonRequest(o);
    const std::vector<RasterTarget> targets = horizonTargets(horizonOutput(o));
    checkOutputPath(targets[0].out, o.dem.path);
    checkOutputPath(targets[1].out.path, o.dem.path);
    const DemSource dem = openDem(o.dem, ctx);
    notePlan(o.search, dem.geometry().terrain, ctx);

    const RasterRun run = planRasterRun(dem, o.tiling, request.search, productTileBytes(horizonBands(request)), ctx);
    const auto start = std::chrono::steady_clock::now();
    const HorizonResult result = runRaster<HorizonResult>(
        run, targets, ctx, o.dem.path, [&](const CellWindow& w, const ProgressFn& p) { return horizonProduct(dem, w, request, p); },
        [](const HorizonResult& r) { return std::vector<const ProductResult*>{&r.horizons, &r.truncation}; });
    const double seconds = secondsSince(start);

    const std::size_t bands = request.azimuthsDeg.size();
    const double nsPerCellDir = seconds * 1e9 / static_cast<double>(dem.width() * dem.height() * bands);
    note(ctx, "wrote " + o.out.path + " (" + std::to_string(bands) + (bands == 1 ? " horizon band" : " horizon bands") +
                  (o.dataType == "Int16" ? ", degrees in 16-bit fixed point" : ", degrees") + ") and " + targets[1].out.path + " (truncation mask); max distance " +
                  formatDistance(result.maxDistanceM) + "; " + formatSeconds(seconds) + " compute, " +
                  formatNumber(std::round(nsPerCellDir * 10) / 10) + " ns per cell per direction");
}

}  // namespace

void registerHorizon(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<HorizonOptions>();
    CLI::App* cmd = app.add_subcommand("horizon", "Horizon elevation angle maps along true azimuths");
    ctx.outputs[cmd->get_name()].companionKeys = {kTruncationMaskKey};
    addDemArgument(cmd, o->dem);
    addOutputOptions(cmd, o->out);
    addPointOptions(cmd, o->point, cmd->get_option("-o"),
                    {{kPvgisFormat, "PVGIS's user horizon file: one height per line, the first due north, then "
                                    "clockwise at equal steps"},
                     {kPvlibFormat, "CSV azimuth,elevation, azimuth clockwise from north, as pvlib's horizon "
                                    "profiles"}});
    auto* az = cmd->add_option("--azimuth", o->azimuthsDeg, "True azimuth(s), degrees clockwise from north (repeatable)")
                   ->expected(1, -1);
    auto* dirs = cmd->add_option("--directions", o->directions, "N azimuths evenly spaced from 0 (0, 360/N, ...); a point query without --azimuth: 48")
                     ->check(finiteRange(1, 4096));
    az->excludes(dirs);
    addSearchOptions(cmd, o->search);
    addTilingOptions(cmd, o->tiling);
    cmd->add_option("--method", o->method, "sweep (fast, default) or reference (brute-force ray march)")
        ->check(CLI::IsMember({"sweep", "reference"}))
        ->capture_default_str();
    cmd->add_option("--ot", o->dataType,
                    "Horizon band type (also -ot): Float32, or Int16 = 16-bit fixed point, -90..90 deg in steps of "
                    "0.00275 deg with GDAL scale/offset (readers get degrees), half the size")
        ->check(CLI::IsMember({"Float32", "Int16"}))
        ->capture_default_str();
    cmd->callback([o, &ctx] {
        refusePointCall(o->point, ctx);
        ctx.takeCall ? ctx.takeCall(horizonCall(*o)) : runHorizon(*o, ctx);
    });
}

}  // namespace demlight::cli
