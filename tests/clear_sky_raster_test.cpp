// Rasters of the clear-sky inputs (--linke-raster, --albedo-raster, --coeff-bh-raster,
// --coeff-dh-raster; demlight/products/irradiance.h ClearSkyRasters): a constant raster gives the
// constant's values, a raster of two halves gives each half its constant's values, tiles give the
// one-piece bits, no data gives nodata, and point queries read the raster at their cell.
#include "cli_runner.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/raster.h"
#include "demlight/products/insolation.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/point.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

namespace demlight {
namespace {

const std::string kRocky = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";
const char* const kBands[] = {"beam", "diffuse", "reflected", "global"};

/// A raster on the DEM's own grid: `left` west of column `split`, `right` from it on.
std::unique_ptr<MemoryRaster> halves(const DemSource& s, float left, float right, std::size_t split) {
    Grid<float> v(s.width(), s.height(), left);
    for (std::size_t r = 0; r < s.height(); ++r)
        for (std::size_t c = split; c < s.width(); ++c) v(c, r) = right;
    return std::make_unique<MemoryRaster>(v, s.geometry().band.ref, std::nullopt);
}

IrradianceRequest morning(DiffuseModel model) {
    IrradianceRequest r;
    r.time = parseZonedInstant("2024-06-21T09:00", "America/Denver");
    r.diffuseModel = model;
    r.search.threads = 2;
    return r;
}

/// Equal bits in every band on the cells of columns [col0, col1).
void expectSameBits(const ProductResult& a, const ProductResult& b, std::size_t col0, std::size_t col1,
                    const std::string& what) {
    for (const char* name : kBands) {
        const Grid<float>& x = a.band(name).values;
        const Grid<float>& y = b.band(name).values;
        ASSERT_TRUE(x.sameShape(y));
        std::size_t differ = 0;
        for (std::size_t r = 0; r < x.height(); ++r)
            for (std::size_t c = col0; c < col1; ++c)
                differ += std::memcmp(&x(c, r), &y(c, r), sizeof(float)) != 0;
        EXPECT_EQ(differ, 0u) << what << ", band " << name;
    }
}

TEST(ClearSkyRasters, ConstantRastersGiveTheConstantsBits) {
    const DemSource source = DemSource::open(kRocky);
    const auto linke = halves(source, 2.5f, 2.5f, 0), albedo = halves(source, 0.3f, 0.3f, 0);
    const auto bh = halves(source, 0.75f, 0.75f, 0), dh = halves(source, 0.875f, 0.875f, 0);
    for (const DiffuseModel model : {DiffuseModel::VisibleSky, DiffuseModel::RSun}) {
        IrradianceRequest constants = morning(model);
        constants.linke = {2.5};
        constants.albedo = 0.3f;  // the float the raster holds
        constants.coeffBh = 0.75;
        constants.coeffDh = 0.875;
        IrradianceRequest rasters = morning(model);
        rasters.rasters = {{linke->path()}, albedo->path(), bh->path(), dh->path()};
        const IrradianceResult a = irradianceProduct(source, source.whole(), constants);
        const IrradianceResult b = irradianceProduct(source, source.whole(), rasters);
        expectSameBits(a, b, 0, source.width(), std::string(diffuseModelName(model)));
        EXPECT_EQ(b.metadata.at("DEMLIGHT_LINKE"), linke->path());
        EXPECT_EQ(b.metadata.at("DEMLIGHT_COEFF_DH"), dh->path());
        EXPECT_EQ(a.metadata.at("DEMLIGHT_LINKE"), "2.5");
    }
}

TEST(ClearSkyRasters, EachHalfOfARasterGetsItsConstantsValues) {
    const DemSource source = DemSource::open(kRocky);
    const std::size_t split = source.width() / 2;
    const auto linke = halves(source, 2.0f, 4.5f, split), bh = halves(source, 1.0f, 0.5f, split);
    IrradianceRequest r = morning(DiffuseModel::VisibleSky);
    r.rasters.linke = {linke->path()};
    r.rasters.coeffBh = bh->path();
    const IrradianceResult both = irradianceProduct(source, source.whole(), r);
    IrradianceRequest west = morning(DiffuseModel::VisibleSky), east = west;
    west.linke = {2.0};
    east.linke = {4.5};
    east.coeffBh = 0.5;
    // Bilinear resampling onto the DEM's own grid reads each cell's own value: no blending.
    expectSameBits(both, irradianceProduct(source, source.whole(), west), 0, split, "west half");
    expectSameBits(both, irradianceProduct(source, source.whole(), east), split, source.width(), "east half");
}

TEST(ClearSkyRasters, InsolationFollowsTheRastersWithinTheBeamTablesBound) {
    const DemSource source = DemSource::open(kRocky);
    const std::size_t split = source.width() / 2;
    const auto linke = halves(source, 2.0f, 4.5f, split), albedo = halves(source, 0.1f, 0.4f, split);
    InsolationRequest base;
    base.zone = TimeZoneSpec::iana("America/Denver");
    base.interval = {parseZonedInstant("2024-06-21T08:00", "America/Denver").utc,
                     parseZonedInstant("2024-06-21T12:00", "America/Denver").utc};
    base.step = std::chrono::minutes(30);
    base.search.threads = 2;
    InsolationRequest r = base, west = base, east = base;
    r.rasters = {{linke->path()}, albedo->path(), "", ""};
    west.linke = {2.0};
    west.albedo = 0.1f;
    east.linke = {4.5};
    east.albedo = 0.4f;
    const InsolationResult got = insolationProduct(source, source.whole(), r);
    const InsolationResult w = insolationProduct(source, source.whole(), west);
    const InsolationResult e = insolationProduct(source, source.whole(), east);
    // A Linke raster evaluates E2-E9 per cell; the constant goes through BeamNormalTable, within
    // 1e-7 of the formula (demlight/lighting/esra.h).
    for (const char* name : kBands) {
        double worst = 0;
        for (std::size_t row = 0; row < source.height(); ++row)
            for (std::size_t col = 0; col < source.width(); ++col) {
                const float x = got.band(name).values(col, row);
                const float y = (col < split ? w : e).band(name).values(col, row);
                if (std::isnan(x) || std::isnan(y)) {
                    EXPECT_EQ(std::isnan(x), std::isnan(y));
                    continue;
                }
                worst = std::max(worst, static_cast<double>(std::abs(x - y) / std::max(1e-3f, std::abs(y))));
            }
        EXPECT_LT(worst, 1e-6) << name;
    }
}

TEST(ClearSkyRasters, TilesGiveTheOnePieceBitsAndNoDataGivesNodata) {
    const DemSource source = DemSource::open(kRocky);
    Grid<float> v(source.width(), source.height(), 3.0f);
    for (std::size_t r = 0; r < source.height(); ++r)
        for (std::size_t c = 0; c < source.width(); ++c) v(c, r) = 2.0f + 3.0f * static_cast<float>(c + r) / 400.0f;
    v(20, 30) = -9999;
    const MemoryRaster linke(v, source.geometry().band.ref, -9999.0);
    const auto albedo = halves(source, 0.1f, 0.35f, 70);
    IrradianceRequest r = morning(DiffuseModel::VisibleSky);
    r.search.maxDistanceM = 3000;
    r.rasters.linke = {linke.path()};
    r.rasters.albedo = albedo->path();
    const IrradianceResult whole = irradianceProduct(source, source.whole(), r);
    EXPECT_TRUE(std::isnan(whole.band("global").values(20, 30)));
    EXPECT_FALSE(std::isnan(whole.band("global").values(21, 30)));
    for (const CellWindow w : {CellWindow{0, 0, 64, 64}, CellWindow{64, 64, 152, 187}, CellWindow{10, 100, 90, 130}}) {
        const IrradianceResult part = irradianceProduct(source, w, r);
        for (const char* name : kBands) {
            const Grid<float> expected = cropGrid(whole.band(name).values, w);
            EXPECT_EQ(std::memcmp(expected.data(), part.band(name).values.data(), expected.size() * sizeof(float)), 0)
                << name << " window " << w.col0 << "," << w.row0;
        }
    }
}

TEST(ClearSkyRasters, PointQueriesReadTheRasterAtTheirCell) {
    const DemSource source = DemSource::open(kRocky);
    const std::size_t split = source.width() / 2;
    const auto linke = halves(source, 2.0f, 4.5f, split);
    const auto& gt = source.geometry().band.ref.geoTransform;
    const PointCell p = locatePoint(source, {gt[0] + 100.5 * gt[1], gt[3] + 50.5 * gt[5], false});
    IrradianceRequest r = morning(DiffuseModel::RSun), constant = r;
    r.rasters.linke = {linke->path()};
    constant.linke = {4.5};  // column 100 is east of the split
    const PointIrradiance a = pointIrradiance(source, p, r), b = pointIrradiance(source, p, constant);
    EXPECT_EQ(a.linke, 4.5);
    EXPECT_EQ(a.irradiance.global(), b.irradiance.global());
}

/// A GeoTIFF of `values.size()` constant bands on the DEM's grid (band b holds values[b]), removed
/// with the object.
struct ConstantBands {
    std::string path;
    ConstantBands(const DemSource& s, const std::vector<float>& values, const std::string& name) {
        path = (std::filesystem::temp_directory_path() /
                ("demlight_" + name + "_" + std::to_string(::getpid()) + ".tif")).string();
        std::vector<Grid<float>> grids;
        for (float v : values) grids.emplace_back(s.width(), s.height(), v);
        std::vector<OutputBand> bands(grids.size());
        for (std::size_t b = 0; b < grids.size(); ++b) bands[b].values = &grids[b];
        writeRaster(path, bands, s.geometry().band.ref, WriteOptions{});
    }
    ConstantBands(const ConstantBands&) = delete;
    ConstantBands& operator=(const ConstantBands&) = delete;
    ~ConstantBands() { std::filesystem::remove(path); }
};

/// Twelve distinct monthly Linke factors, January first.
std::vector<double> monthlyLinke() {
    std::vector<double> v;
    for (int m = 0; m < 12; ++m) v.push_back(2.0 + 0.2 * m);
    return v;
}

InsolationRequest yearOf2023() {
    InsolationRequest r;
    r.zone = TimeZoneSpec::iana("America/Denver");
    r.firstDay = std::chrono::sys_days{std::chrono::year{2023} / 1 / 1};
    r.lastDay = std::chrono::sys_days{std::chrono::year{2023} / 12 / 31};
    r.step = std::chrono::hours(1);
    r.directions = 8;
    r.search.threads = 2;
    return r;
}

/// Every valid cell of every band within `tolerance` (relative), NaN where the other is NaN.
void expectClose(const ProductResult& a, const ProductResult& b, double tolerance, const std::string& what) {
    for (const char* name : kBands) {
        const Grid<float>& x = a.band(name).values;
        const Grid<float>& y = b.band(name).values;
        double worst = 0;
        for (std::size_t k = 0; k < x.size(); ++k) {
            if (std::isnan(x.data()[k]) || std::isnan(y.data()[k])) {
                EXPECT_EQ(std::isnan(x.data()[k]), std::isnan(y.data()[k])) << what;
                continue;
            }
            worst = std::max(worst, std::abs(static_cast<double>(x.data()[k]) - y.data()[k]) /
                                        std::max(1e-3, std::abs(static_cast<double>(y.data()[k]))));
        }
        EXPECT_LT(worst, tolerance) << what << ", band " << name;
    }
}

// A 12-band Linke raster is twelve monthly maps (it was read as its first band, January's, for the
// whole year: 8 % too much beam on this year): a year with twelve constant monthly maps, as one
// 12-band file or as twelve files, gives the year of the twelve monthly constants. The constant
// path reads BeamNormalTable, within 1e-7 of the formulas a raster evaluates (demlight/lighting/esra.h).
TEST(ClearSkyRasters, TwelveMonthlyLinkeMapsGiveTheYearOfTwelveMonthlyConstants) {
    const DemSource source = DemSource::open(kRocky);
    const std::vector<double> linke = monthlyLinke();
    InsolationRequest constants = yearOf2023();
    constants.linke = linke;
    const InsolationResult expected = insolationProduct(source, source.whole(), constants);

    const ConstantBands twelveBands(source, std::vector<float>(linke.begin(), linke.end()), "linke12");
    InsolationRequest oneFile = yearOf2023();
    oneFile.rasters.linke = {twelveBands.path};
    expectClose(insolationProduct(source, source.whole(), oneFile), expected, 1e-6, "one 12-band file");

    std::vector<std::unique_ptr<ConstantBands>> files;
    InsolationRequest twelveFiles = yearOf2023();
    for (std::size_t m = 0; m < 12; ++m) {
        files.push_back(std::make_unique<ConstantBands>(source, std::vector<float>{static_cast<float>(linke[m])},
                                                        "linke_m" + std::to_string(m)));
        twelveFiles.rasters.linke.push_back(files.back()->path);
    }
    expectClose(insolationProduct(source, source.whole(), twelveFiles), expected, 1e-6, "twelve files");
}

// An instant (irradiance, and the point queries of irradiance and insolation) takes its month's map.
TEST(ClearSkyRasters, AnInstantAndThePointQueriesTakeTheirMonthsMap) {
    const DemSource source = DemSource::open(kRocky);
    const std::vector<double> linke = monthlyLinke();
    const ConstantBands twelveBands(source, std::vector<float>(linke.begin(), linke.end()), "linke12i");
    IrradianceRequest r = morning(DiffuseModel::VisibleSky), constant = r;  // June 21st
    r.rasters.linke = {twelveBands.path};
    constant.linke = {static_cast<float>(linke[5])};
    expectSameBits(irradianceProduct(source, source.whole(), r), irradianceProduct(source, source.whole(), constant), 0,
                   source.width(), "June");

    const auto& gt = source.geometry().band.ref.geoTransform;
    const PointCell p = locatePoint(source, {gt[0] + 100.5 * gt[1], gt[3] + 50.5 * gt[5], false});
    EXPECT_EQ(pointIrradiance(source, p, r).linke, static_cast<float>(linke[5]));
    InsolationRequest year = yearOf2023(), yearConstants = yearOf2023();
    year.rasters.linke = {twelveBands.path};
    yearConstants.linke.clear();
    for (double v : linke) yearConstants.linke.push_back(static_cast<float>(v));
    const PointInsolation a = pointInsolation(source, p, year), b = pointInsolation(source, p, yearConstants);
    EXPECT_DOUBLE_EQ(a.irradiation.global(), b.irradiation.global());
}

// Band counts other than 1 and 12, and path counts other than 1 and 12, are refused by name.
TEST(ClearSkyRasters, OtherLinkeBandAndFileCountsAreRefused) {
    const DemSource source = DemSource::open(kRocky);
    const ConstantBands five(source, std::vector<float>(5, 3.0f), "linke5");
    const testing::RunResult run = testing::runDemlight(
        "-q insolation '" + kRocky + "' -o /tmp/never.tif --start 2023-01-01 --end 2023-01-02 --tz UTC --linke-raster '" +
        five.path + "'");
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.err.find("--linke-raster"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("has 5 bands; expected 1 (the whole period) or 12"), std::string::npos) << run.err;

    const ConstantBands one(source, {3.0f}, "linke1");
    InsolationRequest three = yearOf2023();
    three.rasters.linke = {one.path, one.path, one.path};
    try {
        insolationProduct(source, source.whole(), three);
        ADD_FAILURE() << "three Linke files were accepted";
    } catch (const FieldError& e) {
        EXPECT_NE(std::string(e.what()).find("3 paths; expected one raster"), std::string::npos) << e.what();
    }
    InsolationRequest twelve = yearOf2023();
    twelve.rasters.linke = std::vector<std::string>(11, one.path);
    twelve.rasters.linke.push_back(five.path);
    EXPECT_THROW(insolationProduct(source, source.whole(), twelve), FieldError);
}

TEST(ClearSkyRasters, OutOfRangeRasterIsRefusedNamingTheOption) {
    const DemSource source = DemSource::open(kRocky);
    Grid<float> bad(source.width(), source.height(), 3.0f);
    bad(5, 5) = 12.0f;  // beyond ESRA's Linke range
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("demlight_linke_" + std::to_string(::getpid()) + ".tif")).string();
    OutputBand band;
    band.values = &bad;
    writeRaster(path, {band}, source.geometry().band.ref, WriteOptions{});
    const testing::RunResult run =
        testing::runDemlight("-q irradiance '" + kRocky + "' -o /tmp/never.tif --time 2024-06-21T09:00Z --linke-raster '" +
                             path + "'");
    std::filesystem::remove(path);
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.err.find("--linke-raster"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("expected values 1-10"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace demlight
