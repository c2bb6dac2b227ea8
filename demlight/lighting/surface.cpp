#include "demlight/lighting/surface.h"

#include "demlight/core/angles.h"
#include "demlight/core/parallel.h"

#include <cmath>
#include <limits>

namespace demlight {

namespace {

/// Derivative dh/du from the neighbours at -1 and +1 along one axis, with the metric distances
/// from the centre to each (metres); one-sided when a neighbour is missing or nodata.
double axisDerivative(double hMinus, double hCentre, double hPlus, double distMinusM, double distPlusM) {
    const bool minus = !std::isnan(hMinus), plus = !std::isnan(hPlus);
    if (minus && plus) return (hPlus - hMinus) / (distMinusM + distPlusM);
    if (plus) return (hPlus - hCentre) / distPlusM;
    if (minus) return (hCentre - hMinus) / distMinusM;
    return 0.0;
}

}  // namespace

Normals computeNormals(const Terrain& t) {
    return computeNormals(t, CellWindow{0, 0, t.width(), t.height()});
}

Normals computeNormals(const Terrain& t, const CellWindow& cells) {
    const std::size_t W = t.width(), H = t.height();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::size_t outW = cells.col1 - cells.col0, outH = cells.row1 - cells.row0;
    Normals n{Grid<float>(outW, outH, nan), Grid<float>(outW, outH, nan), Grid<float>(outW, outH, nan)};
    const Grid<float>& h = t.heightsM;
    parallelFor(cells.row0, cells.row1, [&](std::size_t row) {
        // Distances between row centres (metres): half of each cell's north-south extent.
        const double toNorthM = row > 0 ? 0.5 * (t.cellHeightM[row - 1] + t.cellHeightM[row]) : 1.0;
        const double toSouthM = row + 1 < H ? 0.5 * (t.cellHeightM[row + 1] + t.cellHeightM[row]) : 1.0;
        const double cellWidthM = t.cellWidthM[row];
        for (std::size_t col = cells.col0; col < cells.col1; ++col) {
            const double hc = h(col, row);
            if (std::isnan(hc)) continue;
            const double west = col > 0 ? h(col - 1, row) : nan;
            const double east = col + 1 < W ? h(col + 1, row) : nan;
            const double north = row > 0 ? h(col, row - 1) : nan;
            const double south = row + 1 < H ? h(col, row + 1) : nan;
            // Gradient along grid east and grid north (metres per metre).
            const double dhdx = axisDerivative(west, hc, east, cellWidthM, cellWidthM);
            const double dhdy = axisDerivative(south, hc, north, toSouthM, toNorthM);
            // Rotate grid axes into true east/north: grid north lies at azimuth gamma.
            const double gammaRad = t.convergence.at(static_cast<double>(col), static_cast<double>(row)) * kDegToRad;
            const double c = std::cos(gammaRad), s = std::sin(gammaRad);
            const double gx = -dhdx, gy = -dhdy;  // horizontal part of the unnormalised normal
            const double ex = gx * c + gy * s;
            const double ny = -gx * s + gy * c;
            const double len = std::sqrt(ex * ex + ny * ny + 1.0);
            const std::size_t oc = col - cells.col0, orow = row - cells.row0;
            n.east(oc, orow) = static_cast<float>(ex / len);
            n.north(oc, orow) = static_cast<float>(ny / len);
            n.up(oc, orow) = static_cast<float>(1.0 / len);
        }
    }, 8);
    return n;
}

}  // namespace demlight
