// Sweep vs reference horizon on real DEMs (docs/design.md §7): median and 99th-percentile absolute
// horizon error (degrees) and sun-visibility mean absolute error, on cells whose horizon is not
// truncated by the DEM edge. The reference runs on a fixed pseudo-random subset of cells.
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/quality.h"
#include "demlight/lighting/sun.h"
#include "demlight/lighting/surface.h"

#include "shared_dem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace demlight {
namespace {

/// Cells given to the reference per DEM and azimuth.
constexpr std::size_t kReferenceCells = 4000;


struct Case {
    std::string file;
    /// Crop (0 = whole DEM) to keep the test fast.
    std::size_t cropW = 0, cropH = 0;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

struct Stats {
    double median = 0, p99 = 0, max = 0, visibilityMae = 0;
    std::size_t cells = 0;
};

Stats measure(const Terrain& t, const Normals& normals, const HorizonParams& p, const HorizonMap& sweep) {
    // Non-truncated valid cells, a fixed pseudo-random subset.
    std::vector<CellIndex> candidates;
    for (std::size_t r = 0; r < t.height(); ++r)
        for (std::size_t c = 0; c < t.width(); ++c)
            if (t.valid(c, r) && !sweep.truncated(c, r)) candidates.push_back({c, r});
    std::mt19937_64 rng(12345);
    std::shuffle(candidates.begin(), candidates.end(), rng);
    if (candidates.size() > kReferenceCells) candidates.resize(kReferenceCells);
    const std::vector<HorizonSample> ref = referenceHorizonAt(t, p, candidates);

    std::vector<double> err;
    double visErr = 0.0;
    std::size_t visCount = 0;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (ref[i].truncated) continue;
        const CellIndex c = candidates[i];
        const double a = sweep.angleDeg(c.col, c.row), b = ref[i].angleDeg;
        err.push_back(std::abs(a - b));
        // Sun visibility at a few elevations where shadows are common.
        for (double sunEl : {3.0, 8.0, 15.0, 30.0}) {
            const Enu n = normals.at(c.col, c.row);
            visErr += std::abs(sunVisibilityClamped(n, a, p.azimuthDeg, sunEl, kSunDiameterDeg) -
                               sunVisibilityClamped(n, b, p.azimuthDeg, sunEl, kSunDiameterDeg));
            ++visCount;
        }
    }
    Stats s;
    s.cells = err.size();
    if (err.empty()) return s;
    std::sort(err.begin(), err.end());
    s.median = err[err.size() / 2];
    s.p99 = err[std::min(err.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(err.size())))];
    s.max = err.back();
    s.visibilityMae = visErr / static_cast<double>(visCount);
    return s;
}

class HorizonRealDem : public ::testing::TestWithParam<Case> {};

TEST_P(HorizonRealDem, SweepMatchesReference) {
    const Case& tc = GetParam();
    const std::optional<Terrain> dem = sharedTerrain(tc.file, tc.cropW, tc.cropH);
    if (!dem) GTEST_SKIP() << "shared DEM not found: " << sharedDemPath(tc.file);
    const Terrain& t = *dem;
    const Normals normals = computeNormals(t);
    // The scene default, capped at a quarter of the DEM's shorter side so that enough cells are
    // not truncated to measure.
    double sideM = std::min(t.cellWidthM[t.height() / 2] * static_cast<double>(t.width()),
                            t.cellHeightM[t.height() / 2] * static_cast<double>(t.height()));
    HorizonParams p;
    p.maxDistanceM = std::min(defaultMaxDistanceM(t), 0.25 * sideM);
    // The scene plan's near field: terrain, by its share of steep steps.
    const ScenePlan plan = planScene(t, Quality::Auto, QualityBudget{});
    p.nearFieldSteps = plan.nearFieldSteps;
    p.farFieldCrossings = plan.farFieldCrossings;
    ASSERT_EQ(p.nearFieldSteps, kTerrainNearFieldSteps);
    std::cout << tc.file << ": " << t.width() << " x " << t.height() << " cells, max distance "
              << p.maxDistanceM << " m, far-field crossings " << (p.farFieldCrossings ? "on" : "off") << "\n";
    for (double az : {0.0, 37.0, 90.0, 123.4, 200.0, 301.7}) {
        p.azimuthDeg = az;
        const auto t0 = std::chrono::steady_clock::now();
        const HorizonMap sweep = sweepHorizon(t, p);
        const double sweepS = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const Stats s = measure(t, normals, p, sweep);
        char line[256];
        std::snprintf(line, sizeof line,
                      "  az %6.1f: regions %3zu, sweep %.3f s; %zu cells: median %.4f deg, p99 %.3f deg, "
                      "max %.2f deg, sun visibility MAE %.5f\n",
                      az, sweepRegions(t, p).size(), sweepS, s.cells, s.median, s.p99, s.max, s.visibilityMae);
        std::cout << line;
        RecordProperty(tc.file + "_az" + std::to_string(az), line);
        ASSERT_GT(s.cells, kReferenceCells / 4);
        // Bounds: the terrain targets (p99 <= 2.5 deg, median no worse than the line-only
        // sweep's 0.07 deg). Without a near field the p99 was 1.6-5.2 deg off the axes: a rough
        // neighbour one or two cells away seen through two scan lines half a cell beside the
        // cell; the near field samples it on the cell's own ray.
        EXPECT_LT(s.median, 0.07) << tc.file << " az " << az;
        EXPECT_LT(s.p99, 2.5) << tc.file << " az " << az;
        EXPECT_LT(s.visibilityMae, 0.01) << tc.file << " az " << az;
    }
}

INSTANTIATE_TEST_SUITE_P(SharedDems, HorizonRealDem,
                         ::testing::Values(Case{"N44W072.hgt", 600, 600}, Case{"big_tujunga_srtm30m_utm11.tif"},
                                           Case{"mount_st_helens_1980_usgs.dem"},
                                           Case{"svalbard_longyearbyen_npi_dtm20.tif"}),
                         [](const ::testing::TestParamInfo<Case>& param) {
                             std::string name = param.param.file.substr(0, param.param.file.find('.'));
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace demlight
