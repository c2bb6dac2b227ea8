#include "demlight/core/sun_field.h"

#include <algorithm>

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

SunField SunField::uniform(double azimuthDeg, double elevationDeg) {
    SunField f;
    f.azimuthDeg = Grid<float>(1, 1, static_cast<float>(azimuthDeg));
    f.elevationDeg = Grid<float>(1, 1, static_cast<float>(elevationDeg));
    f.centreAzimuthDeg = azimuthDeg;
    f.centreElevationDeg = elevationDeg;
    return f;
}

SunField SunField::onTile(std::size_t col0, std::size_t row0, std::size_t width) const {
    SunField f = *this;
    f.colOffset += static_cast<double>(col0);
    f.rowOffset += static_cast<double>(row0);
    if (f.fullWidth == 0) f.fullWidth = width;
    return f;
}

std::pair<double, double> SunField::at(double col, double row) const {
    return atFull(col + colOffset, row + rowOffset);
}

std::pair<double, double> SunField::atFull(double col, double row) const {
    return {bilinear(azimuthDeg, stepCells, col, row), bilinear(elevationDeg, stepCells, col, row)};
}

std::pair<double, double> SunField::azimuthRange(std::size_t col0, std::size_t row0,
                                                 std::size_t col1, std::size_t row1) const {
    // The field is bilinear, so its extremes over a window lie at the window's corners or at
    // lattice nodes inside it.
    double lo = 1e9, hi = -1e9;
    const auto take = [&](double v) { lo = std::min(lo, v), hi = std::max(hi, v); };
    for (double c : {static_cast<double>(col0), static_cast<double>(col1)})
        for (double r : {static_cast<double>(row0), static_cast<double>(row1)}) take(atFull(c, r).first);
    for (std::size_t j = row0 / stepCells; j < azimuthDeg.height() && j * stepCells <= row1; ++j)
        for (std::size_t i = col0 / stepCells; i < azimuthDeg.width() && i * stepCells <= col1; ++i)
            if (i * stepCells >= col0 && j * stepCells >= row0) take(azimuthDeg(i, j));
    return {lo, hi};
}

std::pair<double, double> SunField::elevationRange() const {
    const auto [lo, hi] = std::minmax_element(elevationDeg.values().begin(), elevationDeg.values().end());
    return {*lo, *hi};
}

}  // namespace demlight
