#include "demlight/lighting/aperture.h"

#include "demlight/lighting/sky_wedge.h"
#include "demlight/lighting/sky_wedge_lanes.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/fast_math.h"
#include "demlight/core/parallel.h"
#include "demlight/core/simd.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace demlight {

using detail::kHalfPi;
using detail::kPi;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

/// Gauss-Legendre nodes/weights on [-1, 1], 8 points (symmetric halves).
constexpr std::array<double, 4> kGaussNodes{0.1834346424956498, 0.5255324099163290,
                                            0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> kGaussWeights{0.3626837833783620, 0.3137066458778873,
                                              0.2223810344533745, 0.1012285362903763};
/// Widest azimuth piece integrated by one Gauss-Legendre rule (radians): 22.5 degrees.
constexpr double kGaussMaxWidthRad = kPi / 8.0;

/// Running integrals of one cell: solid angle and the unnormalised mean direction.
struct ApertureSums {
    double omega = 0.0, ve = 0.0, vn = 0.0, vu = 0.0;
};

/// Adds an azimuth piece of the given width whose lower limit is the constant `lower` (with its
/// sine and cosine) up to the zenith; cosDrop = cos phiA - cos phiB, sinRise = sin phiB - sin phiA.
void addConstantLowerPiece(double width, double cosDrop, double sinRise, double lower, double sinL,
                           double cosL, ApertureSums& s) {
    const double cos2 = kPi / 4.0 - (0.5 * lower + 0.5 * sinL * cosL);
    s.omega += width * (1.0 - sinL);
    s.ve += cosDrop * cos2;
    s.vn += sinRise * cos2;
    s.vu += width * (0.5 - 0.5 * sinL * sinL);
}

/// The wedge where the tangent plane rises, for sectors of 180 degrees or more (D <= 2), where
/// the algebraic pieces do not apply: cut angles, and Gauss-Legendre directions on the plane
/// pieces (which a nearly vertical plane's steep rise defeats).
void addApertureSectorGaussLegendre(const EnuVector& n, const detail::AzimuthRange& r, double lower,
                                    double sinL, double cosL, ApertureSums& s) {
    const double cos2Top = detail::cos2Antiderivative(kHalfPi);
    const double sinCosTop = detail::sinCosAntiderivative(kHalfPi);
    const detail::NormalFrame f = detail::makeNormalFrame(n);
    const double phi1 = r.phi1, phi2 = r.phi2;
    detail::forEachWedgePiece(f, phi1, phi2, lower, kHalfPi, [&](double a, double b,
                                                                 detail::PieceLower kind) {
        if (kind == detail::PieceLower::Constant) {
            addConstantLowerPiece(b - a, std::cos(a) - std::cos(b), std::sin(b) - std::sin(a), lower, sinL,
                                  cosL, s);
            return;
        }
        // Tangent-plane lower limit. Solid angle: integral of sin(thetaP) d psi
        // = asin(R cos psi) (unit normal, so R^2 + N_up^2 = 1).
        const double rH = f.horizontal < detail::kFlatNormalEps ? 0.0 : f.horizontal;
        s.omega += (b - a) - (std::asin(std::min(1.0, rH * std::cos(b + f.delta))) -
                              std::asin(std::min(1.0, rH * std::cos(a + f.delta))));
        // Direction: Gauss-Legendre in azimuth, exact in elevation.
        const int pieces = std::max(1, static_cast<int>(std::ceil((b - a) / kGaussMaxWidthRad)));
        const double h = (b - a) / pieces;
        for (int p = 0; p < pieces; ++p) {
            const double mid = a + (p + 0.5) * h;
            for (std::size_t g = 0; g < kGaussNodes.size(); ++g) {
                for (double sign : {-1.0, 1.0}) {
                    const double phi = mid + sign * 0.5 * h * kGaussNodes[g];
                    const double w = 0.5 * h * kGaussWeights[g];
                    const double thetaP = detail::planeElevation(f, phi);
                    const double cos2 = cos2Top - detail::cos2Antiderivative(thetaP);
                    s.ve += w * std::sin(phi) * cos2;
                    s.vn += w * std::cos(phi) * cos2;
                    s.vu += w * (sinCosTop - detail::sinCosAntiderivative(thetaP));
                }
            }
        }
    });
}

/// addApertureSector for a sector narrower than pi on detail::forEachAlgebraicPiece's pieces, in
/// closed form (no Gauss-Legendre, no angles). On a plane piece (lower limit thetaP, with
/// tan thetaP = -a / N_up, a = R sin psi, psi = phi + delta, k = R / N_up):
///  - solid angle: width - [asin(R cos psi)] = width - [asin b];
///  - up: (1/2) integral d psi / (1 + k^2 sin^2 psi) = L / 2 (detail::planeLWithoutPsi);
///  - east and north: integral (sin phi, cos phi) (pi/4 + g) with g = (atan x + x / (1 + x^2)) / 2,
///    x = k sin psi. With sin phi = sin psi cos delta - cos psi sin delta (cos phi likewise),
///    I_c = integral cos psi g = sin psi atan(k sin psi) / 2 (substitute u = sin psi: the
///    logarithms cancel) and I_s = integral sin psi g = (k L - cos psi atan(k sin psi)) / 2 (by
///    parts; the rest sums to k integral d psi / (1 + k^2 sin^2 psi)).
/// `n` is a unit normal with horizontal part R >= kFlatNormalEps.
void addApertureSectorAlgebraic(const EnuVector& n, const detail::AzimuthRange& r, double lower,
                                double sinL, double cosL, ApertureSums& s) {
    const double ne = n.east, nn = n.north, nu = n.up;
    const double horizontal = std::sqrt(ne * ne + nn * nn);
    const detail::PlaneConstants c = detail::planeConstants(horizontal, nu);
    const double cosDelta = ne / horizontal, sinDelta = nn / horizontal;
    // Per end: arcsine of b (fast: asin x = atan(x / sqrt(1 - x^2))), L without its psi term,
    // and I_s, I_c without I_s's psi term (k width / (2 m), added per piece).
    auto planeTerms = [&](const detail::PieceEnd& e, double& asinB, double& l, double& iS, double& iC) {
        const double bUnit = std::clamp(e.b, -1.0, 1.0);
        asinB = fastAtan(bUnit / std::sqrt(std::max(0.0, 1.0 - bUnit * bUnit)));
        l = detail::planeLWithoutPsi(c, e);
        const double atanX = fastAtan(e.a / nu);  // atan(k sin psi)
        iC = 0.5 * (e.a / horizontal) * atanX;
        iS = 0.5 * (c.k * l - (e.b / horizontal) * atanX);
    };
    detail::forEachAlgebraicPiece(ne, nn, nu, horizontal, r, sinL, cosL,
                                  [&](const detail::PieceEnd& p, const detail::PieceEnd& q, double width,
                                      bool plane) {
        const double cosDrop = p.cos - q.cos, sinRise = q.sin - p.sin;
        if (!plane) {
            addConstantLowerPiece(width, cosDrop, sinRise, lower, sinL, cosL, s);
            return;
        }
        double asinP, lP, sP, cP, asinQ, lQ, sQ, cQ;
        planeTerms(p, asinP, lP, sP, cP);
        planeTerms(q, asinQ, lQ, sQ, cQ);
        const double deltaL = lQ - lP + width / c.m;
        const double deltaS = sQ - sP + 0.5 * c.k * width / c.m, deltaC = cQ - cP;
        s.omega += width - (asinQ - asinP);
        s.ve += kPi / 4.0 * cosDrop + cosDelta * deltaS - sinDelta * deltaC;
        s.vn += kPi / 4.0 * sinRise + cosDelta * deltaC + sinDelta * deltaS;
        s.vu += 0.5 * deltaL;
    });
}

/// A sector's constants for accumulateApertureRowFast.
struct FastApertureSector {
    double sin1, cos1, sin2, cos2;
    double cosDrop, sinRise;  // cos phi1 - cos phi2, sin phi2 - sin phi1
    double width;             // radians
    bool narrow;              // narrower than pi: the plane test and the algebraic pieces apply
};

FastApertureSector makeFastApertureSector(const detail::AzimuthRange& r) {
    return {r.sin1, r.cos1, r.sin2, r.cos2, r.cos1 - r.cos2, r.sin2 - r.sin1, r.phi2 - r.phi1,
            r.phi2 - r.phi1 < kPi};
}

/// One row of one sector, branch-free so the compiler vectorises it (double, as the sums): the
/// constant-limit closed form of addApertureSector for every cell whose tangent plane stays below
/// its horizon across the sector (a flat cell's plane is the horizontal, so its limit is
/// max(h, 0)); the others get kept = 0 and are left to the caller (kept is a double, not a byte
/// flag: GCC does not narrow double-lane masks to bytes). NaN inputs make omega NaN.
/// The pointers do not alias (restrict: nine arrays are more than the vectoriser checks).
/// Inlined where it is called, on the widest SimdPath.
template <bool Narrow>
DEMLIGHT_INLINE inline void accumulateApertureRowFast(const float* __restrict h, const float* __restrict e,
                               const float* __restrict n, const float* __restrict u,
                               double* __restrict omega, double* __restrict ve, double* __restrict vn,
                               double* __restrict vu, double* __restrict kept, std::size_t cols,
                               const FastApertureSector c) {
    constexpr double kFlatEps2 = detail::kFlatNormalEps * detail::kFlatNormalEps;
    for (std::size_t col = 0; col < cols; ++col) {
        const double hc = h[col], ec = e[col], nc = n[col], uc = u[col];
        const double up = std::max(uc, kMinNormalUp);  // NaN stays NaN
        const double inverseLength = 1.0 / std::sqrt(ec * ec + nc * nc + up * up);
        const double ne = ec * inverseLength, nn = nc * inverseLength, nu = up * inverseLength;
        const double horizontal2 = ne * ne + nn * nn;
        const bool flat = horizontal2 < kFlatEps2;
        const double clamped = std::clamp(hc, -90.0, 90.0) * kDegToRad;  // NaN stays NaN
        const double lower = std::max(clamped, flat ? 0.0 : -kHalfPi);
        const SinCos l = fastSinCosElevation(lower);
        // detail::planeBelowAcross: the lowest a(phi) over the sector against `lower`.
        const double aMin = detail::lowestA(ne, nn, c.sin1, c.cos1, c.sin2, c.cos2);
        const bool planeRises = !flat && (!Narrow || aMin * l.cos + nu * l.sin < 0.0);
        const double keep = planeRises ? 0.0 : 1.0;
        const double cos2 = kPi / 4.0 - (0.5 * lower + 0.5 * l.sin * l.cos);
        omega[col] += keep * c.width * (1.0 - l.sin) + (hc + ec + nc + uc) * 0.0;
        ve[col] += keep * c.cosDrop * cos2;
        vn[col] += keep * c.sinRise * cos2;
        vu[col] += keep * c.width * (0.5 - 0.5 * l.sin * l.sin);
        kept[col] = keep;
    }
}

/// Adds the wedge [phi1, phi2] x [lower, 90 deg] of a unit normal, clipped to its hemisphere:
/// the constant limit where the tangent plane stays below `lower` across the sector, else the
/// closed form on algebraic pieces (a tilted plane, a sector narrower than 180 degrees), else
/// Gauss-Legendre.
void addApertureSector(const EnuVector& n, const detail::AzimuthRange& r, double lower, ApertureSums& s) {
    const auto [sinL, cosL] = fastSinCosElevation(lower);  // lower is an elevation
    if (detail::planeBelowAcross(r, n.east, n.north, n.up, sinL, cosL)) {
        addConstantLowerPiece(r.phi2 - r.phi1, r.cos1 - r.cos2, r.sin2 - r.sin1, lower, sinL, cosL, s);
    } else if (r.phi2 - r.phi1 < kPi &&
               n.east * n.east + n.north * n.north >= detail::kFlatNormalEps * detail::kFlatNormalEps) {
        addApertureSectorAlgebraic(n, r, lower, sinL, cosL, s);
    } else {
        addApertureSectorGaussLegendre(n, r, lower, sinL, cosL, s);
    }
}


Aperture finishAperture(const ApertureSums& s, const EnuVector& normal) {
    Aperture a;
    a.solidAngleSr = std::clamp(s.omega, 0.0, 2.0 * kPi);
    a.radiusDeg = apertureRadiusDeg(a.solidAngleSr);
    const double len = std::sqrt(s.ve * s.ve + s.vn * s.vn + s.vu * s.vu);
    a.bentNormal = len > 0.0 ? EnuVector{s.ve / len, s.vn / len, s.vu / len} : normal;
    return a;
}

double clampUnit(double x) { return std::clamp(x, -1.0, 1.0); }

}  // namespace

double apertureRadiusDeg(double solidAngleSr) {
    // Oat & Sander Sec. 2: r_p = acos(1 - A_p / 2 pi).
    return std::acos(clampUnit(1.0 - solidAngleSr / (2.0 * kPi))) / kDegToRad;
}

Aperture aperture(std::span<const float> horizonDeg, const EnuVector& normal) {
    const EnuVector unit = detail::unitNormal(normal);
    ApertureSums s;
    for (std::size_t i = 0; i < horizonDeg.size(); ++i) {
        const auto [phi1, phi2] = detail::sectorBoundsRad(i, horizonDeg.size());
        addApertureSector(unit, detail::makeAzimuthRange(phi1, phi2),
                          std::clamp<double>(horizonDeg[i], -90.0, 90.0) * kDegToRad, s);
    }
    return finishAperture(s, normal);
}

double capAreaSr(double rRad) { return 2.0 * kPi * (1.0 - std::cos(rRad)); }

double capIntersectionAreaSr(double r1, double r2, double d) {
    // Oat & Sander Sec. 3.1, after Tovchigrechko & Vakser 2001.
    if (r1 <= 0.0 || r2 <= 0.0) return 0.0;
    if (std::min(r1, r2) <= std::max(r1, r2) - d) return capAreaSr(std::min(r1, r2));
    if (r1 + r2 <= d) return 0.0;
    const double c1 = std::cos(r1), c2 = std::cos(r2), cd = std::cos(d);
    const double s1 = std::sin(r1), s2 = std::sin(r2), sd = std::sin(d);
    const double area =
        2.0 * (kPi - std::acos(clampUnit((cd - c1 * c2) / (s1 * s2))) -
               c1 * std::acos(clampUnit((c2 - cd * c1) / (sd * s1))) -
               c2 * std::acos(clampUnit((c1 - cd * c2) / (sd * s2))));
    return std::clamp(area, 0.0, capAreaSr(std::min(r1, r2)));
}

double capIntersectionAreaSmoothSr(double r1, double r2, double d) {
    // Oat & Sander Sec. 3.2: smoothstep between full and no intersection.
    if (r1 <= 0.0 || r2 <= 0.0) return 0.0;
    const double diff = std::abs(r1 - r2);
    const double x = std::clamp(1.0 - (d - diff) / (r1 + r2 - diff), 0.0, 1.0);
    return capAreaSr(std::min(r1, r2)) * x * x * (3.0 - 2.0 * x);
}

namespace {

EnuVector scaled(const EnuVector& v, double s) { return {v.east * s, v.north * s, v.up * s}; }
EnuVector added(const EnuVector& a, const EnuVector& b) {
    return {a.east + b.east, a.north + b.north, a.up + b.up};
}
double dotEnu(const EnuVector& a, const EnuVector& b) {
    return a.east * b.east + a.north * b.north + a.up * b.up;
}

/// Unit tangent at `from` pointing along the great circle towards `to`; false if parallel.
bool tangentTowards(const EnuVector& from, const EnuVector& to, EnuVector& t) {
    t = added(to, scaled(from, -dotEnu(from, to)));
    const double len = std::sqrt(dotEnu(t, t));
    if (len < 1e-15) return false;
    t = scaled(t, 1.0 / len);
    return true;
}

}  // namespace

EnuVector capIntersectionVector(const EnuVector& c1, double r1, const EnuVector& c2, double r2) {
    if (r1 <= 0.0 || r2 <= 0.0) return {0.0, 0.0, 0.0};
    const double cd = clampUnit(dotEnu(c1, c2));
    const double d = std::acos(cd);
    // Full containment: the smaller cap, integral v d(omega) = pi sin^2 r c.
    if (std::min(r1, r2) <= std::max(r1, r2) - d) {
        const double r = std::min(r1, r2);
        return scaled(r1 <= r2 ? c1 : c2, kPi * std::sin(r) * std::sin(r));
    }
    if (r1 + r2 <= d) return {0.0, 0.0, 0.0};
    EnuVector t1, t2;
    if (!tangentTowards(c1, c2, t1) || !tangentTowards(c2, c1, t2)) return {0.0, 0.0, 0.0};
    const double sd = std::sin(d);
    const double s1 = std::sin(r1), k1 = std::cos(r1), s2 = std::sin(r2), k2 = std::cos(r2);
    // Half-angles of the boundary arcs (the same ratios as in the area formula).
    const double a1 = std::acos(clampUnit((k2 - cd * k1) / (sd * s1)));
    const double a2 = std::acos(clampUnit((k1 - cd * k2) / (sd * s2)));
    const EnuVector arc1 = added(scaled(c1, a1 * s1 * s1), scaled(t1, -s1 * k1 * std::sin(a1)));
    const EnuVector arc2 = added(scaled(c2, a2 * s2 * s2), scaled(t2, -s2 * k2 * std::sin(a2)));
    return added(arc1, arc2);
}

EnuVector capIntersectionCentroid(const EnuVector& light, double lightRadiusRad,
                                  const EnuVector& ap, double apertureRadiusRad) {
    const EnuVector m = capIntersectionVector(light, lightRadiusRad, ap, apertureRadiusRad);
    const double len = std::sqrt(dotEnu(m, m));
    return len > 0.0 ? scaled(m, 1.0 / len) : light;
}

EnuVector capIntersectionCentroidFast(const EnuVector& light, double lightRadiusRad,
                                      const EnuVector& ap, double apertureRadiusRad) {
    const double d = std::acos(clampUnit(dotEnu(light, ap)));
    EnuVector t;
    if (d >= lightRadiusRad + apertureRadiusRad || !tangentTowards(light, ap, t)) return light;
    // Lens extent along the great circle, measured from the light centre towards `ap`.
    const double t0 = std::max(-lightRadiusRad, d - apertureRadiusRad);
    const double t1 = std::min(lightRadiusRad, d + apertureRadiusRad);
    const double mid = 0.5 * (t0 + t1);
    return added(scaled(light, std::cos(mid)), scaled(t, std::sin(mid)));
}

// ---- ApertureAccumulator ---------------------------------------------------------------------

ApertureAccumulator::ApertureAccumulator(const Grid<float>& normalEast,
                                         const Grid<float>& normalNorth,
                                         const Grid<float>& normalUp, std::size_t directions)
    : east_(normalEast),
      north_(normalNorth),
      up_(normalUp),
      directions_(directions),
      added_(directions, false),
      omega_(normalEast.width(), normalEast.height(), 0.0),
      ve_(normalEast.width(), normalEast.height(), 0.0),
      vn_(normalEast.width(), normalEast.height(), 0.0),
      vu_(normalEast.width(), normalEast.height(), 0.0) {
    if (!east_.sameShape(north_) || !east_.sameShape(up_))
        throw Error("aperture: the east, north and up normal grids differ in size");
    if (directions == 0) throw Error("aperture: the number of directions must be at least 1");
}

void ApertureAccumulator::addDirection(std::size_t index, const Grid<float>& horizonDeg) {
    addDirection(index, horizonDeg, CellWindow{0, 0, horizonDeg.width(), horizonDeg.height()});
}

void ApertureAccumulator::addDirection(std::size_t index, const Grid<float>& horizonDeg, const CellWindow& cells) {
    if (index >= directions_)
        throw Error("aperture: direction index " + std::to_string(index) + " out of range 0.." +
                    std::to_string(directions_ - 1));
    if (added_[index]) throw Error("aperture: direction " + std::to_string(index) + " added twice");
    if (cells.col1 - cells.col0 != east_.width() || cells.row1 - cells.row0 != east_.height() ||
        cells.col1 > horizonDeg.width() || cells.row1 > horizonDeg.height() || cells.col0 > cells.col1 ||
        cells.row0 > cells.row1)
        throw Error("aperture: horizon grid size differs from the normal grids");
    added_[index] = true;
    const auto [phi1, phi2] = detail::sectorBoundsRad(index, directions_);
    const detail::AzimuthRange sector = detail::makeAzimuthRange(phi1, phi2);
    const std::size_t width = east_.width();
    const FastApertureSector fast = makeFastApertureSector(sector);
    [[maybe_unused]] const bool eightAtOnce =
        fast.narrow && simdPath() == SimdPath::Avx512;
    parallelFor(0, east_.height(), [&](std::size_t row) {
        thread_local std::vector<double> keptBuffer;
        keptBuffer.resize(width);
        double* kept = keptBuffer.data();
        const float* h = horizonDeg.rowPtr(cells.row0 + row) + cells.col0;
        const float* e = east_.rowPtr(row);
        const float* n = north_.rowPtr(row);
        const float* u = up_.rowPtr(row);
        double* omega = omega_.rowPtr(row);
        double* ve = ve_.rowPtr(row);
        double* vn = vn_.rowPtr(row);
        double* vu = vu_.rowPtr(row);
        // Pass 1, vectorised: the sector where the constant lower limit holds throughout.
        onWidestPath([&]() DEMLIGHT_INLINE {
            if (fast.narrow) {
                accumulateApertureRowFast<true>(h, e, n, u, omega, ve, vn, vu, kept, width, fast);
            } else {
                accumulateApertureRowFast<false>(h, e, n, u, omega, ve, vn, vu, kept, width, fast);
            }
        });
        // Pass 2: where the tangent plane rises above the horizon inside the sector; under a
        // sector narrower than pi, eight such cells at once (demlight/lighting/sky_wedge_lanes.h).
        const auto addExact = [&](std::size_t col) {
            ApertureSums sums{omega[col], ve[col], vn[col], vu[col]};
            const EnuVector unit = detail::unitNormal({e[col], n[col], u[col]});
            const double lower = std::clamp<double>(h[col], -90.0, 90.0) * kDegToRad;
            if (fast.narrow) {  // pass 1 found the plane rising: the algebraic pieces directly
                const auto [sinL, cosL] = fastSinCosElevation(lower);
                addApertureSectorAlgebraic(unit, sector, lower, sinL, cosL, sums);
            } else {
                addApertureSector(unit, sector, lower, sums);
            }
            omega[col] = sums.omega;
            ve[col] = sums.ve;
            vn[col] = sums.vn;
            vu[col] = sums.vu;
        };
#ifdef DEMLIGHT_SKY_LANES
        thread_local std::vector<std::size_t> exactCols;
        exactCols.clear();
#endif
        for (std::size_t col = 0; col < width; ++col) {
            if (kept[col] != 0.0) continue;
            if (std::isnan(h[col]) || std::isnan(e[col]) || std::isnan(n[col]) || std::isnan(u[col])) {
                omega[col] = kNaN;
                continue;
            }
#ifdef DEMLIGHT_SKY_LANES
            if (eightAtOnce) {
                exactCols.push_back(col);
                continue;
            }
#endif
            addExact(col);
        }
#ifdef DEMLIGHT_SKY_LANES
        detail::inGroupsOfEight(exactCols, [&](const std::size_t* cols) {
            alignas(64) double le[detail::kSkyLanes], ln[detail::kSkyLanes], lu[detail::kSkyLanes],
                lh[detail::kSkyLanes], lo[detail::kSkyLanes], lve[detail::kSkyLanes], lvn[detail::kSkyLanes],
                lvu[detail::kSkyLanes];
            detail::gather8(e, cols, le);
            detail::gather8(n, cols, ln);
            detail::gather8(u, cols, lu);
            detail::gather8(h, cols, lh);
            detail::gather8(omega, cols, lo);
            detail::gather8(ve, cols, lve);
            detail::gather8(vn, cols, lvn);
            detail::gather8(vu, cols, lvu);
            detail::risingApertureSector8(le, ln, lu, lh, sector, lo, lve, lvn, lvu);
            detail::scatter8(lo, cols, omega);
            detail::scatter8(lve, cols, ve);
            detail::scatter8(lvn, cols, vn);
            detail::scatter8(lvu, cols, vu);
        }, addExact);
#endif
    });
}

ApertureMaps ApertureAccumulator::finish() const {
    for (std::size_t i = 0; i < directions_; ++i)
        if (!added_[i])
            throw Error("aperture: direction " + std::to_string(i) + " of " +
                        std::to_string(directions_) + " was never added");
    const std::size_t w = east_.width(), ht = east_.height();
    ApertureMaps out{Grid<float>(w, ht, kNaNf), Grid<float>(w, ht, kNaNf),
                     Grid<float>(w, ht, kNaNf), Grid<float>(w, ht, kNaNf),
                     Grid<float>(w, ht, kNaNf)};
    parallelFor(0, ht, [&](std::size_t row) {
        for (std::size_t col = 0; col < w; ++col) {
            if (std::isnan(omega_(col, row))) continue;
            const EnuVector normal{east_(col, row), north_(col, row), up_(col, row)};
            const Aperture a = finishAperture(
                {omega_(col, row), ve_(col, row), vn_(col, row), vu_(col, row)}, normal);
            out.bentEast(col, row) = static_cast<float>(a.bentNormal.east);
            out.bentNorth(col, row) = static_cast<float>(a.bentNormal.north);
            out.bentUp(col, row) = static_cast<float>(a.bentNormal.up);
            out.radiusDeg(col, row) = static_cast<float>(a.radiusDeg);
            out.solidAngleSr(col, row) = static_cast<float>(a.solidAngleSr);
        }
    });
    return out;
}

ApertureMaps computeAperture(const std::vector<const Grid<float>*>& horizonsDeg,
                             const Grid<float>& normalEast, const Grid<float>& normalNorth,
                             const Grid<float>& normalUp) {
    ApertureAccumulator acc(normalEast, normalNorth, normalUp, horizonsDeg.size());
    for (std::size_t i = 0; i < horizonsDeg.size(); ++i) {
        if (!horizonsDeg[i])
            throw Error("aperture: horizon grid " + std::to_string(i) + " is null");
        acc.addDirection(i, *horizonsDeg[i]);
    }
    return acc.finish();
}

}  // namespace demlight
