// The exact range limit of a sweep: the second pass over a line's chunks (limitRangePass), and
// the one tangent expression both passes evaluate (rangeSlope).
#include "demlight/lighting/sweep/hull.h"

#include <algorithm>
#include <limits>

namespace demlight::sweep {

// rangeSlope: see hull.h (one definition, not inlined, so both passes get the same bits).
[[gnu::noinline]] float rangeSlope(double gP, double sigmaP, double gQ, double sigmaQ, double invR) {
    return static_cast<float>((gP - gQ) / (sigmaQ - sigmaP) - sigmaQ * invR);
}

/// Second pass of a range-limited line (maxDistanceM = L). The first pass reset its hull whenever
/// floor(σ/L) changed, so each cell saw exactly the points of its own chunk farther than itself,
/// all within L. The points within L that it missed lie in the previous (farther) chunk with
/// σ ≥ σ_cell - L. Walking the cells of a chunk from near to far, that set grows at its far end,
/// so an upper hull built by adding points in order of distance answers every cell (binary search
/// for the tangent); the result is max-ed into the planes. Exact: O(n log n) per line. A cell is
/// skipped when no point of the hull could beat its first-pass value (highest g over the nearest
/// distance), which is most cells.
void limitRangePass(const RangeLog& log, double maxDistanceM, double invR, std::vector<HullPoint>& hull) {
    const auto& pts = log.points;
    if (log.nQueries == 0) return;
    if (hull.size() < log.nPoints) hull.resize(log.nPoints);
    long chunk = std::numeric_limits<long>::min();
    std::size_t next = 0;  // candidate points are pts[0, next), the farthest first
    std::size_t top = 0;   // hull = hull[0, top), nearest first
    double maxG = -std::numeric_limits<double>::infinity();
    for (std::size_t qi = log.nQueries; qi-- > 0;) {
        const RangeLog::Query* q = &log.queries[qi];
        if (q->straddles) {
            // Its points are the walk's chunk's from q->sigmaM - L up to pointsBefore; a nearer
            // cell of its chunk may have put nearer ones into the hull, so scan them directly
            // (at most nearFieldSteps cells per line and chunk get here).
            float& cell = *q->cell;
            const double limit = q->sigmaM - maxDistanceM;
            for (std::size_t i = q->pointsBefore; i-- > 0 && pts[i].sigmaM >= limit;)
                cell = std::max(cell, rangeSlope(pts[i].g, pts[i].sigmaM, q->gCell, q->sigmaM, invR));
            continue;
        }
        if (q->chunk != chunk) {
            chunk = q->chunk;
            top = 0;
            maxG = -std::numeric_limits<double>::infinity();
            next = q->pointsBefore;
            while (next > 0 && pts[next - 1].chunk >= chunk) --next;
        }
        // Grow the hull with previous-chunk points within range of this cell.
        const double limit = q->sigmaM - maxDistanceM;
        while (next > 0 && pts[next - 1].sigmaM >= limit && pts[next - 1].chunk == chunk - 1) {
            const RangeLog::Point& pt = pts[--next];
            const HullPoint p{pt.sigmaM, pt.g};
            maxG = std::max(maxG, p.g);
            // Points arrive farther each time (x = -σ increasing): keep right turns only.
            while (top >= 2) {
                const HullPoint& o = hull[top - 2];
                const HullPoint& a = hull[top - 1];
                const double cross = (o.sigmaM - a.sigmaM) * (p.g - o.g) - (a.g - o.g) * (o.sigmaM - p.sigmaM);
                if (cross < 0.0) break;
                --top;
            }
            hull[top++] = p;
        }
        if (top == 0) continue;
        // Upper bound of the slope to any hull point: the highest g at the distance that makes
        // it steepest (the nearest point if above the cell, else the farthest).
        const double rise = maxG - q->gCell;
        const double boundDistM = q->sigmaM - (rise >= 0.0 ? hull[0].sigmaM : hull[top - 1].sigmaM);
        float& cell = *q->cell;
        if (static_cast<float>(rise / boundDistM - q->sigmaM * invR) <= cell) continue;
        // Slopes compared without divisions: two a step made the search a chain of divisions
        // (docs/performance.md, "The range pass without divisions").
        std::size_t lo = 0, hi = top - 1;
        while (lo < hi) {
            const std::size_t mid = (lo + hi) / 2;
            if (steeperFrom(hull[mid + 1], hull[mid], q->sigmaM, q->gCell)) lo = mid + 1; else hi = mid;
        }
        cell = std::max(cell, rangeSlope(hull[lo].g, hull[lo].sigmaM, q->gCell, q->sigmaM, invR));
    }
}

}  // namespace demlight::sweep
