// Sky factors: analytic cases (flat, tilted plane, V valley, paraboloid pit, wall), patches,
// f_sky limits, monotonicity, the dense reference, and the streaming grid driver.
#include "demlight/core/parallel.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/sky_wedge.h"
#include "demlight/lighting/sky_wedge_lanes.h"
#include "rising_planes.h"

#include "demlight/core/error.h"
#include "demlight/core/simd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace demlight {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

/// Horizons sampled at the sector centres i * 360 / D.
std::vector<float> sampleHorizons(const std::function<double(double)>& horizonDeg, int d) {
    std::vector<float> h(static_cast<std::size_t>(d));
    for (int i = 0; i < d; ++i) h[static_cast<std::size_t>(i)] = static_cast<float>(horizonDeg(360.0 * i / d));
    return h;
}

/// Unit normal of a plane sloping down towards aspectDeg with slope slopeDeg.
bool sameGridBits(const Grid<float>& a, const Grid<float>& b) {
    return a.sameShape(b) && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

EnuVector slopeNormal(double slopeDeg, double aspectDeg) {
    return {std::sin(slopeDeg * kDeg) * std::sin(aspectDeg * kDeg),
            std::sin(slopeDeg * kDeg) * std::cos(aspectDeg * kDeg), std::cos(slopeDeg * kDeg)};
}

/// Elevation (degrees) of the plane with normal n in azimuth az.
double planeElevationDeg(const EnuVector& n, double azDeg) {
    const double a = n.east * std::sin(azDeg * kDeg) + n.north * std::cos(azDeg * kDeg);
    return std::atan(-a / n.up) / kDeg;
}

/// V valley with side slopes beta and axis azimuth axisDeg, seen from the floor.
std::function<double(double)> vValley(double betaDeg, double axisDeg) {
    return [=](double az) {
        return std::atan(std::tan(betaDeg * kDeg) * std::abs(std::sin((az - axisDeg) * kDeg))) / kDeg;
    };
}

#ifdef DEMLIGHT_SKY_LANES
// The exact pass eight cells at once gives each cell the scalar chain's K (sky.cpp's pass 2:
// unitNormal, the clamped elevation, its sine and cosine, sectorPiKAboveLower / pi), on normals
// of every slope and aspect, horizons from below the plane to the zenith, and the sectors of 4 to
// 64 directions.
TEST(Sky, RisingSectorKEightAtOnceIsTheScalarChain) {
    if (!processorHasAvx512()) GTEST_SKIP() << "no AVX-512 path on this processor";
    std::mt19937_64 rng(20261205);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), slope(0.0, 80.0), horizon(-95.0, 95.0);
    std::size_t cells = 0, crossing = 0, differing = 0, differingFloats = 0;
    for (const std::size_t directions : {4u, 7u, 16u, 32u, 64u}) {
        for (std::size_t index = 0; index < directions; ++index) {
            const auto [phi1, phi2] = detail::sectorBoundsRad(index, directions);
            const detail::AzimuthRange r = detail::makeAzimuthRange(phi1, phi2);
            for (int group = 0; group < 200; ++group) {
                alignas(64) double e[8], n[8], u[8], h[8], k[8];
                for (int l = 0; l < 8; ++l) {
                    // Grid-like normals (floats), some of them nearly level or nearly vertical (a
                    // level one has no plane to rise: pass 1 takes it).
                    const double s = l == 0 ? 1e-6 : std::tan(slope(rng) * std::numbers::pi / 180.0);
                    const double a = unit(rng) * std::numbers::pi;
                    e[l] = static_cast<float>(s * std::sin(a));
                    n[l] = static_cast<float>(s * std::cos(a));
                    u[l] = l == 1 ? 1e-9 : 1.0;
                    h[l] = static_cast<float>(l == 2 ? 90.0 : horizon(rng));
                }
                detail::risingSectorK8(e, n, u, h, r, k);
                for (int l = 0; l < 8; ++l) {
                    const EnuVector normal = detail::unitNormal({e[l], n[l], u[l]});
                    const double hRad = std::clamp(h[l], -90.0, 90.0) * kDegToRad;
                    const SinCos sc = fastSinCosElevation(hRad);
                    const double scalar =
                        detail::sectorPiKAboveLower(normal.east, normal.north, normal.up, r, hRad, sc.sin, sc.cos) /
                        std::numbers::pi;
                    // The same expressions, none contracted into a fused multiply-add: the same bits.
                    ASSERT_EQ(k[l], scalar)
                        << directions << " directions, sector " << index << ", lane " << l << ": " << k[l]
                        << " vs " << scalar << " (normal " << e[l] << " " << n[l] << " " << u[l] << ", horizon "
                        << h[l] << ")";
                    differing += k[l] != scalar;
                    differingFloats += static_cast<float>(k[l]) != static_cast<float>(scalar);
                    ++cells;
                    const double t = normal.up * sc.sin, q = std::hypot(normal.east, normal.north) * sc.cos;
                    crossing += std::abs(t) < q;
                }
            }
        }
    }
    EXPECT_GT(crossing, cells / 4) << "too few cells whose plane crosses the horizon to test the cuts";
    std::cout << "risingSectorK8: " << differing << " of " << cells << " cells differ from the scalar chain in the double, "
              << differingFloats << " as floats\n";
}
#endif

// The sky's exact pass eight cells at once against one cell at a time, through computeSky.
TEST(Sky, EightCellsAtOnceAreOneAtATime) {
    const std::size_t w = 67, h = 23;
    std::mt19937_64 rng(20261206);
    if (!processorHasAvx512()) GTEST_SKIP() << "no AVX-512 path on this processor";
    double worst = 0;
    std::size_t cells = 0, differing = 0;
    for (const int d : {3, 8, 16, 32}) {
        const RisingPlaneGrids g = risingPlaneGrids(w, h, d, rng);
        const std::vector<const Grid<float>*> ptrs = g.horizonPointers();
        const SkyMaps eight = [&] {
            const detail::ScopedSimdPath path(SimdPath::Avx512);
            return computeSky(ptrs, g.east, g.north, g.up, 0.2, {});
        }();
        const SkyMaps one = [&] {
            const detail::ScopedSimdPath path(SimdPath::Portable);
            return computeSky(ptrs, g.east, g.north, g.up, 0.2, {});
        }();
        for (const auto& [a, b] : {std::pair{&eight.skyK, &one.skyK}, std::pair{&eight.skyFactor, &one.skyFactor}})
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
        EXPECT_TRUE(sameGridBits(eight.skyFraction, one.skyFraction));  // pass 1 only
    }
    std::cout << "[ sky ] eight cells at once against one: " << differing << " of " << cells
              << " values differ, at most by " << worst << "\n";
}

TEST(Sky, FlatGroundGivesExactlyOne) {
    for (int d : {1, 4, 6, 7, 8, 16, 36, 64, 360}) {
        for (double h : {0.0, -0.5, -10.0}) {
            const std::vector<float> hz(static_cast<std::size_t>(d), static_cast<float>(h));
            EXPECT_EQ(static_cast<float>(skyK(hz, {0, 0, 1})), 1.0f) << "D=" << d;
            EXPECT_NEAR(skyK(hz, {0, 0, 1}), 1.0, 1e-15) << "D=" << d;
            EXPECT_EQ(svfHorizontal(hz), 1.0);
            EXPECT_EQ(skyFraction(hz), 1.0);
            for (double c : {0.0, 0.3, 1.0}) EXPECT_NEAR(skyFactor(skyK(hz, {0, 0, 1}), c), 1.0, 1e-15);
        }
    }
    // Powers of two are exact in double too.
    for (int d : {4, 8, 16, 64}) {
        const std::vector<float> hz(static_cast<std::size_t>(d), 0.0f);
        EXPECT_EQ(skyK(hz, {0, 0, 1}), 1.0) << "D=" << d;
    }
}

// Regression guard for the exact (per-azimuth) clamping to the tangent plane: a tilted plane
// with nothing above it sees its whole normal hemisphere, K = 1, for every D. Clamping at the
// sector centre would get this wrong by O(1/D).
TEST(Sky, TiltedPlaneWithOpenSkyGivesOneForEveryD) {
    for (double slope : {5.0, 30.0, 60.0, 85.0}) {
        for (double aspect : {0.0, 37.0, 135.0, 300.0}) {
            const EnuVector n = slopeNormal(slope, aspect);
            for (int d : {1, 3, 4, 8, 64}) {
                const std::vector<float> low(static_cast<std::size_t>(d), -90.0f);
                EXPECT_NEAR(skyK(low, n), 1.0, 1e-12) << slope << " " << aspect << " D=" << d;
            }
            // The dense reference agrees.
            EXPECT_NEAR(referenceSky([](double) { return -90.0; }, n).skyK, 1.0, 1e-12);
        }
    }
}

// An infinite planar slope's own horizon is its tangent plane: K -> 1 as D grows, and the
// horizontal-plane SVF -> (1 + cos beta) / 2 (analytic: mean sin^2 over the uphill half).
TEST(Sky, InfiniteSlopeConverges) {
    const double beta = 30.0;
    const EnuVector n = slopeNormal(beta, 200.0);
    double prevErr = 1.0;
    for (int d : {8, 16, 32, 64, 128}) {
        const auto hz = sampleHorizons([&](double az) { return planeElevationDeg(n, az); }, d);
        const double err = std::abs(skyK(hz, n) - 1.0);
        std::cout << "[ measured ] 30-degree slope, horizon = own plane: |K - 1| D" << d << "="
                  << err << "\n";
        EXPECT_LT(err, prevErr * 0.6) << "D=" << d;
        prevErr = err;
        EXPECT_NEAR(svfHorizontal(hz), 0.5 * (1.0 + std::cos(beta * kDeg)), 3.0 / (d * d));
    }
    EXPECT_LT(prevErr, 1e-3);
}

// V valley (side slopes beta) seen from its floor: SVF = K = cos(beta) exactly for the
// continuous horizon (mean of 1/(1 + tan^2 b sin^2) is cos b). The D-sector value converges.
TEST(Sky, VValleyFloorConvergesToCosBeta) {
    for (double beta : {10.0, 30.0, 50.0}) {
        const auto horizon = vValley(beta, 30.0);
        const double exact = std::cos(beta * kDeg);
        const SkyReference ref = referenceSky(horizon, {0, 0, 1}, 4096);
        EXPECT_NEAR(ref.skyK, exact, 1e-6);
        EXPECT_NEAR(ref.svfHorizontal, exact, 1e-6);
        // Unweighted fraction: mean sin h = 2 beta / pi (analytic).
        EXPECT_NEAR(ref.skyFraction, 1.0 - 2.0 * beta * kDeg / kPi, 1e-6);
        // cos^2 h = 1 / (1 + tan^2 b sin^2(phi - axis)) is smooth and periodic, so the
        // sector sum converges geometrically; from D = 64 on only the float rounding of the
        // horizons (~1e-8) is left.
        double prevErr = 1.0;
        std::cout << "[ measured ] V valley beta " << beta << " |K - cos b|:";
        for (int d : {2, 4, 8, 16, 64, 256}) {
            const auto hz = sampleHorizons(horizon, d);
            const double k = skyK(hz, {0, 0, 1});
            EXPECT_NEAR(k, svfHorizontal(hz), 1e-12);  // up normal: K is the Dozier SVF
            const double err = std::abs(k - exact);
            std::cout << " D" << d << "=" << err;
            EXPECT_LE(err, prevErr + 2e-8) << "beta=" << beta << " D=" << d;
            if (d >= 64) {
                EXPECT_LT(err, 1e-7) << "beta=" << beta << " D=" << d;
            }
            prevErr = err;
        }
        std::cout << "\n";
    }
}

/// Horizon (degrees) of the bowl z = a r^2 for r < r0, z = a r0^2 beyond, seen from (x0, y0)
/// on its surface: brute-force march along the ray in fine steps.
double pitHorizonDeg(double a, double r0, double x0, double y0, double azDeg) {
    const auto z = [&](double x, double y) { return a * std::min(x * x + y * y, r0 * r0); };
    const double z0 = z(x0, y0);
    const double dx = std::sin(azDeg * kDeg), dy = std::cos(azDeg * kDeg);
    double best = -std::numeric_limits<double>::infinity();
    for (double s = 1e-3; s < 4.0 * r0; s += 1e-3)
        best = std::max(best, std::atan((z(x0 + s * dx, y0 + s * dy) - z0) / s));
    return best / kDeg;
}

TEST(Sky, ParaboloidPit) {
    const double a = 0.5, r0 = 1.0;  // rim at 26.57 degrees seen from the centre
    // Centre: uniform horizon atan(a r0), K = SVF = cos^2 h for any D.
    const double hc = std::atan(a * r0);
    for (int d : {4, 8, 64}) {
        const auto hz = sampleHorizons([&](double az) { return pitHorizonDeg(a, r0, 0, 0, az); }, d);
        EXPECT_NEAR(skyK(hz, {0, 0, 1}), std::cos(hc) * std::cos(hc), 1e-5);
    }
    // Off centre on the tilted wall: D-sector K converges to the dense reference.
    const double x0 = 0.5, y0 = 0.2;
    EnuVector n{-2 * a * x0, -2 * a * y0, 1.0};
    const double len = std::sqrt(n.east * n.east + n.north * n.north + 1.0);
    n = {n.east / len, n.north / len, n.up / len};
    const auto horizon = [&](double az) { return pitHorizonDeg(a, r0, x0, y0, az); };
    const double ref = referenceSky(horizon, n, 2048).skyK;
    EXPECT_GT(ref, 0.5);
    EXPECT_LT(ref, 1.0);
    double err8 = 0, err64 = 0;
    for (int d : {8, 64}) {
        const double err = std::abs(skyK(sampleHorizons(horizon, d), n) - ref);
        (d == 8 ? err8 : err64) = err;
    }
    std::cout << "[ measured ] paraboloid pit off-centre K " << ref << ": |K_D - ref| D8=" << err8
              << " D64=" << err64 << "\n";
    EXPECT_LT(err64, 2e-3);
    EXPECT_LT(err64, err8);
}

TEST(Sky, WallBlocksHalfTheSky) {
    // Wall of 90 degrees over the sectors 0..D/2-1 (azimuths [-w/2, 180 - w/2)).
    for (int d : {2, 8, 64}) {
        std::vector<float> hz(static_cast<std::size_t>(d), 0.0f);
        for (int i = 0; i < d / 2; ++i) hz[static_cast<std::size_t>(i)] = 90.0f;
        EXPECT_NEAR(skyK(hz, {0, 0, 1}), 0.5, 1e-14);
        EXPECT_NEAR(svfHorizontal(hz), 0.5, 1e-14);
        EXPECT_NEAR(skyFraction(hz), 0.5, 1e-14);
        // A normal leaning towards the open side sees more than a normal leaning at the wall,
        // and both match the dense reference of the same piecewise-constant horizon.
        const double w = 360.0 / d;
        const auto wall = [&](double az) {
            const double rel = std::fmod(az + 0.5 * w + 360.0, 360.0);
            return rel < 180.0 ? 90.0 : 0.0;
        };
        const double open = 270.0 - 0.5 * w;  // centre of the open half
        const EnuVector towardsOpen = slopeNormal(30.0, open);
        const EnuVector towardsWall = slopeNormal(30.0, open - 180.0);
        const double kOpen = skyK(hz, towardsOpen), kWall = skyK(hz, towardsWall);
        EXPECT_GT(kOpen, 0.5);
        EXPECT_LT(kWall, 0.5);
        EXPECT_NEAR(kOpen, referenceSky(wall, towardsOpen, 1 << 16).skyK, 1e-4);
        EXPECT_NEAR(kWall, referenceSky(wall, towardsWall, 1 << 16).skyK, 1e-4);
    }
    // Same with the wedge primitive directly.
    EXPECT_NEAR(skyKWedge({0, 0, 1}, 0, 180, 90) + skyKWedge({0, 0, 1}, 180, 360, 0), 0.5, 1e-15);
}

TEST(Sky, WedgeElevationBandsOnFlatGround) {
    // Up normal: the band [e0, e1] holds sin^2 e1 - sin^2 e0 of K.
    const EnuVector up{0, 0, 1};
    EXPECT_NEAR(skyKWedge(up, 0, 360, 0, 0, 30), 0.25, 1e-15);
    EXPECT_NEAR(skyKWedge(up, 0, 360, 0, 30, 60), 0.5, 1e-15);
    EXPECT_NEAR(skyKWedge(up, 0, 360, 0, 60, 90), 0.25, 1e-15);
    EXPECT_NEAR(skyKWedge(up, 0, 90, 45, 0, 90), 0.125, 1e-15);
}

struct RandomCell {
    std::vector<float> horizons;
    EnuVector normal;
};

RandomCell randomCell(std::mt19937_64& rng, int d) {
    std::uniform_real_distribution<double> slope(0.0, 70.0), aspect(0.0, 360.0), h(-30.0, 60.0);
    RandomCell c;
    c.normal = slopeNormal(slope(rng), aspect(rng));
    for (int i = 0; i < d; ++i) c.horizons.push_back(static_cast<float>(h(rng)));
    return c;
}

TEST(Sky, PatchesSumToK) {
    std::mt19937_64 rng(20240621);
    for (const char* spec : {"sky", "sectors:4", "bands:0,30,60,90", "sectors:4,bands:0,45,90",
                             "sectors:3, bands:-10,20,90", "sectors:7", "bands:-90,90"}) {
        const SkyPatches patches = parseSkyPatches(spec);
        for (int d : {1, 8, 13, 64}) {
            for (int trial = 0; trial < 20; ++trial) {
                const RandomCell c = randomCell(rng, d);
                std::vector<double> k(patches.size());
                skyPatchK(c.horizons, c.normal, patches, k);
                double sum = 0.0;
                for (double v : k) {
                    EXPECT_GE(v, -1e-15);
                    sum += v;
                }
                EXPECT_NEAR(sum, skyK(c.horizons, c.normal), 1e-12) << spec << " D=" << d;
            }
        }
    }
    // Flat open ground: four quarters, and the band split sin^2.
    std::vector<double> k4(4);
    skyPatchK(std::vector<float>(16, 0.0f), {0, 0, 1}, parseSkyPatches("sectors:4"), k4);
    for (double v : k4) EXPECT_NEAR(v, 0.25, 1e-15);
    std::vector<double> kb(3);
    skyPatchK(std::vector<float>(16, 0.0f), {0, 0, 1}, parseSkyPatches("bands:0,30,60,90"), kb);
    EXPECT_NEAR(kb[0], 0.25, 1e-15);
    EXPECT_NEAR(kb[1], 0.5, 1e-15);
    EXPECT_NEAR(kb[2], 0.25, 1e-15);
}

TEST(Sky, PatchSpecParsing) {
    const SkyPatches p = parseSkyPatches("sectors:4,bands:0,45,90");
    ASSERT_EQ(p.size(), 8u);
    EXPECT_EQ(p.patches[0].azimuth0Deg, -45.0);
    EXPECT_EQ(p.patches[0].azimuth1Deg, 45.0);
    EXPECT_EQ(p.patches[0].elevation0Deg, -90.0);  // first band reaches down to -90
    EXPECT_EQ(p.patches[1].elevation0Deg, 45.0);
    EXPECT_EQ(p.patches[7].azimuth0Deg, 225.0);
    // Names say what the patch holds: the first band from -90, whatever E0 was.
    EXPECT_EQ(p.patches[0].name, "az -45..45 el -90..45");
    EXPECT_EQ(parseSkyPatches("bands:10,30,90").patches[0].name, "az 0..360 el -90..30");
    EXPECT_EQ(parseSkyPatches(" sky ").size(), 1u);

    for (const char* bad : {"", "sectors:", "sectors:0", "sectors:2.5", "sectors:x", "sectors:400",
                            "bands:0", "bands:0,45", "bands:10,5,90", "bands:0,100", "bands:-100,90",
                            "foo:3", "sectors:4,sectors:2", "sectors:4,7", "bands:0,,90"}) {
        EXPECT_THROW(parseSkyPatches(bad), Error) << bad;
    }
    try {
        parseSkyPatches("bands:0,45");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("90"), std::string::npos) << e.what();
    }
}

TEST(Sky, SkyFactorLimits) {
    EXPECT_EQ(skyFactor(0.0, 0.0), 0.0);
    EXPECT_EQ(skyFactor(0.0, 1.0), 0.0);  // 0/0 corner defined as 0
    EXPECT_EQ(skyFactor(0.7, 1.0), 1.0);  // perfect reflector: interreflection fills the rest
    EXPECT_EQ(skyFactor(1.0, 0.6), 1.0);
    EXPECT_DOUBLE_EQ(skyFactor(0.7, 0.0), 0.7);
    EXPECT_DOUBLE_EQ(skyFactor(0.5, 0.5), 0.5 / 0.75);
    EXPECT_EQ(skyFactor(1e-300, 1.0), 1.0);
    EXPECT_TRUE(std::isfinite(skyFactor(1e-300, 1.0 - 1e-16)));
    // Monotone in albedo and in K; out-of-range inputs clamp.
    double prev = 0.0;
    for (double c = 0.0; c <= 1.0; c += 0.05) {
        const double f = skyFactor(0.4, c);
        EXPECT_GE(f, prev);
        EXPECT_GE(f, 0.4);
        EXPECT_LE(f, 1.0);
        prev = f;
    }
    EXPECT_EQ(skyFactor(1.5, 0.3), 1.0);
    EXPECT_EQ(skyFactor(0.5, 2.0), 1.0);
}

// Raising any one horizon never increases K, the patch K values, or the SVFs.
TEST(Sky, MonotoneInEveryHorizon) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> bump(0.0, 25.0);
    const SkyPatches patches = parseSkyPatches("sectors:3,bands:0,40,90");
    for (int d : {4, 8, 32}) {
        for (int trial = 0; trial < 100; ++trial) {
            RandomCell c = randomCell(rng, d);
            const double k0 = skyK(c.horizons, c.normal);
            std::vector<double> p0(patches.size()), p1(patches.size());
            skyPatchK(c.horizons, c.normal, patches, p0);
            const double svf0 = svfHorizontal(c.horizons), frac0 = skyFraction(c.horizons);
            const std::size_t i = static_cast<std::size_t>(trial) % c.horizons.size();
            c.horizons[i] = static_cast<float>(std::min(90.0, c.horizons[i] + bump(rng)));
            EXPECT_LE(skyK(c.horizons, c.normal), k0 + 1e-14);
            skyPatchK(c.horizons, c.normal, patches, p1);
            for (std::size_t p = 0; p < p0.size(); ++p) EXPECT_LE(p1[p], p0[p] + 1e-14);
            EXPECT_LE(svfHorizontal(c.horizons), svf0 + 1e-15);
            EXPECT_LE(skyFraction(c.horizons), frac0 + 1e-15);
            EXPECT_GE(skyK(c.horizons, c.normal), 0.0);
        }
    }
}

// The D-sector kernel integrates exactly the piecewise-constant horizon, so against the dense
// reference of that same step function the only error is the reference's own quadrature.
TEST(Sky, ExactForPiecewiseConstantHorizon) {
    std::mt19937_64 rng(11);
    for (int trial = 0; trial < 10; ++trial) {
        const int d = 8;
        const RandomCell c = randomCell(rng, d);
        const auto step = [&](double az) {
            const int i = static_cast<int>(std::floor(az / 45.0 + 0.5)) % d;
            return static_cast<double>(c.horizons[static_cast<std::size_t>(i)]);
        };
        EXPECT_NEAR(skyK(c.horizons, c.normal), referenceSky(step, c.normal, 1 << 16).skyK, 2e-5);
    }
}

// ---- Grid driver -----------------------------------------------------------------------------

struct TestScene {
    Grid<float> east, north, up;
    std::vector<Grid<float>> horizons;
};

TestScene randomScene(std::size_t w, std::size_t h, int d, unsigned seed) {
    std::mt19937_64 rng(seed);
    TestScene s{Grid<float>(w, h), Grid<float>(w, h), Grid<float>(w, h), {}};
    for (int i = 0; i < d; ++i) s.horizons.emplace_back(w, h);
    for (std::size_t r = 0; r < h; ++r)
        for (std::size_t c = 0; c < w; ++c) {
            const RandomCell cell = randomCell(rng, d);
            s.east(c, r) = static_cast<float>(cell.normal.east);
            s.north(c, r) = static_cast<float>(cell.normal.north);
            s.up(c, r) = static_cast<float>(cell.normal.up);
            for (int i = 0; i < d; ++i) s.horizons[static_cast<std::size_t>(i)](c, r) = cell.horizons[static_cast<std::size_t>(i)];
        }
    return s;
}

std::vector<const Grid<float>*> pointers(const std::vector<Grid<float>>& grids) {
    std::vector<const Grid<float>*> out;
    for (const auto& g : grids) out.push_back(&g);
    return out;
}

// The accumulator's algebraic sector integral (cut azimuths as unit vectors, no angles) against
// the general wedge (cut angles by asin, pieces by angle): random normals from flat to nearly
// vertical, sectors of D = 3..64 and arbitrary ranges narrower than 180 deg, lower limits anywhere and near the
// plane's own elevation inside the range, so that pieces with 0, 1 and 2 cuts all occur.
TEST(Sky, AlgebraicSectorMatchesTheGeneralWedge) {
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int cutCases[3] = {0, 0, 0};
    double worst = 0.0;
    for (int trial = 0; trial < 20000; ++trial) {
        const double slopeDeg = trial % 7 == 0 ? 89.9 + 0.099 * unit(rng) : 89.0 * unit(rng);
        EnuVector n = slopeNormal(slopeDeg, 360.0 * unit(rng));
        if (trial % 11 == 0) n = {1e-9, -2e-9, 1.0};  // barely tilted
        double az0Deg, az1Deg;
        if (trial % 2 == 0) {
            const int d = std::array{3, 4, 5, 8, 16, 32, 64}[static_cast<std::size_t>(trial / 2) % 7];
            const double w = 360.0 / d;
            az0Deg = w * std::floor(d * unit(rng)) - 0.5 * w;
            az1Deg = az0Deg + w;
        } else {
            az0Deg = 720.0 * unit(rng) - 360.0;
            az1Deg = az0Deg + 179.9 * unit(rng) + 0.01;
        }
        // Lower limit: anywhere, or the plane's elevation at a random azimuth of the range.
        double lowerDeg = 180.0 * unit(rng) - 90.0;
        if (trial % 3 != 0) lowerDeg = planeElevationDeg(n, az0Deg + (az1Deg - az0Deg) * unit(rng));
        if (trial % 97 == 0) lowerDeg = trial % 2 ? 90.0 : -90.0;
        const double lower = lowerDeg * kDeg;
        const detail::AzimuthRange r = detail::makeAzimuthRange(az0Deg * kDeg, az1Deg * kDeg);
        const double fast = detail::sectorPiKAboveLower(n.east, n.north, n.up, r, lower, std::sin(lower),
                                                        std::cos(lower)) / kPi;
        const double general = skyKWedge(n, az0Deg, az1Deg, lowerDeg);
        worst = std::max(worst, std::abs(fast - general));
        ASSERT_NEAR(fast, general, 1e-9) << "trial " << trial << " slope " << slopeDeg << " range " << az0Deg
                                         << ".." << az1Deg << " lower " << lowerDeg;
        // Cuts inside the range: sign changes of plane-above-lower along a fine sampling.
        int changes = 0;
        bool above = false;
        for (int i = 0; i <= 400; ++i) {
            const double az = az0Deg + (az1Deg - az0Deg) * i / 400.0;
            const bool a = planeElevationDeg(n, az) > lowerDeg;
            if (i > 0 && a != above) ++changes;
            above = a;
        }
        ++cutCases[std::min(changes, 2)];
    }
    std::cout << "[ sky ] algebraic sector vs general wedge: worst |dK| " << worst << "; ranges with 0/1/2 cuts "
              << cutCases[0] << "/" << cutCases[1] << "/" << cutCases[2] << "\n";
    EXPECT_GT(cutCases[1], 1000);
    EXPECT_GT(cutCases[2], 20);
}

TEST(SkyGrid, MatchesPerCellKernelsAndIsThreadDeterministic) {
    const int d = 16;
    TestScene s = randomScene(23, 17, d, 3);
    s.horizons[5](4, 6) = std::numeric_limits<float>::quiet_NaN();  // nodata cell
    s.up(7, 2) = std::numeric_limits<float>::quiet_NaN();            // nodata normal
    const SkyPatches patches = parseSkyPatches("sectors:4,bands:0,45,90");
    const SkyMaps one = withThreads(1, [&] { return computeSky(pointers(s.horizons), s.east, s.north, s.up, 0.3, patches); });
    const SkyMaps many = withThreads(4, [&] { return computeSky(pointers(s.horizons), s.east, s.north, s.up, 0.3, patches); });
    // Bitwise comparison (NaN != NaN).
    for (std::size_t i = 0; i < one.skyK.size(); ++i) {
        EXPECT_EQ(std::memcmp(&one.skyK.data()[i], &many.skyK.data()[i], sizeof(float)), 0);
        EXPECT_EQ(std::memcmp(&one.skyFactor.data()[i], &many.skyFactor.data()[i], sizeof(float)), 0);
    }
    EXPECT_TRUE(std::isnan(one.skyK(4, 6)));
    EXPECT_TRUE(std::isnan(one.svfHorizontal(4, 6)));
    EXPECT_TRUE(std::isnan(one.patchK[0](4, 6)));
    EXPECT_TRUE(std::isnan(one.skyK(7, 2)));
    EXPECT_TRUE(std::isnan(one.skyFactor(7, 2)));
    for (std::size_t r = 0; r < 17; ++r)
        for (std::size_t c = 0; c < 23; ++c) {
            if ((c == 4 && r == 6) || (c == 7 && r == 2)) continue;
            std::vector<float> hz;
            for (int i = 0; i < d; ++i) hz.push_back(s.horizons[static_cast<std::size_t>(i)](c, r));
            const EnuVector n{s.east(c, r), s.north(c, r), s.up(c, r)};
            const double k = skyK(hz, n);
            EXPECT_NEAR(one.skyK(c, r), k, 1e-6);
            EXPECT_NEAR(one.skyFactor(c, r), skyFactor(k, 0.3), 1e-6);
            EXPECT_NEAR(one.svfHorizontal(c, r), svfHorizontal(hz), 1e-6);
            EXPECT_NEAR(one.skyFraction(c, r), skyFraction(hz), 1e-6);
            double sum = 0.0;
            for (const auto& g : one.patchK) sum += g(c, r);
            EXPECT_NEAR(sum, one.skyK(c, r), 1e-5);
        }
}

TEST(SkyGrid, NodataRunsAtRowEndsAreNaNAndLeaveTheOtherCells) {
    // The accumulation leaves out a row's runs of NaN horizons at both ends (a coastal DEM's sea)
    // and sets their sums to NaN. Cells are accumulated independently, so every other cell must
    // keep the bits it has without those NaNs, and every cell with a NaN horizon must end NaN
    // in every map, its normal being valid. Runs of 1, 3 and 17 cells (the vectorised pass then
    // starts off its alignment), a whole row, a run in one direction only, and a run that grows
    // from one direction to a later one (the sums a direction set to NaN are not set again).
    const int d = 16;
    const std::size_t w = 40, h = 6;
    const TestScene clean = randomScene(w, h, d, 31);
    TestScene coast = clean;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const auto blank = [&](std::size_t row, std::size_t c0, std::size_t c1, int only = -1) {
        for (int i = 0; i < d; ++i)
            if (only < 0 || i == only)
                for (std::size_t c = c0; c < c1; ++c) coast.horizons[static_cast<std::size_t>(i)](c, row) = nan;
    };
    blank(0, 0, 1);
    blank(0, 37, 40);
    blank(1, 0, 17);
    blank(2, 0, 40);
    blank(3, 23, 40);
    blank(4, 0, 3, 5);  // direction 5 only
    blank(5, 0, 2, 2);  // a run that a later direction widens
    blank(5, 0, 6, 9);
    const SkyPatches patches = parseSkyPatches("sectors:4");
    const SkyMaps a = computeSky(pointers(coast.horizons), coast.east, coast.north, coast.up, 0.3, patches);
    const SkyMaps b = computeSky(pointers(clean.horizons), clean.east, clean.north, clean.up, 0.3, patches);
    std::size_t nanCells = 0;
    for (std::size_t r = 0; r < h; ++r)
        for (std::size_t c = 0; c < w; ++c) {
            bool anyNan = false;
            for (const Grid<float>& g : coast.horizons) anyNan = anyNan || std::isnan(g(c, r));
            for (const auto& [mapA, mapB] : {std::pair{&a.svfHorizontal, &b.svfHorizontal},
                                             std::pair{&a.skyFraction, &b.skyFraction}, std::pair{&a.skyK, &b.skyK},
                                             std::pair{&a.skyFactor, &b.skyFactor}, std::pair{&a.patchK[2], &b.patchK[2]}}) {
                if (anyNan) {
                    EXPECT_TRUE(std::isnan((*mapA)(c, r))) << c << " " << r;
                } else {
                    EXPECT_EQ(std::memcmp(&(*mapA)(c, r), &(*mapB)(c, r), sizeof(float)), 0) << c << " " << r;
                }
            }
            nanCells += anyNan;
        }
    EXPECT_EQ(nanCells, 1u + 3u + 17u + 40u + 17u + 3u + 6u);
}

TEST(SkyGrid, StreamingInAnyOrderAndAlbedoRaster) {
    const int d = 8;
    const TestScene s = randomScene(9, 5, d, 5);
    SkyAccumulator acc(s.east, s.north, s.up, d);
    for (int i = d - 1; i >= 0; --i) acc.addDirection(static_cast<std::size_t>(i), s.horizons[static_cast<std::size_t>(i)]);
    Grid<float> albedo(9, 5, 0.25f);
    albedo(2, 3) = std::numeric_limits<float>::quiet_NaN();
    const SkyMaps m = acc.finish(albedo);
    const SkyMaps ref = computeSky(pointers(s.horizons), s.east, s.north, s.up, 0.25);
    for (std::size_t i = 0; i < m.skyK.size(); ++i) EXPECT_NEAR(m.skyK.data()[i], ref.skyK.data()[i], 1e-6);
    EXPECT_TRUE(std::isnan(m.skyFactor(2, 3)));
    EXPECT_FALSE(std::isnan(m.skyK(2, 3)));
    EXPECT_TRUE(m.patchK.empty());
}

TEST(SkyGrid, FinishingInPlaceGivesTheSameMaps) {
    const int d = 8;
    const TestScene s = randomScene(11, 7, d, 8);
    const SkyPatches patches = parseSkyPatches("sectors:2");
    SkyAccumulator acc(s.east, s.north, s.up, d, patches);
    for (int i = 0; i < d; ++i) acc.addDirection(static_cast<std::size_t>(i), s.horizons[static_cast<std::size_t>(i)]);
    const SkyMaps copied = acc.finish(0.3);
    const SkyMaps again = acc.finish(0.3);  // the const form leaves the sums as they were
    const SkyMaps moved = std::move(acc).finish(0.3);
    auto same = [](const Grid<float>& a, const Grid<float>& b) {
        return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
    };
    for (const SkyMaps* m : {&again, &moved}) {
        EXPECT_TRUE(same(copied.svfHorizontal, m->svfHorizontal));
        EXPECT_TRUE(same(copied.skyFraction, m->skyFraction));
        EXPECT_TRUE(same(copied.skyK, m->skyK));
        EXPECT_TRUE(same(copied.skyFactor, m->skyFactor));
        ASSERT_EQ(m->patchK.size(), 2u);
        EXPECT_TRUE(same(copied.patchK[1], m->patchK[1]));
    }
}

TEST(SkyGrid, RejectsBadUse) {
    const TestScene s = randomScene(4, 3, 4, 1);
    SkyAccumulator acc(s.east, s.north, s.up, 4);
    acc.addDirection(0, s.horizons[0]);
    EXPECT_THROW(acc.addDirection(0, s.horizons[0]), Error);  // twice
    EXPECT_THROW(acc.addDirection(4, s.horizons[0]), Error);  // out of range
    EXPECT_THROW(acc.addDirection(1, Grid<float>(3, 3)), Error);  // wrong shape
    EXPECT_THROW(acc.finish(0.2), Error);                       // directions missing
    EXPECT_THROW(SkyAccumulator(s.east, s.north, Grid<float>(1, 1), 4), Error);
    EXPECT_THROW(SkyAccumulator(s.east, s.north, s.up, 0), Error);
}

// skyFactorOf: per cell skyFactor(K, C); NaN where K or C is NaN (a NaN albedo must not read as
// a white sky: skyFactor clamps C, and clamp keeps NaN, but min(1, NaN) would give 1).
TEST(Sky, SkyFactorOfAGridIsNanWhereKOrTheAlbedoIs) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Grid<float> k(3, 1), c(3, 1);
    k(0, 0) = 0.6f, k(1, 0) = nan, k(2, 0) = 0.6f;
    c(0, 0) = 0.3f, c(1, 0) = 0.3f, c(2, 0) = nan;
    const Grid<float> f = skyFactorOf(k, &c, 0.0);
    EXPECT_FLOAT_EQ(f(0, 0), 0.6f / (0.7f + 0.3f * 0.6f));
    EXPECT_TRUE(std::isnan(f(1, 0)));
    EXPECT_TRUE(std::isnan(f(2, 0)));
    EXPECT_FLOAT_EQ(skyFactorOf(k, nullptr, 0.0)(2, 0), 0.6f);  // C = 0: f = K
}

}  // namespace
}  // namespace demlight
