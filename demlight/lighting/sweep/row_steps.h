// Metric step lengths of straight scan lines on a grid whose cell sizes vary by row (geographic
// grids), and their smallest and largest over every row of a grid without evaluating each row:
// plans made on a whole DEM's grid must not cost a pass over its rows per region.
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace demlight {

/// Length (metres) of one line step of dc columns and dr rows in a row of cells w x h metres.
inline double lineStepM(double dc, double dr, double widthM, double heightM) {
    return std::hypot(dc * widthM, dr * heightM);
}

/// Bounds of the cell sizes over a tree of row ranges, so that the extremes of lineStepM over all
/// rows are found by evaluating only the rows of ranges that can hold them (a few dozen on a
/// geographic grid, where cell sizes change monotonically with latitude).
class RowStepBounds {
public:
    /// Per-row cell sizes (metres, positive and finite); the vectors must outlive this object.
    RowStepBounds(const std::vector<double>& cellWidthM, const std::vector<double>& cellHeightM);

    /// The smallest and largest lineStepM(dc, dr, ...) over all rows: the same values as a scan
    /// of every row (`rowsEvaluated`, when given, receives how many rows it evaluated).
    std::pair<double, double> range(double dc, double dr, std::size_t* rowsEvaluated = nullptr) const;

    /// Rows in a leaf of the tree.
    static constexpr std::size_t kLeafRows = 16;

private:
    struct Node {
        double minWidthM, minHeightM, maxWidthM, maxHeightM;
    };
    /// Updates `best` with the rows of node `index` of `level` that can beat it (largest when
    /// `largest`, else smallest).
    void search(std::size_t level, std::size_t index, double dc, double dr, bool largest, double& best,
                std::size_t& rows) const;

    const std::vector<double>& widthM_;
    const std::vector<double>& heightM_;
    std::vector<std::vector<Node>> levels_;  // levels_[0]: leaves; each next level halves the count
};

}  // namespace demlight
