// computeSunFrame over a DEM whose sun azimuth varies from cell to cell, by both strategies (one
// sweep following the azimuth; windowed sweeps at a few azimuths, interpolated per cell), against
// the reference horizon taken at every sampled cell's own sun azimuth (docs/design.md §7), on a
// real DEM.
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/sun.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/surface.h"

#include "shared_dem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <vector>

namespace demlight {
namespace {

/// A field whose azimuth runs linearly across the columns from az0 to az1 (and a little down
/// the rows), at a fixed elevation: a DEM far wider than any real one, so that the frame needs
/// several sweep azimuths.
SunField slantedField(std::size_t width, std::size_t height, double az0, double az1, double elevationDeg) {
    SunField f;
    f.stepCells = 32;
    const std::size_t nw = width / f.stepCells + 2, nh = height / f.stepCells + 2;
    f.azimuthDeg = Grid<float>(nw, nh, 0.0f);
    f.elevationDeg = Grid<float>(nw, nh, static_cast<float>(elevationDeg));
    for (std::size_t j = 0; j < nh; ++j)
        for (std::size_t i = 0; i < nw; ++i) {
            const double u = static_cast<double>(i * f.stepCells) / static_cast<double>(width);
            const double v = static_cast<double>(j * f.stepCells) / static_cast<double>(height);
            f.azimuthDeg(i, j) = static_cast<float>(az0 + (az1 - az0) * u + 0.3 * v);
        }
    f.centreAzimuthDeg = 0.5 * (az0 + az1);
    f.centreElevationDeg = elevationDeg;
    return f;
}

class SunFrameStrategy : public ::testing::TestWithParam<SunSweepStrategy> {};

TEST_P(SunFrameStrategy, MatchesThePerCellReferenceAcrossAnAzimuthSpread) {
    const std::optional<Terrain> dem = sharedTerrain("big_tujunga_srtm30m_utm11.tif", 400, 400);
    if (!dem) GTEST_SKIP() << "shared DEM not found";
    const Terrain& t = *dem;
    const Normals normals = computeNormals(t);
    const SunField field = slantedField(t.width(), t.height(), 150.0, 153.2, 12.0);

    SunFrameParams params;
    params.maxDistanceM = 8000;
    params.strategy = GetParam();
    const SunFrame frame = computeSunFrame(t, normals, field, params);
    // Following: 3.5 deg of spread at a 0.21 deg tolerance; interpolating: 8 azimuths.
    ASSERT_GE(frame.sweepRegions, 8u);

    // Reference: every sampled cell at its own sun azimuth.
    const std::vector<CellIndex> cells = sampleValidCells(t, 1500, 7);
    ASSERT_EQ(cells.size(), 1500u);
    double visError = 0;
    std::size_t visWrong = 0;
    for (const CellIndex& cell : cells) {
        const auto [az, el] = field.at(static_cast<double>(cell.col) + 0.5, static_cast<double>(cell.row) + 0.5);
        HorizonParams hp;
        hp.azimuthDeg = az;
        hp.maxDistanceM = *params.maxDistanceM;
        const HorizonSample ref = referenceHorizonAt(t, hp, std::span<const CellIndex>(&cell, 1))[0];
        const SunTerms exact = sunTerms(normals.at(cell.col, cell.row), ref.angleDeg, az, el, params.sunDiameterDeg);
        const double got = frame.light.visibility(cell.col, cell.row);
        ASSERT_TRUE(std::isfinite(got));
        visError += std::abs(got - exact.visibility);
        if (std::abs(got - exact.visibility) > 0.5) ++visWrong;
    }
    const double n = static_cast<double>(cells.size());
    // Same budget as the sweep itself against the reference (tests/horizon_realdem_test.cpp).
    EXPECT_LT(visError / n, 0.01);
    EXPECT_LT(static_cast<double>(visWrong) / n, 0.01);
}

INSTANTIATE_TEST_SUITE_P(BothStrategies, SunFrameStrategy,
                         ::testing::Values(SunSweepStrategy::Following, SunSweepStrategy::Interpolating),
                         [](const ::testing::TestParamInfo<SunSweepStrategy>& param) {
                             return std::string(param.param == SunSweepStrategy::Following ? "Following"
                                                                                          : "Interpolating");
                         });

// The one-sweep frame shades whole rows in a vectorised pass; it must give sunTerms() for every
// cell: random normals (flat to 85 deg), horizons below, near and above the tangent plane and the
// sun (and NaN), sun angles varying along the row, a disk and a point sun.
TEST(SunFrame, RowShadingIsSunTermsPerCell) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const std::size_t cols = 997;
    std::vector<float> h(cols), e(cols), n(cols), u(cols), vis(cols), irr(cols);
    std::vector<double> sinAz(cols), cosAz(cols), sinEl(cols), cosEl(cols), elDeg(cols);
    std::vector<SunAngles> suns(cols);
    for (std::size_t c = 0; c < cols; ++c) {
        const double slope = 85.0 * unit(rng) * (c % 5 == 0 ? 0.0 : 1.0), aspect = 360.0 * unit(rng);
        e[c] = static_cast<float>(std::sin(slope * kDegToRad) * std::sin(aspect * kDegToRad));
        n[c] = static_cast<float>(std::sin(slope * kDegToRad) * std::cos(aspect * kDegToRad));
        u[c] = static_cast<float>(std::cos(slope * kDegToRad));
        // The elevation a float holds exactly, so that a horizon set to it ties.
        const double az = 360.0 * unit(rng), el = static_cast<float>(100.0 * unit(rng) - 10.0);
        suns[c] = {az, el, std::sin(az * kDegToRad), std::cos(az * kDegToRad), std::sin(el * kDegToRad),
                   std::cos(el * kDegToRad)};
        sinAz[c] = suns[c].sinAzimuth, cosAz[c] = suns[c].cosAzimuth;
        sinEl[c] = suns[c].sinElevation, cosEl[c] = suns[c].cosElevation, elDeg[c] = el;
        // Horizon: anywhere, at the sun's elevation (exact ties), or within the disk.
        const double pick = unit(rng);
        h[c] = static_cast<float>(pick < 0.4 ? 180.0 * unit(rng) - 90.0 : pick < 0.6 ? el : el + unit(rng) - 0.5);
        if (c % 97 == 3) h[c] = std::numeric_limits<float>::quiet_NaN();
    }
    const detail::SunRowAngles angles{sinAz.data(), cosAz.data(), sinEl.data(), cosEl.data(), elDeg.data()};
    for (const double diameter : {kSunDiameterDeg, 0.0}) {
        detail::shadeSunRow(h.data(), e.data(), n.data(), u.data(), angles, vis.data(), irr.data(), cols, diameter);
        for (std::size_t c = 0; c < cols; ++c) {
            const SunTerms want = sunTerms(Enu{e[c], n[c], u[c]}, h[c], suns[c], diameter);
            if (std::isnan(h[c])) {
                EXPECT_TRUE(std::isnan(vis[c]) && std::isnan(irr[c])) << c;
                continue;
            }
            EXPECT_NEAR(vis[c], want.visibility, 1e-6) << "col " << c << " diameter " << diameter;
            EXPECT_NEAR(irr[c], want.irradiance, 1e-6) << "col " << c << " diameter " << diameter;
        }
    }
}

TEST(SunFrame, RowAnglesMatchTheFieldAndTheLibraryTrigonometry) {
    // forEachSunInRow against SunField::at and <cmath> at every cell: a field slanted across
    // columns and rows (lattice intervals of 32 cells, a partial last one), across north.
    const std::size_t width = 200, height = 70;
    const SunField field = slantedField(width, height, 358.0, 363.5, 25.0);
    SunField tilted = field;
    for (std::size_t j = 0; j < tilted.elevationDeg.height(); ++j)
        for (std::size_t i = 0; i < tilted.elevationDeg.width(); ++i)
            // Kinks at every node: a run across one would leave the bilinear field.
            tilted.elevationDeg(i, j) = static_cast<float>(20.0 + 0.7 * static_cast<double>(i) + 0.5 * static_cast<double>(i % 2) -
                                                          0.4 * static_cast<double>(j));
    for (std::size_t row : {0u, 33u, 69u}) {
        std::size_t visited = 0;
        forEachSunInRow(tilted, row, width, [&](std::size_t col, const SunAngles& sun) {
            ASSERT_EQ(col, visited++);
            const auto [az, el] = tilted.at(static_cast<double>(col) + 0.5, static_cast<double>(row) + 0.5);
            ASSERT_NEAR(sun.azimuthDeg, az, 1e-9);
            ASSERT_NEAR(sun.elevationDeg, el, 1e-9);
            ASSERT_NEAR(sun.sinAzimuth, std::sin(az * kDegToRad), 1e-12);
            ASSERT_NEAR(sun.cosAzimuth, std::cos(az * kDegToRad), 1e-12);
            ASSERT_NEAR(sun.sinElevation, std::sin(el * kDegToRad), 1e-12);
            ASSERT_NEAR(sun.cosElevation, std::cos(el * kDegToRad), 1e-12);
        });
        EXPECT_EQ(visited, width);
    }
}

TEST(SunFrame, ProgressCountsTheFrameOnceWhateverTheSweeps) {
    const Terrain t = makeUniformTerrain(Grid<float>(200, 150, 100.0f), 30.0);
    const Normals normals = computeNormals(t);
    const SunField field = slantedField(t.width(), t.height(), 100.0, 104.0, 20.0);
    double lastFraction = 0;
    ProgressCounter counter([&](double f, const std::string&) { lastFraction = f; return true; }, "frame",
                            t.heightsM.size(), 1000);
    const SunFrame frame = computeSunFrame(t, normals, field, SunFrameParams{}, &counter);
    EXPECT_GE(frame.sweepRegions, 2u);
    EXPECT_NEAR(lastFraction, 1.0, 1e-9);
    // Flat open ground: fully lit everywhere.
    for (float v : frame.light.visibility.values()) ASSERT_FLOAT_EQ(v, 1.0f);
}

}  // namespace
}  // namespace demlight
