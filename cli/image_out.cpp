// Picture output; see image_out.h.
#include "cli/image_out.h"

#include "src/error.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <filesystem>
#include <memory>
#include <unistd.h>

namespace demlight::cli {
namespace {

namespace fs = std::filesystem;

/// Gamma of display-encoded colour rasters (decoded to linear albedo).
constexpr double kDisplayGamma = 2.2;

std::string extensionOf(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::unique_ptr<OIIO::ImageOutput> createOutput(const std::string& path) {
    const std::string ext = extensionOf(path);
    if (ext.empty()) throw Error(path + ": the output needs an image extension (.png, .jpg, .exr, .gif)");
    auto out = OIIO::ImageOutput::create(ext);
    if (!out) throw Error(path + ": OpenImageIO cannot write '." + ext + "' files");
    return out;
}

/// A hidden temporary name beside `path`, so the rename stays on one file system.
fs::path tempPathFor(const std::string& path) {
    const fs::path p(path);
    return p.parent_path() / ("." + p.filename().string() + ".tmp" + std::to_string(::getpid()));
}

void commit(const fs::path& tmp, const std::string& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error(path + ": cannot write: rename failed");
    }
}

[[noreturn]] void fail(OIIO::ImageOutput& out, const fs::path& tmp, const std::string& path) {
    const std::string msg = out.geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write image: " + msg);
}

/// RGBA to RGB copy for formats without alpha.
std::vector<std::uint8_t> dropAlpha(const Image8& image) {
    std::vector<std::uint8_t> rgb(image.width * image.height * 3);
    for (std::size_t i = 0; i < image.width * image.height; ++i)
        std::copy_n(image.rgba.data() + 4 * i, 3, rgb.data() + 3 * i);
    return rgb;
}

}  // namespace

std::vector<Grid<float>> loadAlbedoRaster(const std::string& path, const Dem& dem,
                                          const std::string& option) {
    std::vector<Grid<float>> bands;
    try {
        bands = readRasterResampled(path, dem.band.ref, dem.terrain.width(), dem.terrain.height());
    } catch (const Error& e) {
        throw Error(option + " " + path + ": " + e.what());
    }
    if (bands.empty()) throw Error(option + " " + path + ": the raster has no bands");
    if (bands.size() < 3) bands = {bands[0], bands[0], bands[0]};
    bands.resize(3);
    float maxValue = 0;
    for (const auto& b : bands)
        for (float v : b.values())
            if (!std::isnan(v)) maxValue = std::max(maxValue, v);
    const double scale = maxValue > 1.0f ? 1.0 / 255.0 : 1.0;
    for (auto& b : bands)
        for (float& v : b.values())
            if (!std::isnan(v))
                v = static_cast<float>(std::pow(std::clamp(v * scale, 0.0, 1.0), kDisplayGamma));
    return bands;
}

void checkImagePath(const std::string& path) { createOutput(path); }

void writeImage(const std::string& path, const Image8& image) {
    auto out = createOutput(path);
    const bool alpha = out->supports("alpha");
    const int channels = alpha ? 4 : 3;
    OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), channels,
                         OIIO::TypeDesc::UINT8);
    if (alpha) spec.alpha_channel = 3;
    const fs::path tmp = tempPathFor(path);
    if (!out->open(tmp.string(), spec)) fail(*out, tmp, path);
    const std::vector<std::uint8_t> rgb = alpha ? std::vector<std::uint8_t>() : dropAlpha(image);
    const std::uint8_t* data = alpha ? image.rgba.data() : rgb.data();
    if (!out->write_image(OIIO::TypeDesc::UINT8, data) || !out->close()) fail(*out, tmp, path);
    commit(tmp, path);
}

void writeAnimatedGif(const std::string& path, const std::vector<Image8>& frames,
                      int framesPerSecond) {
    if (frames.empty()) throw Error(path + ": no frames to write");
    auto out = OIIO::ImageOutput::create("gif");
    if (!out) throw Error(path + ": this OpenImageIO cannot write GIF");
    if (!out->supports("multiimage") || !out->supports("appendsubimage"))
        throw Error(path + ": this OpenImageIO's GIF writer cannot write animations");
    // RGB frames: GIF transparency is one palette entry; nodata shows as neutral grey.
    std::vector<OIIO::ImageSpec> specs(
        frames.size(), OIIO::ImageSpec(static_cast<int>(frames[0].width),
                                       static_cast<int>(frames[0].height), 3, OIIO::TypeDesc::UINT8));
    const int fps[2] = {framesPerSecond, 1};
    for (auto& s : specs) {
        s.attribute("FramesPerSecond", OIIO::TypeRational, fps);
        s.attribute("oiio:LoopCount", 0);
        s.attribute("gif:LoopCount", 0);
    }
    const fs::path tmp = tempPathFor(path);
    if (!out->open(tmp.string(), static_cast<int>(specs.size()), specs.data())) fail(*out, tmp, path);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        if (i > 0 && !out->open(tmp.string(), specs[i], OIIO::ImageOutput::AppendSubimage))
            fail(*out, tmp, path);
        const std::vector<std::uint8_t> rgb = dropAlpha(frames[i]);
        if (!out->write_image(OIIO::TypeDesc::UINT8, rgb.data())) fail(*out, tmp, path);
    }
    if (!out->close()) fail(*out, tmp, path);
    commit(tmp, path);
}

}  // namespace demlight::cli
