// libdemlight_oiio.so: picture output through OpenImageIO; see oiio_plugin.h.
#include "cli/plugin/oiio_plugin.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

namespace {

constexpr int kVersion = 1;

int failWith(const std::string& message, char* err, std::size_t errSize) {
    if (err && errSize > 0) {
        const std::size_t n = std::min(message.size(), errSize - 1);
        std::memcpy(err, message.data(), n);
        err[n] = '\0';
    }
    return 1;
}

struct Gif {
    std::unique_ptr<OIIO::ImageOutput> out;
    OIIO::ImageSpec spec;
    std::string path;
    int fps = 10;
    bool open = false;
};

}  // namespace

extern "C" {

int demlight_oiio_version() { return kVersion; }

int demlight_oiio_check(const char* ext, int* alpha, char* err, std::size_t errSize) {
    auto out = OIIO::ImageOutput::create(ext);
    if (!out) return failWith(std::string("OpenImageIO cannot write '.") + ext + "' files", err, errSize);
    if (alpha) *alpha = out->supports("alpha") ? 1 : 0;
    return 0;
}

int demlight_oiio_write(const char* path, const char* ext, const std::uint8_t* pixels, std::size_t width,
                        std::size_t height, int channels, char* err, std::size_t errSize) {
    auto out = OIIO::ImageOutput::create(ext);
    if (!out) return failWith(std::string("OpenImageIO cannot write '.") + ext + "' files", err, errSize);
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), channels, OIIO::TypeDesc::UINT8);
    if (channels == 4) spec.alpha_channel = 3;
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels) || !out->close())
        return failWith(out->geterror(), err, errSize);
    return 0;
}

void* demlight_oiio_gif_open(const char* path, int framesPerSecond, char* err, std::size_t errSize) {
    auto gif = std::make_unique<Gif>();
    gif->out = OIIO::ImageOutput::create("gif");
    if (!gif->out) {
        failWith("this OpenImageIO cannot write GIF", err, errSize);
        return nullptr;
    }
    if (!gif->out->supports("appendsubimage")) {
        failWith("this OpenImageIO's GIF writer cannot write animations", err, errSize);
        return nullptr;
    }
    gif->path = path;
    gif->fps = framesPerSecond;
    return gif.release();
}

int demlight_oiio_gif_add(void* handle, const std::uint8_t* rgb, std::size_t width, std::size_t height, char* err,
                          std::size_t errSize) {
    Gif& gif = *static_cast<Gif*>(handle);
    if (!gif.open) {
        gif.spec = OIIO::ImageSpec(static_cast<int>(width), static_cast<int>(height), 3, OIIO::TypeDesc::UINT8);
        const int fps[2] = {gif.fps, 1};
        gif.spec.attribute("FramesPerSecond", OIIO::TypeRational, fps);
        gif.spec.attribute("oiio:LoopCount", 0);
        if (!gif.out->open(gif.path, gif.spec)) return failWith(gif.out->geterror(), err, errSize);
        gif.open = true;
    } else {
        if (static_cast<int>(width) != gif.spec.width || static_cast<int>(height) != gif.spec.height)
            return failWith("GIF frames differ in size", err, errSize);
        if (!gif.out->open(gif.path, gif.spec, OIIO::ImageOutput::AppendSubimage))
            return failWith(gif.out->geterror(), err, errSize);
    }
    if (!gif.out->write_image(OIIO::TypeDesc::UINT8, rgb)) return failWith(gif.out->geterror(), err, errSize);
    return 0;
}

int demlight_oiio_gif_close(void* handle, char* err, std::size_t errSize) {
    Gif& gif = *static_cast<Gif*>(handle);
    if (!gif.open) return failWith("no frames to write", err, errSize);
    gif.open = false;
    if (!gif.out->close()) return failWith(gif.out->geterror(), err, errSize);
    return 0;
}

void demlight_oiio_gif_free(void* handle) {
    auto* gif = static_cast<Gif*>(handle);
    if (!gif) return;
    if (gif->open) gif->out->close();
    delete gif;
}
}
