#include "demlight/lighting/sequence_fit.h"

#include "demlight/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demlight {
namespace {

double toUnit(double t, double t0, double t1) {
    return t1 > t0 ? std::clamp(2 * (t - t0) / (t1 - t0) - 1, -1.0, 1.0) : 0.0;
}

/// Solves the small symmetric system G c = b in place (Gaussian elimination with pivoting).
std::vector<double> solve(std::vector<std::vector<double>> g, std::vector<double> b) {
    const std::size_t n = b.size();
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t p = i;
        for (std::size_t r = i + 1; r < n; ++r)
            if (std::abs(g[r][i]) > std::abs(g[p][i])) p = r;
        std::swap(g[i], g[p]);
        std::swap(b[i], b[p]);
        if (std::abs(g[i][i]) < 1e-300) throw Error("sequence fit: too few distinct frame times for the degree");
        for (std::size_t r = i + 1; r < n; ++r) {
            const double f = g[r][i] / g[i][i];
            for (std::size_t c = i; c < n; ++c) g[r][c] -= f * g[i][c];
            b[r] -= f * b[i];
        }
    }
    std::vector<double> x(n);
    for (std::size_t i = n; i-- > 0;) {
        double s = b[i];
        for (std::size_t c = i + 1; c < n; ++c) s -= g[i][c] * x[c];
        x[i] = s / g[i][i];
    }
    return x;
}

}  // namespace

double legendreP(int j, double x) {
    if (j == 0) return 1.0;
    double prev = 1.0, cur = x;
    for (int k = 1; k < j; ++k) {
        const double next = ((2 * k + 1) * x * cur - k * prev) / (k + 1);
        prev = cur;
        cur = next;
    }
    return cur;
}

SequenceFitter::SequenceFitter(std::vector<double> timesSec, int degree, std::size_t width,
                               std::size_t height)
    : times_(std::move(timesSec)), degree_(degree), sumSquares_(width, height, 0.0) {
    if (degree < 0 || degree > 12) throw Error("sequence fit: degree must be in 0..12");
    if (times_.size() < static_cast<std::size_t>(degree) + 1)
        throw Error("sequence fit: degree " + std::to_string(degree) + " needs at least " +
                    std::to_string(degree + 1) + " frames");
    moments_.assign(static_cast<std::size_t>(degree) + 1, Grid<double>(width, height, 0.0));
}

void SequenceFitter::addFrame(std::size_t index, const Grid<float>& values) {
    const auto [t0, t1] = std::minmax_element(times_.begin(), times_.end());
    const double x = toUnit(times_.at(index), *t0, *t1);
    for (int j = 0; j <= degree_; ++j) {
        const double p = legendreP(j, x);
        double* m = moments_[static_cast<std::size_t>(j)].data();
        for (std::size_t i = 0; i < values.size(); ++i) m[i] += p * values.data()[i];
    }
    for (std::size_t i = 0; i < values.size(); ++i)
        sumSquares_.data()[i] += static_cast<double>(values.data()[i]) * values.data()[i];
}

SequenceFit SequenceFitter::finish() const {
    const auto [t0, t1] = std::minmax_element(times_.begin(), times_.end());
    const std::size_t n = static_cast<std::size_t>(degree_) + 1;
    // Gram matrix G_ij = sum_k P_i(x_k) P_j(x_k); the same for every cell.
    std::vector<std::vector<double>> gram(n, std::vector<double>(n, 0.0));
    for (double t : times_) {
        const double x = toUnit(t, *t0, *t1);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < n; ++j)
                gram[i][j] += legendreP(static_cast<int>(i), x) * legendreP(static_cast<int>(j), x);
    }
    // Columns of G^-1 once, then c = G^-1 b per cell.
    std::vector<std::vector<double>> inverse(n);
    for (std::size_t j = 0; j < n; ++j) {
        std::vector<double> e(n, 0.0);
        e[j] = 1.0;
        inverse[j] = solve(gram, e);
    }
    SequenceFit fit;
    fit.degree = degree_;
    fit.t0Sec = *t0;
    fit.t1Sec = *t1;
    const std::size_t w = sumSquares_.width(), h = sumSquares_.height();
    fit.coefficients.assign(n, Grid<float>(w, h));
    fit.rmsError = Grid<float>(w, h);
    std::vector<double> c(n);
    for (std::size_t cell = 0; cell < w * h; ++cell) {
        for (std::size_t i = 0; i < n; ++i) {
            c[i] = 0;
            for (std::size_t j = 0; j < n; ++j) c[i] += inverse[j][i] * moments_[j].data()[cell];
        }
        // Least squares: residual sum of squares = sum v^2 - c . b.
        double explained = 0;
        for (std::size_t i = 0; i < n; ++i) {
            fit.coefficients[i].data()[cell] = static_cast<float>(c[i]);
            explained += c[i] * moments_[i].data()[cell];
        }
        // (std::max would turn a nodata cell's NaN into 0.)
        const double rss = sumSquares_.data()[cell] - explained;
        fit.rmsError.data()[cell] =
            std::isnan(rss) ? std::numeric_limits<float>::quiet_NaN()
                            : static_cast<float>(std::sqrt(std::max(0.0, rss) / static_cast<double>(times_.size())));
    }
    return fit;
}

Grid<float> evaluateSequence(const SequenceFit& fit, double tSec) {
    const double x = toUnit(tSec, fit.t0Sec, fit.t1Sec);
    Grid<float> out(fit.coefficients.front().width(), fit.coefficients.front().height(), 0.0f);
    for (int j = 0; j <= fit.degree; ++j) {
        const auto p = static_cast<float>(legendreP(j, x));
        const float* c = fit.coefficients[static_cast<std::size_t>(j)].data();
        for (std::size_t i = 0; i < out.size(); ++i) out.data()[i] += p * c[i];
    }
    return out;
}

}  // namespace demlight
