// Square ground pixels for previews (demlight/lighting/preview.h toGroundPixels): the size rule, area
// averaging when shrinking, linear interpolation when stretching, nodata kept transparent, and
// square-cell grids left byte for byte as they were.
#include "demlight/lighting/preview.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace demlight {
namespace {

/// A flat terrain of cols x rows cells, each widthM east-west by heightM north-south (a lat/lon
/// grid away from the equator has widthM < heightM).
Terrain cellTerrain(std::size_t cols, std::size_t rows, double widthM, double heightM) {
    Terrain t = makeUniformTerrain(Grid<float>(cols, rows, 0.0f), heightM);
    t.cellWidthM.assign(rows, widthM);
    return t;
}

Image8 filled(std::size_t w, std::size_t h, std::array<std::uint8_t, 4> px) {
    Image8 img;
    img.width = w;
    img.height = h;
    img.rgba.resize(w * h * 4);
    for (std::size_t i = 0; i < w * h; ++i)
        for (int k = 0; k < 4; ++k) img.rgba[i * 4 + static_cast<std::size_t>(k)] = px[static_cast<std::size_t>(k)];
    return img;
}

const std::uint8_t* pixel(const Image8& img, std::size_t col, std::size_t row) {
    return img.rgba.data() + (row * img.width + col) * 4;
}

TEST(GroundPixels, WidthFollowsTheMiddleRowsCellShape) {
    struct Case {
        std::size_t cols, rows;
        double widthM, heightM;
        std::size_t expectedWidth;
    };
    const std::vector<Case> cases = {
        {40, 10, 30, 60, 20},    // 2:1 tall cells (about 60 deg N): half as wide
        {40, 10, 60, 30, 80},    // 1:2 wide cells: twice as wide
        {2401, 1201, 60.0, 92.4, 1559},  // a 1/1200 x 1/1200 deg tile at 49 N: 144 x 111 km
        {3, 4, 1, 100, 1},       // never narrower than one pixel
        {7, 3, 30, 30, 7},       // square cells: unchanged
    };
    for (const auto& c : cases) {
        const Terrain t = cellTerrain(c.cols, c.rows, c.widthM, c.heightM);
        const Image8 out = toGroundPixels(filled(c.cols, c.rows, {10, 20, 30, 255}), t);
        EXPECT_EQ(out.width, c.expectedWidth) << c.cols << " x " << c.rows;
        EXPECT_EQ(out.height, c.rows);
        EXPECT_EQ(out.rgba.size(), out.width * out.height * 4);
    }
    // Only the middle row decides: the others may differ (rows of a lat/lon DEM do).
    Terrain t = cellTerrain(40, 11, 30, 60);
    t.cellWidthM[0] = 60;
    t.cellWidthM[10] = 10;
    EXPECT_EQ(toGroundPixels(filled(40, 11, {1, 2, 3, 255}), t).width, 20u);
}

TEST(GroundPixels, SquareCellsLeaveThePictureByteForByte) {
    std::mt19937 rng(7);
    Image8 img = filled(33, 21, {0, 0, 0, 0});
    for (auto& b : img.rgba) b = static_cast<std::uint8_t>(rng());
    // Nearly square cells round to the same width too (Rocky Mountain's 233.6 x 234.3 m).
    for (const double widthM : {25.0, 233.6}) {
        const double heightM = widthM == 25.0 ? 25.0 : 234.3;
        const Image8 out = toGroundPixels(img, cellTerrain(33, 21, widthM, heightM));
        EXPECT_EQ(out.width, img.width);
        EXPECT_EQ(out.height, img.height);
        EXPECT_EQ(out.rgba, img.rgba);
    }
}

TEST(GroundPixels, AUniformColourStaysUniform) {
    for (const double widthM : {30.0, 45.0, 60.0, 77.0, 120.0}) {  // shrink 2x .. stretch 2x
        const Terrain t = cellTerrain(61, 5, widthM, 60.0);
        const Image8 out = toGroundPixels(filled(61, 5, {200, 101, 7, 255}), t);
        for (std::size_t r = 0; r < out.height; ++r)
            for (std::size_t c = 0; c < out.width; ++c) {
                const std::uint8_t* p = pixel(out, c, r);
                ASSERT_EQ(p[0], 200);
                ASSERT_EQ(p[1], 101);
                ASSERT_EQ(p[2], 7);
                ASSERT_EQ(p[3], 255) << "width " << widthM << " at " << c;
            }
    }
}

TEST(GroundPixels, ShrinkingAveragesByArea) {
    // Alternating black and white columns halved: every pixel is the mean, 127.5 -> 128.
    Image8 img = filled(40, 2, {0, 0, 0, 255});
    for (std::size_t r = 0; r < 2; ++r)
        for (std::size_t c = 1; c < 40; c += 2)
            for (int k = 0; k < 3; ++k) img.rgba[(r * 40 + c) * 4 + static_cast<std::size_t>(k)] = 255;
    const Image8 out = toGroundPixels(img, cellTerrain(40, 2, 30, 60));
    ASSERT_EQ(out.width, 20u);
    for (std::size_t c = 0; c < out.width; ++c) EXPECT_EQ(pixel(out, c, 1)[0], 128) << c;
    // By a third: 3 input pixels per 1; output 0 covers columns 0 (black), 1 (white), 2 (black).
    const Image8 third = toGroundPixels(img, cellTerrain(40, 2, 20, 60));
    ASSERT_EQ(third.width, 13u);  // round(40 / 3)
    // 40/13 input pixels per output: column 0 covers [0, 3.077): 0, 1, 2 whole, 3 (white) 0.077.
    EXPECT_EQ(pixel(third, 0, 0)[0], static_cast<int>(std::lround(255 * (1 + 0.0769230769) / (40.0 / 13))));
}

TEST(GroundPixels, StretchingInterpolatesBetweenPixelCentres) {
    // Two pixels, black and white, stretched 4x: centres of the outer output pixels sit before
    // the first input centre (clamped), the middle ones ramp.
    Image8 img = filled(2, 1, {0, 0, 0, 255});
    for (int k = 0; k < 3; ++k) img.rgba[4 + static_cast<std::size_t>(k)] = 255;
    const Image8 out = toGroundPixels(img, cellTerrain(2, 1, 120, 30));
    ASSERT_EQ(out.width, 8u);
    // Output j samples input x = (j + 0.5) / 4 - 0.5.
    const int expected[8] = {0, 0, 32, 96, 159, 223, 255, 255};
    for (std::size_t j = 0; j < 8; ++j) EXPECT_EQ(pixel(out, j, 0)[0], expected[j]) << j;
}

TEST(GroundPixels, NodataStaysTransparent) {
    for (const double widthM : {30.0, 120.0}) {  // shrinking and stretching
        // Columns 20..39 of 60 are nodata (grey, alpha 0), the rest a colour.
        Image8 img = filled(60, 3, {40, 80, 120, 255});
        for (std::size_t r = 0; r < 3; ++r)
            for (std::size_t c = 20; c < 40; ++c) {
                std::uint8_t* p = img.rgba.data() + (r * 60 + c) * 4;
                p[0] = p[1] = p[2] = kNodataGrey;
                p[3] = 0;
            }
        const Image8 out = toGroundPixels(img, cellTerrain(60, 3, widthM, 60));
        const double scale = 60.0 / static_cast<double>(out.width);  // input px per output px
        for (std::size_t c = 0; c < out.width; ++c) {
            // The input span the pixel reads (with its interpolation neighbours when stretching).
            const double lo = std::max(0.0, (static_cast<double>(c) + 0.5) * scale - 0.5 - 1);
            const double hi = (static_cast<double>(c) + 0.5) * scale + 0.5 + 1;
            const std::uint8_t* p = pixel(out, c, 1);
            if (lo >= 20 && hi <= 40) {
                EXPECT_EQ(p[3], 0) << "inside the void: " << c;
                EXPECT_EQ(p[0], kNodataGrey) << c;
            } else if (hi <= 20 || lo >= 40) {
                EXPECT_EQ(p[3], 255) << "away from the void: " << c;
            }
            if (p[3] != 0) {  // partly covered edge pixels keep the colour, not a grey blend
                EXPECT_EQ(p[0], 40) << c;
                EXPECT_EQ(p[2], 120) << c;
            }
        }
    }
}

TEST(GroundPixels, RefusesAPictureOfAnotherSize) {
    EXPECT_THROW(toGroundPixels(filled(10, 5, {0, 0, 0, 255}), cellTerrain(10, 6, 30, 60)), Error);
    EXPECT_THROW(toGroundPixels(filled(11, 5, {0, 0, 0, 255}), cellTerrain(10, 5, 30, 60)), Error);
}

/// The header's rule written out per channel, one pixel at a time: each output pixel's input
/// columns and weights (area covered when shrinking, linear between centres when stretching), the
/// colour averaged over the opaque ones, alpha over all, each rounded half away from zero.
std::array<std::uint8_t, 4> referencePixel(const Image8& img, std::size_t row, std::size_t j, std::size_t outWidth) {
    const std::size_t inWidth = img.width;
    const double scale = static_cast<double>(inWidth) / static_cast<double>(outWidth);
    std::vector<std::pair<std::size_t, double>> taps;
    if (outWidth < inWidth) {
        const double a = static_cast<double>(j) * scale, b = static_cast<double>(j + 1) * scale;
        for (std::size_t k = static_cast<std::size_t>(std::floor(a)); k < inWidth && static_cast<double>(k) < b; ++k) {
            const double w = std::min(static_cast<double>(k + 1), b) - std::max(static_cast<double>(k), a);
            if (w > 0) taps.emplace_back(k, w);
        }
    } else {
        const double x = std::clamp((static_cast<double>(j) + 0.5) * scale - 0.5, 0.0, static_cast<double>(inWidth - 1));
        const auto k0 = static_cast<std::size_t>(std::floor(x));
        const std::size_t k1 = std::min(k0 + 1, inWidth - 1);
        const double t = x - static_cast<double>(k0);
        if (1.0 - t > 0) taps.emplace_back(k0, 1.0 - t);
        if (k1 != k0 && t > 0) taps.emplace_back(k1, t);
    }
    double colour[3] = {0, 0, 0}, alpha = 0, opaque = 0, all = 0;
    for (const auto& [k, w] : taps) {
        const std::uint8_t* p = pixel(img, k, row);
        all += w;
        if (p[3] == 0) continue;
        for (int c = 0; c < 3; ++c) colour[c] += w * p[c];
        alpha += w * p[3];
        opaque += w;
    }
    if (opaque == 0) return {kNodataGrey, kNodataGrey, kNodataGrey, 0};
    auto byte = [](double v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L)); };
    return {byte(colour[0] / opaque), byte(colour[1] / opaque), byte(colour[2] / opaque), byte(alpha / all)};
}

// Every pixel of random pictures (random colours, alpha, and transparent runs) shrunk and
// stretched by several factors is the rule's per-channel answer, byte for byte: the resampler
// works on the four channels at once and must round each as lround does, halves up.
TEST(GroundPixels, EveryPixelIsTheRulesPerChannelAnswer) {
    std::mt19937 rng(20261204);
    std::uniform_int_distribution<int> byte(0, 255), coin(0, 9);
    for (const double widthM : {9.0, 20.0, 29.0, 30.0 * 2.0 / 3.0, 41.0, 60.0, 75.0, 133.0}) {
        Image8 img = filled(97, 6, {0, 0, 0, 255});
        for (std::size_t i = 0; i < 97 * 6; ++i) {
            std::uint8_t* p = img.rgba.data() + i * 4;
            for (int k = 0; k < 4; ++k) p[k] = static_cast<std::uint8_t>(byte(rng));
            if (coin(rng) == 0) p[3] = 0;                               // scattered nodata
            if (i % 97 >= 40 && i % 97 < 47) p[3] = 0;                  // a transparent run
            if (coin(rng) == 1) p[0] = p[1] = p[2] = (i % 2) ? 255 : 0;  // halves between neighbours
        }
        const Image8 out = toGroundPixels(img, cellTerrain(97, 6, widthM, 30));
        for (std::size_t r = 0; r < 6; ++r)
            for (std::size_t j = 0; j < out.width; ++j) {
                const auto want = referencePixel(img, r, j, out.width);
                for (int k = 0; k < 4; ++k)
                    ASSERT_EQ(pixel(out, j, r)[k], want[static_cast<std::size_t>(k)])
                        << "width " << widthM << " row " << r << " col " << j << " channel " << k;
            }
    }
}

}  // namespace
}  // namespace demlight
