#include "geo/sun_field.h"

#include <algorithm>
#include <cmath>

namespace demlight {
namespace {

double bilinear(const Grid<float>& g, std::size_t step, double col, double row) {
    const double fi = std::clamp(col / static_cast<double>(step), 0.0, static_cast<double>(g.width() - 1));
    const double fj = std::clamp(row / static_cast<double>(step), 0.0, static_cast<double>(g.height() - 1));
    const auto i0 = static_cast<std::size_t>(fi);
    const auto j0 = static_cast<std::size_t>(fj);
    const std::size_t i1 = std::min(i0 + 1, g.width() - 1);
    const std::size_t j1 = std::min(j0 + 1, g.height() - 1);
    const double u = fi - static_cast<double>(i0), v = fj - static_cast<double>(j0);
    return (g(i0, j0) * (1 - u) + g(i1, j0) * u) * (1 - v) + (g(i0, j1) * (1 - u) + g(i1, j1) * u) * v;
}

}  // namespace

std::pair<double, double> SunField::at(double col, double row) const {
    return {bilinear(azimuthDeg, stepCells, col, row), bilinear(elevationDeg, stepCells, col, row)};
}

std::pair<double, double> SunField::azimuthRange(std::size_t col0, std::size_t row0,
                                                 std::size_t col1, std::size_t row1) const {
    // The field is bilinear, so its extremes over a window lie at lattice nodes inside it or at
    // the window's corners.
    double lo = 1e9, hi = -1e9;
    const auto take = [&](double v) { lo = std::min(lo, v), hi = std::max(hi, v); };
    for (double c : {static_cast<double>(col0), static_cast<double>(col1)})
        for (double r : {static_cast<double>(row0), static_cast<double>(row1)}) take(at(c, r).first);
    for (std::size_t j = row0 / stepCells; j < azimuthDeg.height() && j * stepCells <= row1; ++j)
        for (std::size_t i = col0 / stepCells; i < azimuthDeg.width() && i * stepCells <= col1; ++i)
            if (i * stepCells >= col0 && j * stepCells >= row0) take(azimuthDeg(i, j));
    return {lo, hi};
}

SunField computeSunField(const Dem& dem, UtcInstant t, const SolarSite& site,
                         const SpaOptions& options, std::size_t stepCells) {
    const Terrain& terrain = dem.terrain;
    const std::size_t w = terrain.width(), h = terrain.height();
    double sum = 0;
    std::size_t n = 0;
    for (float z : terrain.heightsM.values())
        if (!std::isnan(z)) sum += z, ++n;
    const double meanHeight = n ? sum / static_cast<double>(n) : 0.0;

    const auto positionAt = [&](double col, double row) {
        SolarSite s = site;
        std::tie(s.latitudeDeg, s.longitudeDeg) = cellLatLon(dem, col, row);
        const auto c = std::min(static_cast<std::size_t>(col), w - 1);
        const auto r = std::min(static_cast<std::size_t>(row), h - 1);
        const float z = terrain.heightsM(c, r);
        s.elevationM = std::isnan(z) ? meanHeight : z;
        return solarPosition(s, t, options);
    };

    SunField f;
    f.stepCells = stepCells;
    f.centre = positionAt(0.5 * static_cast<double>(w), 0.5 * static_cast<double>(h));
    const std::size_t ni = (w - 1) / stepCells + 2, nj = (h - 1) / stepCells + 2;
    f.azimuthDeg = Grid<float>(ni, nj);
    f.elevationDeg = Grid<float>(ni, nj);
    for (std::size_t j = 0; j < nj; ++j) {
        for (std::size_t i = 0; i < ni; ++i) {
            const double col = static_cast<double>(std::min(i * stepCells, w - 1)) + 0.5;
            const double row = static_cast<double>(std::min(j * stepCells, h - 1)) + 0.5;
            const SolarPosition p = positionAt(col, row);
            // Unwrap around the centre azimuth.
            double az = p.azimuthDeg;
            while (az - f.centre.azimuthDeg > 180.0) az -= 360.0;
            while (az - f.centre.azimuthDeg < -180.0) az += 360.0;
            f.azimuthDeg(i, j) = static_cast<float>(az);
            f.elevationDeg(i, j) = static_cast<float>(p.elevationDeg);
        }
    }
    return f;
}

}  // namespace demlight
