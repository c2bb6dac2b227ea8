// demlight quicklook: the colour map, ticks and range as units; the command on the first band of
// every raster product's output, read back as a picture.
#include "cli_runner.h"
#include "demlight/geo/raster.h"
#include "demlight/products/quicklook.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;

struct Picture {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
    const std::uint8_t* at(int x, int y) const { return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
};

Picture readPicture(const std::string& path) {
    Picture p;
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        ADD_FAILURE() << path << ": " << OIIO::geterror();
        return p;
    }
    p.width = in->spec().width;
    p.height = in->spec().height;
    EXPECT_EQ(in->spec().nchannels, 4) << path;
    p.rgba.resize(static_cast<std::size_t>(p.width) * p.height * 4);
    EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, p.rgba.data()));
    return p;
}

TEST(Quicklook, ViridisEndsAndMiddleAreMatplotlibs) {
    // viridis(0), viridis(0.5), viridis(1) as matplotlib lists them: #440154, #21908C (its
    // 0.5 entry is #21918C; the nine-point table's middle is R's #21908C), #FDE725.
    EXPECT_EQ(viridis(0.0), (std::array<std::uint8_t, 3>{0x44, 0x01, 0x54}));
    EXPECT_EQ(viridis(0.5), (std::array<std::uint8_t, 3>{0x21, 0x90, 0x8C}));
    EXPECT_EQ(viridis(1.0), (std::array<std::uint8_t, 3>{0xFD, 0xE7, 0x25}));
    EXPECT_EQ(viridis(-3.0), viridis(0.0));
    EXPECT_EQ(viridis(7.0), viridis(1.0));
    // Perceptual order: lightness (Rec. 709 luma here) grows along the map.
    double last = -1;
    for (int i = 0; i <= 64; ++i) {
        const auto c = viridis(i / 64.0);
        const double luma = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        EXPECT_GT(luma, last) << "at " << i / 64.0;
        last = luma;
    }
}

TEST(Quicklook, TicksAreRoundAndInsideTheRange) {
    EXPECT_EQ(niceTicks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
    EXPECT_EQ(niceTicks(991.4, 2491.6, 5), (std::vector<double>{1000, 1500, 2000}));
    const std::vector<double> small = niceTicks(0.123, 0.129, 5);
    ASSERT_GE(small.size(), 3u);
    for (double t : small) EXPECT_TRUE(t >= 0.123 && t <= 0.129) << t;
}

TEST(Quicklook, RangeIsThePercentilesOfTheFiniteValues) {
    Grid<float> g(101, 1);
    for (std::size_t i = 0; i < 101; ++i) g(i, 0) = static_cast<float>(i);
    g(5, 0) = std::numeric_limits<float>::quiet_NaN();
    g(6, 0) = std::numeric_limits<float>::infinity();
    const auto r = quantileRange(g, 0.0, 1.0);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->first, 0);
    EXPECT_EQ(r->second, 100);
    EXPECT_FALSE(quantileRange(Grid<float>(3, 3, std::numeric_limits<float>::quiet_NaN()), 0.01, 0.99));
}

TEST(Quicklook, ColourBandAveragesFiniteCellsAndLeavesNodataTransparent) {
    Grid<float> g(4, 2, 0.0f);
    g(2, 0) = g(3, 0) = g(2, 1) = g(3, 1) = 1.0f;
    g(0, 1) = std::numeric_limits<float>::quiet_NaN();
    const Image8 img = colourBand(g, 0, 1, 2, 1);  // each pixel: a 2 x 2 block of cells
    ASSERT_EQ(img.rgba.size(), 8u);
    EXPECT_EQ(img.rgba[0], viridis(0)[0]);  // the NaN cell is left out of the mean, not read as 0
    EXPECT_EQ(img.rgba[3], 255);
    EXPECT_EQ(img.rgba[4], viridis(1)[0]);
    Grid<float> empty(2, 2, std::numeric_limits<float>::quiet_NaN());
    EXPECT_EQ(colourBand(empty, 0, 1, 2, 2).rgba[3], 0);
}

// Every raster product's output, and its first band drawn: a picture with the map's colours,
// transparent nodata, dark title text above the map and the bar beside it.
TEST(Quicklook, DrawsTheFirstBandOfEveryProduct) {
    const fs::path dir = fs::temp_directory_path() / ("demlight_quicklook_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    // The St Helens sample: its corners are nodata.
    const std::string dem = std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem";
    const std::string time = " --time 2024-06-21T14:00Z";
    const std::string day = " --date 2024-06-21 --tz UTC --step 2h";
    const auto out = [&](const std::string& name) { return " -o " + (dir / name).string(); };
    const std::vector<std::pair<std::string, std::string>> runs = {
        {"horizon.tif", "horizon " + dem + out("horizon.tif") + " --directions 2"},
        {"sun.tif", "sun " + dem + out("sun.tif") + time},
        {"sky.tif", "sky " + dem + out("sky.tif")},
        {"aperture.tif", "aperture " + dem + out("aperture.tif")},
        {"light.tif", "light " + dem + out("light.tif") + time},
        {"irradiance.tif", "irradiance " + dem + out("irradiance.tif") + time},
        {"insolation.tif", "insolation " + dem + out("insolation.tif") + day},
        {"sunhours.tif", "sunhours " + dem + out("sunhours.tif") + day},
        {"tl/sky_k.tif", "timelapse " + dem + out("tl") +
                             " --start 2024-06-21T14:00Z --end 2024-06-21T15:00Z --step 1h --formats tif --fit-degree 1"},
        {"sequence.tif", "sequence " + (dir / "tl" / "sequence_fit.tif").string() + out("sequence.tif") + time},
    };
    for (const auto& [file, run] : runs) {
        const auto made = testing::runDemlight("-q " + run);
        ASSERT_EQ(made.exitCode, 0) << run << "\n" << made.err;
        const std::string raster = (dir / file).string();
        const std::string png = raster + ".png";
        const auto looked = testing::runDemlight("-q quicklook " + raster + " -o " + png + " --size 200");
        ASSERT_EQ(looked.exitCode, 0) << file << "\n" << looked.err;
        const Picture p = readPicture(png);
        ASSERT_GT(p.width, 200) << file;  // the map's 200 pixels, the bar and its labels
        // The title: dark text in the top margin.
        int dark = 0;
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < p.width; ++x) dark += p.at(x, y)[0] < 128 ? 1 : 0;
        EXPECT_GT(dark, 50) << file << ": no title";
        // The map: every opaque pixel of its middle row is a viridis colour (blue channel of
        // viridis never falls below 0x25), and nodata cells (the DEM's own) are transparent.
        const RasterSummary s = inspectRaster(raster);
        EXPECT_FALSE(s.descriptions.empty());
        int opaque = 0, transparent = 0;
        for (int y = 60; y < p.height - 20; ++y)
            for (int x = 12; x < 212 && x < p.width; ++x) (p.at(x, y)[3] == 255 ? opaque : transparent) += 1;
        EXPECT_GT(opaque, 1000) << file;
        EXPECT_GT(transparent, 0) << file << ": the sample's nodata corner should be transparent";
    }
    // A band by its description, and one that is not there (the message lists the bands).
    EXPECT_EQ(testing::runDemlight("-q quicklook " + (dir / "sun.tif").string() + " --band sun_irradiance -o " +
                                   (dir / "b.png").string())
                  .exitCode,
              0);
    const auto missing =
        testing::runDemlight("-q quicklook " + (dir / "sun.tif").string() + " --band nope -o " + (dir / "c.png").string());
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_NE(missing.err.find("sun_visibility"), std::string::npos) << missing.err;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace demlight
