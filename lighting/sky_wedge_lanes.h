// The sky accumulation's exact pass (cells whose tangent plane rises above the horizon in a
// sector narrower than pi) for eight cells at once, one per AVX-512 lane: the scalar chain
// unitNormal -> clampElevationRad -> fastSinCosElevation -> sectorPiKAboveLower / pi of
// sky_wedge.h and sky.cpp written as the same expressions on vectors (GCC's vector extensions:
// + - * / act per lane, and it contracts them as it does the scalar ones), its branches as
// selects. Each lane gets the scalar chain's bits (tests/sky_test.cpp compares them).
#pragma once

#include "lighting/sky_wedge.h"
#include "src/angles.h"

#if defined(__AVX512F__)
// GCC 12 reports its own intrinsics' deliberately undefined start values (_mm512_undefined_*)
// as (maybe) uninitialized where they are inlined (as in lighting/horizon_sweep.cpp).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif
#include <immintrin.h>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#define DEMLIGHT_SKY_LANES 1
#endif

namespace demlight::detail {

#ifdef DEMLIGHT_SKY_LANES
inline constexpr std::size_t kSkyLanes = 8;

namespace lanes {

using D8 = double __attribute__((vector_size(64)));
using M8 = long long __attribute__((vector_size(64)));  // a comparison's lanes: all ones or zero

inline D8 splat(double x) { return D8{x, x, x, x, x, x, x, x}; }  // (0 + x would turn -0 into +0)
inline D8 select(M8 m, D8 a, D8 b) { return m ? a : b; }
inline D8 sqrt8(D8 x) { return reinterpret_cast<D8>(_mm512_sqrt_pd(reinterpret_cast<__m512d>(x))); }
inline constexpr long long kSignBit = std::numeric_limits<long long>::min();
inline D8 abs8(D8 x) { return reinterpret_cast<D8>(reinterpret_cast<M8>(x) & ~kSignBit); }

/// fastAtan (src/fast_math.h), lane by lane.
inline D8 fastAtan8(D8 x) {
    constexpr double kTanPi8 = 0.41421356237309503;
    constexpr double kPi4 = std::numbers::pi / 4.0, kPi2 = std::numbers::pi / 2.0;
    const D8 ax = abs8(x);
    const D8 inverse = 1.0 / ax;
    const M8 invert = ax > 1.0;
    const D8 t = select(invert, inverse, ax);
    const M8 shift = t > kTanPi8;
    const D8 shifted = (t - 1.0) / (t + 1.0);
    const D8 u = select(shift, shifted, t);
    const D8 u2 = u * u;
    D8 p = splat(1.0 / 17.0);
    p = p * u2 - 1.0 / 15.0;
    p = p * u2 + 1.0 / 13.0;
    p = p * u2 - 1.0 / 11.0;
    p = p * u2 + 1.0 / 9.0;
    p = p * u2 - 1.0 / 7.0;
    p = p * u2 + 1.0 / 5.0;
    p = p * u2 - 1.0 / 3.0;
    p = p * u2 + 1.0;
    D8 r = p * u;
    r = select(shift, r + kPi4, r);
    r = select(invert, kPi2 - r, r);
    return reinterpret_cast<D8>((reinterpret_cast<M8>(r) & ~kSignBit) | (reinterpret_cast<M8>(x) & kSignBit));
}

/// fastSinCosElevation, lane by lane.
inline void fastSinCosElevation8(D8 x, D8& sinX, D8& cosX) {
    const D8 x2 = x * x;
    D8 s = splat(1.0 / 355687428096000.0);
    s = s * x2 - 1.0 / 1307674368000.0;
    s = s * x2 + 1.0 / 6227020800.0;
    s = s * x2 - 1.0 / 39916800.0;
    s = s * x2 + 1.0 / 362880.0;
    s = s * x2 - 1.0 / 5040.0;
    s = s * x2 + 1.0 / 120.0;
    s = s * x2 - 1.0 / 6.0;
    s = s * x2 + 1.0;
    D8 c = splat(-1.0 / 6402373705728000.0);
    c = c * x2 + 1.0 / 20922789888000.0;
    c = c * x2 - 1.0 / 87178291200.0;
    c = c * x2 + 1.0 / 479001600.0;
    c = c * x2 - 1.0 / 3628800.0;
    c = c * x2 + 1.0 / 40320.0;
    c = c * x2 - 1.0 / 720.0;
    c = c * x2 + 1.0 / 24.0;
    c = c * x2 - 1.0 / 2.0;
    c = c * x2 + 1.0;
    sinX = s * x;
    cosX = c;
}

/// A piece end of forEachAlgebraicPiece (PieceEnd) in every lane.
struct End8 {
    D8 sin, cos, offset, a, b;
};

inline End8 select(M8 m, const End8& x, const End8& y) {
    return {select(m, x.sin, y.sin), select(m, x.cos, y.cos), select(m, x.offset, y.offset), select(m, x.a, y.a),
            select(m, x.b, y.b)};
}

}  // namespace lanes

/// For eight cells at once: the sector's K (pi K / pi) above each cell's horizon hDeg (degrees)
/// clipped to its tangent plane, the normal (e, n, u) as the grids hold it (unitNormal makes it
/// unit), the sector r narrower than pi. The scalar chain's bits in every lane; no NaN input.
inline void risingSectorK8(const double e[kSkyLanes], const double n[kSkyLanes], const double u[kSkyLanes],
                           const double hDeg[kSkyLanes], const AzimuthRange& r, double k[kSkyLanes]) {
    using namespace lanes;
    D8 e8, n8, u8, h8;
    __builtin_memcpy(&e8, e, sizeof e8);
    __builtin_memcpy(&n8, n, sizeof n8);
    __builtin_memcpy(&u8, u, sizeof u8);
    __builtin_memcpy(&h8, hDeg, sizeof h8);
    // unitNormal
    const D8 up = select(u8 < kMinNormalUp, splat(kMinNormalUp), u8);  // std::max(u, kMinNormalUp)
    const D8 len = sqrt8(e8 * e8 + n8 * n8 + up * up);
    const D8 ne = e8 / len, nn = n8 / len, nu = up / len;
    // clampElevationRad, fastSinCosElevation
    const D8 clamped = select(h8 < -90.0, splat(-90.0), select(90.0 < h8, splat(90.0), h8));
    const D8 lower = clamped * kDegToRad;
    D8 sinL, cosL;
    fastSinCosElevation8(lower, sinL, cosL);
    // sectorPiKAboveLower
    const D8 horizontal = sqrt8(ne * ne + nn * nn);
    const D8 kc = horizontal / nu;
    const D8 m = sqrt8(1.0 + kc * kc);
    const D8 mMinus1 = kc * kc / (m + 1.0);
    const auto planeJ = [&](const End8& x) {
        const D8 planeAtan = fastAtan8(mMinus1 * x.a * x.b / (x.b * x.b + m * x.a * x.a));
        return -x.b * fastAtan8(x.a / nu) + nu * m * planeAtan;
    };
    const D8 constantCos2 = 0.5 * lower + 0.5 * sinL * cosL;
    const D8 constantSinCos = 0.5 * sinL * sinL;
    const auto end = [&](D8 sinPhi, D8 cosPhi, D8 offset) {
        return End8{sinPhi, cosPhi, offset, ne * sinPhi + nn * cosPhi, ne * cosPhi - nn * sinPhi};
    };
    const End8 first = end(splat(r.sin1), splat(r.cos1), splat(0.0));
    const End8 last = end(splat(r.sin2), splat(r.cos2), splat(r.phi2 - r.phi1));
    // The plane's crossings of the lower limit strictly inside the range (at most two).
    const D8 t = nu * sinL, q = horizontal * cosL;
    const M8 crosses = abs8(t) < q;
    const D8 s = -t / q;
    const D8 c = sqrt8((1.0 - s) * (1.0 + s));
    End8 cut[2];
    M8 inside[2];
    for (int i = 0; i < 2; ++i) {
        const D8 cosPsi = i == 0 ? c : -c;
        const D8 sinPhi = (s * ne - cosPsi * nn) / horizontal;
        const D8 cosPhi = (cosPsi * ne + s * nn) / horizontal;
        const D8 fromStart = sinPhi * r.cos1 - cosPhi * r.sin1;
        const D8 toEnd = cosPhi * r.sin2 - sinPhi * r.cos2;
        inside[i] = crosses & (fromStart > 0.0) & (toEnd > 0.0);
        // angleAbove(fromStart, x)
        const D8 x = cosPhi * r.cos1 + sinPhi * r.sin1;
        const D8 offset = select(x > 0.0, fastAtan8(fromStart / x), kHalfPi + fastAtan8(-x / fromStart));
        cut[i] = end(sinPhi, cosPhi, offset);
    }
    // The ends in order: first, the cuts inside (swapped when out of order), last; a missing cut
    // is `last` again, whose piece has no width and is skipped as the scalar loop skips it.
    const M8 both = inside[0] & inside[1];
    const M8 swap = both & (cut[1].offset < cut[0].offset);
    const End8 secondIfBoth = select(swap, cut[0], cut[1]);
    const End8 middle0 = select(inside[0], select(swap, cut[1], cut[0]), select(inside[1], cut[1], last));
    const End8 middle1 = select(both, secondIfBoth, last);
    const End8* ends[4] = {&first, &middle0, &middle1, &last};
    // J at each end, selected as the ends are (the scalar loop evaluates it per piece: the same bits).
    const D8 jFirst = planeJ(first), jCut0 = planeJ(cut[0]), jCut1 = planeJ(cut[1]), jLast = planeJ(last);
    const D8 j[4] = {jFirst, select(inside[0], select(swap, jCut1, jCut0), select(inside[1], jCut1, jLast)),
                     select(both, select(swap, jCut0, jCut1), jLast), jLast};
    D8 piK = splat(0.0);
    for (int i = 0; i < 3; ++i) {
        const End8& p = *ends[i];
        const End8& qEnd = *ends[i + 1];
        const D8 width = qEnd.offset - p.offset;
        const M8 piece = width > 0.0;
        const D8 midSin = p.sin + qEnd.sin, midCos = p.cos + qEnd.cos;
        const D8 midLength = sqrt8(midSin * midSin + midCos * midCos);
        const M8 plane = (p.a + qEnd.a) * cosL + nu * sinL * midLength < 0.0;
        const D8 aInt = ne * (p.cos - qEnd.cos) + nn * (qEnd.sin - p.sin);
        piK = select(piece, piK + (aInt * (kPi / 4.0) + nu * width * 0.5), piK);
        const D8 withPlane = piK + 0.5 * (j[i + 1] - j[i] + nu * mMinus1 * width);
        const D8 withConstant = piK - (aInt * constantCos2 + nu * width * constantSinCos);
        piK = select(piece, select(plane, withPlane, withConstant), piK);
    }
    const D8 out = piK / kPi;
    __builtin_memcpy(k, &out, sizeof out);
}
#endif

}  // namespace demlight::detail
