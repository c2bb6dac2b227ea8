// Compact lightmap sequences: a day of frames stored per cell as a low-order polynomial in time
// (Hoffman & Mitchell's "polynomial texture maps" applied over time rather than light direction;
// Hoffman & Mitchell 2001a). Each cell's values v_k at times t_k are fitted in least squares by
//     v(t) ≈ sum_j c_j P_j(x),   x = 2 (t - t0) / (t1 - t0) - 1 in [-1, 1],
// with Legendre polynomials P_j, j = 0..degree. Frames stream in one at a time, so only the
// (degree + 2) accumulators per cell are held, never the sequence.
#pragma once

#include "demlight/core/grid.h"

#include <vector>

namespace demlight {

/// Legendre polynomial P_j(x) (Bonnet's recursion).
double legendreP(int j, double x);

/// The stored sequence: coefficients per cell plus the time span they cover.
struct SequenceFit {
    int degree = 0;
    double t0Sec = 0, t1Sec = 0;           ///< time span (seconds on any common clock)
    std::vector<Grid<float>> coefficients; ///< c_0 .. c_degree; NaN at nodata
    Grid<float> rmsError;                  ///< per-cell RMS residual over the fitted frames
};

/// Streams frames into the least-squares fit.
class SequenceFitter {
public:
    /// `timesSec` are the frame instants (at least degree + 1 distinct values).
    SequenceFitter(std::vector<double> timesSec, int degree, std::size_t width, std::size_t height);
    /// Adds frame `index` (its values at timesSec[index]); NaN cells stay NaN.
    void addFrame(std::size_t index, const Grid<float>& values);
    /// Solves for the coefficients and the residuals.
    SequenceFit finish() const;

private:
    std::vector<double> times_;
    int degree_;
    std::vector<Grid<double>> moments_;  ///< b_j = sum_k P_j(x_k) v_k per cell
    Grid<double> sumSquares_;            ///< sum_k v_k^2 per cell
};

/// The reader: reconstructs the lightmap at time tSec (clamped to the fitted span).
Grid<float> evaluateSequence(const SequenceFit& fit, double tSec);

}  // namespace demlight
