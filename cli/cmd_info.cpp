// demlight info DEM [--json]: what demlight sees in a DEM before lighting it.
#include "cli/commands.h"
#include "geo/dem.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>

namespace demlight::cli {
namespace {

/// Sun elevation used for the "longest shadow" figure (degrees).
constexpr double kLowSunDeg = 5.0;
/// Points per DEM edge when finding the lat/lon extent of a projected DEM.
constexpr int kEdgeSamples = 16;

struct InfoOptions {
    std::string demPath;
    bool json = false;
};

void runInfo(const InfoOptions& o) {
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;
    const std::size_t w = t.width(), h = t.height();

    const auto [zMin, zMax] = heightRangeM(t.heightsM);
    const double relief = static_cast<double>(zMax) - static_cast<double>(zMin);
    const double nodataShare = static_cast<double>(dem.band.nodataCount) / static_cast<double>(w * h);

    // Lat/lon extent along the outline (a projected grid's edges are curves in lat/lon).
    double latMin = 90, latMax = -90, lonMin = 180, lonMax = -180;
    for (int k = 0; k <= kEdgeSamples; ++k) {
        const double f = static_cast<double>(k) / kEdgeSamples;
        const double cols = static_cast<double>(w), rows = static_cast<double>(h);
        for (auto [c, r] : {std::pair(f * cols, 0.0), std::pair(f * cols, rows),
                            std::pair(0.0, f * rows), std::pair(cols, f * rows)}) {
            const auto [lat, lon] = cellLatLon(dem, c, r);
            latMin = std::min(latMin, lat), latMax = std::max(latMax, lat);
            lonMin = std::min(lonMin, lon), lonMax = std::max(lonMax, lon);
        }
    }

    const std::size_t rowsOfInterest[3] = {h - 1, h / 2, 0};  // south, centre, north
    const char* rowNames[3] = {"south", "centre", "north"};
    const auto [gammaMin, gammaMax] = t.convergence.range();
    const double shadowM = relief / std::tan(kLowSunDeg * M_PI / 180.0);

    if (o.json) {
        nlohmann::json j;
        j["path"] = o.demPath;
        j["width"] = w;
        j["height"] = h;
        j["crs_name"] = dem.crs.name;
        j["epsg"] = dem.crs.epsg ? nlohmann::json(*dem.crs.epsg) : nlohmann::json(nullptr);
        j["geographic"] = dem.crs.geographic;
        j["extent"] = {{"lat_min", latMin}, {"lat_max", latMax}, {"lon_min", lonMin}, {"lon_max", lonMax}};
        nlohmann::json cells = nlohmann::json::object();
        for (int i = 0; i < 3; ++i) {
            const std::size_t r = rowsOfInterest[i];
            cells[rowNames[i]] = {{"row", r}, {"latitude_deg", t.rowLatitudeDeg[r]},
                                  {"x_m", t.cellWidthM[r]}, {"y_m", t.cellHeightM[r]}};
        }
        j["cell_size_m"] = cells;
        j["elevation_min_m"] = zMin;
        j["elevation_max_m"] = zMax;
        j["relief_m"] = relief;
        j["nodata_fraction"] = nodataShare;
        j["nodata_value"] = dem.band.nodata ? nlohmann::json(*dem.band.nodata) : nlohmann::json(nullptr);
        if (!dem.crs.geographic)
            j["convergence_deg"] = {{"min", gammaMin}, {"max", gammaMax}};
        else
            j["convergence_deg"] = nullptr;
        j["longest_shadow_m_at_5deg"] = shadowM;
        std::cout << j.dump(2) << "\n";
        return;
    }

    std::printf("DEM:            %s\n", o.demPath.c_str());
    std::printf("Size:           %zu x %zu cells (%zu)\n", w, h, w * h);
    std::printf("CRS:            %s (%s)%s\n", dem.crs.name.c_str(),
                dem.crs.epsg ? ("EPSG:" + std::to_string(*dem.crs.epsg)).c_str() : "no EPSG code",
                dem.crs.geographic ? ", geographic" : ", projected");
    std::printf("Extent:         lat %.6f .. %.6f, lon %.6f .. %.6f\n", latMin, latMax, lonMin, lonMax);
    if (dem.crs.geographic) {
        for (int i = 0; i < 3; ++i) {
            const std::size_t r = rowsOfInterest[i];
            std::printf("Cell size:      %-6s row %zu (lat %.4f): %.3f m x %.3f m\n", rowNames[i], r,
                        t.rowLatitudeDeg[r], t.cellWidthM[r], t.cellHeightM[r]);
        }
    } else {
        std::printf("Cell size:      %.3f m x %.3f m\n", t.cellWidthM[0], t.cellHeightM[0]);
    }
    std::printf("Elevation:      min %.2f m, max %.2f m, relief %.2f m\n", zMin, zMax, relief);
    std::printf("Nodata:         %.3f %% of cells (%zu)", 100.0 * nodataShare, dem.band.nodataCount);
    if (dem.band.nodata) std::printf(", nodata value %g", *dem.band.nodata);
    std::printf("\n");
    if (!dem.crs.geographic)
        std::printf("Convergence:    %.4f .. %.4f deg (grid north, clockwise from true north)\n",
                    gammaMin, gammaMax);
    std::printf("Longest shadow: %.0f m at %.0f deg sun elevation (relief / tan %.0f deg)\n", shadowM,
                kLowSunDeg, kLowSunDeg);
}

}  // namespace

void registerInfo(CLI::App& app, CliContext&) {
    auto opts = std::make_shared<InfoOptions>();
    CLI::App* cmd = app.add_subcommand("info", "Describe a DEM: size, CRS, extent, metric cell size, "
                                               "elevations, nodata, convergence");
    cmd->add_option("DEM", opts->demPath, "Input DEM (any raster GDAL reads)")->required();
    cmd->add_flag("--json", opts->json, "Print one JSON object instead of text");
    cmd->callback([opts] { runInfo(*opts); });
}

}  // namespace demlight::cli
