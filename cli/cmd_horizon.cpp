// demlight horizon DEM -o OUT.tif (--azimuth DEG... | --directions N): horizon angle maps, one
// Float32 band per azimuth (demlight/products/horizon.h), and the truncation mask in OUT.truncated.tif.
#include "cli/common.h"
#include "cli/declared.h"
#include "cli/point_options.h"
#include "cli/progress_bar.h"
#include "demlight/run/raster_commands.h"
#include "demlight/products/point.h"
#include "demlight/core/error.h"

#include <cmath>
#include <filesystem>
#include <iostream>

namespace demlight::cli {
namespace {

struct HorizonOptions {
    std::unique_ptr<RasterCommandOf<HorizonParameters>> command = horizonCommand();
    std::string& demPath = command->demPath;
    OutputOptions& out = command->out;
    bool& verbose = command->verbose;
    PointOptions point;
    HorizonParameters& p = command->values;
};

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
    refuseRasterOptions(o.p.tiling);
    const bool solarFile = o.point.format == kPvgisFormat || o.point.format == kPvlibFormat;
    if (solarFile && !o.p.azimuthsDeg.empty())
        throw Error("--point-format " + o.point.format +
                    " writes a profile at equidistant azimuths from north: give --directions N (default 48), not "
                    "--azimuth");
    const HorizonRequest request = horizonRequest(o.p, /*point=*/true);
    const DemSource dem = openPointDem({o.demPath, o.p.heights}, o.p.search, ctx);
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
    const HorizonRequest request = horizonRequest(o.p);
    const ProductWork<HorizonResult> work = horizonWork(request, o.p);
    const std::vector<RasterTarget> targets = work.targets(o.out);
    const auto [result, cells, readSeconds, seconds] =
        runRasterCommand(work, o.demPath, targets, &request.search, o.verbose, ctx);
    const std::size_t bands = request.azimuthsDeg.size();
    const double nsPerCellDir = seconds * 1e9 / static_cast<double>(cells * bands);
    note(ctx, "wrote " + o.out.path + " (" + std::to_string(bands) + (bands == 1 ? " horizon band" : " horizon bands") +
                  (o.p.dataType == "Int16" ? ", degrees in 16-bit fixed point" : ", degrees") + ") and " + targets[1].out.path + " (truncation mask); max distance " +
                  formatDistance(result.maxDistanceM) + "; " + formatSeconds(seconds) + " compute, " +
                  formatNumber(std::round(nsPerCellDir * 10) / 10) + " ns per cell per direction");
}

}  // namespace

void registerHorizon(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<HorizonOptions>();
    declarePointOptions(o->command->declaration(), o->point,
                        {{kPvgisFormat, "PVGIS's user horizon file: one height per line, the first due north, then "
                                        "clockwise at equal steps"},
                         {kPvlibFormat, "CSV azimuth,elevation, azimuth clockwise from north, as pvlib's horizon "
                                        "profiles"}});
    CLI::App* cmd = addDeclaredCommand(app, o->command->declaration(), ctx);
    ctx.outputs[cmd->get_name()].companionKeys = {kTruncationMaskKey};
    cmd->callback([o, &ctx] { runHorizon(*o, ctx); });
}

}  // namespace demlight::cli
