// Polynomial sequences: exact on polynomials up to the degree, least-squares residual matches
// a direct evaluation, NaN stays NaN, and a lit-then-shadowed cell shows the documented error.
#include "demlight/lighting/sequence_fit.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace demlight {
namespace {

TEST(Legendre, KnownValues) {
    EXPECT_DOUBLE_EQ(legendreP(2, 0.5), 0.5 * (3 * 0.25 - 1));
    EXPECT_DOUBLE_EQ(legendreP(3, -1.0), -1.0);
    EXPECT_NEAR(legendreP(4, 0.3), (35 * std::pow(0.3, 4) - 30 * 0.09 + 3) / 8, 1e-15);
}

TEST(SequenceFit, ReproducesAPolynomialOfItsDegreeExactly) {
    std::vector<double> times;
    for (int k = 0; k < 20; ++k) times.push_back(1000.0 + 600.0 * k);
    SequenceFitter fitter(times, 3, 2, 1);
    const auto f = [](double t) { const double u = (t - 1000) / 3600; return 0.2 + 0.5 * u - 0.1 * u * u + 0.01 * u * u * u; };
    for (std::size_t k = 0; k < times.size(); ++k) {
        Grid<float> g(2, 1);
        g(0, 0) = static_cast<float>(f(times[k]));
        g(1, 0) = std::numeric_limits<float>::quiet_NaN();
        fitter.addFrame(k, g);
    }
    const SequenceFit fit = fitter.finish();
    for (double t : {1000.0, 4321.0, 12400.0}) {
        const Grid<float> v = evaluateSequence(fit, t);
        EXPECT_NEAR(v(0, 0), f(t), 2e-6);
        EXPECT_TRUE(std::isnan(v(1, 0)));
    }
    EXPECT_LT(fit.rmsError(0, 0), 1e-5);
    EXPECT_TRUE(std::isnan(fit.rmsError(1, 0)));  // nodata has no residual, not a perfect fit
}

TEST(SequenceFit, ResidualEqualsDirectEvaluationForAShadowStep) {
    // Lit for 10 frames then in shadow for 10: no low-order polynomial follows the step.
    std::vector<double> times;
    for (int k = 0; k < 20; ++k) times.push_back(k);
    SequenceFitter fitter(times, 4, 1, 1);
    for (std::size_t k = 0; k < 20; ++k) fitter.addFrame(k, Grid<float>(1, 1, k < 10 ? 1.0f : 0.0f));
    const SequenceFit fit = fitter.finish();
    double ss = 0;
    for (std::size_t k = 0; k < 20; ++k) {
        const double d = evaluateSequence(fit, times[k])(0, 0) - (k < 10 ? 1.0 : 0.0);
        ss += d * d;
    }
    EXPECT_NEAR(fit.rmsError(0, 0), std::sqrt(ss / 20), 1e-5);
    EXPECT_GT(fit.rmsError(0, 0), 0.05);  // the step is smoothed: the known cost of compactness
}

TEST(SequenceFit, RejectsTooFewFrames) {
    EXPECT_THROW(SequenceFitter({0.0, 1.0}, 3, 1, 1), Error);
}

}  // namespace
}  // namespace demlight
