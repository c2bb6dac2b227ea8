// The polynomial atan/sin/cos of src/fast_math.h against <cmath> over their whole domains.
#include "src/fast_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace demlight {
namespace {

TEST(FastMath, AtanWithin3e9RadOverTheRealLine) {
    double worst = 0.0;
    for (int i = -200000; i <= 200000; ++i) {
        // Dense near 0 and out to |x| = 1e6 (steep slopes and grazing lines).
        const double u = i / 20000.0;
        const double x = std::copysign(std::expm1(std::abs(u) * 1.4), u);
        worst = std::max(worst, std::abs(fastAtan(x) - std::atan(x)));
    }
    EXPECT_LT(worst, 3e-9);
    EXPECT_EQ(fastAtan(0.0), 0.0);
    EXPECT_NEAR(fastAtan(std::numeric_limits<double>::infinity()), std::numbers::pi / 2, 1e-15);
}

TEST(FastMath, SinCosWithin1e13OverElevations) {
    double worstSin = 0.0, worstCos = 0.0;
    for (int i = -100000; i <= 100000; ++i) {
        const double x = std::numbers::pi / 2 * i / 100000.0;
        const auto [s, c] = fastSinCosElevation(x);
        worstSin = std::max(worstSin, std::abs(s - std::sin(x)));
        worstCos = std::max(worstCos, std::abs(c - std::cos(x)));
    }
    EXPECT_LT(worstSin, 1e-13);
    EXPECT_LT(worstCos, 1e-13);
    EXPECT_TRUE(std::isnan(fastSinCosElevation(std::numeric_limits<double>::quiet_NaN()).sin));
}

}  // namespace
}  // namespace demlight
