// Polynomial atan, sin and cos for the per-cell inner loops (horizon sweep, sky accumulation),
// accurate far below a float's resolution and several times cheaper than libm's calls, which
// cannot be inlined or vectorised. tests/fast_math_test.cpp measures them against <cmath>.
#pragma once

#include <cmath>
#include <numbers>

namespace demlight {

/// atan(x) (radians) to within 3e-9 rad: fold |x| into [0, 1] (atan x = π/2 - atan 1/x), then
/// into |u| <= tan(π/8) (atan t = π/4 + atan((t-1)/(t+1))), then the Taylor series to u^17,
/// whose remainder is below tan(π/8)^19 / 19. Both folds are computed and then selected, with no
/// branch, so loops over it vectorise (GCC keeps a conditional division unvectorised).
inline double fastAtan(double x) {
    constexpr double kTanPi8 = 0.41421356237309503;
    constexpr double kPi4 = std::numbers::pi / 4.0, kPi2 = std::numbers::pi / 2.0;
    const double ax = std::abs(x);
    const double inverse = 1.0 / ax;
    const bool invert = ax > 1.0;
    const double t = invert ? inverse : ax;
    const bool shift = t > kTanPi8;
    const double shifted = (t - 1.0) / (t + 1.0);
    const double u = shift ? shifted : t;
    const double u2 = u * u;
    double p = 1.0 / 17.0;
    p = p * u2 - 1.0 / 15.0;
    p = p * u2 + 1.0 / 13.0;
    p = p * u2 - 1.0 / 11.0;
    p = p * u2 + 1.0 / 9.0;
    p = p * u2 - 1.0 / 7.0;
    p = p * u2 + 1.0 / 5.0;
    p = p * u2 - 1.0 / 3.0;
    p = p * u2 + 1.0;
    double r = p * u;
    if (shift) r += kPi4;
    if (invert) r = kPi2 - r;
    return std::copysign(r, x);
}

/// sin and cos of x in [-π/2, π/2] (radians; an elevation angle) by their Taylor series to x^17
/// and x^18, whose remainders at |x| = π/2 are below 5e-14 and 4e-15. Outside that range the
/// result is meaningless; NaN propagates.
struct SinCos {
    double sin, cos;
};
inline SinCos fastSinCosElevation(double x) {
    const double x2 = x * x;
    double s = 1.0 / 355687428096000.0;          // 1/17!
    s = s * x2 - 1.0 / 1307674368000.0;          // -1/15!
    s = s * x2 + 1.0 / 6227020800.0;             // 1/13!
    s = s * x2 - 1.0 / 39916800.0;               // -1/11!
    s = s * x2 + 1.0 / 362880.0;                 // 1/9!
    s = s * x2 - 1.0 / 5040.0;                   // -1/7!
    s = s * x2 + 1.0 / 120.0;                    // 1/5!
    s = s * x2 - 1.0 / 6.0;                      // -1/3!
    s = s * x2 + 1.0;
    double c = -1.0 / 6402373705728000.0;        // -1/18!
    c = c * x2 + 1.0 / 20922789888000.0;         // 1/16!
    c = c * x2 - 1.0 / 87178291200.0;            // -1/14!
    c = c * x2 + 1.0 / 479001600.0;              // 1/12!
    c = c * x2 - 1.0 / 3628800.0;                // -1/10!
    c = c * x2 + 1.0 / 40320.0;                  // 1/8!
    c = c * x2 - 1.0 / 720.0;                    // -1/6!
    c = c * x2 + 1.0 / 24.0;                     // 1/4!
    c = c * x2 - 1.0 / 2.0;                      // -1/2!
    c = c * x2 + 1.0;
    return {s * x, c};
}

/// sin and cos of any finite x (radians): x reduced to [-π, π] by the nearest multiple of 2π
/// (in two parts, exact to ~1e-16 |x| / π), reflected into [-π/2, π/2], then
/// fastSinCosElevation. Within 1e-13 of <cmath> for |x| up to a few turns; beyond 1e6 rad, NaN
/// and infinities, <cmath> itself.
inline SinCos fastSinCos(double x) {
    constexpr double kTwoPiHi = 6.283185307179586, kTwoPiLo = 2.4492935982947064e-16;
    constexpr double kInvTwoPi = 1.0 / (2.0 * std::numbers::pi);
    constexpr double kPi = std::numbers::pi, kHalfPi = std::numbers::pi / 2.0;
    // NaN, infinities and angles of many turns (never from the callers) go to <cmath>; the
    // conversion to an integer below is defined only for finite, moderate values.
    if (!(std::abs(x) <= 1e6)) return {std::sin(x), std::cos(x)};
    const double turns = static_cast<double>(static_cast<long long>(x * kInvTwoPi + (x >= 0.0 ? 0.5 : -0.5)));
    const double r = (x - turns * kTwoPiHi) - turns * kTwoPiLo;
    if (r > kHalfPi) {
        const SinCos t = fastSinCosElevation(kPi - r);
        return {t.sin, -t.cos};
    }
    if (r < -kHalfPi) {
        const SinCos t = fastSinCosElevation(-kPi - r);
        return {t.sin, -t.cos};
    }
    return fastSinCosElevation(r);
}

/// sin x for x in [-π/2, π/2] in float arithmetic, by the Taylor series to x^11 (remainder below
/// 6e-8 at |x| = π/2, a float's own resolution): for sums kept in float, where the branch-free
/// form lets the compiler vectorise the loop. NaN propagates.
inline float fastSinElevationF(float x) {
    const float x2 = x * x;
    float s = -1.0f / 39916800.0f;  // -1/11!
    s = s * x2 + 1.0f / 362880.0f;  // 1/9!
    s = s * x2 - 1.0f / 5040.0f;    // -1/7!
    s = s * x2 + 1.0f / 120.0f;     // 1/5!
    s = s * x2 - 1.0f / 6.0f;       // -1/3!
    s = s * x2 + 1.0f;
    return s * x;
}

}  // namespace demlight
