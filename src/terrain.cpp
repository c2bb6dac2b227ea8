#include "src/terrain.h"

#include <algorithm>
#include <limits>

namespace demlight {

double ConvergenceField::at(double col, double row) const {
    if (gammaDeg.empty()) return 0.0;
    const double step = static_cast<double>(stepCells);
    const double maxI = static_cast<double>(gammaDeg.width() - 1);
    const double maxJ = static_cast<double>(gammaDeg.height() - 1);
    const double fi = std::clamp(col / step, 0.0, maxI);
    const double fj = std::clamp(row / step, 0.0, maxJ);
    const auto i0 = static_cast<std::size_t>(fi);
    const auto j0 = static_cast<std::size_t>(fj);
    const std::size_t i1 = std::min(i0 + 1, gammaDeg.width() - 1);
    const std::size_t j1 = std::min(j0 + 1, gammaDeg.height() - 1);
    const double u = fi - static_cast<double>(i0);
    const double v = fj - static_cast<double>(j0);
    const double top = gammaDeg(i0, j0) * (1 - u) + gammaDeg(i1, j0) * u;
    const double bottom = gammaDeg(i0, j1) * (1 - u) + gammaDeg(i1, j1) * u;
    return top * (1 - v) + bottom * v;
}

std::pair<double, double> ConvergenceField::range() const {
    if (gammaDeg.empty()) return {0.0, 0.0};
    const auto [lo, hi] = std::minmax_element(gammaDeg.values().begin(), gammaDeg.values().end());
    return {*lo, *hi};
}

std::pair<float, float> heightRangeM(const Grid<float>& heightsM) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (float z : heightsM.values()) {
        if (std::isnan(z)) continue;
        lo = std::min(lo, z);
        hi = std::max(hi, z);
    }
    return {lo, hi};
}

Terrain makeUniformTerrain(Grid<float> heightsM, double cellSizeM) {
    Terrain t;
    const std::size_t rows = heightsM.height();
    t.heightsM = std::move(heightsM);
    t.cellWidthM.assign(rows, cellSizeM);
    t.cellHeightM.assign(rows, cellSizeM);
    return t;
}

}  // namespace demlight
