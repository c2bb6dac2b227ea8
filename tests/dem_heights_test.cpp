// Heights in metres whatever the DEM stores: one terrain written three ways (Float32 metres, Int16
// decimetres with band scale 0.1 and offset 200, Float32 feet with unit "ft") must load as the
// same heights; units and overrides; GDAL virtual paths (/vsizip/); and `info` reporting what it
// applied. The files are made with GDAL's own tools (tests do not link GDAL), skipped when absent.
#include "cli_runner.h"
#include "demlight/geo/dem.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/time.h"
#include "demlight/products/sun.h"
#include "demlight/geo/raster.h"
#include "demlight/core/terrain.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>
#include <unistd.h>

namespace demlight {
namespace {

namespace fs = std::filesystem;

const std::string kSamples = DEMLIGHT_SAMPLES_DIR;
/// Metres per foot and the decimetre step of the Int16 file.
constexpr double kFootM = 0.3048;
constexpr double kDecimetreM = 0.1;
/// Offset (metres) of the Int16 file: its raw values are decimetres above 200 m.
constexpr double kOffsetM = 200;
/// Feet heights are float(metres / 0.3048) and come back as float(feet * 0.3048): two float
/// roundings of heights under 600 m, each below 3.1e-5 m.
constexpr float kFeetRoundTripM = 1e-4f;

bool run(const std::string& command) { return std::system(("(" + command + ") >/dev/null 2>&1").c_str()) == 0; }

std::string shellQuoted(const fs::path& p) {
    std::string text(1, '\'');  // appended, not "'" + s: GCC 12 warns falsely (-Wrestrict) on that
    text += p.string();
    text += '\'';
    return text;
}

HeightOptions zUnitOption(const std::string& unit) {
    HeightOptions o;
    o.zUnit = unit;
    return o;
}
HeightOptions zFactorOption(double factor) {
    HeightOptions o;
    o.zFactor = factor;
    return o;
}

/// The same terrain three ways, plus the same feet file declaring an unknown unit and a zip of
/// the metres file. Per process (ctest runs tests in parallel processes), removed at exit.
struct HeightFiles {
    fs::path dir;
    std::string metres, decimetres, feet, furlong, zip;
    std::string alpha, masked;  // the Luxembourg sample's nodata as an alpha band and as a mask, cells 0
    std::string complex;        // the metres as CFloat32
    std::string skipReason;  // non-empty: GDAL's command-line tools are missing

    HeightFiles() {
        dir = fs::temp_directory_path() / ("demlight_test_dem_heights_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        metres = (dir / "metres.tif").string();
        decimetres = (dir / "decimetres.tif").string();
        feet = (dir / "feet.tif").string();
        furlong = (dir / "furlong.tif").string();
        zip = (dir / "dem.zip").string();
        alpha = (dir / "alpha.tif").string();
        masked = (dir / "masked.tif").string();
        complex = (dir / "complex.tif").string();
        if (!run("command -v gdalwarp && command -v gdal_translate && command -v gdal_edit.py")) {
            skipReason = "GDAL's command-line tools (gdalwarp, gdal_translate, gdal_edit.py) are not installed";
            return;
        }
        // Resampled (bilinear, in Float32) so the heights have fractions; the border stays nodata.
        const fs::path fine = dir / "fine.tif";
        const bool made =
            run("gdalwarp -q -ot Float32 -wt Float32 -r bilinear -ts 150 140 " +
                shellQuoted(fs::path(kSamples) / "luxembourg_elev_terra.tif") + " " + shellQuoted(fine)) &&
            // decimetres above 200 m, rounded: (h - 200) * 10
            run("gdal_translate -q -ot Int16 -scale 200 201 0 10 -a_scale 0.1 -a_offset 200 -a_nodata -32768 " +
                shellQuoted(fine) + " " + shellQuoted(decimetres)) &&
            // the same terrain in metres, unscaled by GDAL: the reference
            run("gdal_translate -q -unscale -ot Float32 " + shellQuoted(decimetres) + " " + shellQuoted(metres)) &&
            run("gdal_translate -q -ot Float32 -scale 0 0.3048 0 1 " + shellQuoted(metres) + " " + shellQuoted(feet)) &&
            run("gdal_edit.py -units ft " + shellQuoted(feet)) &&
            run("gdal_translate -q " + shellQuoted(feet) + " " + shellQuoted(furlong)) &&
            run("gdal_edit.py -units furlong " + shellQuoted(furlong)) &&
            run("cd " + shellQuoted(dir) + " && python3 -m zipfile -c dem.zip metres.tif") &&
            // Int16 heights and an Int16 alpha band, 0 outside the border (no nodata value), as
            // gdalwarp -dstalpha writes them; then the alpha as an internal mask.
            run("gdalwarp -q -r near -dstalpha -dstnodata None " +
                shellQuoted(fs::path(kSamples) / "luxembourg_elev_terra.tif") + " " + shellQuoted(alpha)) &&
            run("gdal_translate -q -b 1 -mask 2 " + shellQuoted(alpha) + " " + shellQuoted(masked)) &&
            run("gdal_translate -q -ot CFloat32 " + shellQuoted(metres) + " " + shellQuoted(complex));
        if (!made) skipReason = "making the test DEMs with GDAL's tools or python3 failed";
    }
    ~HeightFiles() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

const HeightFiles& files() {
    static const HeightFiles f;
    return f;
}

#define REQUIRE_HEIGHT_FILES()                                           \
    if (!files().skipReason.empty()) GTEST_SKIP() << files().skipReason

/// Same shape, NaN in the same cells and every other value the same bits.
::testing::AssertionResult sameBits(const Grid<float>& a, const Grid<float>& b) {
    if (!a.sameShape(b)) return ::testing::AssertionFailure() << "grids differ in size";
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a.data()[i], &b.data()[i], sizeof(float)) != 0 &&
            !(std::isnan(a.data()[i]) && std::isnan(b.data()[i])))
            return ::testing::AssertionFailure() << "cell " << i << ": " << a.data()[i] << " vs " << b.data()[i];
    return ::testing::AssertionSuccess();
}

std::size_t countNan(const Grid<float>& g) {
    std::size_t n = 0;
    for (float v : g.values()) n += std::isnan(v);
    return n;
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(DemHeights, ScaledInt16DecimetresGiveTheMetresBitForBit) {
    REQUIRE_HEIGHT_FILES();
    const Dem m = loadDem(files().metres);
    const Dem dm = loadDem(files().decimetres);
    EXPECT_EQ(dm.heights.scale, kDecimetreM);
    EXPECT_EQ(dm.heights.offset, kOffsetM);
    EXPECT_EQ(dm.heights.toMetres, 1.0);
    EXPECT_EQ(dm.heights.unit, "");
    EXPECT_EQ(dm.heights.source, "default (no unit declared: metres)");
    // The band keeps its raw values and raw nodata value (outputs carry the nodata over).
    ASSERT_TRUE(dm.band.nodata.has_value());
    EXPECT_EQ(*dm.band.nodata, -32768.0);
    EXPECT_EQ(dm.band.scale, kDecimetreM);
    // Both are float(raw * 0.1 + 200) computed in double, GDAL's for metres.tif and demlight's.
    EXPECT_TRUE(sameBits(dm.terrain.heightsM, m.terrain.heightsM));
    EXPECT_GT(countNan(m.terrain.heightsM), 0u);
    EXPECT_LT(countNan(m.terrain.heightsM), m.terrain.heightsM.size());
    EXPECT_EQ(dm.band.nodataCount, countNan(m.terrain.heightsM));
    // Guards against the raw decimetres passing as metres.
    const auto [lo, hi] = heightRangeM(dm.terrain.heightsM);
    EXPECT_GT(lo, 100.0f);
    EXPECT_LT(hi, 600.0f);
}

TEST(DemHeights, FeetWithUnitFtGiveTheMetres) {
    REQUIRE_HEIGHT_FILES();
    const Dem m = loadDem(files().metres);
    const Dem ft = loadDem(files().feet);
    EXPECT_EQ(ft.heights.unit, "ft");
    EXPECT_EQ(ft.heights.toMetres, kFootM);
    EXPECT_EQ(ft.heights.source, "band");
    const Grid<float>& a = m.terrain.heightsM;
    const Grid<float>& b = ft.terrain.heightsM;
    ASSERT_TRUE(a.sameShape(b));
    float worstM = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(std::isnan(a.data()[i]), std::isnan(b.data()[i])) << "cell " << i;
        if (!std::isnan(a.data()[i])) worstM = std::max(worstM, std::abs(a.data()[i] - b.data()[i]));
    }
    EXPECT_LE(worstM, kFeetRoundTripM);
}

// The lightmaps, not only the heights: decimetres with a scale and feet with a unit light the
// same terrain as metres (decimetres bit for bit; feet within the rounding of the feet file).
TEST(DemHeights, ScaledAndFeetDemsGiveTheLightmapsOfMetres) {
    REQUIRE_HEIGHT_FILES();
    SunRequest request;
    request.time = parseZonedInstant("2024-06-21T06:30:00Z", "");  // a low morning sun: long shadows
    request.search.threads = 2;
    const auto lightmaps = [&](const std::string& path) {
        const DemSource dem = DemSource::open(path);
        return sunProduct(dem, dem.whole(), request);
    };
    const SunResult m = lightmaps(files().metres), dm = lightmaps(files().decimetres), ft = lightmaps(files().feet);
    for (const char* band : {"sun_visibility", "sun_irradiance"}) {
        EXPECT_TRUE(sameBits(dm.band(band).values, m.band(band).values)) << band;
        const Grid<float>& a = m.band(band).values;
        const Grid<float>& b = ft.band(band).values;
        double sum = 0;
        std::size_t n = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            ASSERT_EQ(std::isnan(a.data()[i]), std::isnan(b.data()[i])) << band << " cell " << i;
            if (!std::isnan(a.data()[i])) sum += std::abs(a.data()[i] - b.data()[i]), ++n;
        }
        EXPECT_LT(sum / static_cast<double>(n), 1e-4) << band;
    }
    // The raw decimetres read as metres would be a different terrain: the test can tell.
    Dem raw = loadDem(files().decimetres, zFactorOption(10.0));
    const DemSource tall(std::move(raw));
    const SunResult wrong = sunProduct(tall, tall.whole(), request);
    EXPECT_FALSE(sameBits(wrong.band("sun_visibility").values, m.band("sun_visibility").values));
}

TEST(DemHeights, ZUnitOverridesTheBandUnit) {
    REQUIRE_HEIGHT_FILES();
    // Feet read as metres: the raw values, untouched.
    const Dem asMetres = loadDem(files().feet, zUnitOption("m"));
    EXPECT_EQ(asMetres.heights.source, "zUnit option");
    EXPECT_EQ(asMetres.heights.unit, "m");
    EXPECT_TRUE(sameBits(asMetres.terrain.heightsM, asMetres.band.values));
    // Metres read as US survey feet.
    const Dem m = loadDem(files().metres);
    const Dem usFeet = loadDem(files().metres, zUnitOption("US survey foot"));
    EXPECT_EQ(usFeet.heights.toMetres, 1200.0 / 3937.0);
    for (std::size_t i = 0; i < m.terrain.heightsM.size(); ++i) {
        const float h = m.terrain.heightsM.data()[i];
        if (std::isnan(h)) continue;
        ASSERT_EQ(usFeet.terrain.heightsM.data()[i], static_cast<float>(h * (1200.0 / 3937.0))) << "cell " << i;
    }
}

TEST(DemHeights, ZFactorReplacesTheUnit) {
    REQUIRE_HEIGHT_FILES();
    const Dem ft = loadDem(files().feet);
    const Dem byFactor = loadDem(files().feet, zFactorOption(kFootM));
    EXPECT_EQ(byFactor.heights.source, "zFactor option");
    EXPECT_EQ(byFactor.heights.toMetres, kFootM);
    EXPECT_TRUE(sameBits(byFactor.terrain.heightsM, ft.terrain.heightsM));
    // An unknown band unit is no obstacle when the factor is given.
    const Dem furlong = loadDem(files().furlong, zFactorOption(kFootM));
    EXPECT_EQ(furlong.heights.unit, "furlong");
    EXPECT_TRUE(sameBits(furlong.terrain.heightsM, ft.terrain.heightsM));
}

TEST(DemHeights, UnknownBandUnitIsRefusedNamingItTheFileAndTheOverride) {
    REQUIRE_HEIGHT_FILES();
    const std::string message = messageOf([] { loadDem(files().furlong); });
    EXPECT_NE(message.find("\"furlong\""), std::string::npos) << message;
    EXPECT_NE(message.find(files().furlong), std::string::npos) << message;
    EXPECT_NE(message.find("z_unit"), std::string::npos) << message;
    EXPECT_NE(message.find("z_factor"), std::string::npos) << message;
}

TEST(DemHeights, InvalidOptionsNameTheFieldAndValue) {
    const std::string dem = kSamples + "/rocky_mountain_np_dem.tif";
    const struct {
        HeightOptions options;
        const char* expected;
    } cases[] = {
        {zFactorOption(-2), "z_factor -2 "},
        {zFactorOption(std::numeric_limits<double>::quiet_NaN()), "z_factor nan "},
        {zFactorOption(std::numeric_limits<double>::infinity()), "z_factor inf "},
        {{"ft", 2}, "exclude each other"},
        {zUnitOption("furlong"), "z_unit \"furlong\" is not a vertical unit"},
        {zUnitOption(" "), "z_unit \" \" is not a vertical unit"},
    };
    for (const auto& c : cases) {
        const std::string message = messageOf([&] { loadDem(dem, c.options); });
        EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    }
}

TEST(DemHeights, KnownUnitSpellings) {
    const double usFootM = 1200.0 / 3937.0;
    const struct {
        const char* unit;
        std::optional<double> metres;
    } cases[] = {
        {"", 1.0},         {"m", 1.0},       {"Metre", 1.0},        {"meter", 1.0},
        {"METRES", 1.0},   {"meters", 1.0},  {"ft", kFootM},        {"Foot", kFootM},
        {"feet", kFootM},  {"international foot", kFootM},          {"US survey foot", usFootM},
        {"us-ft", usFootM}, {"ftUS", usFootM}, {"US survey feet", usFootM},
        {"cm", 0.01},      {"dm", 0.1},      {"mm", 0.001},         {"km", 1000.0},
        {"furlong", std::nullopt}, {"m/s", std::nullopt}, {"degrees", std::nullopt},
    };
    for (const auto& c : cases) EXPECT_EQ(metresPerUnit(c.unit), c.metres) << '"' << c.unit << '"';
}

TEST(DemHeights, EverySampleLoadsAsItsRawBandBitForBit) {
    std::vector<std::string> paths;
    for (const auto& entry : fs::directory_iterator(kSamples))
        if (entry.path().extension() != ".md") paths.push_back(entry.path().string());
    if (fs::exists(DEMLIGHT_SHARED_DEM_DIR))
        for (const auto& entry : fs::directory_iterator(DEMLIGHT_SHARED_DEM_DIR))
            if (entry.path().extension() != ".md") paths.push_back(entry.path().string());
    ASSERT_GE(paths.size(), 3u);
    for (const auto& path : paths) {
        SCOPED_TRACE(path);
        const Dem dem = loadDem(path);
        EXPECT_EQ(dem.heights.scale, 1.0);
        EXPECT_EQ(dem.heights.offset, 0.0);
        EXPECT_EQ(dem.heights.toMetres, 1.0);
        EXPECT_TRUE(sameBits(dem.terrain.heightsM, readRasterBand(path).values));
    }
}

TEST(DemMask, AlphaBandsAndMasksAreNodataWholeAndInWindows) {
    REQUIRE_HEIGHT_FILES();
    const std::string original = (fs::path(kSamples) / "luxembourg_elev_terra.tif").string();
    const Dem reference = loadDem(original);  // nodata -32768 outside the border: 3942 cells
    ASSERT_EQ(countNan(reference.terrain.heightsM), 3942u);
    for (const std::string& path : {files().alpha, files().masked}) {
        ASSERT_FALSE(readRasterHeader(path).nodata.has_value()) << path << ": only the mask may say nodata";
        const Dem dem = loadDem(path);
        EXPECT_EQ(dem.band.nodataCount, 3942u) << path;
        EXPECT_TRUE(sameBits(dem.terrain.heightsM, reference.terrain.heightsM)) << path;
        const DemSource source = DemSource::open(path);
        const CellWindow w{10, 20, 60, 70};
        EXPECT_TRUE(sameBits(source.heightsM(w), DemSource::open(original).heightsM(w))) << path;
    }
}

TEST(DemHeights, ComplexBandsAreRefusedNamingTheType) {
    REQUIRE_HEIGHT_FILES();
    const std::string message = messageOf([] { loadDem(files().complex); });
    EXPECT_NE(message.find("holds complex numbers (CFloat32)"), std::string::npos) << message;
}

TEST(DemVirtualPath, ZipMemberLoadsLikeTheFile) {
    REQUIRE_HEIGHT_FILES();
    const Dem plain = loadDem(files().metres);
    const std::string inZip = "/vsizip/" + files().zip + "/metres.tif";
    const Dem zipped = loadDem(inZip);
    EXPECT_EQ(zipped.band.path, inZip);
    EXPECT_TRUE(sameBits(zipped.terrain.heightsM, plain.terrain.heightsM));
    EXPECT_EQ(zipped.band.ref.geoTransform, plain.band.ref.geoTransform);
}

TEST(DemVirtualPath, MissingFilesAreStillNoSuchFile) {
    REQUIRE_HEIGHT_FILES();
    for (const std::string& path :
         {"/vsizip/" + files().zip + "/absent.tif", (files().dir / "absent.tif").string()}) {
        const std::string message = messageOf([&] { loadDem(path); });
        EXPECT_NE(message.find("cannot open '" + path + "': no such file"), std::string::npos) << message;
    }
}

TEST(DemHeightsCli, InfoPrintsTheAppliedTransform) {
    REQUIRE_HEIGHT_FILES();
    auto r = testing::runDemlight("info '" + files().decimetres + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("Heights:        scale 0.1, offset 200, unit none -> metres x 1 "
                         "(default (no unit declared: metres))\n"),
              std::string::npos)
        << r.out;

    r = testing::runDemlight("info '" + files().feet + "' --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("height_scale"), 1.0);
    EXPECT_EQ(j.at("height_offset"), 0.0);
    EXPECT_EQ(j.at("height_unit"), "ft");
    EXPECT_EQ(j.at("height_to_metres"), kFootM);
    EXPECT_EQ(j.at("height_source"), "band");
    const auto [lowM, highM] = heightRangeM(loadDem(files().metres).terrain.heightsM);
    EXPECT_NEAR(j.at("elevation_min_m").get<double>(), lowM, kFeetRoundTripM);
    EXPECT_NEAR(j.at("elevation_max_m").get<double>(), highM, kFeetRoundTripM);

    r = testing::runDemlight("info '/vsizip/" + files().zip + "/metres.tif' --z-unit ft");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("unit \"ft\" -> metres x 0.3048 (zUnit option)"), std::string::npos) << r.out;
}

TEST(DemHeightsCli, InfoNamesFlagsNotFields) {
    REQUIRE_HEIGHT_FILES();
    auto r = testing::runDemlight("info '" + files().furlong + "'");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("\"furlong\""), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--z-unit"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--z-factor"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("HeightOptions"), std::string::npos) << r.err;

    r = testing::runDemlight("info '" + files().furlong + "' --z-factor 201.168 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out).at("height_source"), "zFactor option");

    r = testing::runDemlight("info '" + files().metres + "' --z-unit furlong");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--z-unit \"furlong\" is not a vertical unit"), std::string::npos) << r.err;

    for (const char* bad : {"--z-factor 0", "--z-factor -1", "--z-unit ft --z-factor 2"}) {
        r = testing::runDemlight("info '" + files().metres + "' " + bad);
        EXPECT_NE(r.exitCode, 0) << bad;
        EXPECT_NE(r.err.find("--z-"), std::string::npos) << bad << ": " << r.err;
    }
}

}  // namespace
}  // namespace demlight
