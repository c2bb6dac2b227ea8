// demlight info DEM [--json] [--z-unit UNIT | --z-factor F]: what demlight sees in a DEM before
// lighting it, heights in metres as demlight reads them.
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/products/info.h"
#include "demlight/core/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <utility>

namespace demlight::cli {
namespace {

struct InfoOptions {
    ParameterSet set{"info", "Describe a DEM: size, CRS, extent, metric cell size, elevations, nodata, convergence"};
    DemOptions dem;
    bool json = false;
};

void printText(const std::string& path, const Dem& dem, const DemInfo& d) {
    const HeightTransform& z = dem.heights;
    std::printf("DEM:            %s\n", path.c_str());
    std::printf("Size:           %zu x %zu cells (%zu)\n", d.width, d.height, d.width * d.height);
    std::printf("CRS:            %s (%s)%s\n", dem.crs.name.c_str(),
                dem.crs.epsg ? ("EPSG:" + std::to_string(*dem.crs.epsg)).c_str() : "no EPSG code",
                dem.crs.geographic ? ", geographic" : ", projected");
    std::printf("Extent:         lat %.6f .. %.6f, lon %.6f .. %.6f\n", d.latMinDeg, d.latMaxDeg, d.lonMinDeg,
                d.lonMaxDeg);
    if (dem.crs.geographic) {
        for (const auto& r : d.rows)
            std::printf("Cell size:      %-6s row %zu (lat %.4f): %.3f m x %.3f m\n", r.name, r.row, r.latitudeDeg,
                        r.cellWidthM, r.cellHeightM);
    } else {
        std::printf("Cell size:      %.3f m x %.3f m\n", d.rows[0].cellWidthM, d.rows[0].cellHeightM);
    }
    std::printf("Heights:        scale %s, offset %s, unit %s -> metres x %s (%s)\n", formatNumber(z.scale).c_str(),
                formatNumber(z.offset).c_str(), z.unit.empty() ? "none" : ("\"" + z.unit + "\"").c_str(),
                formatNumber(z.toMetres).c_str(), z.source.c_str());
    std::printf("Elevation:      min %.2f m, max %.2f m, relief %.2f m\n", d.elevationMinM, d.elevationMaxM, d.reliefM);
    std::printf("Nodata:         %.3f %% of cells (%zu)", 100.0 * d.nodataFraction, dem.band.nodataCount);
    if (dem.band.nodata) std::printf(", nodata value %g", *dem.band.nodata);
    std::printf("\n");
    if (d.convergenceDeg)
        std::printf("Convergence:    %.4f .. %.4f deg (grid north, clockwise from true north)\n",
                    d.convergenceDeg->first, d.convergenceDeg->second);
    std::printf("Longest shadow: %.0f m at %.0f deg sun elevation (relief / tan %.0f deg)\n", d.longestShadowM,
                kInfoLowSunDeg, kInfoLowSunDeg);
}

void runInfo(const InfoOptions& o, const CliContext& ctx) {
    const DemSource source = openDem(o.dem, ctx);
    if (o.json)
        std::cout << infoJson(o.dem.path, source, 2) << "\n";
    else
        printText(o.dem.path, source.geometry(), describeDem(source));
}

}  // namespace

void registerInfo(CLI::App& app, CliContext& ctx) {
    auto opts = std::make_shared<InfoOptions>();
    ParameterSet& set = opts->set;
    declareDemOptions(set, opts->dem);
    set.add("json", opts->json, "JSON", "Print one JSON object instead of text");
    commandLineOnly(set);
    CLI::App* cmd = addDeclaredCommand(app, set, ctx);
    cmd->callback([opts, &ctx] { runInfo(*opts, ctx); });
}

}  // namespace demlight::cli
