// End-to-end: `render` and `timelapse` follow the scene plan of --quality / --tolerance / -v.
// Each is checked against a command whose plan wiring is independent of theirs: a timelapse
// frame must hold exactly the bands `sun` and `sky` write under the same options, and a render
// must be exactly the timelapse preview of the same instant. A command that ignored the plan
// would fail these (auto and full differ in sky directions, distances and the sun lattice).
#include "cli_runner.h"
#include "demlight/geo/raster.h"
#include "demlight/lighting/quality.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;
using testing::runDemlight;

const std::string kRocky = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";
const std::string kTime = "2024-06-21T08:00-06:00";

fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("demlight_quality_cli_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::vector<char> fileBytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

/// A PNG's bytes without its tEXt chunks (each chunk: 4-byte length, type, data, CRC).
std::vector<char> withoutTextChunks(const std::vector<char>& png) {
    const auto u32 = [&](std::size_t at) {
        return (std::uint32_t{static_cast<std::uint8_t>(png[at])} << 24) |
               (std::uint32_t{static_cast<std::uint8_t>(png[at + 1])} << 16) |
               (std::uint32_t{static_cast<std::uint8_t>(png[at + 2])} << 8) | std::uint32_t{static_cast<std::uint8_t>(png[at + 3])};
    };
    std::vector<char> out(png.begin(), png.begin() + std::min<std::size_t>(8, png.size()));
    for (std::size_t at = 8; at + 12 <= png.size();) {
        const std::size_t n = u32(at);
        if (std::string(&png[at + 4], 4) != "tEXt") out.insert(out.end(), png.begin() + at, png.begin() + at + 12 + n);
        at += 12 + n;
    }
    return out;
}

/// Same shape and the same value (or both NaN) in every cell.
bool sameGrid(const Grid<float>& a, const Grid<float>& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const float x = a.data()[i], y = b.data()[i];
        if (!(x == y || (std::isnan(x) && std::isnan(y)))) return false;
    }
    return true;
}

/// Runs `timelapse` for the one instant kTime with `options`; returns the frame's path.
fs::path timelapseFrame(const fs::path& dir, const std::string& options) {
    const auto r = runDemlight("-q timelapse " + kRocky + " -o " + dir.string() + " --start " + kTime + " --end " +
                               kTime + " --formats tif,png " + options);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return dir / "frame_000.tif";
}

TEST(QualityCli, TimelapseFramesHoldTheSunAndSkyOfTheSamePlan) {
    const fs::path d = scratch("timelapse");
    std::vector<Grid<float>> skyK;
    for (const std::string options : {"--quality auto", "--quality full", "--tolerance 5"}) {
        SCOPED_TRACE(options);
        const fs::path dir = d / std::to_string(skyK.size());
        const fs::path frame = timelapseFrame(dir, options);
        const std::string sun = (dir / "sun.tif").string(), sky = (dir / "sky.tif").string();
        auto r = runDemlight("-q sun " + kRocky + " -o " + sun + " --time " + kTime + " " + options);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = runDemlight("-q sky " + kRocky + " -o " + sky + " " + options);
        ASSERT_EQ(r.exitCode, 0) << r.err;

        RasterSummary summary;
        const std::vector<Grid<float>> f = readRasterBands(frame.string(), &summary);
        const std::vector<Grid<float>> s = readRasterBands(sun), k = readRasterBands(sky);
        ASSERT_EQ(f.size(), 2u);  // sun_visibility, sun_irradiance: the order of `sun`
        EXPECT_EQ(summary.descriptions, (std::vector<std::string>{"sun_visibility", "sun_irradiance"}));
        EXPECT_TRUE(sameGrid(f[0], s[0])) << "sun_visibility differs from `sun`";
        EXPECT_TRUE(sameGrid(f[1], s[1])) << "sun_irradiance differs from `sun`";
        const std::vector<Grid<float>> frameSky = readRasterBands((frame.parent_path() / "sky_k.tif").string());
        ASSERT_EQ(frameSky.size(), 1u);  // sky_k, once for all frames
        EXPECT_TRUE(sameGrid(frameSky[0], k[2])) << "sky_k differs from `sky`'s sky_K";
        skyK.push_back(frameSky[0]);

        const auto& meta = summary.metadata;
        const bool full = options == "--quality full";
        EXPECT_EQ(meta.at("DEMLIGHT_QUALITY"), full ? "full" : "auto");
        EXPECT_EQ(meta.at("DEMLIGHT_SKY_DIRECTIONS"), std::to_string(full ? kFullSkyDirections : kAutoSkyDirections));
        EXPECT_NE(meta.at("DEMLIGHT_EXPECTED_ERROR_DEG").find("median"), std::string::npos);
        EXPECT_NE(meta.at("DEMLIGHT_PLAN").find("sky_directions="), std::string::npos);
        // Rocky Mountain: 56 km search; the curvature drop 0.22 deg is above a tenth of the
        // default 0.1 deg tolerance and below a tenth of 5 deg.
        EXPECT_EQ(meta.at("DEMLIGHT_CURVATURE"), options == "--tolerance 5" ? "off" : "on");
    }
    EXPECT_FALSE(sameGrid(skyK[0], skyK[1])) << "auto and full gave the same sky";
    EXPECT_FALSE(sameGrid(skyK[0], skyK[2])) << "--tolerance 5 (curvature off) gave the default sky";
}

// A time-lapse draws a night picture once and gives it to the following frames while their
// visibility cells and sky scale stay the same (the sun's direction then adds nothing): from
// deep night into twilight, where the sky scale starts to change, every frame's picture must
// still be `render`'s at its instant.
TEST(QualityCli, TimelapseNightPicturesAreTheRendersOfTheirInstants) {
    const fs::path d = scratch("nightpictures");
    const std::vector<std::string> times = {"2024-06-21T01:00-06:00", "2024-06-21T02:30-06:00",
                                            "2024-06-21T03:40-06:00", "2024-06-21T04:10-06:00",
                                            "2024-06-21T04:40-06:00"};
    // Every 10 minutes from 01:00 to 04:40: the sun from -26 to -8 deg at the sample (twilight
    // from -12 deg, frame 19 on).
    const auto r = runDemlight("-q timelapse " + kRocky + " -o " + (d / "tl").string() + " --start " + times.front() +
                               " --end " + times.back() + " --step 10m --formats png");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const std::string& time : times) {
        SCOPED_TRACE(time);
        const fs::path png = d / ("render_" + time.substr(11, 2) + time.substr(14, 2) + ".png");
        const auto rr = runDemlight("-q render " + kRocky + " -o " + png.string() + " --time " + time);
        ASSERT_EQ(rr.exitCode, 0) << rr.err;
        const int minutes = (std::stoi(time.substr(11, 2)) - 1) * 60 + std::stoi(time.substr(14, 2));
        char frame[32];
        std::snprintf(frame, sizeof frame, "frame_%03d.png", minutes / 10);
        EXPECT_EQ(withoutTextChunks(fileBytes(png)), withoutTextChunks(fileBytes(d / "tl" / frame)));
    }
    // The night's pictures are one picture, and twilight's are brighter ones.
    EXPECT_EQ(withoutTextChunks(fileBytes(d / "tl" / "frame_000.png")), withoutTextChunks(fileBytes(d / "tl" / "frame_009.png")));
    EXPECT_NE(withoutTextChunks(fileBytes(d / "tl" / "frame_000.png")), withoutTextChunks(fileBytes(d / "tl" / "frame_022.png")));
    // A repeated picture is compressed once; each file still carries its own instant.
    const std::vector<char> repeated = fileBytes(d / "tl" / "frame_009.png");
    EXPECT_NE(std::search(repeated.begin(), repeated.end(), times[1].begin(), times[1].begin() + 16), repeated.end())
        << "frame 9's text does not name 02:30";
    fs::remove_all(d);
}

TEST(QualityCli, RenderIsTheTimelapsePreviewOfTheSamePlan) {
    const fs::path d = scratch("render");
    std::vector<std::vector<char>> pictures;
    for (const std::string quality : {"auto", "full"}) {
        SCOPED_TRACE(quality);
        const fs::path png = d / (quality + ".png");
        const auto r = runDemlight("render " + kRocky + " -o " + png.string() + " --time " + kTime +
                                   " --quality " + quality + " -v");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        // -v prints the plan; the closing note says what was used.
        const std::string directions = std::to_string(quality == "full" ? kFullSkyDirections : kAutoSkyDirections);
        EXPECT_NE(r.err.find("scene plan (--quality " + quality + ")"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("sky_directions=" + directions), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("expected horizon error: median"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(directions + " sky directions"), std::string::npos) << r.err;

        timelapseFrame(d / ("tl_" + quality), "--quality " + quality);
        pictures.push_back(fileBytes(png));
        // The frame's PNG also carries its time (tEXt chunks); the pictures are the same.
        EXPECT_EQ(withoutTextChunks(pictures.back()), withoutTextChunks(fileBytes(d / ("tl_" + quality) / "frame_000.png")))
            << "render differs from the timelapse preview";
    }
    EXPECT_NE(pictures[0], pictures[1]) << "auto and full gave the same picture";

    // Without -v nothing of the plan is printed.
    const auto r = runDemlight("render " + kRocky + " -o " + (d / "quiet.png").string() + " --time " + kTime);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("scene plan"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace demlight
