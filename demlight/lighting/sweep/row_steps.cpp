#include "demlight/lighting/sweep/row_steps.h"

#include <algorithm>
#include <limits>

namespace demlight {

namespace {

/// A range of rows is skipped only when its bound misses the best value by more than this share: the
/// bound and the rows' steps are each within an ulp of the exact hypot (glibc), and the exact
/// hypot grows with either side, so a skipped range cannot hold a new extreme.
constexpr double kBoundMargin = 1e-9;

}  // namespace

RowStepBounds::RowStepBounds(const std::vector<double>& cellWidthM, const std::vector<double>& cellHeightM)
    : widthM_(cellWidthM), heightM_(cellHeightM) {
    const std::size_t rows = cellWidthM.size();
    std::vector<Node> leaves((rows + kLeafRows - 1) / kLeafRows,
                             Node{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), 0, 0});
    for (std::size_t r = 0; r < rows; ++r) {
        Node& n = leaves[r / kLeafRows];
        n.minWidthM = std::min(n.minWidthM, cellWidthM[r]);
        n.minHeightM = std::min(n.minHeightM, cellHeightM[r]);
        n.maxWidthM = std::max(n.maxWidthM, cellWidthM[r]);
        n.maxHeightM = std::max(n.maxHeightM, cellHeightM[r]);
    }
    levels_.push_back(std::move(leaves));
    while (levels_.back().size() > 1) {
        const std::vector<Node>& below = levels_.back();
        std::vector<Node> up((below.size() + 1) / 2);
        for (std::size_t i = 0; i < up.size(); ++i) {
            const Node& a = below[2 * i];
            const Node& b = 2 * i + 1 < below.size() ? below[2 * i + 1] : a;
            up[i] = {std::min(a.minWidthM, b.minWidthM), std::min(a.minHeightM, b.minHeightM),
                     std::max(a.maxWidthM, b.maxWidthM), std::max(a.maxHeightM, b.maxHeightM)};
        }
        levels_.push_back(std::move(up));
    }
}

void RowStepBounds::search(std::size_t level, std::size_t index, double dc, double dr, bool largest,
                           double& best, std::size_t& rows) const {
    const Node& n = levels_[level][index];
    if (largest ? lineStepM(dc, dr, n.maxWidthM, n.maxHeightM) * (1 + kBoundMargin) <= best
                : lineStepM(dc, dr, n.minWidthM, n.minHeightM) * (1 - kBoundMargin) >= best)
        return;
    if (level == 0) {
        for (std::size_t r = index * kLeafRows, end = std::min(r + kLeafRows, widthM_.size()); r < end; ++r) {
            const double s = lineStepM(dc, dr, widthM_[r], heightM_[r]);
            best = largest ? std::max(best, s) : std::min(best, s);
            ++rows;
        }
        return;
    }
    const std::vector<Node>& below = levels_[level - 1];
    std::size_t first = 2 * index, second = 2 * index + 1;
    if (second >= below.size()) {
        search(level - 1, first, dc, dr, largest, best, rows);
        return;
    }
    // The child whose bound is more extreme first: its rows most likely set `best`.
    const auto bound = [&](std::size_t i) {
        const Node& c = below[i];
        return largest ? lineStepM(dc, dr, c.maxWidthM, c.maxHeightM) : -lineStepM(dc, dr, c.minWidthM, c.minHeightM);
    };
    if (bound(second) > bound(first)) std::swap(first, second);
    search(level - 1, first, dc, dr, largest, best, rows);
    search(level - 1, second, dc, dr, largest, best, rows);
}

std::pair<double, double> RowStepBounds::range(double dc, double dr, std::size_t* rowsEvaluated) const {
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    std::size_t rows = 0;
    if (!widthM_.empty()) {
        const std::size_t top = levels_.size() - 1;
        search(top, 0, dc, dr, false, lo, rows);
        search(top, 0, dc, dr, true, hi, rows);
    }
    if (rowsEvaluated) *rowsEvaluated = rows;
    return {lo, hi};
}

}  // namespace demlight
