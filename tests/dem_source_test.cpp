// A DEM read window by window from its file (DemSource::open) is the DEM loadDem reads whole:
// the same heights, raw values, georeference, per-row geometry, convergence and frame, and the
// same product bits; it holds no heights of its own.
#include "demlight/geo/dem.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/sun_field.h"
#include "demlight/geo/time.h"
#include "demlight/products/horizon.h"
#include "demlight/products/sun.h"
#include "shared_dem.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;

const std::string kHelens = std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem";
const std::string kRocky = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";

::testing::AssertionResult sameBits(const Grid<float>& a, const Grid<float>& b) {
    if (!a.sameShape(b)) return ::testing::AssertionFailure() << "grids differ in size";
    if (a.size() > 0 && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) != 0) {  // empty: no data()
        for (std::size_t i = 0; i < a.size(); ++i)
            if (std::memcmp(&a.data()[i], &b.data()[i], sizeof(float)) != 0)
                return ::testing::AssertionFailure() << "cell " << i << ": " << a.data()[i] << " vs " << b.data()[i];
    }
    return ::testing::AssertionSuccess();
}

/// Every field a product reads of a Dem, compared.
void expectSameDem(const Dem& a, const Dem& b, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_TRUE(sameBits(a.terrain.heightsM, b.terrain.heightsM));
    EXPECT_TRUE(sameBits(a.band.values, b.band.values));
    EXPECT_EQ(a.band.nodataCount, b.band.nodataCount);
    EXPECT_EQ(a.band.ref.geoTransform, b.band.ref.geoTransform);
    EXPECT_EQ(a.band.ref.crsWkt, b.band.ref.crsWkt);
    EXPECT_EQ(a.band.nodata.has_value(), b.band.nodata.has_value());
    EXPECT_EQ(a.terrain.cellWidthM, b.terrain.cellWidthM);
    EXPECT_EQ(a.terrain.cellHeightM, b.terrain.cellHeightM);
    EXPECT_EQ(a.terrain.rowLatitudeDeg, b.terrain.rowLatitudeDeg);
    EXPECT_TRUE(sameBits(a.terrain.convergence.gammaDeg, b.terrain.convergence.gammaDeg));
    EXPECT_EQ(a.terrain.convergence.colOffset, b.terrain.convergence.colOffset);
    EXPECT_EQ(a.terrain.convergence.rowOffset, b.terrain.convergence.rowOffset);
    EXPECT_EQ(a.terrain.frameCol0, b.terrain.frameCol0);
    EXPECT_EQ(a.terrain.frameRow0, b.terrain.frameRow0);
    ASSERT_EQ(a.terrain.frame == nullptr, b.terrain.frame == nullptr);
    if (a.terrain.frame) {
        EXPECT_EQ(a.terrain.frame->width, b.terrain.frame->width);
        EXPECT_EQ(a.terrain.frame->height, b.terrain.frame->height);
        EXPECT_EQ(a.terrain.frame->lowM, b.terrain.frame->lowM);
        EXPECT_EQ(a.terrain.frame->highM, b.terrain.frame->highM);
    }
}

TEST(DemSource, AFileReadByWindowIsTheDemLoadedWhole) {
    for (const std::string& path : {kHelens, kRocky}) {
        const DemSource streamed = DemSource::open(path);
        const DemSource held(loadDem(path));
        EXPECT_EQ(streamed.held(), nullptr) << path;
        EXPECT_TRUE(streamed.geometry().terrain.heightsM.empty()) << path;
        ASSERT_EQ(streamed.width(), held.width());
        ASSERT_EQ(streamed.height(), held.height());
        EXPECT_EQ(streamed.meanHeightM(), held.meanHeightM()) << path;
        EXPECT_EQ(streamed.frame()->lowM, held.frame()->lowM);
        EXPECT_EQ(streamed.frame()->highM, held.frame()->highM);
        expectSameDem(streamed.read(streamed.whole()), loadDem(path), path + " whole");
        const std::size_t w = streamed.width(), h = streamed.height();
        for (const CellWindow& win : {CellWindow{0, 0, 17, 23}, CellWindow{w / 3, h / 4, w / 3 + 64, h / 4 + 50},
                                      CellWindow{w - 31, h - 7, w, h}, CellWindow{5, 0, w, 1}}) {
            expectSameDem(streamed.read(win), held.read(win), path + " window " + std::to_string(win.col0) + "," +
                                                                  std::to_string(win.row0));
        }
        for (const std::size_t step : {std::size_t{16}, std::size_t{64}}) {
            const NodeHeights a = streamed.nodeHeights(step), b = nodeHeights(loadDem(path).terrain.heightsM, step);
            EXPECT_TRUE(sameBits(a.nodesM, b.nodesM)) << path << " step " << step;
            EXPECT_EQ(std::memcmp(&a.centreM, &b.centreM, sizeof(float)), 0) << path;
            EXPECT_EQ(a.meanM, b.meanM) << path;
            // Each node against the cell it names (demlight/core/sun_field.h's lattice), read here directly.
            const Grid<float>& z = loadDem(path).terrain.heightsM;
            ASSERT_EQ(a.nodesM.width(), (w - 1) / step + 2);
            ASSERT_EQ(a.nodesM.height(), (h - 1) / step + 2);
            for (std::size_t j = 0; j < a.nodesM.height(); ++j)
                for (std::size_t i = 0; i < a.nodesM.width(); ++i) {
                    const float want = z(std::min(i * step, w - 1), std::min(j * step, h - 1));
                    EXPECT_EQ(std::memcmp(&a.nodesM(i, j), &want, sizeof(float)), 0) << path << " node " << i << "," << j;
                }
            double sum = 0;
            std::size_t valid = 0;
            for (float v : z.values())
                if (!std::isnan(v)) sum += v, ++valid;
            EXPECT_EQ(a.meanM, sum / static_cast<double>(valid)) << path;  // row order, as computeSunField summed
            const float centre = z(w / 2, h / 2);
            EXPECT_EQ(std::memcmp(&a.centreM, &centre, sizeof(float)), 0) << path;
        }
    }
}

TEST(DemSource, ProductsOfAStreamedDemAreTheBitsOfTheDemInMemory) {
    const DemSource streamed = DemSource::open(kHelens);
    const DemSource held(loadDem(kHelens));
    SunRequest sun;
    sun.time = parseZonedInstant("2024-06-21T07:30", "America/Los_Angeles");
    sun.search.threads = 2;
    HorizonRequest horizon;
    horizon.azimuthsDeg = {37.5};
    horizon.search.threads = 2;
    for (const CellWindow& win : {streamed.whole(), CellWindow{40, 60, 200, 180}}) {
        const SunResult a = sunProduct(streamed, win, sun), b = sunProduct(held, win, sun);
        ASSERT_EQ(a.bands.size(), b.bands.size());
        for (std::size_t k = 0; k < a.bands.size(); ++k) EXPECT_TRUE(sameBits(a.bands[k].values, b.bands[k].values));
        EXPECT_EQ(a.metadata, b.metadata);
        EXPECT_EQ(a.ref.geoTransform, b.ref.geoTransform);
        const HorizonResult c = horizonProduct(streamed, win, horizon), d = horizonProduct(held, win, horizon);
        EXPECT_TRUE(sameBits(c.horizons.bands[0].values, d.horizons.bands[0].values));
    }
}

TEST(DemSource, TheOpeningPassRefusesADemWithoutHeightsAsLoadDemDoes) {
    const fs::path dir = fs::temp_directory_path() / ("demlight_test_dem_source_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string empty = (dir / "all_nodata.tif").string();
    const std::string command = "gdal_translate -q -a_nodata 0 -scale 0 100000 0 0 -ot Int16 '" + kRocky + "' '" + empty +
                                "' >/dev/null 2>&1";
    if (std::system(command.c_str()) != 0) GTEST_SKIP() << "gdal_translate is not installed";
    std::string streamedMessage, loadedMessage;
    try {
        DemSource::open(empty);
    } catch (const Error& e) {
        streamedMessage = e.what();
    }
    try {
        loadDem(empty);
    } catch (const Error& e) {
        loadedMessage = e.what();
    }
    EXPECT_NE(streamedMessage.find("every cell is nodata"), std::string::npos) << streamedMessage;
    EXPECT_EQ(streamedMessage, loadedMessage);
    const DemSource ok = DemSource::open(kRocky);
    EXPECT_THROW(ok.read({0, 0, ok.width() + 1, 5}), Error);
    fs::remove_all(dir);
}

/// A real DEM of a million cells and more, read in windows as the CLI's tiles read it.
TEST(DemSource, SharedDemWindowsAreTheDemLoadedWhole) {
    const std::string path = sharedDemPath("N48W125_srtm1.tif");
    if (!fs::exists(path)) GTEST_SKIP() << path << " absent";
    const DemSource streamed = DemSource::open(path);
    const Dem whole = loadDem(path);
    const DemSource held(whole);
    EXPECT_EQ(streamed.meanHeightM(), held.meanHeightM());
    const CellWindow win{1234, 2000, 2345, 3601};
    expectSameDem(streamed.read(win), held.read(win), "N48W125 window");
}


// The opening pass's results kept for later processes (demlight/geo/opening_cache.h): the same
// bits from the file as from the pass; a changed DEM, a VRT's changed source, other height
// options or a damaged file run the pass again; small DEMs are not kept.
class OpeningCacheTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("demlight_opening_cache_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "dem");
        dem_ = (dir_ / "dem" / "rocky.tif").string();
        fs::copy_file(kRocky, dem_);
        cache_.folder = (dir_ / "cache").string();
        cache_.minCells = 0;
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::vector<fs::path> cacheFiles() const {
        std::vector<fs::path> out;
        if (fs::exists(cache_.folder))
            for (const auto& e : fs::directory_iterator(cache_.folder)) out.push_back(e.path());
        return out;
    }
    /// Rewrites the cache file's "valid" line: a source opened from the file shows the value.
    void plantValidCount(std::size_t valid) const {
        const fs::path file = cacheFiles().at(0);
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        std::string s = text.str();
        const std::size_t at = s.find("\nvalid ") + 7;
        s.replace(at, s.find('\n', at) - at, std::to_string(valid));
        std::ofstream(file, std::ios::trunc) << s;
    }
    fs::path dir_;
    std::string dem_;
    OpeningCache cache_;
};

TEST_F(OpeningCacheTest, TheKeptPassGivesThePassBitsAndAChangedDemRunsItAgain) {
    const DemSource first = DemSource::open(dem_, {}, {}, cache_);
    ASSERT_EQ(cacheFiles().size(), 1u);
    EXPECT_EQ(fs::status(cache_.folder).permissions() & fs::perms::all, fs::perms::owner_all);
    const DemSource second = DemSource::open(dem_, {}, {}, cache_);
    EXPECT_EQ(std::memcmp(&first.frame()->lowM, &second.frame()->lowM, sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(&first.frame()->highM, &second.frame()->highM, sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(&first.frame()->steepStepShare, &second.frame()->steepStepShare, sizeof(double)), 0);
    const double meanFirst = first.meanHeightM(), meanSecond = second.meanHeightM();
    EXPECT_EQ(std::memcmp(&meanFirst, &meanSecond, sizeof(double)), 0);
    EXPECT_EQ(first.validCells(), second.validCells());
    EXPECT_EQ(first.geometry().band.nodataCount, second.geometry().band.nodataCount);
    // Read from the file, not passed again: a planted count shows.
    plantValidCount(first.validCells() - 7);
    EXPECT_EQ(DemSource::open(dem_, {}, {}, cache_).validCells(), first.validCells() - 7);
    // Other height options are another key; no cache, the pass.
    EXPECT_EQ(DemSource::open(dem_, {"ft", 0}, {}, cache_).validCells(), first.validCells());
    EXPECT_EQ(DemSource::open(dem_, {}, {}, OpeningCache{}).validCells(), first.validCells());
    // A DEM written since: its modification time changes the key, and the pass runs again.
    fs::last_write_time(dem_, fs::last_write_time(dem_) + std::chrono::seconds(5));
    EXPECT_EQ(DemSource::open(dem_, {}, {}, cache_).validCells(), first.validCells());
}

TEST_F(OpeningCacheTest, ADamagedFileOrAChangedVrtSourceRunsThePassAgain) {
    const DemSource first = DemSource::open(dem_, {}, {}, cache_);
    plantValidCount(first.validCells() - 7);
    {
        const fs::path file = cacheFiles().at(0);
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        std::string s = text.str();
        s.replace(s.find("\nmean ") + 6, 4, "zz!!");
        std::ofstream(file, std::ios::trunc) << s;
    }
    EXPECT_EQ(DemSource::open(dem_, {}, {}, cache_).validCells(), first.validCells());

    const std::string vrt = (dir_ / "dem" / "mosaic.vrt").string();
    ASSERT_EQ(std::system(("gdalbuildvrt -q '" + vrt + "' '" + dem_ + "'").c_str()), 0);
    fs::remove_all(cache_.folder);
    EXPECT_EQ(DemSource::open(vrt, {}, {}, cache_).validCells(), first.validCells());
    plantValidCount(first.validCells() - 7);
    EXPECT_EQ(DemSource::open(vrt, {}, {}, cache_).validCells(), first.validCells() - 7);
    fs::last_write_time(dem_, fs::last_write_time(dem_) + std::chrono::seconds(5));  // the source, not the VRT
    EXPECT_EQ(DemSource::open(vrt, {}, {}, cache_).validCells(), first.validCells());
}

TEST_F(OpeningCacheTest, SmallDemsAndNoFolderKeepNothing) {
    cache_.minCells = 1u << 30;
    DemSource::open(dem_, {}, {}, cache_);
    EXPECT_TRUE(cacheFiles().empty());
    ::setenv("DEMLIGHT_CACHE_DIR", "", 1);
    EXPECT_TRUE(OpeningCache::fromEnvironment().folder.empty());
    ::setenv("DEMLIGHT_CACHE_DIR", "/somewhere", 1);
    EXPECT_EQ(OpeningCache::fromEnvironment().folder, "/somewhere");
    ::setenv("DEMLIGHT_CACHE", "off", 1);
    EXPECT_TRUE(OpeningCache::fromEnvironment().folder.empty());
    ::unsetenv("DEMLIGHT_CACHE");
    ::unsetenv("DEMLIGHT_CACHE_DIR");
}

}  // namespace
}  // namespace demlight
