// Ambient aperture: analytic apertures (flat, tilted plane, V valley, wall), the cap-cap
// intersection against Monte Carlo, the smoothstep approximation's error, the centroid
// Lambert term, the aperture / hemisphere lighting models, and the streaming grid driver.
#include "demlight/core/parallel.h"
#include "demlight/lighting/aperture.h"
#include "demlight/lighting/lighting_models.h"
#include "demlight/lighting/sky.h"
#include "rising_planes.h"

#include "demlight/core/error.h"
#include "demlight/core/simd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace demlight {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

EnuVector slopeNormal(double slopeDeg, double aspectDeg) {
    return {std::sin(slopeDeg * kDeg) * std::sin(aspectDeg * kDeg),
            std::sin(slopeDeg * kDeg) * std::cos(aspectDeg * kDeg), std::cos(slopeDeg * kDeg)};
}

double dot(const EnuVector& a, const EnuVector& b) {
    return a.east * b.east + a.north * b.north + a.up * b.up;
}

/// Orthonormal basis (t1, t2) perpendicular to unit c.
void basis(const EnuVector& c, EnuVector& t1, EnuVector& t2) {
    const EnuVector a = std::abs(c.up) < 0.9 ? EnuVector{0, 0, 1} : EnuVector{1, 0, 0};
    t1 = {a.north * c.up - a.up * c.north, a.up * c.east - a.east * c.up,
          a.east * c.north - a.north * c.east};
    const double l = std::sqrt(dot(t1, t1));
    t1 = {t1.east / l, t1.north / l, t1.up / l};
    t2 = {c.north * t1.up - c.up * t1.north, c.up * t1.east - c.east * t1.up,
          c.east * t1.north - c.north * t1.east};
}

TEST(Aperture, FlatGround) {
    for (int d : {4, 8, 64}) {
        const Aperture a = aperture(std::vector<float>(static_cast<std::size_t>(d), 0.0f), {0, 0, 1});
        EXPECT_NEAR(a.solidAngleSr, 2 * kPi, 1e-12);
        EXPECT_NEAR(a.radiusDeg, 90.0, 1e-9);
        EXPECT_NEAR(a.bentNormal.east, 0.0, 1e-12);
        EXPECT_NEAR(a.bentNormal.north, 0.0, 1e-12);
        EXPECT_NEAR(a.bentNormal.up, 1.0, 1e-12);
    }
    EXPECT_DOUBLE_EQ(apertureRadiusDeg(0.0), 0.0);
    EXPECT_DOUBLE_EQ(apertureRadiusDeg(2 * kPi), 90.0);
    EXPECT_NEAR(apertureRadiusDeg(kPi), 60.0, 1e-12);
}

TEST(Aperture, TiltedPlaneSeesItsWholeHemisphere) {
    for (double slope : {20.0, 60.0}) {
        const EnuVector n = slopeNormal(slope, 110.0);
        for (int d : {1, 4, 8, 64}) {
            const Aperture a = aperture(std::vector<float>(static_cast<std::size_t>(d), -90.0f), n);
            EXPECT_NEAR(a.solidAngleSr, 2 * kPi, 1e-12) << slope << " D=" << d;
            EXPECT_NEAR(dot(a.bentNormal, n), 1.0, 1e-11) << slope << " D=" << d;
        }
    }
}

// V valley floor: A_p = integral (1 - sin h) d phi = 2 pi - 4 beta (mean sin h = 2 beta / pi),
// bent normal straight up by symmetry.
TEST(Aperture, VValleyFloor) {
    for (double beta : {15.0, 40.0}) {
        const double exact = 2 * kPi - 4 * beta * kDeg;
        const auto horizon = [&](double az) {
            return std::atan(std::tan(beta * kDeg) * std::abs(std::sin((az - 30.0) * kDeg))) / kDeg;
        };
        EXPECT_NEAR(referenceSky(horizon, {0, 0, 1}, 4096).solidAngleSr, exact, 1e-6);
        double prevErr = 10.0;
        for (int d : {8, 32, 128}) {
            std::vector<float> hz;
            for (int i = 0; i < d; ++i) hz.push_back(static_cast<float>(horizon(360.0 * i / d)));
            const Aperture a = aperture(hz, {0, 0, 1});
            const double err = std::abs(a.solidAngleSr - exact);
            EXPECT_LE(err, prevErr);
            prevErr = err;
            EXPECT_NEAR(a.bentNormal.up, 1.0, 1e-9);
            EXPECT_NEAR(a.radiusDeg, std::acos(1 - a.solidAngleSr / (2 * kPi)) / kDeg, 1e-12);
        }
        EXPECT_LT(prevErr, 1e-3);
    }
}

// Wall over sectors 0..D/2-1: A_p = pi, r_p = 60 deg, bent normal 45 deg up towards the open
// side's centre azimuth 270 - w/2.
TEST(Aperture, WallBlocksHalfTheSky) {
    for (int d : {2, 8, 64}) {
        std::vector<float> hz(static_cast<std::size_t>(d), 0.0f);
        for (int i = 0; i < d / 2; ++i) hz[static_cast<std::size_t>(i)] = 90.0f;
        const Aperture a = aperture(hz, {0, 0, 1});
        EXPECT_NEAR(a.solidAngleSr, kPi, 1e-12);
        EXPECT_NEAR(a.radiusDeg, 60.0, 1e-9);
        const EnuVector expect = directionEnu(270.0 - 180.0 / d, 45.0);
        EXPECT_NEAR(dot(a.bentNormal, expect), 1.0, 1e-12) << "D=" << d;
    }
}

TEST(Aperture, MatchesDenseReferenceOnRandomCells) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> slope(0, 70), aspect(0, 360), hd(-30, 60);
    for (int trial = 0; trial < 10; ++trial) {
        const int d = 8;
        const EnuVector n = slopeNormal(slope(rng), aspect(rng));
        std::vector<float> hz;
        for (int i = 0; i < d; ++i) hz.push_back(static_cast<float>(hd(rng)));
        const auto step = [&](double az) {
            return static_cast<double>(hz[static_cast<std::size_t>(std::floor(az / 45.0 + 0.5)) % d]);
        };
        const SkyReference ref = referenceSky(step, n, 1 << 16);
        const Aperture a = aperture(hz, n);
        EXPECT_NEAR(a.solidAngleSr, ref.solidAngleSr, 1e-4);
        EXPECT_NEAR(dot(a.bentNormal, ref.bentNormal), 1.0, 1e-8);
    }
}

TEST(Aperture, MonotoneInEveryHorizon) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> slope(0, 70), aspect(0, 360), hd(-30, 60), bump(0, 20);
    for (int trial = 0; trial < 200; ++trial) {
        const EnuVector n = slopeNormal(slope(rng), aspect(rng));
        std::vector<float> hz;
        for (int i = 0; i < 16; ++i) hz.push_back(static_cast<float>(hd(rng)));
        const double a0 = aperture(hz, n).solidAngleSr;
        hz[static_cast<std::size_t>(trial % 16)] += static_cast<float>(bump(rng));
        EXPECT_LE(aperture(hz, n).solidAngleSr, a0 + 1e-13);
    }
}

// ---- Spherical caps --------------------------------------------------------------------------

/// Monte Carlo intersection area: uniform samples inside cap 1 (area known), fraction in cap 2.
/// Returns {estimate, standard error}.
std::pair<double, double> monteCarloIntersection(double r1, double r2, double d, int samples,
                                                 std::mt19937_64& rng) {
    // Cap 1 centred on (0, 0, 1), cap 2 tilted by d towards east.
    const EnuVector c2{std::sin(d), 0, std::cos(d)};
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int inside = 0;
    for (int i = 0; i < samples; ++i) {
        const double z = 1.0 - u(rng) * (1.0 - std::cos(r1));  // uniform in area
        const double phi = 2 * kPi * u(rng);
        const double s = std::sqrt(std::max(0.0, 1 - z * z));
        const EnuVector v{s * std::cos(phi), s * std::sin(phi), z};
        if (dot(v, c2) >= std::cos(r2)) ++inside;
    }
    const double p = static_cast<double>(inside) / samples;
    const double area1 = capAreaSr(r1);
    return {p * area1, area1 * std::sqrt(std::max(p * (1 - p), 1e-12) / samples)};
}

TEST(Caps, ExactIntersectionMatchesMonteCarlo) {
    struct Case {
        double r1, r2, d;  // degrees
    };
    const Case cases[] = {
        {30, 30, 0},      {30, 10, 15},   {30, 10, 20},    // containment (boundary too)
        {30, 10, 25},     {45, 60, 50},   {60, 60, 100},   // partial
        {90, 90, 90},     {90, 20, 100},  {90, 0.265, 89.9}, {90, 0.265, 90.2},
        {0.265, 0.265, 0.3}, {0.265, 2.0, 2.1}, {5, 80, 82}, {89, 89, 170},
        {120, 45, 100},   {150, 150, 170},                  // caps larger than a hemisphere
        {10, 10, 25},     {45, 45, 90},   {0.265, 30, 40}, // disjoint (touching too)
    };
    std::mt19937_64 rng(12345);
    for (const Case& c : cases) {
        const double exact = capIntersectionAreaSr(c.r1 * kDeg, c.r2 * kDeg, c.d * kDeg);
        EXPECT_NEAR(exact, capIntersectionAreaSr(c.r2 * kDeg, c.r1 * kDeg, c.d * kDeg), 1e-14);
        const auto [mc, se] = monteCarloIntersection(c.r1 * kDeg, c.r2 * kDeg, c.d * kDeg, 400000, rng);
        EXPECT_NEAR(exact, mc, 5 * se + 1e-12)
            << "r1=" << c.r1 << " r2=" << c.r2 << " d=" << c.d;
    }
    EXPECT_DOUBLE_EQ(capIntersectionAreaSr(0.5, 0.2, 0.1), capAreaSr(0.2));
    EXPECT_EQ(capIntersectionAreaSr(0.5, 0.2, 0.8), 0.0);
    EXPECT_EQ(capIntersectionAreaSr(0.0, 0.2, 0.0), 0.0);
}

TEST(Caps, SmoothstepApproximationWithinStatedError) {
    // Radii 0.25..90 degrees, separations across the whole partial range.
    double worst = 0.0, worstR1 = 0, worstR2 = 0, worstSun = 0.0;
    for (double r1 : {0.25, 0.5, 2.0, 10.0, 30.0, 60.0, 90.0}) {
        for (double r2 : {0.25, 1.0, 5.0, 20.0, 45.0, 75.0, 90.0}) {
            const double a = r1 * kDeg, b = r2 * kDeg;
            const double lo = std::abs(a - b), hi = a + b;
            for (int i = 0; i <= 400; ++i) {
                const double d = lo + (hi - lo) * i / 400.0;
                const double exact = capIntersectionAreaSr(a, b, d);
                const double smooth = capIntersectionAreaSmoothSr(a, b, d);
                const double err = std::abs(smooth - exact) / capAreaSr(std::min(a, b));
                if (err > worst) worst = err, worstR1 = r1, worstR2 = r2;
            }
            // Exact at both ends.
            EXPECT_NEAR(capIntersectionAreaSmoothSr(a, b, lo), capAreaSr(std::min(a, b)), 1e-15);
            EXPECT_EQ(capIntersectionAreaSmoothSr(a, b, hi), 0.0);
        }
    }
    // The case that matters for the sun: a 0.265-degree disk against apertures of 10..90 deg.
    for (double rp = 10.0; rp <= 90.0; rp += 5.0) {
        const double a = kSunRadiusDeg * kDeg, b = rp * kDeg;
        for (int i = 0; i <= 400; ++i) {
            const double d = (b - a) + 2 * a * i / 400.0;
            worstSun = std::max(worstSun, std::abs(capIntersectionAreaSmoothSr(a, b, d) -
                                                   capIntersectionAreaSr(a, b, d)) /
                                              capAreaSr(a));
        }
    }
    std::cout << "[ measured ] smoothstep cap intersection: max |error| / smaller cap area = "
              << worst << " (at r1 " << worstR1 << ", r2 " << worstR2 << " deg); sun disk vs "
              << "aperture 10..90 deg: " << worstSun << "\n";
    EXPECT_LE(worst, kCapSmoothstepMaxError);
    EXPECT_LE(worstSun, kCapSmoothstepSunMaxError);
}

TEST(Caps, IntersectionVectorAndCentroid) {
    const EnuVector up{0, 0, 1};
    const EnuVector sun = directionEnu(120.0, 30.0);
    // Containment: the inner cap's centre; the vector is pi sin^2 r c.
    EXPECT_NEAR(dot(capIntersectionCentroid(sun, 0.005, up, kPi / 2), sun), 1.0, 1e-15);
    EXPECT_NEAR(dot(capIntersectionCentroidFast(sun, 0.005, up, kPi / 2), sun), 1.0, 1e-15);
    EXPECT_NEAR(dot(capIntersectionCentroid(sun, 1.5, up, 0.1), up), 1.0, 1e-12);
    const EnuVector m = capIntersectionVector(sun, 0.3, up, kPi / 2);
    EXPECT_NEAR(dot(m, sun), kPi * std::sin(0.3) * std::sin(0.3), 1e-14);
    // Partial overlaps: the mean Lambert term over the lens (Monte Carlo inside the light cap)
    // against N.vector / area (exact) and against the cheap centroid (approximate).
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    struct Case {
        double rlDeg, rpDeg, lightElevDeg, bentElevDeg, slopeDeg;
    };
    // Light centre on the aperture rim (half covered), partly covered, and large caps.
    const Case cases[] = {{0.265, 50, 5, 55, 35}, {2.65, 50, 5, 55, 35}, {2.65, 50, 3, 55, 0},
                          {20, 40, 30, 60, 20},   {30, 70, 10, 50, 10}};
    for (const Case& c : cases) {
        const double rl = c.rlDeg * kDeg, rp = c.rpDeg * kDeg;
        const EnuVector normal = slopeNormal(c.slopeDeg, 120.0);
        const EnuVector bent = directionEnu(300.0, c.bentElevDeg);
        const EnuVector light = directionEnu(300.0, c.lightElevDeg);
        EnuVector t1, t2;
        basis(light, t1, t2);
        double sum = 0.0, sum2 = 0.0;
        EnuVector mean{0, 0, 0};
        int n = 0;
        const int samples = 400000;
        for (int i = 0; i < samples; ++i) {
            const double z = 1.0 - u(rng) * (1.0 - std::cos(rl));
            const double phi = 2 * kPi * u(rng), s = std::sqrt(1 - z * z);
            const double a = s * std::cos(phi), b = s * std::sin(phi);
            const EnuVector v{z * light.east + a * t1.east + b * t2.east,
                              z * light.north + a * t1.north + b * t2.north,
                              z * light.up + a * t1.up + b * t2.up};
            if (dot(v, bent) < std::cos(rp)) continue;
            const double l = dot(v, normal);
            sum += l, sum2 += l * l, ++n;
            mean = {mean.east + v.east, mean.north + v.north, mean.up + v.up};
        }
        const double area = capIntersectionAreaSr(rl, rp, std::acos(dot(light, bent)));
        const double mcLambert = sum / n;
        const double se = std::sqrt(std::max(sum2 / n - mcLambert * mcLambert, 0.0) / n);
        const EnuVector vec = capIntersectionVector(light, rl, bent, rp);
        EXPECT_NEAR(dot(vec, normal) / area, mcLambert, 5 * se + 1e-12) << c.rlDeg << " " << c.rpDeg;
        // The vector's direction is the Monte Carlo mean direction.
        const double ml = std::sqrt(dot(mean, mean));
        const EnuVector cen = capIntersectionCentroid(light, rl, bent, rp);
        EXPECT_NEAR(dot(cen, {mean.east / ml, mean.north / ml, mean.up / ml}), 1.0, 1e-6);
        const double fast = dot(capIntersectionCentroidFast(light, rl, bent, rp), normal);
        std::cout << "[ measured ] light r " << c.rlDeg << " aperture r " << c.rpDeg
                  << ": Lambert exact " << dot(vec, normal) / area << " MC " << mcLambert
                  << " fast-centroid " << fast << "\n";
    }
}

// ---- Lighting models -------------------------------------------------------------------------

TEST(LightingModels, ParseNames) {
    for (SunModel m : {SunModel::Horizon, SunModel::Aperture, SunModel::ApertureSmooth})
        EXPECT_EQ(parseSunModel(sunModelName(m)), m);
    for (SkyModel m : {SkyModel::StewartLanger, SkyModel::Hemisphere, SkyModel::None})
        EXPECT_EQ(parseSkyModel(skyModelName(m)), m);
    EXPECT_THROW(parseSunModel("phong"), Error);
    EXPECT_THROW(parseSunModel("hemisphere"), Error);  // a sky model, not a sun model
    EXPECT_THROW(parseSkyModel("horizon"), Error);
}

TEST(LightingModels, ApertureOnFlatGround) {
    const Aperture flat = aperture(std::vector<float>(8, 0.0f), {0, 0, 1});
    for (bool smooth : {false, true}) {
        ApertureLightParams p;
        p.smoothIntersection = smooth;
        const ApertureLight zenith = apertureLight({0, 0, 1}, flat, {0, 0, 1}, p);
        EXPECT_NEAR(zenith.sun, 1.0, 1e-12);
        EXPECT_NEAR(zenith.ambient, 1.0 - capAreaSr(kSunRadiusDeg * kDeg) / (2 * kPi), 1e-12);
        // Sun at 30 degrees: Lambert sin(30).
        EXPECT_NEAR(apertureLight({0, 0, 1}, flat, directionEnu(90, 30), p).sun, 0.5,
                    1e-6);
        // Sun below the horizon: no direct light.
        EXPECT_EQ(apertureLight({0, 0, 1}, flat, directionEnu(90, -1), p).sun, 0.0);
        // Sun centre on the horizon: half the disk above it. Exact: the half-disk's Lambert
        // mean is its centroid elevation 4 r / 3 pi, times half the area -> 2 r / 3 pi.
        // Smooth: half the area at the cheap centroid r / 2 -> sin(r / 2) / 2.
        const double rl = kSunRadiusDeg * kDeg;
        const double horizonSun =
            apertureLight({0, 0, 1}, flat, directionEnu(90, 0), p).sun;
        EXPECT_NEAR(horizonSun, smooth ? 0.5 * std::sin(0.5 * rl) : 2.0 * rl / (3.0 * kPi),
                    1e-4 * rl);
    }
}

TEST(LightingModels, ApertureWallShadowsTheSun) {
    // Wall on the east half: an eastern sun at 30 degrees is blocked... approximately, since a
    // cap is fitted to the visible half: the cap around the bent normal (45 deg up, west) with
    // r_p = 60 deg reaches only to 15 degrees beyond the zenith.
    std::vector<float> hz(8, 0.0f);
    for (int i = 0; i < 4; ++i) hz[static_cast<std::size_t>(i)] = 90.0f;
    const Aperture a = aperture(hz, {0, 0, 1});
    ApertureLightParams p;
    const double east = apertureLight({0, 0, 1}, a, directionEnu(67.5, 30), p).sun;
    const double west = apertureLight({0, 0, 1}, a, directionEnu(247.5, 30), p).sun;
    EXPECT_EQ(east, 0.0);
    EXPECT_NEAR(west, 0.5, 1e-3);
}

TEST(LightingModels, Hemisphere) {
    EXPECT_DOUBLE_EQ(hemisphereLight(1.0, 0.8, 0.1), 0.8);
    EXPECT_DOUBLE_EQ(hemisphereLight(-1.0, 0.8, 0.1), 0.1);
    EXPECT_DOUBLE_EQ(hemisphereLight(0.0, 0.8, 0.1), 0.45);
    Grid<float> up(3, 2, 1.0f);
    up(1, 1) = 0.0f;
    up(2, 1) = std::numeric_limits<float>::quiet_NaN();
    Grid<float> albedo(3, 2, 0.5f);
    HemisphereParams p;
    p.skyRadiance = 1.0;
    p.groundIrradiance = 0.8;
    const Grid<float> out = applyHemisphereLight(up, p, &albedo);
    EXPECT_FLOAT_EQ(out(0, 0), 1.0f);
    EXPECT_FLOAT_EQ(out(1, 1), 0.5f * (1.0f + 0.4f));
    EXPECT_TRUE(std::isnan(out(2, 1)));
    const Grid<float> wrongSize(1, 1);
    EXPECT_THROW(applyHemisphereLight(up, p, &wrongSize), Error);
}

// ---- Grid driver -----------------------------------------------------------------------------

// The accumulator integrates each sector in closed form on algebraic pieces (demlight/lighting/aperture.cpp,
// addApertureSectorAlgebraic) and vectorises the constant-limit case; the per-cell kernel
// aperture() takes the closed form too where the plane rises. Every cell of random grids, from
// flat (with negative horizons) to nearly vertical normals, horizons anywhere and near the
// tangent plane's own elevation, D = 3..64, against the dense reference (a midpoint rule over
// azimuths aligned with the sectors, so the horizon's steps fall between samples).
TEST(ApertureGrid, ClosedFormSectorsMatchTheDenseReference) {
    const std::size_t w = 24, h = 16;
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worstRef = 0, worstKernelRef = 0;
    for (const int d : {3, 4, 5, 8, 16, 64}) {
        Grid<float> e(w, h), n(w, h), u(w, h);
        std::vector<Grid<float>> hz(static_cast<std::size_t>(d), Grid<float>(w, h));
        Grid<float> slopes(w, h);
        for (std::size_t r = 0; r < h; ++r)
            for (std::size_t c = 0; c < w; ++c) {
                const std::size_t k = r * w + c;
                const double slopeDeg = k % 9 == 0 ? 0.0 : k % 7 == 0 ? 88.0 + 1.9 * unit(rng) : 80.0 * unit(rng);
                slopes(c, r) = static_cast<float>(slopeDeg);
                const EnuVector nv = slopeNormal(slopeDeg, 360.0 * unit(rng));
                e(c, r) = static_cast<float>(nv.east);
                n(c, r) = static_cast<float>(nv.north);
                u(c, r) = static_cast<float>(nv.up);
                for (int i = 0; i < d; ++i) {
                    // The plane's elevation at a random azimuth of the sector, or anywhere.
                    const double az = (i + unit(rng) - 0.5) * 360.0 / d * kDeg;
                    const double plane = std::atan(-(nv.east * std::sin(az) + nv.north * std::cos(az)) / nv.up) / kDeg;
                    hz[static_cast<std::size_t>(i)](c, r) =
                        static_cast<float>(unit(rng) < 0.5 ? plane : 170.0 * unit(rng) - 85.0);
                }
            }
        std::vector<const Grid<float>*> ptrs;
        for (const auto& g : hz) ptrs.push_back(&g);
        const ApertureMaps maps = computeAperture(ptrs, e, n, u);
        const int samples = 2 * d * (4000 / d + 1);  // sample cells end on sector edges
        for (std::size_t r = 0; r < h; ++r)
            for (std::size_t c = 0; c < w; ++c) {
                std::vector<float> cell;
                for (const auto& g : hz) cell.push_back(g(c, r));
                const EnuVector normal{e(c, r), n(c, r), u(c, r)};
                const auto horizon = [&](double azDeg) {
                    const double sector = std::floor(azDeg / (360.0 / d) + 0.5);
                    return static_cast<double>(cell[static_cast<std::size_t>(static_cast<int>(sector) % d)]);
                };
                const SkyReference ref = referenceSky(horizon, normal, samples);
                const Aperture kernel = aperture(cell, normal);
                const double bent[3] = {maps.bentEast(c, r), maps.bentNorth(c, r), maps.bentUp(c, r)};
                const double refBent[3] = {ref.bentNormal.east, ref.bentNormal.north, ref.bentNormal.up};
                const double kernelBent[3] = {kernel.bentNormal.east, kernel.bentNormal.north, kernel.bentNormal.up};
                double err = std::abs(maps.solidAngleSr(c, r) - ref.solidAngleSr);
                double kernelErr = std::abs(kernel.solidAngleSr - ref.solidAngleSr);
                for (int i = 0; i < 3; ++i) {
                    err = std::max(err, std::abs(bent[i] - refBent[i]));
                    kernelErr = std::max(kernelErr, std::abs(kernelBent[i] - refBent[i]));
                }
                worstRef = std::max(worstRef, err);
                worstKernelRef = std::max(worstKernelRef, kernelErr);
                ASSERT_LT(err, 2e-5) << "D " << d << " cell " << c << "," << r << " slope " << slopes(c, r);
                ASSERT_LT(kernelErr, 2e-5) << "kernel, D " << d << " cell " << c << "," << r << " slope " << slopes(c, r);
            }
    }
    std::cout << "[ aperture ] worst |error| of solid angle (sr) and bent normal against the dense reference: "
              << "grid " << worstRef << ", kernel " << worstKernelRef << "\n";
}

// The exact pass eight cells at once (demlight/lighting/sky_wedge_lanes.h) against one cell at a time,
// on random grids of every slope with horizons near the tangent plane's elevation: the same
// maps (the same expressions, none contracted into a fused multiply-add), and the path taken by
// most cells whose plane rises.
TEST(ApertureGrid, EightCellsAtOnceAreOneAtATime) {
    const std::size_t w = 67, h = 23;
    std::mt19937_64 rng(20261205);
    if (!processorHasAvx512()) GTEST_SKIP() << "no AVX-512 path on this processor";
    double worst = 0;
    std::size_t cells = 0, differing = 0;
    for (const int d : {3, 8, 16, 32}) {
        const RisingPlaneGrids g = risingPlaneGrids(w, h, d, rng);
        const std::vector<const Grid<float>*> ptrs = g.horizonPointers();
        const ApertureMaps eight = [&] {
            const detail::ScopedSimdPath path(SimdPath::Avx512);
            return computeAperture(ptrs, g.east, g.north, g.up);
        }();
        const ApertureMaps one = [&] {
            const detail::ScopedSimdPath path(SimdPath::Portable);
            return computeAperture(ptrs, g.east, g.north, g.up);
        }();
        const std::pair<const Grid<float>*, const Grid<float>*> maps[] = {
            {&eight.bentEast, &one.bentEast}, {&eight.bentNorth, &one.bentNorth}, {&eight.bentUp, &one.bentUp},
            {&eight.solidAngleSr, &one.solidAngleSr}, {&eight.radiusDeg, &one.radiusDeg}};
        for (const auto& [a, b] : maps)
            for (std::size_t k = 0; k < a->size(); ++k) {
                const float x = a->data()[k], y = b->data()[k];
                if (std::isnan(x) || std::isnan(y)) {
                    ASSERT_TRUE(std::isnan(x) && std::isnan(y)) << "D " << d << " cell " << k;
                    continue;
                }
                ++cells;
                differing += x != y;
                worst = std::max(worst, static_cast<double>(std::abs(x - y)));
                ASSERT_EQ(x, y) << "D " << d << " cell " << k;
            }
    }
    std::cout << "[ aperture ] eight cells at once against one: " << differing << " of " << cells
              << " values differ, at most by " << worst << "\n";
}

TEST(ApertureGrid, MatchesKernelThreadDeterministicNodata) {
    const std::size_t w = 11, h = 7;
    const int d = 8;
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> slope(0, 60), aspect(0, 360), hd(-20, 50);
    Grid<float> e(w, h), n(w, h), u(w, h);
    std::vector<Grid<float>> hz(d, Grid<float>(w, h));
    for (std::size_t r = 0; r < h; ++r)
        for (std::size_t c = 0; c < w; ++c) {
            const EnuVector nv = slopeNormal(slope(rng), aspect(rng));
            e(c, r) = static_cast<float>(nv.east);
            n(c, r) = static_cast<float>(nv.north);
            u(c, r) = static_cast<float>(nv.up);
            for (auto& g : hz) g(c, r) = static_cast<float>(hd(rng));
        }
    hz[3](2, 2) = std::numeric_limits<float>::quiet_NaN();
    std::vector<const Grid<float>*> ptrs;
    for (const auto& g : hz) ptrs.push_back(&g);
    const ApertureMaps one = withThreads(1, [&] { return computeAperture(ptrs, e, n, u); });
    const ApertureMaps many = withThreads(4, [&] { return computeAperture(ptrs, e, n, u); });
    EXPECT_EQ(std::memcmp(one.bentEast.data(), many.bentEast.data(), w * h * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(one.radiusDeg.data(), many.radiusDeg.data(), w * h * sizeof(float)), 0);
    EXPECT_TRUE(std::isnan(one.solidAngleSr(2, 2)));
    EXPECT_TRUE(std::isnan(one.bentUp(2, 2)));
    const std::vector<float> cell{hz[0](5, 4), hz[1](5, 4), hz[2](5, 4), hz[3](5, 4),
                                  hz[4](5, 4), hz[5](5, 4), hz[6](5, 4), hz[7](5, 4)};
    const Aperture a = aperture(cell, {e(5, 4), n(5, 4), u(5, 4)});
    EXPECT_NEAR(one.solidAngleSr(5, 4), a.solidAngleSr, 1e-5);
    EXPECT_NEAR(one.radiusDeg(5, 4), a.radiusDeg, 1e-4);
    EXPECT_NEAR(one.bentNorth(5, 4), a.bentNormal.north, 1e-6);

    const ApertureLightMaps lit = applyApertureLight(one, e, n, u, directionEnu(180, 40),
                                                     ApertureLightParams{});
    EXPECT_TRUE(std::isnan(lit.sun(2, 2)));
    EXPECT_GE(lit.ambient(5, 4), 0.0f);

    ApertureAccumulator acc(e, n, u, d);
    EXPECT_THROW(acc.finish(), Error);
    EXPECT_THROW(acc.addDirection(8, hz[0]), Error);
}

}  // namespace
}  // namespace demlight
