// The polynomial atan/sin/cos of demlight/core/fast_math.h against <cmath> over their whole domains.
#include "demlight/core/fast_math.h"

#include <gtest/gtest.h>

#include <algorithm>
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

/// Largest |sin - std::sin| and |cos - std::cos| of a SinCos function over the angles it is given.
struct WorstSinCos {
    double sin = 0.0, cos = 0.0;
    template <class F>
    void add(F f, double x) {
        const auto [s, c] = f(x);
        sin = std::max(sin, std::abs(s - std::sin(x)));
        cos = std::max(cos, std::abs(c - std::cos(x)));
    }
};

TEST(FastMath, SinCosWithin1e13OverElevations) {
    WorstSinCos worst;
    for (int i = -100000; i <= 100000; ++i)
        worst.add(fastSinCosElevation, std::numbers::pi / 2 * i / 100000.0);
    EXPECT_LT(worst.sin, 1e-13);
    EXPECT_LT(worst.cos, 1e-13);
    EXPECT_TRUE(std::isnan(fastSinCosElevation(std::numeric_limits<double>::quiet_NaN()).sin));
}

TEST(FastMath, SinCosWithin1e13OverSeveralTurns) {
    // fastSinCos reduces any angle; the sky wedges pass azimuths plus a normal's direction, a
    // few turns at most. Include the reflection seams at +-pi/2 and +-pi.
    WorstSinCos worst;
    for (int i = -200000; i <= 200000; ++i) {
        const double x = 4.0 * std::numbers::pi * i / 100000.0;  // -8 pi .. 8 pi
        for (double y : {x, std::numbers::pi / 2 + x * 1e-9, std::numbers::pi - x * 1e-9}) worst.add(fastSinCos, y);
    }
    EXPECT_LT(worst.sin, 1e-13);
    EXPECT_LT(worst.cos, 1e-13);
    EXPECT_TRUE(std::isnan(fastSinCos(std::numeric_limits<double>::quiet_NaN()).cos));
}

TEST(FastMath, FloatSinWithinFloatResolution) {
    float worst = 0.0f;
    for (int i = -100000; i <= 100000; ++i) {
        const float x = static_cast<float>(std::numbers::pi / 2 * i / 100000.0);
        worst = std::max(worst, std::abs(fastSinElevationF(x) - static_cast<float>(std::sin(static_cast<double>(x)))));
    }
    EXPECT_LT(worst, 2e-7f);
    EXPECT_TRUE(std::isnan(fastSinElevationF(std::numeric_limits<float>::quiet_NaN())));
}

}  // namespace
}  // namespace demlight
