// demlight info DEM [--json] [--z-unit UNIT | --z-factor F]: what demlight sees in a DEM before
// lighting it, heights in metres as demlight reads them.
#include "cli/commands.h"
#include "cli/common.h"
#include "geo/dem.h"
#include "src/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <utility>

namespace demlight::cli {
namespace {

/// Sun elevation used for the "longest shadow" figure (degrees).
constexpr double kLowSunDeg = 5.0;
/// Points per DEM edge when finding the lat/lon extent of a projected DEM.
constexpr int kEdgeSamples = 16;

struct InfoOptions {
    std::string demPath;
    bool json = false;
    HeightOptions heights;
};

/// The library names HeightOptions fields in its messages; the user typed flags.
std::string withHeightFlags(std::string message) {
    const std::pair<std::string, std::string> fieldToFlag[] = {{"HeightOptions::zUnit", "--z-unit"},
                                                               {"HeightOptions::zFactor", "--z-factor"}};
    for (const auto& [field, flag] : fieldToFlag)
        for (auto at = message.find(field); at != std::string::npos; at = message.find(field, at + flag.size()))
            message.replace(at, field.size(), flag);
    return message;
}

Dem loadInfoDem(const InfoOptions& o) {
    try {
        return loadDem(o.demPath, o.heights);
    } catch (const Cancelled&) {
        throw;
    } catch (const Error& e) {
        throw Error(withHeightFlags(e.what()));
    }
}

void runInfo(const InfoOptions& o) {
    const Dem dem = loadInfoDem(o);
    const HeightTransform& z = dem.heights;
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
        j["height_scale"] = z.scale;
        j["height_offset"] = z.offset;
        j["height_unit"] = z.unit;
        j["height_to_metres"] = z.toMetres;
        j["height_source"] = z.source;
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
    std::printf("Heights:        scale %s, offset %s, unit %s -> metres x %s (%s)\n", formatNumber(z.scale).c_str(),
                formatNumber(z.offset).c_str(), z.unit.empty() ? "none" : ("\"" + z.unit + "\"").c_str(),
                formatNumber(z.toMetres).c_str(), z.source.c_str());
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
    CLI::Option* zUnit =
        cmd->add_option("--z-unit", opts->heights.zUnit,
                        "Vertical unit of the heights instead of the band's own (m, ft, US survey foot, cm, dm, "
                        "mm, km)");
    CLI::Option* zFactor = cmd->add_option("--z-factor", opts->heights.zFactor,
                                           "Metres per height unit (after the band's scale and offset), "
                                           "instead of converting a unit")
                                ->check(finiteRange(0, std::numeric_limits<double>::infinity(), /*lowOpen=*/true));
    zUnit->excludes(zFactor);
    cmd->callback([opts] { runInfo(*opts); });
}

}  // namespace demlight::cli
