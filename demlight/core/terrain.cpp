#include "demlight/core/terrain.h"

#include <algorithm>
#include <array>
#include <limits>

namespace demlight {

double ConvergenceField::at(double col, double row) const {
    if (gammaDeg.empty()) return 0.0;
    const double step = static_cast<double>(stepCells);
    const double maxI = static_cast<double>(gammaDeg.width() - 1);
    const double maxJ = static_cast<double>(gammaDeg.height() - 1);
    const double fi = std::clamp((col + colOffset) / step, 0.0, maxI);
    const double fj = std::clamp((row + rowOffset) / step, 0.0, maxJ);
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
    // Comparisons with NaN are false, so `z < lo ? z : lo` skips nodata without a branch; kLanes
    // independent running extremes let the compiler keep them in one vector register (sun frames
    // call this once per frame; docs/measurements.md#srcterraincpp-heightrangem).
    constexpr std::size_t kLanes = 16;
    constexpr float kInf = std::numeric_limits<float>::infinity();
    std::array<float, kLanes> lo, hi;
    lo.fill(kInf);
    hi.fill(-kInf);
    const float* z = heightsM.data();
    const std::size_t n = heightsM.size();
    std::size_t i = 0;
    for (; i + kLanes <= n; i += kLanes) {
        for (std::size_t k = 0; k < kLanes; ++k) {
            lo[k] = z[i + k] < lo[k] ? z[i + k] : lo[k];
            hi[k] = hi[k] < z[i + k] ? z[i + k] : hi[k];
        }
    }
    for (; i < n; ++i) {
        lo[0] = z[i] < lo[0] ? z[i] : lo[0];
        hi[0] = hi[0] < z[i] ? z[i] : hi[0];
    }
    return {*std::min_element(lo.begin(), lo.end()), *std::max_element(hi.begin(), hi.end())};
}

double diagonalM(const Terrain& t) {
    return diagonalM(FullGridRef{t.width(), t.height(), t.cellWidthM, t.cellHeightM, t.convergence, 0, 0, t});
}

double diagonalM(const FullGridRef& g) {
    double heightM = 0, widthM = 0;
    for (std::size_t r = 0; r < g.height; ++r) {
        heightM += g.cellHeightM[r];
        widthM = std::max(widthM, g.cellWidthM[r] * static_cast<double>(g.width));
    }
    return std::hypot(widthM, heightM);
}

namespace {

/// Per-row geometry of a window (no heights, no convergence).
Terrain cutRows(const Terrain& t, std::size_t row0, std::size_t h) {
    Terrain out;
    const auto slice = [](const std::vector<double>& v, std::size_t from, std::size_t n) {
        return v.empty() ? std::vector<double>{} : std::vector<double>(v.begin() + static_cast<long>(from),
                                                                      v.begin() + static_cast<long>(from + n));
    };
    out.cellWidthM = slice(t.cellWidthM, row0, h);
    out.cellHeightM = slice(t.cellHeightM, row0, h);
    out.rowLatitudeDeg = slice(t.rowLatitudeDeg, row0, h);
    return out;
}

/// Heights and per-row geometry of a window (no convergence).
Terrain cutCells(const Terrain& t, std::size_t col0, std::size_t row0, std::size_t w, std::size_t h) {
    Terrain out = cutRows(t, row0, h);
    out.heightsM = Grid<float>(w, h);
    for (std::size_t r = 0; r < h; ++r)
        for (std::size_t c = 0; c < w; ++c) out.heightsM(c, r) = t.heightsM(col0 + c, row0 + r);
    return out;
}

/// A tile's convergence (the same lattice, offset) and frame.
void placeTile(const Terrain& t, const CellWindow& w, std::shared_ptr<const GridFrame> frame, Terrain& out) {
    out.convergence = t.convergence;
    out.convergence.colOffset += static_cast<double>(w.col0);
    out.convergence.rowOffset += static_cast<double>(w.row0);
    out.frame = std::move(frame);
    out.frameCol0 = t.frameCol0 + w.col0;
    out.frameRow0 = t.frameRow0 + w.row0;
}

}  // namespace

Terrain cropTerrain(const Terrain& t, std::size_t col0, std::size_t row0, std::size_t w, std::size_t h) {
    Terrain out = cutCells(t, col0, row0, w, h);
    if (!t.convergence.empty()) {
        constexpr std::size_t kStep = 16;
        out.convergence.stepCells = kStep;
        out.convergence.gammaDeg = Grid<float>((w + kStep - 1) / kStep + 1, (h + kStep - 1) / kStep + 1);
        for (std::size_t j = 0; j < out.convergence.gammaDeg.height(); ++j)
            for (std::size_t i = 0; i < out.convergence.gammaDeg.width(); ++i)
                out.convergence.gammaDeg(i, j) = static_cast<float>(
                    t.convergence.at(static_cast<double>(col0 + std::min(i * kStep, w - 1)),
                                     static_cast<double>(row0 + std::min(j * kStep, h - 1))));
    }
    return out;
}

std::shared_ptr<const GridFrame> frameOf(const Terrain& t) {
    if (t.frame) return t.frame;
    const auto [lo, hi] = heightRangeM(t.heightsM);
    SteepSteps steps;
    steps.add(t.heightsM, 0, t.cellWidthM, t.cellHeightM);
    return std::make_shared<const GridFrame>(
        GridFrame{t.width(), t.height(), t.cellWidthM, t.cellHeightM, t.convergence, lo, hi, steps.share()});
}

void SteepSteps::add(const Grid<float>& rows, std::size_t row0, const std::vector<double>& cellWidthM,
                     const std::vector<double>& cellHeightM) {
    const std::size_t w = rows.width();
    for (std::size_t r = 0; r < rows.height(); ++r) {
        const float* z = rows.rowPtr(r);
        const std::size_t row = row0 + r;
        const double across = cellWidthM[row];
        // Between this row and the one above: the mean of their cell heights apart.
        const double down = row > 0 ? 0.5 * (cellHeightM[row] + cellHeightM[row - 1]) : 0.0;
        const bool above = row > 0 && lastRow_.size() == w;
        for (std::size_t c = 0; c < w; ++c) {
            if (std::isnan(z[c])) continue;
            ++valid;
            if (c + 1 < w && !std::isnan(z[c + 1]) && std::abs(z[c + 1] - z[c]) > across) ++steep;
            if (above && !std::isnan(lastRow_[c]) && std::abs(lastRow_[c] - z[c]) > down) ++steep;
        }
        lastRow_.assign(z, z + w);
    }
}

Terrain tileOf(const Terrain& t, const CellWindow& w) { return tileOf(t, w, frameOf(t)); }

Terrain tileOf(const Terrain& t, const CellWindow& w, std::shared_ptr<const GridFrame> frame) {
    Terrain out = cutCells(t, w.col0, w.row0, w.col1 - w.col0, w.row1 - w.row0);
    placeTile(t, w, std::move(frame), out);
    return out;
}

Terrain tileOf(const Terrain& geometry, const CellWindow& w, std::shared_ptr<const GridFrame> frame,
               Grid<float> heightsM) {
    Terrain out = cutRows(geometry, w.row0, w.row1 - w.row0);
    out.heightsM = std::move(heightsM);
    placeTile(geometry, w, std::move(frame), out);
    return out;
}

FullGridRef fullGrid(const Terrain& t) {
    if (t.frame) {
        const GridFrame& f = *t.frame;
        return {f.width, f.height, f.cellWidthM, f.cellHeightM, f.convergence, t.frameCol0, t.frameRow0, t};
    }
    return {t.width(), t.height(), t.cellWidthM, t.cellHeightM, t.convergence, 0, 0, t};
}

std::pair<float, float> FullGridRef::heightRangeM() const {
    if (terrain.frame) return {terrain.frame->lowM, terrain.frame->highM};
    return demlight::heightRangeM(terrain.heightsM);
}

double FullGridRef::steepStepShare() const {
    if (terrain.frame) return terrain.frame->steepStepShare;
    SteepSteps steps;
    steps.add(terrain.heightsM, 0, terrain.cellWidthM, terrain.cellHeightM);
    return steps.share();
}

double FullGridRef::minCellM() const {
    double m = std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < height; ++r) m = std::min({m, cellWidthM[r], cellHeightM[r]});
    return m;
}

Terrain cropTerrainCentre(const Terrain& t, std::size_t w, std::size_t h) {
    w = std::min(w, t.width());
    h = std::min(h, t.height());
    return cropTerrain(t, (t.width() - w) / 2, (t.height() - h) / 2, w, h);
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
