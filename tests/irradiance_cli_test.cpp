// End-to-end tests of `demlight irradiance`: the file it writes (bands, types, units,
// georeference, metadata), tiles and windows through the shared raster options, and its
// messages for bad options.
#include "cli_runner.h"
#include "demlight/geo/raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;
using testing::runDemlight;

const std::string kRocky = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";
const std::string kArgs = "--time 2024-06-21T09:00 --tz America/Denver --threads 2";

class IrradianceCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("demlight_irr_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    fs::path dir_;
};

TEST_F(IrradianceCli, WritesFourFloat32BandsInWattsPerSquareMetreOnTheInputsGrid) {
    const std::string out = path("irr.tif");
    const testing::RunResult r = runDemlight("-q irradiance '" + kRocky + "' -o '" + out + "' " + kArgs +
                                             " --linke 2.5 --albedo 0.3 --diffuse-model rsun");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const RasterSummary s = inspectRaster(out);
    const RasterSummary in = inspectRaster(kRocky);
    EXPECT_EQ(s.descriptions, (std::vector<std::string>{"beam", "diffuse", "reflected", "global"}));
    EXPECT_EQ(s.units, std::vector<std::string>(4, "W m-2"));
    EXPECT_EQ(s.dataTypes, std::vector<std::string>(4, "Float32"));
    EXPECT_EQ(s.width, in.width);
    EXPECT_EQ(s.height, in.height);
    EXPECT_EQ(s.ref.geoTransform, in.ref.geoTransform);
    EXPECT_EQ(s.ref.crsWkt, in.ref.crsWkt);
    EXPECT_EQ(s.metadata.at("DEMLIGHT_PRODUCT"), "irradiance");
    EXPECT_EQ(s.metadata.at("DEMLIGHT_LINKE"), "2.5");
    EXPECT_EQ(s.metadata.at("DEMLIGHT_ALBEDO"), "0.3");
    EXPECT_EQ(s.metadata.at("DEMLIGHT_DIFFUSE_MODEL"), "rsun");
    EXPECT_EQ(s.metadata.at("DEMLIGHT_TIME_LOCAL"), "2024-06-21T09:00:00-06:00");
    EXPECT_NE(s.metadata.at("DEMLIGHT_COMMAND").find("irradiance"), std::string::npos);
    const std::vector<Grid<float>> bands = readRasterBands(out);
    ASSERT_EQ(bands.size(), 4u);
    double globalSum = 0;
    for (std::size_t k = 0; k < bands[3].size(); ++k)
        if (!std::isnan(bands[3].data()[k])) globalSum += bands[3].data()[k];
    EXPECT_GT(globalSum / static_cast<double>(bands[3].size()), 100.0) << "a June morning gives hundreds of W/m2";
}

TEST_F(IrradianceCli, TilesAndWindowsWriteTheOnePieceBits) {
    const std::string whole = path("whole.tif"), tiled = path("tiled.tif"), window = path("window.tif");
    ASSERT_EQ(runDemlight("-q irradiance '" + kRocky + "' -o '" + whole + "' " + kArgs).exitCode, 0);
    const testing::RunResult t = runDemlight("-q irradiance '" + kRocky + "' -o '" + tiled + "' " + kArgs + " --tile-size 64");
    ASSERT_EQ(t.exitCode, 0) << t.err;
    const testing::RunResult w =
        runDemlight("-q irradiance '" + kRocky + "' -o '" + window + "' " + kArgs + " --srcwin 30 40 50 60 -of COG");
    ASSERT_EQ(w.exitCode, 0) << w.err;
    const std::vector<Grid<float>> a = readRasterBands(whole), b = readRasterBands(tiled), c = readRasterBands(window);
    ASSERT_EQ(a.size(), 4u);
    ASSERT_EQ(b.size(), 4u);
    ASSERT_EQ(c.size(), 4u);
    for (std::size_t band = 0; band < 4; ++band) {
        EXPECT_EQ(std::memcmp(a[band].data(), b[band].data(), a[band].size() * sizeof(float)), 0) << band;
        for (std::size_t row = 0; row < 60; ++row)
            for (std::size_t col = 0; col < 50; ++col) {
                const float x = a[band](col + 30, row + 40), y = c[band](col, row);
                ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << "band " << band << " cell " << col << "," << row;
            }
    }
    EXPECT_EQ(inspectRaster(window).driver, "GTiff");  // a COG is a GeoTIFF
}

TEST_F(IrradianceCli, BadOptionsFailWithAMessageNamingTheFlag) {
    const std::string out = path("bad.tif");
    const auto err = [&](const std::string& extra) {
        const testing::RunResult r = runDemlight("irradiance '" + kRocky + "' -o '" + out + "' " + kArgs + " " + extra);
        EXPECT_NE(r.exitCode, 0) << extra;
        return r.err;
    };
    EXPECT_NE(err("--linke 3,4").find("--linke"), std::string::npos);
    EXPECT_NE(err("--linke 0.2").find("--linke"), std::string::npos);
    EXPECT_NE(err("--linke abc").find("--linke"), std::string::npos);
    EXPECT_NE(err("--coeff-bh 1.5").find("--coeff-bh"), std::string::npos);
    EXPECT_NE(err("--diffuse-model perez").find("--diffuse-model"), std::string::npos);
    EXPECT_FALSE(fs::exists(out));
    const testing::RunResult noZone = runDemlight("irradiance '" + kRocky + "' -o '" + out + "' --time 2024-06-21T09:00");
    EXPECT_NE(noZone.exitCode, 0);
    EXPECT_NE(noZone.err.find("--tz"), std::string::npos) << noZone.err;
}

TEST_F(IrradianceCli, InsolationWritesKilowattHoursAndItsWindowsAreTheOnePieceBits) {
    const std::string whole = path("ins.tif"), window = path("ins_window.tif");
    const std::string args = " --date 2024-06-21 --tz America/Denver --step 30m --sky-directions 16 --threads 2";
    const testing::RunResult r = runDemlight("-q insolation '" + kRocky + "' -o '" + whole + "'" + args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const RasterSummary s = inspectRaster(whole);
    EXPECT_EQ(s.descriptions, (std::vector<std::string>{"beam", "diffuse", "reflected", "global", "sun_hours"}));
    EXPECT_EQ(s.units, (std::vector<std::string>{"kWh m-2", "kWh m-2", "kWh m-2", "kWh m-2", "hours"}));
    EXPECT_EQ(s.dataTypes, std::vector<std::string>(5, "Float32"));
    EXPECT_EQ(s.ref.geoTransform, inspectRaster(kRocky).ref.geoTransform);
    EXPECT_EQ(s.metadata.at("DEMLIGHT_PRODUCT"), "insolation");
    EXPECT_EQ(s.metadata.at("DEMLIGHT_DIRECTIONS"), "16");
    const testing::RunResult w =
        runDemlight("-q insolation '" + kRocky + "' -o '" + window + "'" + args + " --srcwin 20 30 60 50");
    ASSERT_EQ(w.exitCode, 0) << w.err;
    const std::vector<Grid<float>> a = readRasterBands(whole), c = readRasterBands(window);
    ASSERT_EQ(c.size(), 5u);
    for (std::size_t band = 0; band < 5; ++band)
        for (std::size_t row = 0; row < 50; ++row)
            for (std::size_t col = 0; col < 60; ++col) {
                const float x = a[band](col + 20, row + 30), y = c[band](col, row);
                ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << "band " << band << " cell " << col << "," << row;
            }
    const testing::RunResult bad =
        runDemlight("insolation '" + kRocky + "' -o '" + path("bad.tif") + "' --start 2024-06-21 --end 2024-06-20 --tz UTC");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("--end"), std::string::npos) << bad.err;
}

TEST_F(IrradianceCli, InsolationPeriodsFromAnIntervalToAYear) {
    const std::string out = path("period.tif");
    const auto period = [&](const std::string& args) {
        const testing::RunResult r = runDemlight("-q insolation '" + kRocky + "' -o '" + out +
                                                 "' --tz America/Denver --step 2h --sky-directions 8 --threads 2 " + args);
        EXPECT_EQ(r.exitCode, 0) << args << ": " << r.err;
        const RasterSummary s = inspectRaster(out);
        return std::pair(s.metadata.at("DEMLIGHT_START"), s.metadata.at("DEMLIGHT_END"));
    };
    EXPECT_EQ(period("--month 2024-02"), std::pair(std::string("2024-02-01T00:00:00-07:00"), std::string("2024-03-01T00:00:00-07:00")));
    EXPECT_EQ(period("--year 2023"), std::pair(std::string("2023-01-01T00:00:00-07:00"), std::string("2024-01-01T00:00:00-07:00")));
    EXPECT_EQ(period("--start 2024-06-21T10:00 --end 2024-06-21T14:30"),
              std::pair(std::string("2024-06-21T10:00:00-06:00"), std::string("2024-06-21T14:30:00-06:00")));
    const auto err = [&](const std::string& args) {
        const testing::RunResult r =
            runDemlight("insolation '" + kRocky + "' -o '" + path("bad.tif") + "' --tz America/Denver " + args);
        EXPECT_NE(r.exitCode, 0) << args;
        return r.err;
    };
    EXPECT_NE(err("--month 2024-13").find("2024-13"), std::string::npos);
    EXPECT_NE(err("--year 2024 --date 2024-01-01").find("not several"), std::string::npos);
    EXPECT_NE(err("--start 2024-06-21T14:00 --end 2024-06-21T10:00").find("--end"), std::string::npos);
    EXPECT_FALSE(fs::exists(path("bad.tif")));
}

}  // namespace
}  // namespace demlight
