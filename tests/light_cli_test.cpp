// End-to-end tests of `demlight light` and `demlight sunhours` options: the scene plan
// (--quality, --tolerance, -v) must reach the computation, not only the help text.
#include "cli_runner.h"
#include "geo/raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;
using testing::runDemlight;

const std::string kHelens = std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem";
const std::string kLightArgs =
    "--time 2024-06-21T07:00 --tz America/Los_Angeles --threads 2";
const std::string kSunhoursArgs = "--date 2024-06-21 --tz America/Los_Angeles --step 60 --threads 2";

/// A fresh scratch folder per test, removed at the end.
class OptionsCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("demlight_light_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    /// Runs demlight and fails the test (with stderr) on a non-zero exit.
    testing::RunResult run(const std::string& args) const {
        const testing::RunResult r = runDemlight(args);
        EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.err;
        return r;
    }

    fs::path dir_;
};

/// Number of valid cells whose values differ by more than `tolerance`.
std::size_t cellsDiffering(const Grid<float>& a, const Grid<float>& b, float tolerance) {
    std::size_t n = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (!std::isnan(a.data()[k]) && std::abs(a.data()[k] - b.data()[k]) > tolerance) ++n;
    return n;
}

// --quality full must reach the sky sweeps (64 directions instead of 16) and be recorded.
TEST_F(OptionsCli, LightQualityFullChangesTheSkyAndIsRecorded) {
    run("-q light " + kHelens + " -o " + path("auto.tif") + " " + kLightArgs);
    run("-q light " + kHelens + " -o " + path("full.tif") + " " + kLightArgs + " --quality full");
    const RasterSummary a = inspectRaster(path("auto.tif"));
    const RasterSummary f = inspectRaster(path("full.tif"));
    EXPECT_EQ(a.metadata.at("DEMLIGHT_QUALITY"), "auto");
    EXPECT_EQ(f.metadata.at("DEMLIGHT_QUALITY"), "full");
    EXPECT_EQ(a.metadata.at("DEMLIGHT_SKY_DIRECTIONS"), "16");
    EXPECT_EQ(f.metadata.at("DEMLIGHT_SKY_DIRECTIONS"), "64");
    EXPECT_NE(f.metadata.at("DEMLIGHT_PLAN").find("full: DEM diagonal"), std::string::npos);
    // The sky term converges with directions: small differences, but in many cells.
    const auto la = readRasterBands(path("auto.tif"));
    const auto lf = readRasterBands(path("full.tif"));
    ASSERT_EQ(la.size(), 1u);
    ASSERT_EQ(lf.size(), 1u);
    EXPECT_GT(cellsDiffering(la[0], lf[0], 1e-4f), la[0].size() / 10);
    EXPECT_EQ(cellsDiffering(la[0], lf[0], 0.1f), 0u);  // same light, only finer
}

// A looser --tolerance turns curvature off on this 17 km scene (its drop is ~0.07 deg), which
// changes the horizons and so the sky term.
TEST_F(OptionsCli, LightToleranceReachesThePlan) {
    run("-q light " + kHelens + " -o " + path("tight.tif") + " " + kLightArgs);
    run("-q light " + kHelens + " -o " + path("loose.tif") + " " + kLightArgs + " --tolerance 2");
    EXPECT_EQ(inspectRaster(path("tight.tif")).metadata.at("DEMLIGHT_CURVATURE"), "on");
    EXPECT_EQ(inspectRaster(path("loose.tif")).metadata.at("DEMLIGHT_CURVATURE"), "off");
    EXPECT_GT(cellsDiffering(readRasterBands(path("tight.tif"))[0], readRasterBands(path("loose.tif"))[0], 0.0f),
              0u);
}

TEST_F(OptionsCli, LightVerbosePrintsThePlan) {
    const auto quiet = run("light " + kHelens + " -o " + path("q.tif") + " " + kLightArgs);
    EXPECT_EQ(quiet.err.find("scene plan"), std::string::npos) << quiet.err;
    const auto r = run("light " + kHelens + " -o " + path("v.tif") + " " + kLightArgs + " -v --quality full");
    EXPECT_NE(r.err.find("scene plan (--quality full)"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("sky_directions=64"), std::string::npos) << r.err;
}

// --quality full must reach the sun lattice (every 16 cells instead of 64: per-cell sun
// positions move slightly, and with them the integrals) and be recorded.
TEST_F(OptionsCli, SunhoursQualityFullChangesTheSunLatticeAndIsRecorded) {
    run("-q sunhours " + kHelens + " -o " + path("auto.tif") + " " + kSunhoursArgs);
    const auto r = run("sunhours " + kHelens + " -o " + path("full.tif") + " " + kSunhoursArgs +
                       " --quality full -v");
    EXPECT_NE(r.err.find("sun_lattice_cells=16"), std::string::npos) << r.err;
    const RasterSummary a = inspectRaster(path("auto.tif"));
    const RasterSummary f = inspectRaster(path("full.tif"));
    EXPECT_EQ(a.metadata.at("DEMLIGHT_QUALITY"), "auto");
    EXPECT_EQ(f.metadata.at("DEMLIGHT_QUALITY"), "full");
    EXPECT_NE(f.metadata.at("DEMLIGHT_PLAN").find("sun_lattice_cells=16"), std::string::npos);
    const auto ba = readRasterBands(path("auto.tif"));
    const auto bf = readRasterBands(path("full.tif"));
    // sun_irradiation: smooth in the sun position, so every lattice change shows; large changes
    // only where a shadow edge moves (the search distance is the DEM diagonal with full).
    EXPECT_GT(cellsDiffering(ba[1], bf[1], 0.0f), ba[1].size() / 10);
    EXPECT_LT(cellsDiffering(ba[1], bf[1], 0.05f), ba[1].size() / 1000);
}

}  // namespace
}  // namespace demlight
