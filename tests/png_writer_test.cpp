// The libdeflate PNG encoder, decoded by an independent reader (OpenImageIO's libpng).
#include "demlight/geo/png_writer.h"
#include "demlight/core/error.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> readRgba(const std::string& path, int& width, int& height) {
    // PNG alpha is straight; keep OpenImageIO from premultiplying it.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    width = spec.width;
    height = spec.height;
    EXPECT_EQ(spec.nchannels, 4);
    EXPECT_EQ(spec.alpha_channel, 3);
    std::vector<std::uint8_t> px(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
    return px;
}

TEST(PngWriter, RoundTripsThroughAnIndependentDecoder) {
    const fs::path dir = fs::temp_directory_path() / "demlight_png_test";
    fs::create_directories(dir);
    std::mt19937 rng(3);
    // Noise (incompressible), smooth gradients with runs, and odd sizes; 700 x 500 spans several
    // IDAT chunks.
    for (const auto& [w, h] : {std::pair<std::size_t, std::size_t>{1, 1}, {3, 2}, {700, 500}}) {
        std::vector<std::uint8_t> rgba(w * h * 4);
        for (std::size_t i = 0; i < rgba.size(); ++i)
            rgba[i] = (i / 4) % 3 == 0 ? static_cast<std::uint8_t>(rng()) : static_cast<std::uint8_t>((i / (4 * w)) & 0xff);
        const std::string path = (dir / ("img" + std::to_string(w) + ".png")).string();
        writePngRgba(path, rgba, w, h);
        int rw = 0, rh = 0;
        const std::vector<std::uint8_t> back = readRgba(path, rw, rh);
        EXPECT_EQ(static_cast<std::size_t>(rw), w);
        EXPECT_EQ(static_cast<std::size_t>(rh), h);
        EXPECT_TRUE(back == rgba) << w << " x " << h;
    }
    fs::remove_all(dir);
}

/// CRC-32 (ISO 3309, as PNG uses it), bit by bit: independent of the encoder's libdeflate.
std::uint32_t bitwiseCrc32(const std::uint8_t* p, std::size_t n) {
    std::uint32_t c = 0xffffffffu;
    for (std::size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xffffffffu;
}

// libpng only warns on a bad CRC in IEND, so the round trip above cannot see it; strict readers
// (ImageMagick) refuse the file. Every chunk's CRC, IEND's included, must be right.
TEST(PngWriter, EveryChunkCarriesItsCrc) {
    const fs::path dir = fs::temp_directory_path() / "demlight_png_crc";
    fs::create_directories(dir);
    const std::string path = (dir / "crc.png").string();
    std::vector<std::uint8_t> rgba(37 * 11 * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<std::uint8_t>(i * 7);
    writePngRgba(path, rgba, 37, 11, {{"Creation Time", "2024-06-21T07:30:00-07:00"}, {"Comment", "frame 3"}});
    std::FILE* f = std::fopen(path.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    std::vector<std::uint8_t> bytes;
    for (int c; (c = std::fgetc(f)) != EOF;) bytes.push_back(static_cast<std::uint8_t>(c));
    std::fclose(f);
    auto u32 = [&](std::size_t at) {
        return (std::uint32_t{bytes[at]} << 24) | (std::uint32_t{bytes[at + 1]} << 16) |
               (std::uint32_t{bytes[at + 2]} << 8) | std::uint32_t{bytes[at + 3]};
    };
    std::size_t at = 8, chunks = 0;
    std::string last;
    std::vector<std::string> texts;
    while (at + 12 <= bytes.size()) {
        const std::uint32_t n = u32(at);
        ASSERT_LE(at + 12 + n, bytes.size());
        last.assign(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
        if (last == "tEXt") texts.emplace_back(reinterpret_cast<const char*>(&bytes[at + 8]), n);
        EXPECT_EQ(u32(at + 8 + n), bitwiseCrc32(&bytes[at + 4], 4 + n)) << "chunk " << last;
        at += 12 + n;
        ++chunks;
    }
    EXPECT_EQ(at, bytes.size());
    EXPECT_EQ(last, "IEND");
    EXPECT_GE(chunks, 5u);
    EXPECT_EQ(texts, (std::vector<std::string>{std::string("Creation Time\0", 14) + "2024-06-21T07:30:00-07:00",
                                               std::string("Comment\0", 8) + "frame 3"}));
    EXPECT_THROW(writePngRgba(path, rgba, 37, 11, {{"", "no keyword"}}), Error);
    fs::remove_all(dir);
}

TEST(PngWriter, RefusesBadSizesAndUnwritablePaths) {
    std::vector<std::uint8_t> rgba(16, 0);
    EXPECT_THROW(writePngRgba("/tmp/demlight_bad.png", rgba, 3, 2), Error);  // 16 != 3*2*4
    EXPECT_THROW(writePngRgba("/tmp/demlight_bad.png", rgba, 0, 4), Error);
    EXPECT_THROW(writePngRgba("/nonexistent-dir/x.png", rgba, 2, 2), Error);
}

}  // namespace
}  // namespace demlight
