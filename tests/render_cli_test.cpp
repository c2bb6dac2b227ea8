// End-to-end tests of `demlight render`, `timelapse` and `sunhours`: run the built binary
// (DEMLIGHT_CLI_PATH) on the Mount St Helens sample and check the pictures it writes.
#include "demlight/geo/raster.h"
#include "demlight/lighting/preview.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <limits>
#include <algorithm>
#include <cmath>
#include <utility>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::string kDem = std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem";
constexpr std::uint32_t kDemWidth = 327, kDemHeight = 468;

/// Runs `demlight -q ARGS`; returns the exit code, stderr appended to `err`.
int runCli(const std::string& args, std::string* err = nullptr) {
    const fs::path errPath = fs::temp_directory_path() / ("demlight_render_test_" + std::to_string(::getpid()) + ".err");
    const std::string cmd = std::string("'") + DEMLIGHT_CLI_PATH + "' -q " + args + " 2>'" +
                            errPath.string() + "'";
    const int status = std::system(cmd.c_str());
    if (err) {
        std::ifstream f(errPath);
        std::stringstream ss;
        ss << f.rdbuf();
        *err = ss.str();
    }
    fs::remove(errPath);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// A fresh scratch folder per test.
fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("demlight_render_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::vector<unsigned char> readFile(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

/// Whether two rasters' bands hold the same values: as many bands, of one shape, every cell
/// equal or NaN in both.
bool sameCells(const std::vector<demlight::Grid<float>>& a, const std::vector<demlight::Grid<float>>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k) {
        if (!a[k].sameShape(b[k])) return false;
        for (std::size_t i = 0; i < a[k].size(); ++i) {
            const float x = a[k].data()[i], y = b[k].data()[i];
            if (!(x == y || (std::isnan(x) && std::isnan(y)))) return false;
        }
    }
    return true;
}

std::uint32_t bigEndian32(const unsigned char* p) {
    return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

/// Checks the PNG signature and that the IHDR chunk gives the DEM's size.
void expectPngOfDemSize(const fs::path& p) {
    const auto bytes = readFile(p);
    ASSERT_GE(bytes.size(), 24u) << p;
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    EXPECT_TRUE(std::equal(signature, signature + 8, bytes.begin())) << p;
    EXPECT_EQ(std::string(bytes.begin() + 12, bytes.begin() + 16), "IHDR");
    EXPECT_EQ(bigEndian32(&bytes[16]), kDemWidth);
    EXPECT_EQ(bigEndian32(&bytes[20]), kDemHeight);
}

/// Pixels of a binary PPM (P6, maxval 255) as RGB bytes; width and height out.
std::vector<unsigned char> readPpm(const fs::path& p, std::uint32_t& w, std::uint32_t& h) {
    std::ifstream f(p, std::ios::binary);
    std::string magic;
    int maxval = 0;
    f >> magic >> w >> h >> maxval;
    f.get();
    std::vector<unsigned char> px(std::size_t(w) * h * 3);
    f.read(reinterpret_cast<char*>(px.data()), static_cast<std::streamsize>(px.size()));
    EXPECT_EQ(magic, "P6");
    EXPECT_EQ(maxval, 255);
    EXPECT_TRUE(f.good());
    return px;
}

// The rig's kernel: Quilez's numbers, gamma only at the end, night never black.
TEST(PreviewRig, FlatCellUnderFullSunIsLinearKeyPlusFills) {
    const demlight::PreviewParams p;
    const demlight::Enu up{0, 0, 1};
    const demlight::Rgb a{0.2, 0.2, 0.2};
    // Zenith sun, open sky: key 1.64 + sky 0.16 (bounce is horizontal: N.b = 0 on flat ground).
    const demlight::Rgb lin = demlight::previewRadiance(up, a, 1.0, 180.0, 90.0, 1.0, p);
    EXPECT_NEAR(lin.r, 0.2 * (1.64 + 0.16), 1e-9);
    EXPECT_NEAR(demlight::toDisplay(lin, p).r, std::pow(0.2 * 1.80, 1 / 2.2), 1e-9);
    // Half-visible sun: the penumbra goes red (blue falls fastest).
    const demlight::Rgb pen = demlight::previewRadiance(up, a, 0.5, 180.0, 90.0, 0.0, p);
    EXPECT_NEAR(pen.r / (0.2 * 1.64), 0.5, 1e-9);
    EXPECT_NEAR(pen.b / (0.2 * 0.99), std::pow(0.5, 1.5), 1e-9);
    // Deep night: only the twilight floor of the sky fill remains.
    const demlight::Rgb night = demlight::previewRadiance(up, a, 0.0, 0.0, -40.0, 1.0, p);
    EXPECT_NEAR(night.b, 0.2 * 0.28 * demlight::kNightSkyFloor, 1e-9);
    EXPECT_GT(demlight::toDisplay(night, p).b, 0.1);
}

// The per-pixel byte lookup renderPreview uses equals lround(255 * toDisplay) for any value,
// exposure and gamma, except within a rounding hair of a step (then by at most one).
TEST(PreviewRig, DisplayBytesMatchGammaAndRounding) {
    for (const auto& [exposure, gamma] : {std::pair{1.0, 2.2}, std::pair{1.7, 2.2}, std::pair{0.5, 1.8}}) {
        demlight::PreviewParams p;
        p.exposure = exposure;
        p.gamma = gamma;
        const demlight::DisplayBytes bytes(p);
        int exact = 0, total = 0;
        for (int i = 0; i <= 200000; ++i) {
            const double v = 3.0 * std::pow(i / 200000.0, 3.0);  // dense near 0, past white
            const double d = demlight::toDisplay({v, v, v}, p).r;
            const long ref = std::lround(std::clamp(d, 0.0, 1.0) * 255.0);
            ASSERT_LE(std::abs(static_cast<long>(bytes(v)) - ref), 1) << v;
            exact += bytes(v) == ref;
            ++total;
        }
        EXPECT_GE(exact, total - 2) << exposure << " " << gamma;
        EXPECT_EQ(bytes(0.0), 0);
        EXPECT_EQ(bytes(1e9), 255);
        // Exactly at each step (the header's thresholds ((k + 1/2) / 255)^gamma / exposure): the
        // byte is k + 1 there and k just below, as upper_bound over the thresholds gives.
        for (int k = 0; k < 255; ++k) {
            const double t = std::pow((k + 0.5) / 255.0, gamma) / exposure;
            ASSERT_EQ(bytes(t), k + 1) << k;
            ASSERT_EQ(bytes(std::nextafter(t, 0.0)), k) << k;
        }
    }
}

// The byte is std::upper_bound over the header's thresholds for every double, whichever way
// DisplayBytes finds it (its bucket table, or its binary search where the table is not kept):
// at, just below and just above each threshold, at the table's bucket edges around them, on a
// dense sweep of magnitudes, and at zero, negatives, denormals, infinity and NaN. The settings
// include ones where the table is kept (gamma 0.15: two thresholds share some buckets) and ones
// where it cannot be (exposure 0; gamma 0.1 and 0.05: three or more share a bucket; gamma 40:
// the thresholds span too many buckets).
TEST(PreviewRig, DisplayBytesIsUpperBoundOverTheThresholdsForEveryValue) {
    const std::pair<double, double> settings[] = {{1.0, 2.2}, {1.7, 2.2}, {0.5, 1.8}, {1.0, 1.0}, {2.5, 2.2},
                                                  {1.0, 0.15}, {1.0, 0.1}, {1.0, 0.05}, {1.0, 40.0}, {0.0, 2.2},
                                                  {1e-3, 3.0}};
    for (const auto& [exposure, gamma] : settings) {
        demlight::PreviewParams p;
        p.exposure = exposure;
        p.gamma = gamma;
        const demlight::DisplayBytes bytes(p);
        std::vector<double> t(255);
        for (int k = 0; k < 255; ++k) t[static_cast<std::size_t>(k)] = std::pow((k + 0.5) / 255.0, gamma) / exposure;
        const auto expected = [&](double v) {
            return static_cast<long>(std::upper_bound(t.begin(), t.end(), v) - t.begin());
        };
        std::vector<double> values = {0.0, -0.0, -1.0, -1e-300, 4.9e-324, 1e-310, 1e-300, 1e300,
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(),
                                      std::numeric_limits<double>::max()};
        constexpr int shift = 52 - demlight::DisplayBytes::kTableMantissaBits;
        for (const double th : t) {
            values.insert(values.end(), {th, std::nextafter(th, 0.0), std::nextafter(th, 1e308)});
            // The first double of th's bucket, the last of the one before, and the next bucket's.
            const std::uint64_t key = std::bit_cast<std::uint64_t>(th) >> shift;
            for (const std::uint64_t edge : {key << shift, (key + 1) << shift})
                values.insert(values.end(), {std::bit_cast<double>(edge), std::bit_cast<double>(edge - 1)});
        }
        for (int i = -4000; i <= 400; ++i) values.push_back(std::pow(10.0, i / 100.0));
        for (const double v : values) ASSERT_EQ(static_cast<long>(bytes(v)), expected(v)) << v << " " << exposure << " " << gamma;
        EXPECT_EQ(bytes(std::numeric_limits<double>::quiet_NaN()), 255);
        EXPECT_EQ(bytes(-std::numeric_limits<double>::quiet_NaN()), 255);
    }
}

// renderPreview's assembly of a picture: per pixel the rig's radiance (previewRadiance, checked
// against Quilez's numbers above) of that cell's normal, visibility, sky light and albedo (the
// raster's, or the flat one where the raster has NaN), its display byte by the definition
// (upper_bound over the thresholds ((k + 1/2) / 255)^gamma / exposure, not DisplayBytes), RGBA
// in that order with alpha 255, and kNodataGrey with alpha 0 where the normal, visibility or sky
// light is nodata. Random normals, visibilities inside and outside [0, 1] and in the penumbra,
// suns by day and in twilight, display settings with and without DisplayBytes' table.
TEST(PreviewRig, RenderedPixelsAreThePerPixelRig) {
    const std::size_t w = 37, h = 11;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    demlight::Normals n{demlight::Grid<float>(w, h), demlight::Grid<float>(w, h), demlight::Grid<float>(w, h)};
    demlight::Grid<float> vis(w, h), sky(w, h);
    std::vector<demlight::Grid<float>> albedo(3, demlight::Grid<float>(w, h));
    for (std::size_t k = 0; k < w * h; ++k) {
        double e = u(rng), no = u(rng), up = 0.2 + unit(rng);
        const double len = std::sqrt(e * e + no * no + up * up);
        n.east.data()[k] = static_cast<float>(e / len);
        n.north.data()[k] = static_cast<float>(no / len);
        n.up.data()[k] = k % 29 == 3 ? nan : static_cast<float>(up / len);
        const float visChoices[] = {0.0f, 1.0f, static_cast<float>(unit(rng)), -0.25f, 1.5f, -0.0f};
        vis.data()[k] = k % 31 == 5 ? nan : visChoices[k % 6];
        sky.data()[k] = k % 37 == 7 ? nan : static_cast<float>(1.2 * unit(rng) - 0.1);
        // NaN in one channel at a time (any one makes the pixel take the flat albedo).
        for (std::size_t c = 0; c < 3; ++c) albedo[c].data()[k] = k % 23 == 2 + 5 * c ? nan : static_cast<float>(unit(rng));
    }
    const std::pair<double, double> suns[] = {{135.0, 40.0}, {250.0, 2.0}, {80.0, -5.0}, {10.0, -30.0}};
    const std::pair<double, double> displays[] = {{1.0, 2.2}, {1.0, 0.15}, {1.0, 0.05}, {2.5, 2.2}};
    for (const auto& [azimuth, elevation] : suns) {
        for (const auto& [exposure, gamma] : displays) {
            for (const bool raster : {false, true}) {
                SCOPED_TRACE(std::to_string(azimuth) + " " + std::to_string(elevation) + " " + std::to_string(gamma) +
                             (raster ? " raster" : ""));
                demlight::PreviewParams p;
                p.exposure = exposure;
                p.gamma = gamma;
                const std::vector<demlight::Grid<float>> a = raster ? albedo : std::vector<demlight::Grid<float>>{};
                const demlight::Image8 img = demlight::renderPreview(n, vis, sky, a, azimuth, elevation, p);
                std::vector<double> thresholds(255);
                for (int k = 0; k < 255; ++k)
                    thresholds[static_cast<std::size_t>(k)] = std::pow((k + 0.5) / 255.0, gamma) / exposure;
                const auto bytes = [&](double v) {
                    return static_cast<long>(std::upper_bound(thresholds.begin(), thresholds.end(), v) -
                                             thresholds.begin());
                };
                for (std::size_t row = 0; row < h; ++row) {
                    for (std::size_t col = 0; col < w; ++col) {
                        const std::uint8_t* px = img.rgba.data() + (row * w + col) * 4;
                        const demlight::Enu nc = n.at(col, row);
                        if (std::isnan(nc.up) || std::isnan(vis(col, row)) || std::isnan(sky(col, row))) {
                            EXPECT_EQ(px[3], 0);
                            EXPECT_EQ(px[0], demlight::kNodataGrey);
                            continue;
                        }
                        demlight::Rgb al{p.albedo, p.albedo, p.albedo};
                        if (raster && !std::isnan(albedo[0](col, row)) && !std::isnan(albedo[1](col, row)) &&
                            !std::isnan(albedo[2](col, row)))
                            al = {albedo[0](col, row), albedo[1](col, row), albedo[2](col, row)};
                        const demlight::Rgb lin =
                            demlight::previewRadiance(nc, al, vis(col, row), azimuth, elevation, sky(col, row), p);
                        ASSERT_EQ(px[0], bytes(lin.r)) << col << " " << row;
                        ASSERT_EQ(px[1], bytes(lin.g)) << col << " " << row;
                        ASSERT_EQ(px[2], bytes(lin.b)) << col << " " << row;
                        ASSERT_EQ(px[3], 255);
                    }
                }
            }
        }
    }
}

TEST(RenderCli, DayPngHasTheDemSize) {
    const fs::path d = scratch("day");
    std::string err;
    ASSERT_EQ(runCli("render '" + kDem + "' -o '" + (d / "day.png").string() +
                         "' --time 2024-06-21T09:00 --tz America/Los_Angeles",
                     &err),
              0)
        << err;
    expectPngOfDemSize(d / "day.png");
    fs::remove_all(d);
}

// Pictures other than PNG go through libdemlight_oiio.so, loaded from demlight's own folder on
// first use: a JPEG is written with it beside the binary; a binary copied away from it still
// writes PNG, and for a JPEG says which file it needs.
TEST(RenderCli, PicturePluginLoadsFromTheBinarysFolder) {
    const fs::path d = scratch("plugin");
    const std::string args = " --time 2024-06-21T09:00 --tz America/Los_Angeles";
    std::string err;
    ASSERT_EQ(runCli("render '" + kDem + "' -o '" + (d / "day.jpg").string() + "'" + args, &err), 0) << err;
    std::ifstream jpeg(d / "day.jpg", std::ios::binary);
    unsigned char magic[3] = {0, 0, 0};
    jpeg.read(reinterpret_cast<char*>(magic), 3);
    EXPECT_TRUE(magic[0] == 0xFF && magic[1] == 0xD8 && magic[2] == 0xFF) << "not a JPEG";

    const fs::path alone = d / "alone";
    fs::create_directories(alone);
    // The launcher and the program it runs, without the plugin beside them.
    fs::copy_file(DEMLIGHT_CLI_PATH, alone / "demlight");
    fs::copy_file(fs::path(DEMLIGHT_CLI_PATH).parent_path() / "demlight-core", alone / "demlight-core");
    const auto run = [&](const std::string& out) {
        // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on "'" + std::string.
        std::string cmd = "'";
        cmd += (alone / "demlight").string();
        cmd += "' -q render '" + kDem + "' -o '";
        cmd += (d / out).string();
        cmd += "'" + args + " 2>'";
        cmd += (d / "err.txt").string();
        cmd += "'";
        const int status = std::system(cmd.c_str());
        std::ifstream f(d / "err.txt");
        std::stringstream ss;
        ss << f.rdbuf();
        err = ss.str();
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    EXPECT_EQ(run("alone.png"), 0) << err;
    expectPngOfDemSize(d / "alone.png");
    EXPECT_NE(run("alone.jpg"), 0);
    EXPECT_NE(err.find("libdemlight_oiio.so"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(d / "alone.jpg"));
    fs::remove_all(d);
}

// Guards "never black noise at night": twilight sky fill keeps the relief visible and smooth.
TEST(RenderCli, NightImageIsNotBlack) {
    const fs::path d = scratch("night");
    std::string err;
    ASSERT_EQ(runCli("render '" + kDem + "' -o '" + (d / "night.ppm").string() +
                         "' --time 2024-06-21T23:30 --tz America/Los_Angeles",
                     &err),
              0)
        << err;
    std::uint32_t w = 0, h = 0;
    const auto px = readPpm(d / "night.ppm", w, h);
    ASSERT_EQ(w, kDemWidth);
    ASSERT_EQ(h, kDemHeight);
    // Valid cells: not the neutral nodata grey. Every one must be visibly above black.
    std::size_t valid = 0, dark = 0;
    for (std::size_t i = 0; i < px.size(); i += 3) {
        if (px[i] == 128 && px[i + 1] == 128 && px[i + 2] == 128) continue;
        ++valid;
        if (px[i] + px[i + 1] + px[i + 2] < 15) ++dark;
    }
    EXPECT_GT(valid, std::size_t(w) * h / 2);
    EXPECT_EQ(dark, 0u);
    fs::remove_all(d);
}

// Frames, previews and the GIF: sizes match the DEM (GIF logical screen, little endian).
TEST(TimelapseCli, WritesFramesPreviewsAndGif) {
    const fs::path d = scratch("timelapse");
    std::string err;
    ASSERT_EQ(runCli("timelapse '" + kDem + "' -o '" + (d / "out").string() +
                         "' --start 2024-06-21T06:00 --end 2024-06-21T07:00 --step 30m "
                         "--tz America/Los_Angeles --sky-directions 4",
                     &err),
              0)
        << err;
    for (const char* f : {"frame_000.tif", "frame_001.tif", "frame_002.tif", "frame_003.tif"})
        EXPECT_EQ(fs::exists(d / "out" / f), std::string(f) != "frame_003.tif") << f;
    EXPECT_TRUE(fs::exists(d / "out" / "sky_k.tif"));
    expectPngOfDemSize(d / "out" / "frame_002.png");
    const auto gif = readFile(d / "out" / "timelapse.gif");
    ASSERT_GE(gif.size(), 10u);
    EXPECT_EQ(std::string(gif.begin(), gif.begin() + 3), "GIF");
    EXPECT_EQ(gif[6] | (gif[7] << 8), int(kDemWidth));
    EXPECT_EQ(gif[8] | (gif[9] << 8), int(kDemHeight));
    fs::remove_all(d);
}

// A frame's sun bands equal `demlight sun` at the same instant (same driver, same sweeps).
TEST(TimelapseCli, FramesMatchDemlightSun) {
    const fs::path d = scratch("tlsun");
    std::string err;
    ASSERT_EQ(runCli("timelapse '" + kDem + "' -o '" + (d / "out").string() +
                         "' --start 2024-06-21T07:30:00-07:00 --end 2024-06-21T07:30:00-07:00 "
                         "--formats tif --sky-directions 4",
                     &err),
              0)
        << err;
    ASSERT_EQ(runCli("sun '" + kDem + "' -o '" + (d / "sun.tif").string() +
                         "' --time 2024-06-21T07:30:00-07:00",
                     &err),
              0)
        << err;
    const demlight::RasterBand ref = demlight::readRasterBand(kDem);
    const auto frame = demlight::readRasterResampled((d / "out" / "frame_000.tif").string(), ref.ref,
                                                     kDemWidth, kDemHeight);
    const auto sun = demlight::readRasterResampled((d / "sun.tif").string(), ref.ref, kDemWidth, kDemHeight);
    ASSERT_EQ(frame.size(), 2u);  // sun_visibility, sun_irradiance as `sun` (sky_k.tif once)
    ASSERT_EQ(sun.size(), 2u);
    EXPECT_EQ(demlight::inspectRaster((d / "out" / "frame_000.tif").string()).descriptions,
              (std::vector<std::string>{"sun_visibility", "sun_irradiance"}));
    std::size_t compared = 0;
    for (std::size_t k = 0; k < frame[0].size(); ++k) {
        const float fi = frame[1].data()[k], si = sun[1].data()[k];
        const float fv = frame[0].data()[k], sv = sun[0].data()[k];
        if (std::isnan(si) || std::isnan(fi)) {
            EXPECT_EQ(std::isnan(si), std::isnan(fi)) << k;
            continue;
        }
        ++compared;
        ASSERT_NEAR(fi, si, 1e-5) << k;  // irradiance
        ASSERT_NEAR(fv, sv, 1e-5) << k;  // visibility
    }
    EXPECT_GT(compared, frame[0].size() / 2);
    fs::remove_all(d);
}

// Night frames after the first are written as copies of its file with their own metadata
// (FrameWriter): each must hold what encoding it would have, its own frame number, times and sun
// in its metadata, and the frames' cells; a day frame after them is encoded (its cells differ).
TEST(TimelapseCli, NightFramesCopiedHoldTheirOwnMetadataAndTheCells) {
    const fs::path d = scratch("tlnight");
    std::string err;
    // 02:00-05:40 local: eleven frames with the sun far below the horizon, then dawn.
    ASSERT_EQ(runCli("timelapse '" + kDem + "' -o '" + (d / "out").string() +
                         "' --start 2024-06-21T02:00 --end 2024-06-21T06:00 --step 20m "
                         "--tz America/Los_Angeles --formats tif --sky-directions 4",
                     &err),
              0)
        << err;
    // The frames' instants and suns from frames.csv.
    std::ifstream csv(d / "out" / "frames.csv");
    std::string line;
    std::getline(csv, line);
    std::vector<std::vector<std::string>> rows;
    while (std::getline(csv, line)) {
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
        rows.push_back(f);
    }
    ASSERT_EQ(rows.size(), 13u);
    const auto frameFile = [&](std::size_t i) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%03zu.tif", i);
        return (d / "out" / name).string();
    };
    const std::vector<demlight::Grid<float>> first = demlight::readRasterBands(frameFile(0));
    const demlight::RasterSummary s0 = demlight::inspectRaster(frameFile(0));
    std::size_t sameAsFirst = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const demlight::RasterSummary s = demlight::inspectRaster(frameFile(i));
        EXPECT_EQ(s.metadata.at("DEMLIGHT_FRAME"), std::to_string(i));
        EXPECT_EQ(s.metadata.at("DEMLIGHT_TIME_LOCAL"), rows[i][1]) << i;
        EXPECT_EQ(s.metadata.at("DEMLIGHT_TIME_UTC"), rows[i][2]) << i;
        EXPECT_EQ(s.metadata.at("DEMLIGHT_SUN_AZIMUTH_DEG"), rows[i][3]) << i;
        EXPECT_EQ(s.metadata.at("DEMLIGHT_SUN_ELEVATION_DEG"), rows[i][4]) << i;
        EXPECT_EQ(s.descriptions, s0.descriptions);
        EXPECT_EQ(s.units, s0.units);
        EXPECT_EQ(s.nodata, s0.nodata);
        EXPECT_EQ(s.ref.geoTransform, s0.ref.geoTransform);
        EXPECT_EQ(s.imageStructure, s0.imageStructure);
        const std::vector<demlight::Grid<float>> bands = demlight::readRasterBands(frameFile(i));
        ASSERT_EQ(bands.size(), 2u);
        const bool same = sameCells(bands, first);
        sameAsFirst += same;
        // A copy's TIFF directory follows its tiles (GDAL rewrote it at the end); an encoded
        // frame's comes first. Classic little-endian TIFF: the first directory's offset at byte 4.
        const std::vector<unsigned char> bytes = readFile(frameFile(i));
        ASSERT_GT(bytes.size(), 8u);
        std::uint32_t ifd = 0;
        std::memcpy(&ifd, bytes.data() + 4, sizeof ifd);
        if (std::stod(rows[i][4]) < -15.0) {
            EXPECT_TRUE(same) << "night frame " << i;
            EXPECT_EQ(ifd < bytes.size() / 2, i == 0) << "night frame " << i << " written by copy unless the first";
        }
    }
    EXPECT_GE(sameAsFirst, 9u);
    EXPECT_LT(sameAsFirst, rows.size());  // dawn: the last frames are lit
    // A night frame alone (so encoded) is the copied frame's file but for the command and number.
    ASSERT_EQ(runCli("timelapse '" + kDem + "' -o '" + (d / "one").string() +
                         "' --start 2024-06-21T03:00 --end 2024-06-21T03:00 "
                         "--tz America/Los_Angeles --formats tif --sky-directions 4",
                     &err),
              0)
        << err;
    demlight::RasterSummary alone = demlight::inspectRaster((d / "one" / "frame_000.tif").string());
    demlight::RasterSummary copied = demlight::inspectRaster(frameFile(3));
    for (auto* m : {&alone.metadata, &copied.metadata}) {
        m->erase("DEMLIGHT_COMMAND");
        m->erase("DEMLIGHT_FRAME");
    }
    EXPECT_EQ(copied.metadata, alone.metadata);
    EXPECT_TRUE(sameCells(demlight::readRasterBands((d / "one" / "frame_000.tif").string()),
                          demlight::readRasterBands(frameFile(3))));
    // Only the outputs are left in the folder: no temporary file, no GDAL sidecar.
    for (const auto& e : fs::directory_iterator(d / "out")) {
        const std::string n = e.path().filename().string();
        EXPECT_TRUE((n.starts_with("frame_") && n.ends_with(".tif")) || n == "sky_k.tif" || n == "frames.csv") << n;
    }
    fs::remove_all(d);
}

// --co reaches every GeoTIFF of a time-lapse, the night frames written as copies included, and
// changes how they are stored, not what they hold; an option GDAL does not list fails before
// any work, leaving no folder.
TEST(TimelapseCli, CreationOptionsReachEveryGeoTiffAndABadOneFailsFirst) {
    const fs::path d = scratch("tlco");
    std::string err;
    const std::string run = "timelapse '" + kDem + "' --start 2024-06-21T02:00 --end 2024-06-21T06:00 --step 1h "
                            "--tz America/Los_Angeles --formats tif --sky-directions 4 -o '";
    ASSERT_EQ(runCli(run + (d / "co").string() + "' -co COMPRESS=DEFLATE -co PREDICTOR=1", &err), 0) << err;
    ASSERT_EQ(runCli(run + (d / "default").string() + "'", &err), 0) << err;
    std::size_t tifs = 0;
    for (const auto& e : fs::directory_iterator(d / "co")) {
        if (e.path().extension() != ".tif") continue;
        ++tifs;
        const demlight::RasterSummary s = demlight::inspectRaster(e.path().string());
        EXPECT_EQ(s.imageStructure.at("COMPRESSION"), "DEFLATE") << e.path();
        EXPECT_EQ(s.imageStructure.count("PREDICTOR"), 0u) << e.path();
        EXPECT_TRUE(sameCells(demlight::readRasterBands(e.path().string()),
                              demlight::readRasterBands((d / "default" / e.path().filename()).string())))
            << e.path();
    }
    EXPECT_EQ(tifs, 6u);  // sky_k.tif and five frames
    EXPECT_EQ(demlight::inspectRaster((d / "default" / "frame_001.tif").string()).imageStructure.at("COMPRESSION"),
              "ZSTD");
    EXPECT_NE(runCli(run + (d / "bad").string() + "' -co NO_SUCH_OPTION=1", &err), 0);
    EXPECT_NE(err.find("NO_SUCH_OPTION"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(d / "bad"));
    fs::remove_all(d);
}

// Bands, names and plausible values of a summer day on the sample.
TEST(SunhoursCli, WritesFiveBands) {
    const fs::path d = scratch("sunhours");
    std::string err;
    ASSERT_EQ(runCli("sunhours '" + kDem + "' -o '" + (d / "sh.tif").string() +
                         "' --date 2024-06-21 --tz America/Los_Angeles --step 30",
                     &err),
              0)
        << err;
    const demlight::RasterSummary s = demlight::inspectRaster((d / "sh.tif").string());
    EXPECT_EQ(s.descriptions,
              (std::vector<std::string>{"sun_hours", "sun_irradiation", "sky_irradiation", "first_lit", "last_lit"}));
    EXPECT_EQ(s.metadata.at("DEMLIGHT_STEP_MIN"), "30");
    const demlight::RasterBand ref = demlight::readRasterBand(kDem);
    const auto b = demlight::readRasterResampled((d / "sh.tif").string(), ref.ref, kDemWidth, kDemHeight);
    const std::size_t centre = (kDemHeight / 2) * kDemWidth + kDemWidth / 2;
    EXPECT_GT(b[0].data()[centre], 8.0f);   // hours of sun on the volcano in June
    EXPECT_LT(b[0].data()[centre], 15.6f);  // at most the astronomical day (sunrise 05:17, sunset 20:47)
    EXPECT_GT(b[2].data()[centre], 0.0f);   // some sky light over the day
    EXPECT_GT(b[3].data()[centre], 5.0f);   // first lit after local sunrise
    EXPECT_LT(b[4].data()[centre], 21.0f);  // last lit before local sunset
    fs::remove_all(d);
}

TEST(TimelapseCli, BadStepNamesTheOption) {
    const fs::path d = scratch("badstep");
    std::string err;
    EXPECT_NE(runCli("timelapse '" + kDem + "' -o '" + (d / "out").string() +
                         "' --start 2024-06-21T06:00Z --end 2024-06-21T07:00Z --step 5x",
                     &err),
              0);
    EXPECT_NE(err.find("--step"), std::string::npos) << err;
    fs::remove_all(d);
}

TEST(LightCli, OneBandOrThreeWithColours) {
    const fs::path d = scratch("light");
    std::string err;
    const std::string base = "light '" + kDem + "' --time 2024-06-21T09:00 --tz America/Los_Angeles "
                             "--sky-directions 4 -o '";
    ASSERT_EQ(runCli(base + (d / "l1.tif").string() + "'", &err), 0) << err;
    const demlight::RasterSummary one = demlight::inspectRaster((d / "l1.tif").string());
    EXPECT_EQ(one.width, kDemWidth);
    EXPECT_EQ(one.height, kDemHeight);
    EXPECT_EQ(one.descriptions, std::vector<std::string>{"light"});
    ASSERT_EQ(runCli(base + (d / "l3.tif").string() + "' --sun-color 1,0.9,0.8", &err), 0) << err;
    EXPECT_EQ(demlight::inspectRaster((d / "l3.tif").string()).descriptions,
              (std::vector<std::string>{"light_r", "light_g", "light_b"}));
    fs::remove_all(d);
}

TEST(RenderCli, TimeWithoutZoneFailsNamingIt) {
    const fs::path d = scratch("nozone");
    std::string err;
    EXPECT_NE(runCli("render '" + kDem + "' -o '" + (d / "x.png").string() + "' --time 2024-06-21T09:00", &err), 0);
    EXPECT_NE(err.find("zone"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(d / "x.png"));
    fs::remove_all(d);
}

TEST(RenderCli, UnknownImageExtensionFails) {
    const fs::path d = scratch("ext");
    std::string err;
    EXPECT_NE(runCli("render '" + kDem + "' -o '" + (d / "x.nosuchformat").string() +
                         "' --time 2024-06-21T09:00Z",
                     &err),
              0);
    EXPECT_NE(err.find("nosuchformat"), std::string::npos) << err;
    fs::remove_all(d);
}

}  // namespace
