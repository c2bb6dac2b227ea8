// Internal geometry shared by sky.cpp and aperture.cpp: a "wedge" is the set of directions with
// azimuth in [phi1, phi2] and elevation in [lower, upper], intersected with the hemisphere
// around the normal N. Within the wedge the lower limit is max(lower, thetaP(phi)), where
// thetaP(phi) = atan(-a(phi) / N_up), a(phi) = N_e sin phi + N_n cos phi, is the elevation of
// the tangent plane in azimuth phi. The wedge is cut where thetaP crosses lower or upper, so
// that on every piece the lower limit is either the constant or the plane. Angles in radians.
#pragma once

#include "demlight/lighting/sky.h"
#include "demlight/core/fast_math.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>

namespace demlight::detail {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kHalfPi = std::numbers::pi / 2.0;
/// Below this horizontal normal component the tangent plane is treated as horizontal.
inline constexpr double kFlatNormalEps = 1e-12;

/// The normal in the form the wedge integrals need: a(phi) = R sin(phi + delta).
struct NormalFrame {
    double east, north, up;
    double horizontal;  ///< R = |(N_e, N_n)|
    double delta;       ///< atan2(N_n, N_e)
};

/// The normal scaled to unit length with up >= kMinNormalUp (inputs are float grids, and the
/// closed forms assume |N| = 1).
inline EnuVector unitNormal(const EnuVector& n) {
    const double up = std::max(n.up, kMinNormalUp);
    const double len = std::sqrt(n.east * n.east + n.north * n.north + up * up);
    return {n.east / len, n.north / len, up / len};
}

/// `n` must come from unitNormal.
inline NormalFrame makeNormalFrame(const EnuVector& n) {
    NormalFrame f{n.east, n.north, n.up, 0.0, 0.0};
    f.horizontal = std::sqrt(f.east * f.east + f.north * f.north);
    f.delta = std::atan2(f.north, f.east);
    return f;
}

/// Tangent-plane elevation (radians) in azimuth phi (radians).
inline double planeElevation(const NormalFrame& f, double phi) {
    if (f.horizontal < kFlatNormalEps) return 0.0;
    return std::atan(-(f.east * std::sin(phi) + f.north * std::cos(phi)) / f.up);
}

/// Sector i of D (D-sector convention of sky.h) spans [phi_i - w/2, phi_i + w/2], w = 2 pi / D.
inline std::pair<double, double> sectorBoundsRad(std::size_t i, std::size_t count) {
    const double width = 2.0 * kPi / static_cast<double>(count);
    const double centre = width * static_cast<double>(i);
    return {centre - 0.5 * width, centre + 0.5 * width};
}

/// An azimuth interval with the sines and cosines of its ends (for the fast path).
struct AzimuthRange {
    double phi1, phi2, sin1, cos1, sin2, cos2;
};

inline AzimuthRange makeAzimuthRange(double phi1, double phi2) {
    return {phi1, phi2, std::sin(phi1), std::cos(phi1), std::sin(phi2), std::cos(phi2)};
}

/// True if the azimuth of the horizontal vector (e, n) lies inside r (r narrower than pi):
/// sin(psi - phi1) >= 0 and sin(phi2 - psi) >= 0.
inline bool rangeContainsAzimuthOf(const AzimuthRange& r, double e, double n) {
    return e * r.cos1 - n * r.sin1 >= 0.0 && n * r.sin2 - e * r.cos2 >= 0.0;
}

/// The lowest a(phi) = N_e sin phi + N_n cos phi over an azimuth range narrower than pi with
/// ends (sin1, cos1) and (sin2, cos2): at an end, or -R if the range contains the azimuth of
/// (-N_e, -N_n) (rangeContainsAzimuthOf). Branch-free, in float or double, for the vectorised
/// row passes of the sky and the aperture as for planeBelowAcross.
template <class T>
inline T lowestA(T ne, T nn, T sin1, T cos1, T sin2, T cos2) {
    const bool steepestDescentInside = ne * cos1 - nn * sin1 <= T(0) && ne * cos2 - nn * sin2 >= T(0);
    return steepestDescentInside ? -std::sqrt(ne * ne + nn * nn)
                                 : std::min(ne * sin1 + nn * cos1, ne * sin2 + nn * cos2);
}

/// True if the tangent plane lies at or below the elevation with sine/cosine (sinE, cosE,
/// cosE >= 0) at every azimuth of r, so the constant lower limit applies across the whole range
/// and no cut is needed. Plane elevation <= e  <=>  a(phi) cos e + N_up sin e >= 0 (lowestA).
/// Only decides for ranges narrower than pi (returns false else).
inline bool planeBelowAcross(const AzimuthRange& r, double ne, double nn, double nu, double sinE,
                             double cosE) {
    if (!(r.phi2 - r.phi1 < kPi)) return false;
    return lowestA(ne, nn, r.sin1, r.cos1, r.sin2, r.cos2) * cosE + nu * sinE >= 0.0;
}

/// True if the tangent plane lies strictly above the elevation with sine/cosine (sinE, cosE,
/// cosE > 0) at every azimuth of r, so the plane is the lower limit across the whole range:
/// a(phi) cos e + N_up sin e < 0 everywhere; the maximum of a(phi) is at an end of r or, if r
/// contains it, at the azimuth of (N_e, N_n) where a = R. Only decides for ranges narrower than
/// pi (returns false else).
inline bool planeAboveAcross(const AzimuthRange& r, double ne, double nn, double nu, double sinE,
                             double cosE) {
    if (!(r.phi2 - r.phi1 < kPi)) return false;
    double aMax = std::max(ne * r.sin1 + nn * r.cos1, ne * r.sin2 + nn * r.cos2);
    if (rangeContainsAzimuthOf(r, ne, nn)) aMax = std::sqrt(ne * ne + nn * nn);
    return aMax * cosE + nu * sinE < 0.0;
}

enum class PieceLower { Constant, Plane };

/// Calls piece(phiA, phiB, PieceLower) for the non-empty pieces of the wedge
/// [phi1, phi2] x [lower, upper] (radians, phi2 - phi1 <= 2 pi, lower/upper in [-pi/2, pi/2]).
template <class Piece>
void forEachWedgePiece(const NormalFrame& f, double phi1, double phi2, double lower,
                       double upper, Piece&& piece) {
    if (!(lower < upper) || !(phi1 < phi2)) return;
    if (f.horizontal < kFlatNormalEps) {
        // Horizontal tangent plane: the clamp is the constant 0.
        if (std::max(lower, 0.0) < upper)
            piece(phi1, phi2, lower >= 0.0 ? PieceLower::Constant : PieceLower::Plane);
        return;
    }
    // Cut points: thetaP(phi) = x  <=>  R sin(phi + delta) = -N_up tan x. The plane never
    // reaches the zenith, so an upper limit of pi/2 cuts nothing.
    std::array<double, 10> cuts{};
    std::size_t count = 0;
    cuts[count++] = phi1;
    const double tanLower = std::tan(lower);
    const double tanUpper = upper < kHalfPi ? std::tan(upper) : std::numeric_limits<double>::infinity();
    for (double tanX : {tanLower, tanUpper}) {
        if (!std::isfinite(tanX)) continue;
        const double s = -f.up * tanX / f.horizontal;
        if (!(std::abs(s) < 1.0)) continue;
        const double base = std::asin(s);
        for (double psi : {base, kPi - base}) {
            double phi = psi - f.delta;
            // Shift into [phi1, phi1 + 2 pi).
            phi -= 2.0 * kPi * std::floor((phi - phi1) / (2.0 * kPi));
            if (phi > phi1 && phi < phi2) cuts[count++] = phi;
        }
    }
    cuts[count++] = phi2;
    std::sort(cuts.begin() + 1, cuts.begin() + static_cast<std::ptrdiff_t>(count) - 1);
    for (std::size_t i = 0; i + 1 < count; ++i) {
        const double a = cuts[i], b = cuts[i + 1];
        if (!(a < b)) continue;
        // thetaP against the limits through tan thetaP = -a(phi) / N_up (tan is increasing):
        // no arctangent per piece.
        const double mid = 0.5 * (a + b);
        const SinCos m = fastSinCos(mid);
        const double tanP = -(f.east * m.sin + f.north * m.cos) / f.up;
        if (tanP >= tanUpper) continue;
        piece(a, b, tanP > tanLower ? PieceLower::Plane : PieceLower::Constant);
    }
}

/// An end of an algebraic wedge piece: its azimuth as a unit vector (sin, cos), its angle from
/// the range's start, and a(phi) = N_e sin phi + N_n cos phi, b(phi) = N_e cos phi - N_n sin phi
/// (R sin psi and R cos psi, psi = phi + delta: the tangent plane rises to atan(-a / N_up)).
struct PieceEnd {
    double sin, cos, offset, a, b;
};

/// Angle in (0, pi) of a direction whose sine and cosine relative to a reference are (y > 0, x).
inline double angleAbove(double y, double x) {
    return x > 0.0 ? fastAtan(y / x) : kHalfPi + fastAtan(-x / y);
}

/// The pieces of forEachWedgePiece for the range r (narrower than pi), the lower limit `lower`
/// (given by its sine and cosine, cosL >= 0) and the zenith as upper limit, without angles: the
/// cut azimuths, where a(phi) cos(lower) + N_up sin(lower) = 0, are unit vectors
/// (sin psi = s, cos psi = +-sqrt(1 - s^2), turned back by delta), and a piece's width is one
/// arctangent of the cross and dot products of its ends. Calls piece(p, q, width, planeLower)
/// for each piece [p, q] in order; the normal (ne, nn, nu) is a unit normal with a horizontal
/// part R = horizontal > 0.
template <class Piece>
void forEachAlgebraicPiece(double ne, double nn, double nu, double horizontal, const AzimuthRange& r,
                           double sinL, double cosL, Piece&& piece) {
    auto end = [&](double sinPhi, double cosPhi, double offset) {
        return PieceEnd{sinPhi, cosPhi, offset, ne * sinPhi + nn * cosPhi, ne * cosPhi - nn * sinPhi};
    };
    std::array<PieceEnd, 4> ends{};
    std::size_t count = 0;
    ends[count++] = end(r.sin1, r.cos1, 0.0);
    const double t = nu * sinL, q = horizontal * cosL;
    if (std::abs(t) < q) {
        const double s = -t / q;
        const double c = std::sqrt((1.0 - s) * (1.0 + s));
        for (const double cosPsi : {c, -c}) {
            const double sinPhi = (s * ne - cosPsi * nn) / horizontal;
            const double cosPhi = (cosPsi * ne + s * nn) / horizontal;
            const double fromStart = sinPhi * r.cos1 - cosPhi * r.sin1;  // sin(phi - phi1)
            const double toEnd = cosPhi * r.sin2 - sinPhi * r.cos2;      // sin(phi2 - phi)
            if (fromStart > 0.0 && toEnd > 0.0)                          // strictly inside
                ends[count++] = end(sinPhi, cosPhi,
                                    angleAbove(fromStart, cosPhi * r.cos1 + sinPhi * r.sin1));
        }
        if (count == 3 && ends[2].offset < ends[1].offset) std::swap(ends[1], ends[2]);
    }
    ends[count++] = end(r.sin2, r.cos2, r.phi2 - r.phi1);
    for (std::size_t i = 0; i + 1 < count; ++i) {
        const PieceEnd& p = ends[i];
        const PieceEnd& qEnd = ends[i + 1];
        const double width = qEnd.offset - p.offset;
        if (!(width > 0.0)) continue;
        // Which limit holds on the piece: the plane against `lower` at its middle azimuth, the
        // bisector (p + q) / |p + q| (a is linear in the azimuth's unit vector).
        const double midSin = p.sin + qEnd.sin, midCos = p.cos + qEnd.cos;
        const double midLength = std::sqrt(midSin * midSin + midCos * midCos);
        piece(p, qEnd, width, (p.a + qEnd.a) * cosL + nu * sinL * midLength < 0.0);
    }
}

/// The tangent plane's constants: k = R / N_up, m = sqrt(1 + k^2), m - 1 without cancellation.
struct PlaneConstants {
    double k, m, mMinus1;
};
inline PlaneConstants planeConstants(double horizontal, double nu) {
    const double k = horizontal / nu;
    const double m = std::sqrt(1.0 + k * k);
    return {k, m, k * k / (m + 1.0)};
}

/// atan((m - 1) sin psi cos psi / (cos^2 psi + m sin^2 psi)) at a piece end, written in a and b:
/// atan(m tan psi) - psi without its branch jump, the part of L (below) and of the sky's
/// plane antiderivative J that is not linear in psi.
inline double planeAtan(const PlaneConstants& c, const PieceEnd& e) {
    return fastAtan(c.mMinus1 * e.a * e.b / (e.b * e.b + c.m * e.a * e.a));
}

/// L(psi) = integral d psi / (1 + k^2 sin^2 psi) = (psi + planeAtan) / m at a piece end, without
/// its psi term (the caller adds width / m).
inline double planeLWithoutPsi(const PlaneConstants& c, const PieceEnd& e) { return planeAtan(c, e) / c.m; }

/// pi * K over the sector r (narrower than pi) from the constant lower limit `lower` (radians,
/// with its sine and cosine, cosL >= 0) up to the zenith, clipped to the tangent plane of the
/// unit normal (ne, nn, nu) with a horizontal part: the integral of forEachWedgePiece and the
/// piece formulas in sky.cpp, on forEachAlgebraicPiece's pieces. The plane antiderivative
/// J(psi) = -R cos psi atan(k sin psi) + N_up (m atan(...) + (m - 1) psi) is written in a and b,
/// its psi term becoming (m - 1) times the width.
inline double sectorPiKAboveLower(double ne, double nn, double nu, const AzimuthRange& r,
                                  double lower, double sinL, double cosL) {
    const double horizontal = std::sqrt(ne * ne + nn * nn);
    const PlaneConstants c = planeConstants(horizontal, nu);
    auto planeJ = [&](const PieceEnd& e) { return -e.b * fastAtan(e.a / nu) + nu * c.m * planeAtan(c, e); };
    const double constantCos2 = 0.5 * lower + 0.5 * sinL * cosL;  // cos2Antiderivative(lower)
    const double constantSinCos = 0.5 * sinL * sinL;              // sinCosAntiderivative(lower)
    double piK = 0.0;
    forEachAlgebraicPiece(ne, nn, nu, horizontal, r, sinL, cosL,
                          [&](const PieceEnd& p, const PieceEnd& q, double width, bool plane) {
        const double aInt = ne * (p.cos - q.cos) + nn * (q.sin - p.sin);
        // Upper limit the zenith: integral_el^(pi/2) (a cos el + N_up sin el) cos el d el.
        piK += aInt * (kPi / 4.0) + nu * width * 0.5;
        if (plane) {
            piK += 0.5 * (planeJ(q) - planeJ(p) + nu * c.mMinus1 * width);
        } else {
            piK -= aInt * constantCos2 + nu * width * constantSinCos;
        }
    });
    return piK;
}

/// Antiderivatives in elevation of cos^2 and sin cos (d omega = cos(el) d el d az).
inline double cos2Antiderivative(double theta) {
    return theta == kHalfPi ? kPi / 4.0 : 0.5 * theta + 0.25 * fastSinCos(2.0 * theta).sin;
}
inline double sinCosAntiderivative(double theta) {
    if (theta == kHalfPi) return 0.5;
    const double s = fastSinCos(theta).sin;
    return 0.5 * s * s;
}

}  // namespace demlight::detail
