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
#include <cstring>
#include <filesystem>
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

}  // namespace
}  // namespace demlight
