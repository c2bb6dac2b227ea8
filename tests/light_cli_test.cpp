// End-to-end tests of `demlight light` and `demlight sunhours` options: the scene plan
// (--quality, --tolerance, -v) must reach the computation, not only the help text.
#include "cli_runner.h"
#include "demlight/geo/raster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
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

const std::string kUtm10Wkt = R"(PROJCS["WGS 84 / UTM zone 10N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",-123],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1],AUTHORITY["EPSG","32610"]])";

/// Synthetic DEM near Mount St Helens (46.2 N): a flat plain at 1000 m, 30 m cells, with a
/// block kHillTop m high over cells [kHill0, kHill1) in both axes.
constexpr std::size_t kPlain = 200, kHill0 = 90, kHill1 = 110;
constexpr float kPlainM = 1000.0f, kHillTopM = 1300.0f;
std::string writeHillDem(const std::string& path) {
    Grid<float> h(kPlain, kPlain, kPlainM);
    for (std::size_t r = kHill0; r < kHill1; ++r)
        for (std::size_t c = kHill0; c < kHill1; ++c) h(c, r) = kHillTopM;
    GeoReference ref;
    ref.geoTransform = {560000, 30, 0, 5120000, 0, -30};
    ref.crsWkt = kUtm10Wkt;
    writeRaster(path, {{&h, nullptr, "height", "m"}}, ref, WriteOptions{});
    return path;
}

/// A raster on the DEM's own grid whose band b is the constant values[b].
void writeConstantRaster(const std::string& path, const std::string& demPath, const std::vector<float>& values) {
    const RasterBand dem = readRasterBand(demPath);
    std::vector<Grid<float>> grids;
    for (float v : values) grids.emplace_back(dem.values.width(), dem.values.height(), v);
    std::vector<OutputBand> bands;
    for (const auto& g : grids) bands.push_back({&g, nullptr, "albedo", "1"});
    writeRaster(path, bands, dem.ref, WriteOptions{});
}

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
    // Same light, only finer: large changes only where full's finer scan tolerance (more sweep
    // regions) moves a sun shadow edge by a cell (measured 20 of 153 000 cells).
    EXPECT_LT(cellsDiffering(la[0], lf[0], 0.1f), la[0].size() / 1000);
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
    // only where a shadow edge moves (full: the DEM diagonal as search distance and a 0.01 deg
    // scan tolerance, so other sweep regions; measured 0.3 % of cells).
    EXPECT_GT(cellsDiffering(ba[1], bf[1], 0.0f), ba[1].size() / 10);
    EXPECT_LT(cellsDiffering(ba[1], bf[1], 0.05f), ba[1].size() / 100);
    // sky_irradiation: the sky term from the plan's 64 directions instead of 16.
    EXPECT_EQ(a.metadata.at("DEMLIGHT_SKY_DIRECTIONS"), "16");
    EXPECT_EQ(f.metadata.at("DEMLIGHT_SKY_DIRECTIONS"), "64");
    EXPECT_GT(cellsDiffering(ba[2], bf[2], 1e-3f), ba[2].size() / 10);
}

/// Clock hours of "...THH:MM:SS..." in `json` after `"key": "`.
double clockHoursOf(const std::string& json, const std::string& key) {
    const std::size_t at = json.find("\"" + key + "\": \"");
    if (at == std::string::npos) return std::nan("");
    const std::size_t t = json.find('T', at + key.size() + 4);
    return std::stod(json.substr(t + 1, 2)) + std::stod(json.substr(t + 4, 2)) / 60 +
           std::stod(json.substr(t + 7, 2)) / 3600;
}

// Band 3: sky_irradiation = f_sky × daylight. f_sky is `demlight sky`'s sky_factor with the same
// plan and albedo; daylight is SPA's sunrise to sunset, taken here from `demlight sunpos` at the
// DEM centre (SPA's rise/set routine, not the per-instant positions sunhours integrates). The DEM
// spans 0.13 deg of latitude, so day lengths differ by +-35 s across it; the 20 min step's linear
// interpolation of the elevation adds ~10 s.
TEST_F(OptionsCli, SunhoursSkyIrradiationIsSkyFactorTimesDayLength) {
    run("-q sunhours " + kHelens + " -o " + path("sh.tif") +
        " --date 2024-06-21 --tz America/Los_Angeles --step 20 --threads 2 --albedo 0.3");
    run("-q sky " + kHelens + " -o " + path("sky.tif") + " --threads 2 --albedo 0.3");
    const RasterSummary s = inspectRaster(path("sh.tif"));
    EXPECT_EQ(s.descriptions,
              (std::vector<std::string>{"sun_hours", "sun_irradiation", "sky_irradiation", "first_lit", "last_lit"}));
    const auto sunpos = run("sunpos --time 2024-06-21T12:00 --tz America/Los_Angeles --lat 46.1875 "
                            "--lon -122.1873 --json");
    const double dayHours = clockHoursOf(sunpos.out, "sunset") - clockHoursOf(sunpos.out, "sunrise");
    ASSERT_NEAR(dayHours, 15.78, 0.05);
    const Grid<float> skyIrr = readRasterBands(path("sh.tif"))[2];
    const Grid<float> skyFactor = readRasterBands(path("sky.tif"))[3];
    std::size_t checked = 0;
    for (std::size_t k = 0; k < skyIrr.size(); ++k) {
        if (std::isnan(skyFactor.data()[k])) continue;
        ASSERT_GT(skyFactor.data()[k], 0.1f);
        ASSERT_NEAR(skyIrr.data()[k] / skyFactor.data()[k], dayHours, 60.0 / 3600) << k;
        ++checked;
    }
    EXPECT_GT(checked, skyIrr.size() / 2);
}

// A cell the sun never reaches gets -1 in first_lit and last_lit: NaN would be written as the
// DEM's nodata value and show as a void. Here: the floor of a 60 m wide, 1 km deep east-west
// trench on the winter solstice at 46 N (the sun peaks near 20 deg).
TEST_F(OptionsCli, SunhoursMarksNeverLitCellsMinusOne) {
    Grid<float> h(40, 40, 1000.0f);
    for (std::size_t c = 0; c < 40; ++c) h(c, 20) = h(c, 21) = 0.0f;
    GeoReference ref;
    ref.geoTransform = {560000, 30, 0, 5120000, 0, -30};
    ref.crsWkt = kUtm10Wkt;
    writeRaster(path("trench.tif"), {{&h, nullptr, "height", "m"}}, ref, WriteOptions{});
    run("-q sunhours " + path("trench.tif") + " -o " + path("sh.tif") +
        " --date 2024-12-21 --tz America/Los_Angeles --step 20 --threads 2");
    const std::vector<Grid<float>> b = readRasterBands(path("sh.tif"));
    for (std::size_t c = 5; c < 35; ++c) {
        EXPECT_EQ(b[0](c, 20), 0.0f) << c;    // no sun hours on the trench floor
        EXPECT_EQ(b[3](c, 20), -1.0f) << c;   // first_lit: never
        EXPECT_EQ(b[4](c, 21), -1.0f) << c;   // last_lit: never
        EXPECT_GT(b[3](c, 5), 7.0f) << c;     // the plain: sunrise after 07:00 PST
        EXPECT_LT(b[4](c, 5), 17.0f) << c;    // sunset before 17:00
    }
}

// --model aperture must reach the sun term. With the sky off the output is the sun term alone:
// on open flat ground both models give sin(sun elevation) (the sun cap lies inside an almost
// hemispherical aperture); in the hill's cast shadow the horizon model gives 0 while a single
// cap, barely narrowed by a compact hill 1-2 km away, still holds the sun.
TEST_F(OptionsCli, LightApertureModelAgreesOnOpenGroundDiffersInShadow) {
    const std::string dem = writeHillDem(path("hill.tif"));
    const std::string args = " --time 2024-03-20T08:30 --tz America/Los_Angeles --sky-model none --threads 2";
    run("-q light " + dem + " -o " + path("horizon.tif") + args);
    run("-q light " + dem + " -o " + path("aperture.tif") + args + " --model aperture");
    run("-q light " + dem + " -o " + path("smooth.tif") + args + " --model aperture-smooth");
    const RasterSummary meta = inspectRaster(path("aperture.tif"));
    EXPECT_EQ(meta.metadata.at("DEMLIGHT_MODEL"), "aperture");
    EXPECT_EQ(meta.metadata.at("DEMLIGHT_DIRECTIONS"), "16");
    EXPECT_EQ(inspectRaster(path("horizon.tif")).metadata.at("DEMLIGHT_MODEL"), "horizon");
    const double elevationDeg = std::stod(meta.metadata.at("DEMLIGHT_SUN_ELEVATION_DEG"));
    ASSERT_GT(elevationDeg, 8.0);  // a morning sun in the east-south-east
    const double flatSun = std::sin(elevationDeg * M_PI / 180.0);
    const Grid<float> hz = readRasterBands(path("horizon.tif"))[0];
    const Grid<float> ap = readRasterBands(path("aperture.tif"))[0];
    const Grid<float> sm = readRasterBands(path("smooth.tif"))[0];
    // Open flat ground: the strip on the sun's side, 40+ cells from the hill, away from the
    // DEM edge the normals are one-sided at.
    std::size_t open = 0;
    for (std::size_t r = 1; r + 1 < kPlain; ++r)
        for (std::size_t c = kHill1 + 40; c + 1 < kPlain; ++c) {
            ++open;
            EXPECT_NEAR(hz(c, r), flatSun, 2e-3) << c << "," << r;
            EXPECT_NEAR(ap(c, r), hz(c, r), 2e-3) << c << "," << r;
            EXPECT_NEAR(sm(c, r), hz(c, r), 2e-3) << c << "," << r;
        }
    EXPECT_GT(open, 5000u);
    // The cast shadow: flat cells west of the hill that the horizon model leaves dark.
    std::size_t shadow = 0, apertureLit = 0;
    for (std::size_t r = 1; r + 1 < kPlain; ++r)
        for (std::size_t c = 1; c + 2 < kHill0; ++c)
            if (hz(c, r) == 0.0f) {
                ++shadow;
                if (ap(c, r) > 0.5 * flatSun) ++apertureLit;
            }
    EXPECT_GT(shadow, 300u);
    EXPECT_GT(apertureLit, shadow / 2) << shadow;
}

// --color-raster: the output is albedo_c x (sun + f_sky(K, albedo_c)) per channel. Checked
// against the sun term (a --sky-model none run) and K (a run with albedo 0, where f_sky = K),
// so on open cells (K ~ 1) the bands are proportional to the albedos.
TEST_F(OptionsCli, LightColorRasterIsPerChannelAlbedo) {
    const std::vector<float> albedo = {0.1f, 0.3f, 0.6f};
    writeConstantRaster(path("rgb.tif"), kHelens, albedo);
    const std::string args = " " + kLightArgs + " --sky-directions 8";
    run("-q light " + kHelens + " -o " + path("sun.tif") + args + " --sky-model none");
    run("-q light " + kHelens + " -o " + path("k.tif") + args + " --albedo 0");
    run("-q light " + kHelens + " -o " + path("rgb_out.tif") + args + " --color-raster " + path("rgb.tif"));
    const RasterSummary meta = inspectRaster(path("rgb_out.tif"));
    EXPECT_EQ(meta.descriptions, (std::vector<std::string>{"reflected_r", "reflected_g", "reflected_b"}));
    const Grid<float> sun = readRasterBands(path("sun.tif"))[0];
    const Grid<float> sunPlusK = readRasterBands(path("k.tif"))[0];
    const auto rgb = readRasterBands(path("rgb_out.tif"));
    ASSERT_EQ(rgb.size(), 3u);
    std::size_t checked = 0, open = 0;
    for (std::size_t k = 0; k < sun.size(); ++k) {
        const double s = sun.data()[k];
        if (std::isnan(s)) continue;
        const double skyK = sunPlusK.data()[k] - s;
        for (std::size_t c = 0; c < 3; ++c) {
            const double expected = albedo[c] * (s + skyK / (1.0 - albedo[c] * (1.0 - skyK)));
            ASSERT_NEAR(rgb[c].data()[k], expected, 2e-5) << k << " channel " << c;
        }
        ++checked;
        if (skyK > 0.999) {
            ++open;
            // Interreflection lifts the brighter channels by at most (1 - K)(a_c - a_r) ~ 0.05 %.
            for (std::size_t c = 1; c < 3; ++c) {
                const double ratio = albedo[c] / albedo[0];
                EXPECT_NEAR(rgb[c].data()[k] / rgb[0].data()[k], ratio, 1e-3 * ratio);
            }
        }
    }
    EXPECT_GT(checked, sun.size() / 2);
    EXPECT_GT(open, 100u) << "open cells (K > 0.999)";
}

TEST_F(OptionsCli, LightColorRasterBadInputFailsCleanly) {
    writeConstantRaster(path("two.tif"), kHelens, {0.2f, 0.3f});
    writeConstantRaster(path("bytes.tif"), kHelens, {200.0f, 120.0f, 60.0f});
    writeConstantRaster(path("rgb.tif"), kHelens, {0.2f, 0.3f, 0.4f});
    const std::string base = "light " + kHelens + " " + kLightArgs + " --sky-directions 4 -o " + path("out.tif");
    const struct {
        std::string args, message;
    } cases[] = {
        {" --color-raster " + path("two.tif"), "expected 3 bands (R, G, B) or one grey band, found 2"},
        {" --color-raster " + path("bytes.tif") + " --color-encoding linear", "expected linear albedo 0-1"},
        {" --color-raster " + path("rgb.tif") + " --albedo 0.3", "do not combine it with --albedo"},
        {" --color-raster " + path("rgb.tif") + " --albedo-raster " + path("rgb.tif"),
         "do not combine it with --albedo-raster"},
    };
    for (const auto& c : cases) {
        const auto r = runDemlight(base + c.args);
        EXPECT_EQ(r.exitCode, 1) << c.args;
        EXPECT_NE(r.err.find("--color-raster"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(path("out.tif"))) << c.args;
        const auto leftovers = std::distance(fs::directory_iterator(dir_), fs::directory_iterator{});
        EXPECT_EQ(leftovers, 3) << "only the three input rasters stay: " << c.args;
    }
}

// One --color-raster file for light and render: an 8-bit picture is display-encoded colour in
// both (--color-encoding auto), the same as its linear decoding given as floats.
TEST_F(OptionsCli, LightAndRenderTakeTheSameColourRaster) {
    const std::vector<float> bytes = {200.0f, 120.0f, 60.0f};
    std::vector<float> linear;
    for (float b : bytes) linear.push_back(static_cast<float>(std::pow(b / 255.0, 2.2)));
    writeConstantRaster(path("photo.tif"), kHelens, bytes);
    writeConstantRaster(path("linear.tif"), kHelens, linear);
    const std::string base = "-q light " + kHelens + " " + kLightArgs + " --sky-directions 4";
    run(base + " --color-raster " + path("photo.tif") + " -o " + path("photo_light.tif"));
    run(base + " --color-raster " + path("photo.tif") + " --color-encoding srgb -o " + path("srgb_light.tif"));
    run(base + " --color-raster " + path("linear.tif") + " -o " + path("linear_light.tif"));
    const auto photo = readRasterBands(path("photo_light.tif"));
    const auto srgb = readRasterBands(path("srgb_light.tif"));
    const auto lin = readRasterBands(path("linear_light.tif"));
    ASSERT_EQ(photo.size(), 3u);
    for (std::size_t c = 0; c < 3; ++c) {
        EXPECT_EQ(cellsDiffering(photo[c], srgb[c], 0.0f), 0u) << c;
        EXPECT_EQ(cellsDiffering(photo[c], lin[c], 1e-6f), 0u) << c;
    }
    run("-q render " + kHelens + " " + kLightArgs + " --sky-directions 4 --color-raster " + path("photo.tif") +
        " -o " + path("photo.png"));
    EXPECT_TRUE(fs::exists(path("photo.png")));
}

// --step takes durations in sunhours as in timelapse; a bare number keeps meaning minutes.
TEST_F(OptionsCli, SunhoursStepTakesDurations) {
    const std::string base = "-q sunhours " + kHelens + " --date 2024-06-21 --tz America/Los_Angeles --threads 2 --sky-directions 4";
    run(base + " --step 1h -o " + path("h.tif"));
    run(base + " --step 60 -o " + path("m.tif"));
    const auto a = readRasterBands(path("h.tif")), b = readRasterBands(path("m.tif"));
    ASSERT_EQ(a.size(), 5u);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(cellsDiffering(a[i], b[i], 0.0f), 0u) << i;
    EXPECT_EQ(inspectRaster(path("h.tif")).metadata.at("DEMLIGHT_STEP_MIN"), "60");
    run(base + " --step 10m -o " + path("ten.tif"));
    EXPECT_EQ(inspectRaster(path("ten.tif")).metadata.at("DEMLIGHT_INSTANTS"), "145");  // 24 h / 10 min + 1
    const auto bad = runDemlight(base + " --step 10x -o " + path("bad.tif"));
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("--step '10x'"), std::string::npos) << bad.err;
}

// A DEM inside a zip archive, read through GDAL's /vsizip/, lights as the file itself.
TEST_F(OptionsCli, VirtualPathsWork) {
    const std::string zip = path("dem.zip");
    ASSERT_EQ(std::system(("cd '" + dir_.string() + "' && cp '" + kHelens + "' helens.dem && python3 -m zipfile -c dem.zip helens.dem").c_str()), 0);
    const std::string args = " --time 2024-06-21T14:30Z --threads 2 -o ";
    run("-q sun /vsizip/" + zip + "/helens.dem" + args + path("zip.tif"));
    run("-q sun " + kHelens + args + path("file.tif"));
    const auto a = readRasterBands(path("zip.tif")), b = readRasterBands(path("file.tif"));
    ASSERT_EQ(a.size(), 2u);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(cellsDiffering(a[i], b[i], 0.0f), 0u) << i;
    const auto missing = runDemlight("-q sun /vsizip/" + zip + "/nothing.dem" + args + path("no.tif"));
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_NE(missing.err.find("nothing.dem"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace demlight
