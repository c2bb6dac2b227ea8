// The upper convex hull of a scan line's points, walked from the line's far end toward the
// observer (Dozier 1981; Timonen & Westerholm 2010), in g = h - σ²/(2 R_eff) so that the
// curved-earth slope is a straight one (docs/design.md §4); the range limit's chunks and the
// state one line keeps between steps. The scalar reference of the hull kernel.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace demlight::sweep {

/// One upper-hull vertex: distance from the line's far end (metres) and g = h - σ²/(2 R_eff).
struct HullPoint {
    double sigmaM;
    double g;
};

/// Range-limited sweeps only: what the second pass (limitRangePass) needs of one line.
struct RangeLog {
    /// A valid line sample, far to near, with the chunk (floor(σ / maxDistanceM)) it fell in.
    struct Point {
        double sigmaM;
        double g;
        long chunk;
    };
    /// A served cell in chunk >= 1, whose first-pass value saw only its own chunk.
    struct Query {
        double sigmaM;
        double gCell;
        long chunk;
        std::size_t pointsBefore;  // points.size() when the cell was served: the farther points
        float* cell;
        /// Delayed serving: the cell's chunk is one past the walk's (it lies within nearFieldSteps
        /// after a chunk boundary), so the farther points it may see end before the chunk's
        /// nearest ones; resolved one by one (limitRangePass).
        bool straddles;
    };
    /// points[0, nPoints) and queries[0, nQueries) are in use; sized once per block (at most
    /// two points and two queries per line step) so the walk appends without capacity checks.
    std::vector<Point> points;
    std::vector<Query> queries;
    std::size_t nPoints = 0, nQueries = 0;
    void reset(std::size_t capacity) {
        if (points.size() < capacity) points.resize(capacity);
        if (queries.size() < 2 * capacity) queries.resize(2 * capacity);
        nPoints = nQueries = 0;
    }
};

/// Per-line state of the far-to-near walk: the hull is buf[lo, hi) with the farthest point at lo.
struct LineState {
    HullPoint* buf;
    std::size_t lo;
    std::size_t hi;
    double edgeArcM;  // arcAt() of the line at the far edge; unused with LineGeometry::sigmaAt
    long chunk;
    double nextChunkM;  // σ at which the chunk changes
    RangeLog* log;      // range-limited sweeps only
    /// Range-limited sweeps: the previous chunk's final hull is kept at buf[prevLo, prevHi) (the
    /// current one starts after it), and the vertex its last tangent touched.
    std::size_t prevLo, prevHi, prevHint;
    /// Delayed serving (nearFieldSteps > 0): the current hull's vertex the line's last tangent touched.
    std::size_t hint;
    /// Range-limited sweeps: the highest g pushed in the current chunk and in the previous one
    /// (-inf when empty), for prevChunkCannotRaise.
    double maxG, prevMaxG;
};

/// Range-limited sweeps: true when no point of the previous chunk's hull can give a cell at
/// (sigmaQ, gQ) a slope above `value` (the current chunk's answer), so that its tangent need not
/// be searched. The bound is rangeSlope() to the highest g of that chunk at the distance that
/// makes it steepest: its nearest point (the chunk's last, always a vertex) when that g is above
/// the cell, else its farthest (its first, never popped). rangeSlope() rises with g and falls
/// with the distance, operation by operation, so it bounds every vertex's; the comparison is
/// strict because this copy of the expression may be contracted differently by the compiler.
inline bool prevChunkCannotRaise(const LineState& line, double sigmaQ, double gQ, double invR, float value) {
    const double rise = line.prevMaxG - gQ;
    const double sigmaP = rise >= 0.0 ? line.buf[line.prevHi - 1].sigmaM : line.buf[line.prevLo].sigmaM;
    return static_cast<float>(rise / (sigmaQ - sigmaP) - sigmaQ * invR) < value;
}

/// A line's walk reaches sigma (metres from the far edge) in a later chunk of maxDistanceM: the
/// hull so far becomes the previous chunk's when the chunks are consecutive, else both empty.
inline void enterChunk(LineState& line, double sigma, double maxDistanceM) {
    const long chunk = static_cast<long>(std::floor(sigma / maxDistanceM));
    if (chunk == line.chunk + 1) {
        line.prevLo = line.lo;
        line.prevHi = line.hi;
        line.prevHint = line.hi > 0 ? line.hi - 1 : 0;
        line.lo = line.hi;
        line.prevMaxG = line.maxG;
    } else {
        line.prevLo = line.prevHi = line.lo = line.hi = 0;
        line.prevMaxG = -std::numeric_limits<double>::infinity();
    }
    line.maxG = -std::numeric_limits<double>::infinity();
    line.chunk = chunk;
    line.nextChunkM = static_cast<double>(line.chunk + 1) * maxDistanceM;
}

/// One past the hull's new top when the point (sigma, g), nearer than every vertex, is pushed:
/// vertex v1 is popped while the slope to v2 (farther) is at least the slope to v1. The vertex
/// below it is the point's tangent vertex.
/// The first two tests are made without branches: a push pops one vertex about two times in
/// three and none or two nearly all the other times, so a loop's exit branch would be
/// mispredicted on about a third of the pushes (measured on Mount St. Helens and the dune edge);
/// the loop runs only from a third pop on. The tests and their order are the loop's, so is the result.
/// Always inlined: it runs once per line and step, and GCC stopped inlining it into the
/// range-limited walk once that sweep also served eight lines at once (the horizon job then took
/// 1.009x the time of this inlined one, 8 pairs: at the noise).
[[gnu::always_inline]] inline std::size_t hullTopAfterPops(const LineState& line, double sigma, double g) {
    const std::size_t lo = line.lo, hi = line.hi;
    const HullPoint* const buf = line.buf;
    // Pop v1 unless the slope to v2 (farther) is below the slope to v1.
    const auto pops = [&](const HullPoint& v1, const HullPoint& v2) {
        return !((v2.g - g) * (sigma - v1.sigmaM) < (v1.g - g) * (sigma - v2.sigmaM));
    };
    if (hi - lo < 2) return hi;
    // The second test reads a vertex that exists only when three do; otherwise it reads the
    // first one again and its answer is masked.
    const bool first = pops(buf[hi - 1], buf[hi - 2]);
    const bool three = hi - lo >= 3;
    const bool second = pops(buf[hi - 2], buf[three ? hi - 3 : hi - 2]) & three;
    std::size_t top = hi - static_cast<std::size_t>(first) - static_cast<std::size_t>(first & second);
    if (first & second) {
        while (top - lo >= 2 && pops(buf[top - 1], buf[top - 2])) --top;
    }
    return top;
}

/// The curved-earth tangent (slope of the sight line) from a cell at (sigmaQ, gQ) to a line
/// point (sigmaP, gP), as both passes evaluate it. Not inlined, so that both get the same bits
/// whatever the compiler contracts at each call: a tile's first pass may find a point its
/// DEM's walk leaves to the exact pass (its previous chunk started later), and the two must agree.
[[gnu::noinline]] float rangeSlope(double gP, double sigmaP, double gQ, double sigmaQ, double invR);

/// slope(a) > slope(b) from a cell at (sigmaQ, gQ) nearer than both points, by cross
/// multiplication (both distances are positive): no division.
inline bool steeperFrom(const HullPoint& a, const HullPoint& b, double sigmaQ, double gQ) {
    return (a.g - gQ) * (sigmaQ - b.sigmaM) > (b.g - gQ) * (sigmaQ - a.sigmaM);
}

/// Largest g-space slope from (sigmaQ, gQ) to the hull, walking from vertex i (the slope from a
/// point nearer than every vertex is unimodal along an upper hull). Slopes are compared by cross
/// multiplication (all distances are positive), so only the answer costs a division.
inline std::size_t tangentVertex(const HullPoint* h, std::size_t lo, std::size_t hi, std::size_t i, double sigmaQ,
                                 double gQ) {
    auto steeper = [&](std::size_t a, std::size_t b) { return steeperFrom(h[a], h[b], sigmaQ, gQ); };
    bool moved = false;
    while (i > lo && steeper(i - 1, i)) {
        --i;
        moved = true;
    }
    if (!moved) {
        while (i + 1 < hi && !steeper(i, i + 1)) ++i;
    }
    return i;
}

inline double tangentSlope(const LineState& line, std::size_t i, double sigmaQ, double gQ) {
    const HullPoint* h = line.buf;
    i = tangentVertex(h, line.lo, line.hi, i, sigmaQ, gQ);
    return (h[i].g - gQ) / (sigmaQ - h[i].sigmaM);
}

/// Second pass of a range-limited line: see range_limit.cpp.
void limitRangePass(const RangeLog& log, double maxDistanceM, double invR, std::vector<HullPoint>& hull);

}  // namespace demlight::sweep
