// The hull kernel of a block of parallel lines (demlight/lighting/hull_lanes.h): the double
// reference against a brute-force maximum over every earlier sample, the portable float kernel
// against the reference within hullSlopeErrorBound, and the AVX-512 kernel bit for bit against
// the portable one, on profiles built to stress its window (deep pops past the five vertices it
// keeps, plateaus, nodata runs, ragged blocks) and on the columns of real DEMs.
#include "demlight/core/error.h"
#include "demlight/core/simd.h"
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/hull_lanes.h"
#include "shared_dem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace demlight {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Lines as a row-major array: sample i of line b at heights[i * stride + b].
struct Profiles {
    HullGeometry geometry;
    std::vector<float> heights;
    std::size_t stride = 0, lines = 0;

    std::size_t samples() const { return geometry.sigmaM.size(); }
    float& at(std::size_t i, std::size_t b) { return heights[i * stride + b]; }
};

/// n samples `spacingM` apart, or (varying) with spacings growing by `growth` per sample, as a
/// geographic grid's rows do along a meridian.
HullGeometry geometry(std::size_t n, double spacingM, double growth, double invRadius) {
    HullGeometry g;
    g.invRadius = invRadius;
    g.sigmaM.assign(n, 0.0);
    for (std::size_t i = 1; i < n; ++i)
        g.sigmaM[i] = g.sigmaM[i - 1] + spacingM * (1.0 + growth * static_cast<double>(i));
    return g;
}

enum class Kernel { reference, portable, vector };

std::vector<float> run(const Profiles& p, Kernel kernel) {
    std::vector<float> out(p.heights.size(), 7.0f);
    HullScratch scratch;
    const HullBlock block{p.heights.data(), out.data(), p.stride, p.lines};
    switch (kernel) {
    case Kernel::reference: hullSlopesReference(p.geometry, block, scratch); break;
    case Kernel::portable: hullSlopesPortable(p.geometry, block, scratch); break;
    case Kernel::vector: hullSlopesVector(p.geometry, block, scratch); break;
    }
    return out;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

/// The largest |h|, drop and |h - drop| of the profiles (the bound's maxAbsGM).
double maxAbsG(const Profiles& p) {
    double m = 0.0;
    for (std::size_t i = 0; i < p.samples(); ++i) {
        const double s = p.geometry.sigmaM[i], drop = 0.5 * s * s * p.geometry.invRadius;
        for (std::size_t b = 0; b < p.lines; ++b) {
            const double h = p.heights[i * p.stride + b];
            if (!std::isnan(h)) m = std::max({m, std::abs(h), drop, std::abs(h - drop)});
        }
    }
    return m;
}

struct Agreement {
    double maxDeg = 0.0;     // largest angle difference
    double maxOfBound = 0.0; // largest difference as a share of the cell's bound
    std::size_t cells = 0;   // cells with a horizon in both
};

/// The float kernels against the reference on p: nodata and no-horizon cells alike, every other
/// cell within the bound, the samples outside the block's lines untouched; and where the
/// processor runs the AVX-512 kernel, its bits the portable kernel's.
Agreement expectVectorMatchesReference(const Profiles& p, const std::string& what) {
    const std::vector<float> ref = run(p, Kernel::reference), vec = run(p, Kernel::portable);
    if (hullVectorKernelAvailable()) {
        EXPECT_TRUE(sameBits(run(p, Kernel::vector), vec)) << what << ": the AVX-512 kernel differs from the portable one";
    }
    const HullSlopeBound limit = hullSlopeErrorBound(p.geometry, maxAbsG(p));
    Agreement a;
    std::size_t failures = 0;
    for (std::size_t i = 0; i < p.samples(); ++i)
        for (std::size_t b = 0; b < p.stride; ++b) {
            const std::size_t k = i * p.stride + b;
            if (b >= p.lines) {
                EXPECT_EQ(vec[k], 7.0f) << what << ": sample " << i << " of column " << b << " is no line's";
                continue;
            }
            const float x = vec[k], y = ref[k];
            if (std::isnan(y) || std::isinf(y) || std::isnan(x) || std::isinf(x)) {
                const bool same = (std::isnan(x) && std::isnan(y)) || x == y;
                if (!same && ++failures <= 5)
                    ADD_FAILURE() << what << ": line " << b << " sample " << i << ": vector " << x << ", reference " << y;
                continue;
            }
            const double diff = std::abs(static_cast<double>(x) - y);
            const double bound = limit.at(y);
            if (diff > bound && ++failures <= 5)
                ADD_FAILURE() << what << ": line " << b << " sample " << i << ": vector " << x << ", reference " << y
                              << ", off by " << diff << " > bound " << bound;
            a.maxOfBound = std::max(a.maxOfBound, diff / bound);
            a.maxDeg = std::max(a.maxDeg, std::abs(std::atan(static_cast<double>(x)) - std::atan(static_cast<double>(y))) *
                                              180.0 / M_PI);
            ++a.cells;
        }
    EXPECT_EQ(failures, 0u) << what;
    return a;
}

#define SKIP_WITHOUT_VECTOR_KERNEL() \
    if (!hullVectorKernelAvailable()) GTEST_SKIP() << "no AVX-512 on this processor: the vector kernel cannot run"

/// Concave ramps (every sample stays on the hull) each ended by a peak that hides the whole ramp:
/// the vector kernel's pops run far past its window. Lanes have ramps of different lengths, so
/// their deep pops fall on different rows.
Profiles rampsAndPeaks(std::size_t lines, std::size_t n, const HullGeometry& geo) {
    Profiles p{geo, std::vector<float>(n * (lines + 3), 0.0f), lines + 3, lines};
    for (std::size_t b = 0; b < lines; ++b) {
        const std::size_t period = 7 + 13 * b % 61;
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t phase = i % period;
            const double x = static_cast<double>(phase) / static_cast<double>(period);
            p.at(i, b) = phase + 1 == period ? static_cast<float>(900.0 + 3.0 * b) : static_cast<float>(400.0 * std::sqrt(x));
        }
    }
    return p;
}

TEST(HullLanes, ReferenceIsTheMaximumOverEveryEarlierSample) {
    std::mt19937 rng(43);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int trial = 0; trial < 40; ++trial) {
        const std::size_t n = 20 + trial * 7, lines = 1 + trial % 5;
        const double invR = trial % 3 == 0 ? 0.0 : 1.0 / 7.3e6 * (1.0 + trial);
        Profiles p{geometry(n, 5.0 + trial, trial % 2 ? 1e-3 : 0.0, invR), std::vector<float>(n * lines), lines, lines};
        for (float& h : p.heights) {
            const double u = uniform(rng);
            // Nodata, plateaus (whole metres repeat) and rough ground.
            h = u < 0.1 ? kNaN : u < 0.4 ? std::round(static_cast<float>(20.0 * uniform(rng))) : static_cast<float>(300.0 * uniform(rng));
        }
        const std::vector<float> ref = run(p, Kernel::reference);
        for (std::size_t b = 0; b < lines; ++b)
            for (std::size_t i = 0; i < n; ++i) {
                const float h = p.at(i, b), got = ref[i * lines + b];
                const std::string where = "trial " + std::to_string(trial) + " line " + std::to_string(b) +
                                          " sample " + std::to_string(i);
                if (std::isnan(h)) {
                    EXPECT_TRUE(std::isnan(got)) << where;
                    continue;
                }
                // The steepest sight line to an earlier sample: rise over distance, less the
                // curvature's drop over that distance (d^2 / 2R, over d).
                double best = -std::numeric_limits<double>::infinity();
                for (std::size_t j = 0; j < i; ++j) {
                    if (std::isnan(p.at(j, b))) continue;
                    const double d = p.geometry.sigmaM[i] - p.geometry.sigmaM[j];
                    best = std::max(best, (static_cast<double>(p.at(j, b)) - h) / d - 0.5 * d * invR);
                }
                if (std::isinf(best))
                    EXPECT_EQ(got, best) << where;
                else
                    EXPECT_NEAR(got, best, 1e-6 * std::abs(best) + 1e-12) << where;
            }
    }
}

TEST(HullLanes, VectorMatchesReferenceOnDeepPops) {
    for (const double growth : {0.0, 2e-6}) {
        const Profiles p = rampsAndPeaks(40, 3000, geometry(3000, 30.0, growth, 1.0 / 7.3e6));
        expectVectorMatchesReference(p, growth > 0 ? "ramps, varying spacing" : "ramps, uniform spacing");
    }
}

TEST(HullLanes, VectorMatchesReferenceOnPlateausAndNodataRuns) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const std::size_t n = 2500, lines = 33;
    Profiles p{geometry(n, 25.0, 0.0, 1.0 / 7.3e6), std::vector<float>(n * 48), 48, lines};
    for (std::size_t b = 0; b < lines; ++b) {
        float level = 100.0f;
        std::size_t run = 0;
        bool nodata = b % 4 == 0;  // some lines start without data
        for (std::size_t i = 0; i < n; ++i) {
            if (run == 0) {
                run = 1 + static_cast<std::size_t>(200.0 * uniform(rng));
                nodata = !nodata && uniform(rng) < 0.3;
                level = static_cast<float>(std::round(600.0 * uniform(rng)));
            }
            --run;
            p.at(i, b) = nodata ? kNaN : level;
        }
    }
    // Rows with no data on any line (a sea), and a plateau held by every line.
    for (std::size_t i = 1000; i < 1040; ++i)
        for (std::size_t b = 0; b < lines; ++b) p.at(i, b) = kNaN;
    for (std::size_t i = 1500; i < 1700; ++i)
        for (std::size_t b = 0; b < lines; ++b) p.at(i, b) = 250.0f;
    expectVectorMatchesReference(p, "plateaus and nodata");
    // A flat earth: plateaus are exactly collinear, every tie pops.
    p.geometry.invRadius = 0.0;
    expectVectorMatchesReference(p, "plateaus and nodata, flat earth");
}

TEST(HullLanes, VectorMatchesReferenceOnRoughGround) {
    std::mt19937 rng(11);
    std::normal_distribution<double> step(0.0, 4.0);
    const std::size_t n = 4000, lines = 64;
    Profiles p{geometry(n, 30.0, 1e-6, 1.0 / 7.3e6), std::vector<float>(n * lines), lines, lines};
    for (std::size_t b = 0; b < lines; ++b) {
        double h = 500.0;
        for (std::size_t i = 0; i < n; ++i) p.at(i, b) = static_cast<float>(h += step(rng));
    }
    const Agreement a = expectVectorMatchesReference(p, "random walk");
    EXPECT_GT(a.cells, n * lines / 2);
}

/// Every full block of 64 columns of a DEM walked from its north edge, distances the sum of the
/// rows' heights as the sweep lays them at azimuth 0.
Agreement expectColumnsMatch(const Terrain& t, const std::string& name) {
    Profiles p;
    p.geometry.sigmaM.assign(t.height(), 0.0);
    for (std::size_t r = 1; r < t.height(); ++r) p.geometry.sigmaM[r] = p.geometry.sigmaM[r - 1] + t.cellHeightM[r - 1];
    p.geometry.invRadius = inverseEffectiveRadius(HorizonParams{});
    p.stride = t.width();
    p.lines = t.width();
    p.heights.assign(t.heightsM.data(), t.heightsM.data() + t.width() * t.height());
    const Agreement a = expectVectorMatchesReference(p, name);
    std::printf("%s: %zu cells, vector kernel within %.2f of its bound, max %.1e deg from the reference\n",
                name.c_str(), a.cells, a.maxOfBound, a.maxDeg);
    return a;
}

TEST(HullLanes, VectorMatchesReferenceOnSampleDems) {
    for (const char* file : {"rocky_mountain_np_dem.tif", "luxembourg_elev_terra.tif", "harlem_dsm_trees_1m.tif"}) {
        const Terrain t = loadDem(std::string(DEMLIGHT_SAMPLES_DIR) + "/" + file).terrain;
        EXPECT_GT(expectColumnsMatch(t, file).cells, 0u) << file;
    }
}

TEST(HullLanes, VectorMatchesReferenceOnSharedDems) {
    std::size_t found = 0;
    for (const char* file : {"N44W072.hgt", "N48W125_srtm1.tif"}) {
        // A band of columns across the whole height keeps the test short.
        const std::optional<Terrain> t = sharedTerrain(file);
        if (!t) continue;
        ++found;
        const Terrain band = cropTerrainCentre(*t, 256, t->height());
        expectColumnsMatch(band, file);
    }
    if (found == 0) GTEST_SKIP() << "shared DEMs not found in " << DEMLIGHT_SHARED_DEM_DIR;
}

/// The sheared lines' served slopes, vector against reference: the same cells without data or
/// horizon, the rest within the bound (the lines' heights are the same floats in both).
void expectShearMatches(const std::vector<float>& heights, std::size_t width, double shear, const HullGeometry& geo,
                        const std::string& what) {
    const std::size_t height = heights.size() / width;
    std::vector<float> ref(heights.size(), 7.0f), vec(heights.size(), 7.0f);
    HullScratch scratch;
    hullShearReference(geo, {heights.data(), ref.data(), width, height, shear}, scratch);
    hullShearVector(geo, {heights.data(), vec.data(), width, height, shear}, scratch);
    Profiles p{geo, heights, width, width};
    const HullSlopeBound limit = hullSlopeErrorBound(geo, maxAbsG(p));
    std::size_t failures = 0, finite = 0;
    for (std::size_t k = 0; k < heights.size(); ++k) {
        const float x = vec[k], y = ref[k];
        const bool ok = std::isfinite(y) ? std::abs(static_cast<double>(x) - y) <= limit.at(y)
                                         : (std::isnan(x) && std::isnan(y)) || x == y;
        finite += std::isfinite(y);
        if (!ok && ++failures <= 5)
            ADD_FAILURE() << what << ": row " << k / width << " column " << k % width << ": vector " << x
                          << ", reference " << y << " (bound " << limit.at(y) << ")";
    }
    EXPECT_EQ(failures, 0u) << what;
    EXPECT_GT(finite, heights.size() / 2) << what;
}

TEST(HullLanes, ShearedLinesMatchReference) {
    SKIP_WITHOUT_VECTOR_KERNEL();
    std::mt19937 rng(5);
    std::normal_distribution<double> step(0.0, 6.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const std::size_t width = 77, height = 900;
    std::vector<float> heights(width * height);
    // Rough ground across and along, a wall, and holes of nodata.
    for (std::size_t c = 0; c < width; ++c) {
        double h = 300.0;
        for (std::size_t r = 0; r < height; ++r) {
            h += step(rng);
            heights[r * width + c] = static_cast<float>(h + (r == 400 ? 500.0 : 0.0) + 3.0 * static_cast<double>(c % 7));
        }
    }
    for (int hole = 0; hole < 30; ++hole) {
        const auto r = static_cast<std::size_t>(uniform(rng) * (height - 10)), c = static_cast<std::size_t>(uniform(rng) * (width - 10));
        for (std::size_t i = 0; i < 6; ++i)
            for (std::size_t j = 0; j < 6; ++j) heights[(r + i) * width + c + j] = kNaN;
    }
    for (const double shear : {0.0, 0.25, std::tan(37.0 * M_PI / 180.0), 1.0})
        for (const double growth : {0.0, 1e-6})
            expectShearMatches(heights, width, shear, geometry(height, 30.0 / std::cos(std::atan(shear)), growth, 1.0 / 7.3e6),
                               "shear " + std::to_string(shear) + " growth " + std::to_string(growth));
    const Terrain t = loadDem(std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif").terrain;
    const std::vector<float> dem(t.heightsM.data(), t.heightsM.data() + t.width() * t.height());
    expectShearMatches(dem, t.width(), std::tan(37.0 * M_PI / 180.0),
                       geometry(t.height(), t.cellHeightM[0] / std::cos(37.0 * M_PI / 180.0), 0.0, 1.0 / 7.3e6),
                       "rocky_mountain_np_dem.tif at 37 deg");
}

TEST(HullLanes, ShearedReferenceServesTheLinesBesideEachCell) {
    // Line m passes row r at column m + r / 2: on even rows through the cell centres (a cell's
    // slope is its own line's), on odd rows halfway (the mean of the two lines beside it; the
    // last column's right line has no data there, off the grid, and the left one serves alone).
    const std::size_t width = 6, height = 5;
    std::vector<float> heights(width * height);
    for (std::size_t r = 0; r < height; ++r)
        for (std::size_t c = 0; c < width; ++c) heights[r * width + c] = static_cast<float>(100.0 - 10.0 * r + 7.0 * c);
    const HullGeometry geo = geometry(height, 10.0, 0.0, 0.0);
    std::vector<float> out(heights.size());
    HullScratch scratch;
    hullShearReference(geo, {heights.data(), out.data(), width, height, 0.5}, scratch);
    // Along every line the ground falls 10 m a row and rises 7 m a column times the shear 0.5: every
    // earlier sample is 6.5 m higher per row back, 10 m a row: slope 0.65 on lines that started at
    // row 0.
    for (std::size_t r = 1; r < height; ++r)
        for (std::size_t c = 0; c < width; ++c) {
            const long left = static_cast<long>(c) - static_cast<long>(r / 2) - 1;  // the left line's column at row 0
            if (left < 0) continue;  // it starts later, on the left edge
            EXPECT_NEAR(out[r * width + c], (10.0 - 3.5) / 10.0, 1e-6) << "row " << r << " column " << c;
        }
    EXPECT_EQ(out[0], -std::numeric_limits<float>::infinity());
}

TEST(HullLanes, DispatchFollowsSimdPath) {
    const Profiles p = rampsAndPeaks(20, 500, geometry(500, 10.0, 0.0, 1.0 / 7.3e6));
    const auto viaDispatch = [&] {
        std::vector<float> out(p.heights.size(), 7.0f);
        HullScratch scratch;
        hullSlopes(p.geometry, HullBlock{p.heights.data(), out.data(), p.stride, p.lines}, scratch);
        return out;
    };
    const std::vector<float> portable = run(p, Kernel::portable);
    {
        detail::ScopedSimdPath path(SimdPath::Portable);
        EXPECT_TRUE(sameBits(viaDispatch(), portable));
    }
    EXPECT_FALSE(sameBits(portable, run(p, Kernel::reference))) << "the float kernel should round differently from the double one";
    if (!hullVectorKernelAvailable()) GTEST_SKIP() << "no AVX-512 on this processor: only the portable path checked";
    detail::ScopedSimdPath avx512(SimdPath::Avx512);
    EXPECT_TRUE(sameBits(viaDispatch(), portable)) << "the AVX-512 path gives the portable path's bits";
}

/// Rows of a geographic grid walked along them: each line its own spacing (HullGeometry::lineScale).
/// The reference is the brute-force maximum at each line's distances, the float kernels within
/// the bound (a bound that ignored the factors would be too tight: the spacing ranges over 3x),
/// and a block of one line a factor gives what the same line gives alone at its own spacing.
TEST(HullLanes, LineFactorsGiveEachLineItsOwnSpacing) {
    std::mt19937 rng(5);
    std::normal_distribution<double> step(0.0, 6.0);
    const std::size_t n = 1500, lines = 37;
    const double invR = 1.0 / 7.3e6;
    Profiles p{geometry(n, 1.0, 0.0, invR), std::vector<float>(n * lines), lines, lines};
    for (std::size_t b = 0; b < lines; ++b) {
        p.geometry.lineScale.push_back(10.0 + 20.0 * static_cast<double>(b) / lines);
        double h = 300.0;
        for (std::size_t i = 0; i < n; ++i) p.at(i, b) = (i + b) % 97 < 5 ? kNaN : static_cast<float>(h += step(rng));
    }
    const std::vector<float> ref = run(p, Kernel::reference);
    for (std::size_t b = 0; b < lines; b += 6)
        for (std::size_t i = 0; i < n; i += 37) {
            if (std::isnan(p.at(i, b))) continue;
            double best = -std::numeric_limits<double>::infinity();
            for (std::size_t j = 0; j < i; ++j) {
                if (std::isnan(p.at(j, b))) continue;
                const double d = static_cast<double>(i - j) * p.geometry.lineScale[b];
                best = std::max(best, (static_cast<double>(p.at(j, b)) - p.at(i, b)) / d - 0.5 * d * invR);
            }
            if (std::isinf(best))
                EXPECT_EQ(ref[i * lines + b], best);
            else
                EXPECT_NEAR(ref[i * lines + b], best, 1e-6 * std::abs(best) + 1e-12) << "line " << b << " sample " << i;
        }
    expectVectorMatchesReference(p, "line factors");
    // Line 20 alone, its spacing in sigmaM.
    Profiles one{geometry(n, p.geometry.lineScale[20], 0.0, invR), std::vector<float>(n), 1, 1};
    for (std::size_t i = 0; i < n; ++i) one.at(i, 0) = p.at(i, 20);
    const std::vector<float> alone = run(one, Kernel::reference);
    for (std::size_t i = 0; i < n; ++i) {
        const float a = alone[i], b = ref[i * lines + 20];
        if (std::isnan(a) || std::isinf(a))
            EXPECT_TRUE((std::isnan(a) && std::isnan(b)) || a == b) << i;
        else
            EXPECT_NEAR(a, b, 1e-6 * std::abs(a)) << i;
    }
    // Factors over a varying spacing are refused.
    Profiles varying = p;
    varying.geometry = geometry(n, 1.0, 1e-3, invR);
    varying.geometry.lineScale = p.geometry.lineScale;
    EXPECT_THROW(run(varying, Kernel::portable), Error);
}

/// Heights and output walked with their own row steps, upward (a negative step), and the first
/// rows walked but not written: the same slopes as the block copied in walking order.
TEST(HullLanes, RowStepsAndFirstOutputRow) {
    const std::size_t n = 700, lines = 21, stride = 25, skip = 90;
    Profiles p = rampsAndPeaks(lines, n, geometry(n, 20.0, 1e-6, 1.0 / 7.3e6));
    // The same heights stored bottom row first, `stride` apart; the output 16 floats a row.
    std::vector<float> upside(n * stride, kNaN);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t b = 0; b < lines; ++b) upside[(n - 1 - i) * stride + b] = p.at(i, b);
    for (const Kernel kernel : {Kernel::reference, Kernel::portable, Kernel::vector}) {
        if (kernel == Kernel::vector && !hullVectorKernelAvailable()) continue;
        const std::vector<float> plain = run(p, kernel);
        std::vector<float> out(n * 32, 7.0f);
        HullBlock block{upside.data() + (n - 1) * stride, out.data(), 0, lines};
        block.heightsRowStep = -static_cast<std::ptrdiff_t>(stride);
        block.outRowStep = 32;
        block.firstOutRow = skip;
        HullScratch scratch;
        if (kernel == Kernel::reference) hullSlopesReference(p.geometry, block, scratch);
        if (kernel == Kernel::portable) hullSlopesPortable(p.geometry, block, scratch);
        if (kernel == Kernel::vector) hullSlopesVector(p.geometry, block, scratch);
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t b = 0; b < 32; ++b) {
                const float got = out[i * 32 + b];
                const float want = i < skip || b >= lines ? 7.0f : plain[i * p.stride + b];
                wrong += std::memcmp(&got, &want, sizeof got) != 0;
            }
        EXPECT_EQ(wrong, 0u) << "kernel " << static_cast<int>(kernel);
    }
}

}  // namespace
}  // namespace demlight
