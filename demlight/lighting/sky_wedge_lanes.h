// The sky's and the aperture's exact passes (cells whose tangent plane rises above the horizon
// in a sector narrower than pi) for eight cells at once, one per AVX-512 lane (on the AVX-512 path
// of demlight/core/simd.h: every function here is compiled for it, DEMLIGHT_AVX512): the scalar chains
// (unitNormal, the clamped elevation, fastSinCosElevation, then sectorPiKAboveLower / pi or
// addApertureSectorAlgebraic, over forEachAlgebraicPiece's pieces) written as the same
// expressions on vectors (GCC's vector extensions: + - * / act per lane), their branches as
// selects. The build contracts no multiply and add into one rounding (-ffp-contract=off), so a
// lane gives the scalar chain's bits (tests/sky_test.cpp and tests/aperture_test.cpp).
#pragma once

#include "demlight/lighting/sky_wedge.h"
#include "demlight/core/angles.h"

#include "demlight/core/avx512.h"

#include <cstddef>
#include <vector>

#ifdef DEMLIGHT_HAS_AVX512_KERNELS
#define DEMLIGHT_SKY_LANES 1
#endif

namespace demlight::detail {

#ifdef DEMLIGHT_SKY_LANES
inline constexpr std::size_t kSkyLanes = 8;

/// A row's cells `cols` (in order), eight at a time: eight(cols + i) for each whole group of
/// eight, then one(col) for each of the rest.
template <class Eight, class One>
void inGroupsOfEight(const std::vector<std::size_t>& cols, Eight&& eight, One&& one) {
    std::size_t i = 0;
    for (; i + kSkyLanes <= cols.size(); i += kSkyLanes) eight(cols.data() + i);
    for (; i < cols.size(); ++i) one(cols[i]);
}

/// row[cols[l]] for the eight lanes, as doubles.
template <class T>
void gather8(const T* row, const std::size_t* cols, double out[kSkyLanes]) {
    for (std::size_t l = 0; l < kSkyLanes; ++l) out[l] = static_cast<double>(row[cols[l]]);
}

/// row[cols[l]] = in[l] for the eight lanes.
inline void scatter8(const double in[kSkyLanes], const std::size_t* cols, double* row) {
    for (std::size_t l = 0; l < kSkyLanes; ++l) row[cols[l]] = in[l];
}

namespace lanes {

using D8 = double __attribute__((vector_size(64)));
using M8 = long long __attribute__((vector_size(64)));  // a comparison's lanes: all ones or zero

DEMLIGHT_AVX512 inline D8 splat(double x) { return D8{x, x, x, x, x, x, x, x}; }  // (0 + x would turn -0 into +0)
DEMLIGHT_AVX512 inline D8 select(M8 m, D8 a, D8 b) { return m ? a : b; }
DEMLIGHT_AVX512 inline D8 sqrt8(D8 x) { return reinterpret_cast<D8>(_mm512_sqrt_pd(reinterpret_cast<__m512d>(x))); }
inline constexpr long long kSignBit = std::numeric_limits<long long>::min();
DEMLIGHT_AVX512 inline D8 abs8(D8 x) { return reinterpret_cast<D8>(reinterpret_cast<M8>(x) & ~kSignBit); }

/// fastAtan (demlight/core/fast_math.h), lane by lane. A mirror rather than one template for both: written
/// once for double and vectors, the scalar function compiled differently and changed the
/// patched sky's values (`sky --patches`, three files of scripts/compare_outputs.sh).
DEMLIGHT_AVX512 inline D8 fastAtan8(D8 x) {
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
DEMLIGHT_AVX512 inline void fastSinCosElevation8(D8 x, D8& sinX, D8& cosX) {
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

DEMLIGHT_AVX512 inline End8 select(M8 m, const End8& x, const End8& y) {
    return {select(m, x.sin, y.sin), select(m, x.cos, y.cos), select(m, x.offset, y.offset), select(m, x.a, y.a),
            select(m, x.b, y.b)};
}

}  // namespace lanes

namespace lanes {

/// Eight cells as the exact passes take them: the unit normal (unitNormal), the horizon
/// clamped to +-90 deg in radians (the lower limit) with its sine and cosine, R = |(N_e, N_n)|.
struct Cells8 {
    D8 ne, nn, nu, lower, sinL, cosL, horizontal;
};

DEMLIGHT_AVX512 inline Cells8 cells8(const double e[8], const double n[8], const double u[8], const double hDeg[8]) {
    D8 e8, n8, u8, h8;
    __builtin_memcpy(&e8, e, sizeof e8);
    __builtin_memcpy(&n8, n, sizeof n8);
    __builtin_memcpy(&u8, u, sizeof u8);
    __builtin_memcpy(&h8, hDeg, sizeof h8);
    Cells8 c;
    const D8 up = select(u8 < kMinNormalUp, splat(kMinNormalUp), u8);  // std::max(u, kMinNormalUp)
    const D8 len = sqrt8(e8 * e8 + n8 * n8 + up * up);
    c.ne = e8 / len;
    c.nn = n8 / len;
    c.nu = up / len;
    const D8 clamped = select(h8 < -90.0, splat(-90.0), select(90.0 < h8, splat(90.0), h8));  // std::clamp
    c.lower = clamped * kDegToRad;
    fastSinCosElevation8(c.lower, c.sinL, c.cosL);
    c.horizontal = sqrt8(c.ne * c.ne + c.nn * c.nn);
    return c;
}

/// forEachAlgebraicPiece's ends in every lane: the range's first and last, and the plane's two
/// crossings of the lower limit, `inside` where strictly inside the range. In order they are
/// first, middle(0), middle(1), last: a missing crossing is `last` again, whose piece has no
/// width and is skipped as the scalar loop skips it.
struct Ends8 {
    End8 first, cut[2], last;
    M8 inside[2], both, swap;
    /// The second and third end (i = 0, 1) of a quantity given at first, cut[0], cut[1], last.
    template <class T>
    DEMLIGHT_AVX512 T middle(int i, const T& c0, const T& c1, const T& l) const {
        return i == 0 ? select(inside[0], select(swap, c1, c0), select(inside[1], c1, l))
                      : select(both, select(swap, c0, c1), l);
    }
};

DEMLIGHT_AVX512 inline Ends8 ends8(const Cells8& c, const AzimuthRange& r) {
    const auto end = [&](D8 sinPhi, D8 cosPhi, D8 offset) DEMLIGHT_AVX512 {
        return End8{sinPhi, cosPhi, offset, c.ne * sinPhi + c.nn * cosPhi, c.ne * cosPhi - c.nn * sinPhi};
    };
    Ends8 e;
    e.first = end(splat(r.sin1), splat(r.cos1), splat(0.0));
    e.last = end(splat(r.sin2), splat(r.cos2), splat(r.phi2 - r.phi1));
    const D8 t = c.nu * c.sinL, q = c.horizontal * c.cosL;
    const M8 crosses = abs8(t) < q;
    const D8 s = -t / q;
    const D8 cc = sqrt8((1.0 - s) * (1.0 + s));
    for (int i = 0; i < 2; ++i) {
        const D8 cosPsi = i == 0 ? cc : -cc;
        const D8 sinPhi = (s * c.ne - cosPsi * c.nn) / c.horizontal;
        const D8 cosPhi = (cosPsi * c.ne + s * c.nn) / c.horizontal;
        const D8 fromStart = sinPhi * r.cos1 - cosPhi * r.sin1;
        const D8 toEnd = cosPhi * r.sin2 - sinPhi * r.cos2;
        e.inside[i] = crosses & (fromStart > 0.0) & (toEnd > 0.0);
        // angleAbove(fromStart, x)
        const D8 x = cosPhi * r.cos1 + sinPhi * r.sin1;
        const D8 offset = select(x > 0.0, fastAtan8(fromStart / x), kHalfPi + fastAtan8(-x / fromStart));
        e.cut[i] = end(sinPhi, cosPhi, offset);
    }
    e.both = e.inside[0] & e.inside[1];
    e.swap = e.both & (e.cut[1].offset < e.cut[0].offset);
    return e;
}

/// The pieces' plane test (forEachAlgebraicPiece): the plane against the lower limit at the
/// piece's middle azimuth.
DEMLIGHT_AVX512 inline M8 planeLower(const Cells8& c, const End8& p, const End8& q) {
    const D8 midSin = p.sin + q.sin, midCos = p.cos + q.cos;
    const D8 midLength = sqrt8(midSin * midSin + midCos * midCos);
    return (p.a + q.a) * c.cosL + c.nu * c.sinL * midLength < 0.0;
}

}  // namespace lanes

/// For eight cells at once: the sector's K (pi K / pi) above each cell's horizon hDeg (degrees)
/// clipped to its tangent plane, the normal (e, n, u) as the grids hold it (unitNormal makes it
/// unit), the sector r narrower than pi: sky.cpp's chain in every lane. No NaN input.
DEMLIGHT_AVX512 inline void risingSectorK8(const double e[kSkyLanes], const double n[kSkyLanes], const double u[kSkyLanes],
                           const double hDeg[kSkyLanes], const AzimuthRange& r, double k[kSkyLanes]) {
    using namespace lanes;
    const Cells8 c = cells8(e, n, u, hDeg);
    const Ends8 x = ends8(c, r);
    // sectorPiKAboveLower's constants and its J at each end (the scalar loop evaluates J per
    // piece: the same bits).
    const D8 kc = c.horizontal / c.nu;
    const D8 m = sqrt8(1.0 + kc * kc);
    const D8 mMinus1 = kc * kc / (m + 1.0);
    const auto planeJ = [&](const End8& y) DEMLIGHT_AVX512 {
        const D8 planeAtan = fastAtan8(mMinus1 * y.a * y.b / (y.b * y.b + m * y.a * y.a));
        return -y.b * fastAtan8(y.a / c.nu) + c.nu * m * planeAtan;
    };
    const D8 constantCos2 = 0.5 * c.lower + 0.5 * c.sinL * c.cosL;
    const D8 constantSinCos = 0.5 * c.sinL * c.sinL;
    const End8 middle0 = x.middle(0, x.cut[0], x.cut[1], x.last), middle1 = x.middle(1, x.cut[0], x.cut[1], x.last);
    const End8* ends[4] = {&x.first, &middle0, &middle1, &x.last};
    const D8 jCut0 = planeJ(x.cut[0]), jCut1 = planeJ(x.cut[1]), jLast = planeJ(x.last);
    const D8 j[4] = {planeJ(x.first), x.middle(0, jCut0, jCut1, jLast), x.middle(1, jCut0, jCut1, jLast), jLast};
    D8 piK = splat(0.0);
    for (int i = 0; i < 3; ++i) {
        const End8& p = *ends[i];
        const End8& q = *ends[i + 1];
        const D8 width = q.offset - p.offset;
        const M8 piece = width > 0.0;
        const M8 plane = planeLower(c, p, q);
        const D8 aInt = c.ne * (p.cos - q.cos) + c.nn * (q.sin - p.sin);
        piK = select(piece, piK + (aInt * (kPi / 4.0) + c.nu * width * 0.5), piK);
        const D8 withPlane = piK + 0.5 * (j[i + 1] - j[i] + c.nu * mMinus1 * width);
        const D8 withConstant = piK - (aInt * constantCos2 + c.nu * width * constantSinCos);
        piK = select(piece, select(plane, withPlane, withConstant), piK);
    }
    const D8 out = piK / kPi;
    __builtin_memcpy(k, &out, sizeof out);
}

/// For eight cells at once: aperture.cpp's exact pass (unitNormal, the clamped lower limit, its
/// sine and cosine, addApertureSectorAlgebraic) adding the sector above each cell's horizon to
/// its sums omega, ve, vn, vu (in and out). The sector r narrower than pi; no NaN input.
DEMLIGHT_AVX512 inline void risingApertureSector8(const double e[kSkyLanes], const double n[kSkyLanes], const double u[kSkyLanes],
                                  const double hDeg[kSkyLanes], const AzimuthRange& r, double omega[kSkyLanes],
                                  double ve[kSkyLanes], double vn[kSkyLanes], double vu[kSkyLanes]) {
    using namespace lanes;
    const Cells8 c = cells8(e, n, u, hDeg);
    const Ends8 x = ends8(c, r);
    const D8 kc = c.horizontal / c.nu;
    const D8 m = sqrt8(1.0 + kc * kc);
    const D8 mMinus1 = kc * kc / (m + 1.0);
    const D8 cosDelta = c.ne / c.horizontal, sinDelta = c.nn / c.horizontal;
    // planeTerms at an end: the arcsine of b, L without its psi term, I_s and I_c.
    struct Terms {
        D8 asinB, l, iS, iC;
    };
    const auto terms = [&](const End8& y) DEMLIGHT_AVX512 {
        const D8 bUnit = select(y.b < -1.0, splat(-1.0), select(1.0 < y.b, splat(1.0), y.b));  // std::clamp
        const D8 rest = 1.0 - bUnit * bUnit;
        Terms t;
        t.asinB = fastAtan8(bUnit / sqrt8(select(0.0 < rest, rest, splat(0.0))));  // std::max(0.0, rest)
        t.l = fastAtan8(mMinus1 * y.a * y.b / (y.b * y.b + m * y.a * y.a)) / m;
        const D8 atanX = fastAtan8(y.a / c.nu);
        t.iC = 0.5 * (y.a / c.horizontal) * atanX;
        t.iS = 0.5 * (kc * t.l - (y.b / c.horizontal) * atanX);
        return t;
    };
    const auto pick = [&](int i, const Terms& t0, const Terms& t1, const Terms& tl) DEMLIGHT_AVX512 {
        return Terms{x.middle(i, t0.asinB, t1.asinB, tl.asinB), x.middle(i, t0.l, t1.l, tl.l),
                     x.middle(i, t0.iS, t1.iS, tl.iS), x.middle(i, t0.iC, t1.iC, tl.iC)};
    };
    const End8 middle0 = x.middle(0, x.cut[0], x.cut[1], x.last), middle1 = x.middle(1, x.cut[0], x.cut[1], x.last);
    const End8* ends[4] = {&x.first, &middle0, &middle1, &x.last};
    const Terms tCut0 = terms(x.cut[0]), tCut1 = terms(x.cut[1]), tLast = terms(x.last);
    const Terms t[4] = {terms(x.first), pick(0, tCut0, tCut1, tLast), pick(1, tCut0, tCut1, tLast), tLast};
    D8 o, de, dn, du;
    __builtin_memcpy(&o, omega, sizeof o);
    __builtin_memcpy(&de, ve, sizeof de);
    __builtin_memcpy(&dn, vn, sizeof dn);
    __builtin_memcpy(&du, vu, sizeof du);
    // addConstantLowerPiece's cos2 (the same for every piece of a cell).
    const D8 cos2 = kPi / 4.0 - (0.5 * c.lower + 0.5 * c.sinL * c.cosL);
    for (int i = 0; i < 3; ++i) {
        const End8& p = *ends[i];
        const End8& q = *ends[i + 1];
        const D8 width = q.offset - p.offset;
        const M8 piece = width > 0.0;
        const M8 plane = planeLower(c, p, q) & piece;
        const M8 constant = ~planeLower(c, p, q) & piece;
        const D8 cosDrop = p.cos - q.cos, sinRise = q.sin - p.sin;
        // A constant lower limit (addConstantLowerPiece).
        const D8 oConstant = o + width * (1.0 - c.sinL);
        const D8 eConstant = de + cosDrop * cos2;
        const D8 nConstant = dn + sinRise * cos2;
        const D8 uConstant = du + width * (0.5 - 0.5 * c.sinL * c.sinL);
        // The plane.
        const Terms& tp = t[i];
        const Terms& tq = t[i + 1];
        const D8 deltaL = tq.l - tp.l + width / m;
        const D8 deltaS = tq.iS - tp.iS + 0.5 * kc * width / m, deltaC = tq.iC - tp.iC;
        const D8 oPlane = o + (width - (tq.asinB - tp.asinB));
        const D8 ePlane = de + (kPi / 4.0 * cosDrop + cosDelta * deltaS - sinDelta * deltaC);
        const D8 nPlane = dn + (kPi / 4.0 * sinRise + cosDelta * deltaC + sinDelta * deltaS);
        const D8 uPlane = du + 0.5 * deltaL;
        o = select(plane, oPlane, select(constant, oConstant, o));
        de = select(plane, ePlane, select(constant, eConstant, de));
        dn = select(plane, nPlane, select(constant, nConstant, dn));
        du = select(plane, uPlane, select(constant, uConstant, du));
    }
    __builtin_memcpy(omega, &o, sizeof o);
    __builtin_memcpy(ve, &de, sizeof de);
    __builtin_memcpy(vn, &dn, sizeof dn);
    __builtin_memcpy(vu, &du, sizeof du);
}
#endif

}  // namespace demlight::detail
