// Internal geometry shared by sky.cpp and aperture.cpp: a "wedge" is the set of directions with
// azimuth in [phi1, phi2] and elevation in [lower, upper], intersected with the hemisphere
// around the normal N. Within the wedge the lower limit is max(lower, thetaP(phi)), where
// thetaP(phi) = atan(-a(phi) / N_up), a(phi) = N_e sin phi + N_n cos phi, is the elevation of
// the tangent plane in azimuth phi. The wedge is cut where thetaP crosses lower or upper, so
// that on every piece the lower limit is either the constant or the plane. Angles in radians.
#pragma once

#include "lighting/sky.h"
#include "src/fast_math.h"

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

/// True if the tangent plane lies at or below the elevation with sine/cosine (sinE, cosE,
/// cosE >= 0) at every azimuth of r, so the constant lower limit applies across the whole range
/// and no cut is needed. Plane elevation <= e  <=>  a(phi) cos e + N_up sin e >= 0; the minimum
/// of a(phi) = N_e sin phi + N_n cos phi is at an end of r or, if r contains it, at the azimuth
/// of (-N_e, -N_n) where a = -R. Only decides for ranges narrower than pi (returns false else).
inline bool planeBelowAcross(const AzimuthRange& r, double ne, double nn, double nu, double sinE,
                             double cosE) {
    if (!(r.phi2 - r.phi1 < kPi)) return false;
    double aMin = std::min(ne * r.sin1 + nn * r.cos1, ne * r.sin2 + nn * r.cos2);
    if (rangeContainsAzimuthOf(r, -ne, -nn)) aMin = -std::sqrt(ne * ne + nn * nn);
    return aMin * cosE + nu * sinE >= 0.0;
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
