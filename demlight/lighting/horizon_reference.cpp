// Reference horizon: a brute-force ray march per cell (docs/design.md §6.1), slow and simple, used
// to measure every fast method. See demlight/lighting/horizon.h.
#include "demlight/lighting/horizon.h"

#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace demlight {

namespace {


/// Bilinear height at fractional cell coordinates (cell centres at integers); nodata corners are
/// dropped and the remaining weights renormalised; NaN when no corner with weight is valid.
double bilinearHeight(const Grid<float>& h, double x, double y) {
    const double maxX = static_cast<double>(h.width() - 1), maxY = static_cast<double>(h.height() - 1);
    x = std::clamp(x, 0.0, maxX);
    y = std::clamp(y, 0.0, maxY);
    const auto c0 = static_cast<std::size_t>(x), r0 = static_cast<std::size_t>(y);
    const std::size_t c1 = std::min(c0 + 1, h.width() - 1), r1 = std::min(r0 + 1, h.height() - 1);
    const double fx = x - static_cast<double>(c0), fy = y - static_cast<double>(r0);
    const double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    const float v[4] = {h(c0, r0), h(c1, r0), h(c0, r1), h(c1, r1)};
    double sum = 0.0, weight = 0.0;
    for (int i = 0; i < 4; ++i) {
        if (w[i] > 0.0 && !std::isnan(v[i])) {
            sum += w[i] * v[i];
            weight += w[i];
        }
    }
    return weight > 0.0 ? sum / weight : std::numeric_limits<double>::quiet_NaN();
}

class RayMarcher {
public:
    RayMarcher(const Terrain& t, const HorizonParams& p)
        : t_(t), azimuthDeg_(wrapAzimuthDeg(p.azimuthDeg)), azimuthAtDeg_(p.azimuthAtDeg),
          maxDistanceM_(p.maxDistanceM), invR_(inverseEffectiveRadius(p)),
          constantGamma_(t.convergence.empty()) {}

    HorizonSample march(std::size_t col, std::size_t row) const {
        HorizonSample out;
        const float h0 = t_.heightsM(col, row);
        if (std::isnan(h0)) {
            out.angleDeg = std::numeric_limits<float>::quiet_NaN();
            return out;
        }
        const double stepM = kReferenceStepOfCell * std::min(t_.cellWidthM[row], t_.cellHeightM[row]);
        const double maxX = static_cast<double>(t_.width()) - 0.5;
        const double maxY = static_cast<double>(t_.height()) - 0.5;
        double x = static_cast<double>(col), y = static_cast<double>(row), d = 0.0;
        const double azimuthDeg = azimuthAtDeg_ ? azimuthAtDeg_(x + static_cast<double>(t_.frameCol0),
                                                               y + static_cast<double>(t_.frameRow0))
                                                : azimuthDeg_;
        double best = -std::numeric_limits<double>::infinity();
        long directionRow = -1;
        double dirCol = 0.0, dirRow = 0.0;
        for (;;) {
            // Re-evaluate the grid direction from the local cell sizes and convergence.
            const long r = std::lround(std::clamp(y, 0.0, maxY - 0.5));
            if (!constantGamma_ || r != directionRow) {
                const double gridAzRad = (azimuthDeg - t_.convergence.at(x, y)) * kDegToRad;
                dirCol = std::sin(gridAzRad) / t_.cellWidthM[static_cast<std::size_t>(r)];
                dirRow = -std::cos(gridAzRad) / t_.cellHeightM[static_cast<std::size_t>(r)];
                directionRow = r;
            }
            x += stepM * dirCol;
            y += stepM * dirRow;
            d += stepM;
            if (d > maxDistanceM_) break;
            if (x < -0.5 || x > maxX || y < -0.5 || y > maxY) {
                out.truncated = 1;
                break;
            }
            // In the outer half cell (beyond the last cell centres) the height is the nearest
            // edge value: bilinearHeight clamps to the hull of the centres. Skipping those samples
            // instead would leave a ray running along the edge with no terrain and no flag.
            const double h = bilinearHeight(t_.heightsM, x, y);
            if (std::isnan(h)) continue;
            // Elevation on a curved earth: the target sits d²/(2 R_eff) lower (docs/design.md §4).
            best = std::max(best, (h - h0 - 0.5 * d * d * invR_) / d);
        }
        out.angleDeg = std::isinf(best) ? static_cast<float>(kNoHorizonDeg)
                                        : static_cast<float>(std::atan(best) * kRadToDeg);
        return out;
    }

private:
    const Terrain& t_;
    double azimuthDeg_;
    std::function<double(double, double)> azimuthAtDeg_;
    double maxDistanceM_;
    double invR_;
    bool constantGamma_;
};

}  // namespace

HorizonMap referenceHorizon(const Terrain& terrain, const HorizonParams& params, ProgressCounter* progress) {
    validateHorizonParams(terrain, params);
    const CellWindow w = params.window ? *params.window : CellWindow{0, 0, terrain.width(), terrain.height()};
    HorizonMap out;
    out.angleDeg = Grid<float>(terrain.width(), terrain.height(), std::numeric_limits<float>::quiet_NaN());
    out.truncated = Grid<std::uint8_t>(terrain.width(), terrain.height(), 0);
    const RayMarcher marcher(terrain, params);
    parallelFor(w.row0, w.row1, [&](std::size_t row) {
        if (progress && progress->cancelled()) return;
        for (std::size_t col = w.col0; col < w.col1; ++col) {
            const HorizonSample s = marcher.march(col, row);
            out.angleDeg(col, row) = s.angleDeg;
            out.truncated(col, row) = s.truncated;
        }
        if (progress) progress->advance(w.col1 - w.col0);
    });
    if (progress) progress->throwIfCancelled();
    return out;
}

std::vector<HorizonSample> referenceHorizonAt(const Terrain& terrain, const HorizonParams& params,
                                              std::span<const CellIndex> cells, ProgressCounter* progress) {
    HorizonParams p = params;
    p.window.reset();
    validateHorizonParams(terrain, p);
    for (const CellIndex& c : cells) {
        if (c.col >= terrain.width() || c.row >= terrain.height())
            throw Error("horizon: cell (" + std::to_string(c.col) + ", " + std::to_string(c.row) +
                        ") is outside the grid");
    }
    std::vector<HorizonSample> out(cells.size());
    const RayMarcher marcher(terrain, p);
    parallelFor(0, cells.size(), [&](std::size_t i) {
        if (progress && progress->cancelled()) return;
        out[i] = marcher.march(cells[i].col, cells[i].row);
        if (progress) progress->advance();
    }, 64);
    if (progress) progress->throwIfCancelled();
    return out;
}

std::vector<CellIndex> sampleValidCells(const Terrain& t, std::size_t count, std::uint64_t seed,
                                        double edgeMarginM) {
    std::size_t marginCols = 0, marginRows = 0;
    if (edgeMarginM > 0) {
        const std::size_t mid = t.height() / 2;
        marginCols = static_cast<std::size_t>(std::ceil(edgeMarginM / t.cellWidthM[mid])) + 2;
        marginRows = static_cast<std::size_t>(std::ceil(edgeMarginM / t.cellHeightM[mid])) + 2;
    }
    std::vector<CellIndex> cells;
    for (std::size_t r = marginRows; r + marginRows < t.height(); ++r)
        for (std::size_t c = marginCols; c + marginCols < t.width(); ++c)
            if (t.valid(c, r)) cells.push_back({c, r});
    std::mt19937_64 rng(seed);
    std::shuffle(cells.begin(), cells.end(), rng);
    if (cells.size() > count) cells.resize(count);
    return cells;
}

}  // namespace demlight
