#include "demlight/products/info.h"

#include <algorithm>
#include <cmath>

namespace demlight {
namespace {

/// Points per DEM edge when finding the lat/lon extent of a projected DEM.
constexpr int kEdgeSamples = 16;

/// `dem` for its georeference and per-row geometry (its heights are not read).
DemInfo describeGrid(const Dem& dem, std::size_t width, std::size_t height, std::pair<float, float> range,
                     std::size_t nodataCount) {
    const Terrain& t = dem.terrain;
    DemInfo d;
    d.width = width;
    d.height = height;
    const auto [zMin, zMax] = range;
    d.elevationMinM = zMin;
    d.elevationMaxM = zMax;
    d.reliefM = static_cast<double>(zMax) - static_cast<double>(zMin);
    d.nodataFraction = static_cast<double>(nodataCount) / static_cast<double>(d.width * d.height);
    const double cols = static_cast<double>(d.width), rows = static_cast<double>(d.height);
    for (int k = 0; k <= kEdgeSamples; ++k) {
        const double f = static_cast<double>(k) / kEdgeSamples;
        for (auto [c, r] : {std::pair(f * cols, 0.0), std::pair(f * cols, rows), std::pair(0.0, f * rows),
                            std::pair(cols, f * rows)}) {
            const auto [lat, lon] = cellLatLon(dem, c, r);
            d.latMinDeg = std::min(d.latMinDeg, lat), d.latMaxDeg = std::max(d.latMaxDeg, lat);
            d.lonMinDeg = std::min(d.lonMinDeg, lon), d.lonMaxDeg = std::max(d.lonMaxDeg, lon);
        }
    }
    const std::size_t rowsOfInterest[3] = {d.height - 1, d.height / 2, 0};
    const char* names[3] = {"south", "centre", "north"};
    for (int i = 0; i < 3; ++i) {
        const std::size_t r = rowsOfInterest[i];
        d.rows[static_cast<std::size_t>(i)] = {names[i], r, t.rowLatitudeDeg[r], t.cellWidthM[r], t.cellHeightM[r]};
    }
    if (!dem.crs.geographic) d.convergenceDeg = t.convergence.range();
    d.longestShadowM = d.reliefM / std::tan(kInfoLowSunDeg * M_PI / 180.0);
    return d;
}

}  // namespace

DemInfo describeDem(const Dem& dem) {
    return describeGrid(dem, dem.terrain.width(), dem.terrain.height(), heightRangeM(dem.terrain.heightsM),
                        dem.band.nodataCount);
}

DemInfo describeDem(const DemSource& source) {
    return describeGrid(source.geometry(), source.width(), source.height(), {source.frame()->lowM, source.frame()->highM},
                        source.width() * source.height() - source.validCells());
}

}  // namespace demlight
