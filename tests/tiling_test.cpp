// Tiles with halos give the same bits as the whole DEM: horizon sweeps laid on the full grid
// (regions, scan lines, distances, chunks and edges), on real DEMs of each kind of CRS.
#include "demlight/geo/dem_source.h"
#include "demlight/geo/time.h"
#include "demlight/lighting/horizon.h"
#include "demlight/products/aperture.h"
#include "demlight/products/horizon.h"
#include "demlight/products/insolation.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/light.h"
#include "demlight/products/sky.h"
#include "demlight/products/sun.h"
#include "demlight/products/sunhours.h"
#include "demlight/products/timelapse.h"
#include "shared_dem.h"
#include "demlight/core/simd.h"
#include "demlight/core/terrain.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace demlight {
namespace {

/// Bitwise equal, NaN equal to NaN (memcmp of the float's bits).
bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Sweeps every tile of `tileSize` cells with its halo and counts cells whose angle or
/// truncation flag differs from the whole DEM's in any bit.
std::size_t tiledMismatches(const Terrain& whole, const HorizonParams& params, std::size_t tileSize) {
    const HorizonMap reference = sweepHorizon(whole, params);
    const std::size_t halo = haloCellsFor(whole, params.maxDistanceM);
    std::size_t bad = 0;
    for (std::size_t r0 = 0; r0 < whole.height(); r0 += tileSize) {
        for (std::size_t c0 = 0; c0 < whole.width(); c0 += tileSize) {
            const CellWindow tile{c0, r0, std::min(whole.width(), c0 + tileSize), std::min(whole.height(), r0 + tileSize)};
            const CellWindow read{tile.col0 - std::min(tile.col0, halo), tile.row0 - std::min(tile.row0, halo),
                                  std::min(whole.width(), tile.col1 + halo), std::min(whole.height(), tile.row1 + halo)};
            const Terrain part = tileOf(whole, read);
            HorizonParams p = params;
            p.window = CellWindow{tile.col0 - read.col0, tile.row0 - read.row0, tile.col1 - read.col0,
                                  tile.row1 - read.row0};
            const HorizonMap h = sweepHorizon(part, p);
            for (std::size_t row = tile.row0; row < tile.row1; ++row) {
                for (std::size_t col = tile.col0; col < tile.col1; ++col) {
                    const std::size_t lc = col - read.col0, lr = row - read.row0;
                    if (!sameBits(h.angleDeg(lc, lr), reference.angleDeg(col, row)) ||
                        h.truncated(lc, lr) != reference.truncated(col, row))
                        ++bad;
                }
            }
        }
    }
    return bad;
}

struct Case {
    const char* dem;
    std::size_t cropW, cropH;
    bool bundled = false;  ///< a sample of the repository (samples/), not of ../shared
    std::size_t sweepTiles[3] = {61, 256, 777};
    std::size_t productTiles[2] = {173, 173};  // one size on the real DEMs: ten products each take minutes
    std::size_t productCropW = 520, productCropH = 430;  ///< centre window the products run on
};

std::string casePath(const Case& c) {
    return c.bundled ? std::string(DEMLIGHT_SAMPLES_DIR) + "/" + c.dem : sharedDemPath(c.dem);
}

/// The case's DEM cropped to its centre (cropW x cropH when both > 0); nullopt when absent.
std::optional<Terrain> caseTerrain(const Case& c) {
    if (!std::filesystem::exists(casePath(c))) return std::nullopt;
    Terrain t = loadDem(casePath(c)).terrain;
    if (c.cropW > 0 && c.cropH > 0) t = cropTerrainCentre(t, c.cropW, c.cropH);
    return t;
}

// One geographic DEM (per-row cell widths), one UTM (convergence), one at 78° N (UTM 33N:
// strong convergence, regions split in both axes).
const Case kCases[] = {
    {"N48W125_srtm1.tif", 700, 600},
    {"big_tujunga_srtm30m_utm11.tif", 0, 0},
    {"svalbard_longyearbyen_npi_dtm20.tif", 800, 700},
};

// The bundled samples, small enough for the sanitizer run (the real DEMs above run in Release
// only): one geographic, one projected (NAD27 UTM, with convergence) with its edges' nodata.
const Case kSamples[] = {
    {"rocky_mountain_np_dem.tif", 0, 0, true, {23, 61, 100}, {90, 90}, 152, 120},
    {"mount_st_helens_1980_usgs.dem", 0, 0, true, {53, 120, 400}, {70, 70}, 140, 120},
};

class TiledSweep : public ::testing::TestWithParam<Case> {};

TEST_P(TiledSweep, TilesWithHalosAreTheWholeDemsBits) {
    const Case c = GetParam();
    const auto t = caseTerrain(c);
    if (!t) GTEST_SKIP() << c.dem << " absent";
    for (const double azimuth : {0.0, 37.0, 90.0, 143.5, 225.0, 301.0}) {
        for (const double distance : {3000.0, std::numeric_limits<double>::infinity()}) {
            HorizonParams p;
            p.azimuthDeg = azimuth;
            p.maxDistanceM = distance;
            // Tiles smaller than the halo, an odd size, and one larger than the DEM's side.
            for (const std::size_t tile : c.sweepTiles) {
                EXPECT_EQ(tiledMismatches(*t, p, tile), 0u)
                    << c.dem << " azimuth " << azimuth << " distance " << distance << " tile " << tile;
            }
        }
    }
}

TEST_P(TiledSweep, NearestLineSweepsTooAsSkyIntegralsRunThem) {
    const Case c = GetParam();
    const auto t = caseTerrain(c);
    if (!t) GTEST_SKIP() << c.dem << " absent";
    for (const double azimuth : {11.25, 191.25}) {
        HorizonParams p;
        p.azimuthDeg = azimuth;
        p.maxDistanceM = 2500;
        p.nearestLine = true;
        EXPECT_EQ(tiledMismatches(*t, p, c.sweepTiles[1]), 0u) << c.dem << " azimuth " << azimuth;
    }
}

TEST_P(TiledSweep, NearFieldTilesToo) {
    // The near field's delayed hull queries, grid-line crossings and per-row stencils, with and
    // without a range limit whose chunks begin inside some cells' near fields.
    const Case c = GetParam();
    const auto t = caseTerrain(c);
    if (!t) GTEST_SKIP() << c.dem << " absent";
    for (const int steps : {4, 16}) {
        for (const double azimuth : {37.0, 143.5, 270.0}) {
            for (const double distance : {2500.0, std::numeric_limits<double>::infinity()}) {
                HorizonParams p;
                p.azimuthDeg = azimuth;
                p.maxDistanceM = distance;
                p.nearFieldSteps = steps;
                EXPECT_EQ(tiledMismatches(*t, p, c.sweepTiles[0]), 0u)
                    << c.dem << " near field " << steps << " azimuth " << azimuth << " distance " << distance;
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(RealDems, TiledSweep, ::testing::ValuesIn(kCases),
                         [](const auto& testInfo) { return demTestName(testInfo.param.dem); });
INSTANTIATE_TEST_SUITE_P(Samples, TiledSweep, ::testing::ValuesIn(kSamples),
                         [](const auto& testInfo) { return demTestName(testInfo.param.dem); });

// ---- Products: every raster product, window by window -----------------------------------------

/// The centre window of a shared DEM as a DEM of its own (no frame: it is the whole DEM here).
std::optional<DemSource> caseSource(const Case& c, std::size_t cols, std::size_t rows) {
    const std::string path = casePath(c);
    if (!std::filesystem::exists(path)) return std::nullopt;
    const DemSource full = DemSource::open(path);
    cols = std::min(cols, full.width()), rows = std::min(rows, full.height());
    const std::size_t c0 = (full.width() - cols) / 2, r0 = (full.height() - rows) / 2;
    Dem cut = full.read({c0, r0, c0 + cols, r0 + rows});
    cut.terrain.frame.reset();
    cut.terrain.frameCol0 = cut.terrain.frameRow0 = 0;
    return DemSource(std::move(cut));
}

using Product = std::function<ProductResult(const DemSource&, const CellWindow&)>;

/// Cells of any band whose bits differ between the whole DEM's result and the result assembled
/// from windows of `tile` cells (each computed by itself, with its halo).
std::size_t windowMismatches(const DemSource& source, const Product& product, std::size_t tile) {
    const ProductResult whole = product(source, source.whole());
    std::size_t bad = 0;
    for (std::size_t r0 = 0; r0 < source.height(); r0 += tile) {
        for (std::size_t c0 = 0; c0 < source.width(); c0 += tile) {
            const CellWindow w{c0, r0, std::min(source.width(), c0 + tile), std::min(source.height(), r0 + tile)};
            const ProductResult part = product(source, w);
            EXPECT_EQ(part.bands.size(), whole.bands.size());
            for (std::size_t b = 0; b < std::min(part.bands.size(), whole.bands.size()); ++b) {
                const ProductBand& pb = part.bands[b];
                const ProductBand& wb = whole.bands[b];
                for (std::size_t row = w.row0; row < w.row1; ++row)
                    for (std::size_t col = w.col0; col < w.col1; ++col) {
                        const std::size_t lc = col - w.col0, lr = row - w.row0;
                        const bool same = pb.flags.empty() ? sameBits(pb.values(lc, lr), wb.values(col, row))
                                                           : pb.flags(lc, lr) == wb.flags(col, row);
                        if (!same) ++bad;
                    }
            }
        }
    }
    return bad;
}

/// A time-lapse of two frames (a morning and a low evening sun in the Americas) with a degree-1
/// fit, as one result: sky_k, each frame's bands in order, then the fit's.
ProductResult timelapseBands(const DemSource& s, const CellWindow& w, std::size_t stackDirections,
                             const SearchRequest& search) {
    TimelapseRequest r;
    r.frames = instantsBetween(parseZonedInstant("2024-06-21T15:30:00Z", ""),
                               parseZonedInstant("2024-06-22T02:30:00Z", ""), std::chrono::minutes(660), 10);
    r.stackDirections = stackDirections;
    r.previews = false;
    r.fitDegree = 1;
    r.search = search;
    ProductResult out;
    TimelapseSink sink;
    const auto append = [&](const ProductResult& part) {
        for (const ProductBand& b : part.bands) out.bands.push_back(b);
    };
    sink.sky = [&](ProductResult&& sky) { append(sky); };
    sink.frame = [&](TimelapseFrame&& f) { append(f.lightmap); };
    const TimelapseResult res = timelapseProduct(s, w, r, sink);
    EXPECT_EQ(res.frames, 2u);
    if (res.fit) append(*res.fit);
    return out;
}

struct ProductCase {
    const char* name;
    Product run;
};

std::vector<ProductCase> productCases() {
    SearchRequest search;
    search.threads = 2;
    const ZonedInstant morning = parseZonedInstant("2024-06-21T15:30:00Z", "");
    const ZonedInstant evening = parseZonedInstant("2024-06-22T02:40:00Z", "");  // low sun in the west (Americas)
    return {
        {"horizon",
         [=](const DemSource& s, const CellWindow& w) {
             HorizonRequest r;
             r.azimuthsDeg = {20, 200};
             r.search = search;
             const HorizonResult h = horizonProduct(s, w, r);
             ProductResult out = h.horizons;
             for (const ProductBand& b : h.truncation.bands) out.bands.push_back(b);
             return out;
         }},
        {"sun",
         [=](const DemSource& s, const CellWindow& w) {
             SunRequest r;
             r.time = morning;
             r.search = search;
             return static_cast<ProductResult>(sunProduct(s, w, r));
         }},
        {"sun_low",
         [=](const DemSource& s, const CellWindow& w) {
             SunRequest r;
             r.time = evening;
             r.search = search;
             return static_cast<ProductResult>(sunProduct(s, w, r));
         }},
        {"sky",
         [=](const DemSource& s, const CellWindow& w) {
             SkyRequest r;
             r.search = search;
             return static_cast<ProductResult>(skyProduct(s, w, r));
         }},
        {"aperture",
         [=](const DemSource& s, const CellWindow& w) {
             ApertureRequest r;
             r.search = search;
             return static_cast<ProductResult>(apertureProduct(s, w, r));
         }},
        {"light",
         [=](const DemSource& s, const CellWindow& w) {
             LightRequest r;
             r.time = morning;
             r.search = search;
             return static_cast<ProductResult>(lightProduct(s, w, r));
         }},
        {"irradiance",
         [=](const DemSource& s, const CellWindow& w) {
             IrradianceRequest r;
             r.time = morning;
             r.search = search;
             return static_cast<ProductResult>(irradianceProduct(s, w, r));
         }},
        {"irradiance_rsun",
         [=](const DemSource& s, const CellWindow& w) {
             IrradianceRequest r;
             r.time = evening;
             r.diffuseModel = DiffuseModel::RSun;
             r.search = search;
             return static_cast<ProductResult>(irradianceProduct(s, w, r));
         }},
        {"insolation",
         [=](const DemSource& s, const CellWindow& w) {
             InsolationRequest r;
             r.firstDay = r.lastDay = parseDate("2024-06-21");
             r.zone = TimeZoneSpec::iana("America/Los_Angeles");
             r.step = std::chrono::minutes(60);
             r.directions = 16;
             r.search = search;
             return static_cast<ProductResult>(insolationProduct(s, w, r));
         }},
        {"sunhours",
         [=](const DemSource& s, const CellWindow& w) {
             SunhoursRequest r;
             r.firstDay = r.lastDay = parseDate("2024-06-21");
             r.step = std::chrono::minutes(90);
             r.search = search;
             return static_cast<ProductResult>(sunhoursProduct(s, w, r));
         }},
        {"sunhours_interpolated",
         [=](const DemSource& s, const CellWindow& w) {
             SunhoursRequest r;
             r.firstDay = r.lastDay = parseDate("2024-06-21");
             r.step = std::chrono::minutes(90);
             r.stackDirections = 8;
             r.search = search;
             return static_cast<ProductResult>(sunhoursProduct(s, w, r));
         }},
        {"timelapse", [=](const DemSource& s, const CellWindow& w) { return timelapseBands(s, w, 0, search); }},
        {"timelapse_interpolated",
         [=](const DemSource& s, const CellWindow& w) { return timelapseBands(s, w, 8, search); }},
    };
}

class TiledProducts : public ::testing::TestWithParam<Case> {};

TEST_P(TiledProducts, WindowsGiveTheWholeDemsBitsForEveryProduct) {
    const Case c = GetParam();
    const auto source = caseSource(c, c.productCropW, c.productCropH);
    if (!source) GTEST_SKIP() << c.dem << " absent";
    for (const ProductCase& p : productCases()) {
        for (const std::size_t tile : std::set<std::size_t>(std::begin(c.productTiles), std::end(c.productTiles))) {
            EXPECT_EQ(windowMismatches(*source, p.run, tile), 0u) << c.dem << " " << p.name << " tile " << tile;
        }
    }
}

// The portable path (DEMLIGHT_SIMD=portable, or an older processor) computes the vector kernels'
// expressions one lane at a time, and their fused multiply-adds by libm: every product's bits
// are the same on every path.
TEST_P(TiledProducts, EveryVectorPathGivesThePortablePathsBitsForEveryProduct) {
    std::vector<SimdPath> paths;
    if (processorHasAvx2()) paths.push_back(SimdPath::Avx2);
    if (processorHasAvx512()) paths.push_back(SimdPath::Avx512);
    if (paths.empty()) GTEST_SKIP() << "no vector path on this processor";
    const Case c = GetParam();
    const auto source = caseSource(c, c.productCropW, c.productCropH);
    if (!source) GTEST_SKIP() << c.dem << " absent";
    for (const ProductCase& p : productCases()) {
        const auto run = [&](SimdPath path) {
            const detail::ScopedSimdPath forced(path);
            return p.run(*source, source->whole());
        };
        const ProductResult portable = run(SimdPath::Portable);
        for (const SimdPath path : paths) {
            const ProductResult wide = run(path);
            ASSERT_EQ(wide.bands.size(), portable.bands.size()) << p.name;
            for (std::size_t b = 0; b < wide.bands.size(); ++b) {
                const ProductBand& x = wide.bands[b];
                const ProductBand& y = portable.bands[b];
                std::size_t differing = 0;
                for (std::size_t row = 0; row < source->height(); ++row)
                    for (std::size_t col = 0; col < source->width(); ++col)
                        differing += x.flags.empty() ? !sameBits(x.values(col, row), y.values(col, row))
                                                     : x.flags(col, row) != y.flags(col, row);
                EXPECT_EQ(differing, 0u) << c.dem << " " << p.name << " band " << b << " on the "
                                         << simdPathName(path) << " path";
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(RealDems, TiledProducts, ::testing::ValuesIn(kCases),
                         [](const auto& testInfo) { return demTestName(testInfo.param.dem); });
INSTANTIATE_TEST_SUITE_P(Samples, TiledProducts, ::testing::ValuesIn(kSamples),
                         [](const auto& testInfo) { return demTestName(testInfo.param.dem); });

TEST(TiledSweep, ATileKnowsTheFullGridItWasCutFrom) {
    Terrain whole = makeUniformTerrain(Grid<float>(50, 40, 1.0f), 10.0);
    const Terrain part = tileOf(whole, CellWindow{5, 7, 25, 30});
    ASSERT_TRUE(part.frame);
    EXPECT_EQ(part.frame->width, 50u);
    EXPECT_EQ(part.frame->height, 40u);
    EXPECT_EQ(part.frameCol0, 5u);
    EXPECT_EQ(part.frameRow0, 7u);
    const Terrain inner = tileOf(part, CellWindow{1, 2, 10, 10});
    EXPECT_EQ(inner.frameCol0, 6u);
    EXPECT_EQ(inner.frameRow0, 9u);
    EXPECT_EQ(inner.frame.get(), part.frame.get());
    EXPECT_DOUBLE_EQ(diagonalM(fullGrid(inner)), diagonalM(whole));
}

}  // namespace
}  // namespace demlight
