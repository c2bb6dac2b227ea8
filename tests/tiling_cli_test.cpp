// The CLI's --tile-size and --srcwin: tiled runs and windows mosaicked by gdalbuildvrt give the
// one-piece output's bytes (gdalinfo -checksum and the values' bytes of every band) on real DEMs
// of each kind of CRS.
#include "cli_runner.h"
#include "demlight/geo/raster.h"
#include "shared_dem.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <unistd.h>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;
using testing::runDemlight;

/// Output of a shell command (stdout), or "" when it fails.
std::string shell(const std::string& cmd) {
    std::FILE* p = popen(cmd.c_str(), "r");
    if (!p) return {};
    const std::string out = testing::readAll(p);
    return pclose(p) == 0 ? out : std::string();
}

/// gdalinfo -checksum's "Checksum=N" lines of every band, in band order, then a hash of every
/// band's values as bytes (read as Float32, nodata as NaN): gdalinfo's checksum rounds
/// floating-point values to whole numbers (sky_K + 0.001 everywhere moves it by one), so only
/// the bytes show that two rasters are the same bit for bit.
std::vector<std::string> checksums(const std::string& path) {
    std::istringstream in(shell("gdalinfo -checksum '" + path + "'"));
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);)
        if (const auto at = line.find("Checksum="); at != std::string::npos) out.push_back(line.substr(at));
    for (const Grid<float>& band : readRasterBands(path))
        out.push_back("bytes=" + std::to_string(std::hash<std::string_view>{}(std::string_view(
                                     reinterpret_cast<const char*>(band.data()), band.size() * sizeof(float)))));
    return out;
}

struct DemCase {
    const char* name;
    const char* srcwin;  // crop of the shared DEM made with gdal_translate ("" = the whole file)
};

// Geographic (SRTM 1"), UTM 11N, and UTM 33N at 78° N.
// 1000 x 520 cells: --tile-size 777 makes two tiles, 256 twelve, 2048 one.
const DemCase kDems[] = {
    {"N48W125_srtm1.tif", "1300 1500 1000 520"},
    {"big_tujunga_srtm30m_utm11.tif", "150 60 1000 520"},
    {"svalbard_longyearbyen_npi_dtm20.tif", "200 200 1000 520"},
};

// Each raster command with options that keep the halo a fraction of the DEM.
const char* const kCommands[] = {
    "horizon --azimuth 135 300 --max-distance 3000",
    "sun --time 2024-06-21T15:30:00Z --max-distance 3000",
    "sky --max-distance 2000",
    "aperture --max-distance 2000",
    "light --time 2024-06-21T15:30:00Z --max-distance 2000",
    "sunhours --date 2024-06-21 --tz UTC --step 2h --max-distance 2000",
};

class TiledCli : public ::testing::TestWithParam<DemCase> {
protected:
    void SetUp() override {
        const DemCase c = GetParam();
        const std::string src = sharedDemPath(c.name);
        if (!fs::exists(src)) GTEST_SKIP() << c.name << " absent";
        dir_ = fs::temp_directory_path() / ("demlight_tiling_" + std::to_string(::getpid()) + "_" +
                                            std::string(c.name).substr(0, 8));
        fs::create_directories(dir_);
        dem_ = (dir_ / "dem.tif").string();
        ASSERT_FALSE(shell("gdal_translate -q -srcwin " + std::string(c.srcwin) + " '" + src + "' '" + dem_ + "' && echo ok")
                         .empty());
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }
    std::string out(const std::string& name) const { return (dir_ / name).string(); }

    fs::path dir_;
    std::string dem_;
};

TEST_P(TiledCli, TilesAndMosaickedWindowsAreTheOnePieceBytes) {
    for (const std::string command : kCommands) {
        const std::string verb = command.substr(0, command.find(' '));
        const std::string options = command.substr(command.find(' '));
        const std::string whole = out(verb + "_whole.tif");
        const auto r = runDemlight(verb + " '" + dem_ + "' -o '" + whole + "'" + options + " -q");
        ASSERT_EQ(r.exitCode, 0) << command << ": " << r.err;
        const std::vector<std::string> expected = checksums(whole);
        ASSERT_FALSE(expected.empty()) << command;
        for (const int tile : {256, 777, 2048}) {
            const std::string tiled = out(verb + "_tile" + std::to_string(tile) + ".tif");
            const auto t = runDemlight(verb + " '" + dem_ + "' -o '" + tiled + "'" + options + " --tile-size " +
                                       std::to_string(tile) + " -q");
            ASSERT_EQ(t.exitCode, 0) << command << " tile " << tile << ": " << t.err;
            EXPECT_EQ(checksums(tiled), expected) << command << " --tile-size " << tile;
        }
        // Four windows, each its own process, mosaicked.
        std::string list;
        for (const char* win : {"0 0 450 250", "450 0 550 250", "0 250 450 270", "450 250 550 270"}) {
            std::string name = win;
            for (char& ch : name) ch = ch == ' ' ? '_' : ch;
            const std::string part = out(verb + "_win_" + name + ".tif");
            const auto w = runDemlight(verb + " '" + dem_ + "' -o '" + part + "'" + options + " --srcwin " + win + " -q");
            ASSERT_EQ(w.exitCode, 0) << command << " --srcwin " << win << ": " << w.err;
            list += " '" + part + "'";
        }
        const std::string vrt = out(verb + "_mosaic.vrt");
        ASSERT_FALSE(shell("gdalbuildvrt -q '" + vrt + "'" + list + " && echo ok").empty()) << command;
        EXPECT_EQ(checksums(vrt), expected) << command << " --srcwin windows mosaicked by gdalbuildvrt";
    }
}

INSTANTIATE_TEST_SUITE_P(RealDems, TiledCli, ::testing::ValuesIn(kDems),
                         [](const auto& testInfo) { return demTestName(testInfo.param.name); });

// ---- Time-lapse frames ---------------------------------------------------------------------------

struct TimelapseCase {
    const char* name;
    bool bundled;        ///< a sample of the repository (samples/), not of ../shared
    const char* crop;    ///< gdal_translate -srcwin of the DEM ("" = the whole file)
    int smallTile, largeTile;  ///< below the halo (--max-distance 1500 m: 51 cells of 30 m) and above
    const char* srcwin;  ///< one window computed by itself
};

// Pacific time: 8 am, noon and 4 pm PDT; the fit needs degree + 1 = 2 frames.
constexpr const char* kTimelapseOptions =
    " --start 2024-06-21T15:00:00Z --end 2024-06-21T23:00:00Z --step 4h --max-distance 1500 --fit-degree 1"
    " --formats tif --threads 2 -q";

/// checksums() of every GeoTIFF in a time-lapse folder (frames, sky_k, sequence_fit), by name,
/// and frames.csv's text.
std::map<std::string, std::vector<std::string>> folderChecksums(const fs::path& dir) {
    std::map<std::string, std::vector<std::string>> out;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() == ".tif") out[name] = checksums(entry.path().string());
        if (name == "frames.csv") {
            std::ifstream in(entry.path());
            std::stringstream text;
            text << in.rdbuf();
            out[name] = {text.str()};
        }
    }
    return out;
}

class TiledTimelapse : public ::testing::TestWithParam<TimelapseCase> {};

TEST_P(TiledTimelapse, TiledFramesAreTheOnePieceFramesBitForBit) {
    const TimelapseCase c = GetParam();
    const std::string src = c.bundled ? std::string(DEMLIGHT_SAMPLES_DIR) + "/" + c.name : sharedDemPath(c.name);
    if (!fs::exists(src)) GTEST_SKIP() << c.name << " absent";
    const fs::path dir = fs::temp_directory_path() / ("demlight_tiled_timelapse_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::string dem = src;
    if (*c.crop) {
        dem = (dir / "dem.tif").string();
        ASSERT_FALSE(shell("gdal_translate -q -srcwin " + std::string(c.crop) + " '" + src + "' '" + dem + "' && echo ok").empty());
    }
    const auto run = [&](const std::string& out, const std::string& extra) {
        const auto r = runDemlight("timelapse '" + dem + "' -o '" + (dir / out).string() + "'" + kTimelapseOptions + extra);
        EXPECT_EQ(r.exitCode, 0) << extra << ": " << r.err;
        return folderChecksums(dir / out);
    };
    for (const std::string mode : {"exact", "interpolated:8"}) {
        const auto whole = run("whole_" + mode, " --horizon-mode " + mode);
        ASSERT_EQ(whole.size(), 3u + 3u) << mode;  // three frames, sky_k, sequence_fit, frames.csv
        for (const int tile : {c.smallTile, c.largeTile})
            EXPECT_EQ(run("tile" + std::to_string(tile) + "_" + mode, " --horizon-mode " + mode + " --tile-size " +
                                                                           std::to_string(tile)),
                      whole)
                << mode << " --tile-size " << tile;
    }
    // A window by itself: every raster is the one-piece raster's window.
    const auto window = run("window", std::string(" --srcwin ") + c.srcwin);
    for (const auto& [name, sums] : window) {
        if (name == "frames.csv") continue;
        const std::string vrt = (dir / (name + ".vrt")).string();
        ASSERT_FALSE(shell("gdal_translate -q -of VRT -srcwin " + std::string(c.srcwin) + " '" +
                           (dir / "whole_exact" / name).string() + "' '" + vrt + "' && echo ok")
                         .empty());
        EXPECT_EQ(sums, checksums(vrt)) << name << " --srcwin " << c.srcwin;
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
}

INSTANTIATE_TEST_SUITE_P(Samples, TiledTimelapse,
                         ::testing::Values(TimelapseCase{"mount_st_helens_1980_usgs.dem", true, "80 120 160 200", 40,
                                                         120, "50 70 70 50"}),
                         [](const auto& testInfo) { return demTestName(testInfo.param.name); });
INSTANTIATE_TEST_SUITE_P(RealDems, TiledTimelapse,
                         ::testing::Values(TimelapseCase{"big_tujunga_srtm30m_utm11.tif", false, "300 100 400 300", 45,
                                                         250, "150 100 150 120"}),
                         [](const auto& testInfo) { return demTestName(testInfo.param.name); });

TEST(TilingCli, TiledTimelapsePicturesAreRefusedNamingFormats) {
    const std::string dem = std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem";
    const fs::path dir = fs::temp_directory_path() / ("demlight_tiled_timelapse_png_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    for (const std::string extra : {" --tile-size 200", " --srcwin 0 0 100 100"}) {
        const auto r = runDemlight("timelapse '" + dem + "' -o '" + dir.string() +
                                   "' --start 2024-06-21T15:00:00Z --end 2024-06-21T16:00:00Z --step 1h" + extra);
        EXPECT_NE(r.exitCode, 0) << extra;
        EXPECT_NE(r.err.find("--formats tif,png,gif"), std::string::npos) << extra << ": " << r.err;
        EXPECT_NE(r.err.find("give --formats tif"), std::string::npos) << extra << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir)) << extra;  // refused before the folder is made
    }
}

TEST(TilingCli, BadTileSizesAndWindowsAreRefusedNamingTheOption) {
    const std::string dem = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";
    const std::string o = (fs::temp_directory_path() / "demlight_tiling_bad.tif").string();
    const auto a = runDemlight("sun '" + dem + "' -o '" + o + "' --time 2024-06-21T15:30:00Z --tile-size 4");
    EXPECT_NE(a.exitCode, 0);
    EXPECT_NE(a.err.find("--tile-size '4'"), std::string::npos) << a.err;
    const auto b = runDemlight("sun '" + dem + "' -o '" + o + "' --time 2024-06-21T15:30:00Z --srcwin 100 100 100 100");
    EXPECT_NE(b.exitCode, 0);
    EXPECT_NE(b.err.find("--srcwin 100 100 100 100"), std::string::npos) << b.err;
    EXPECT_FALSE(fs::exists(o));
    // Negative numbers are refused before they are read as cell counts: -5 would wrap to 2^64 - 5
    // and the window's end back inside the DEM, an empty window "written" with exit 0.
    for (const std::string window : {"-5 0 10 10", "0 -5 10 10", "0 0 -10 10"}) {
        const auto c = runDemlight("sun '" + dem + "' -o '" + o + "' --time 2024-06-21T15:30:00Z --srcwin " + window);
        EXPECT_EQ(c.exitCode, 2) << window << ": " << c.err;
        EXPECT_NE(c.err.find("--srcwin"), std::string::npos) << window << ": " << c.err;
        EXPECT_EQ(c.err.find("18446744073709"), std::string::npos) << window << ": " << c.err;
        EXPECT_FALSE(fs::exists(o)) << window;
    }
}

}  // namespace
}  // namespace demlight
