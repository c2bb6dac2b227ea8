// libdemlight_oiio.so: picture output through OpenImageIO; see oiio_plugin.h.
#include "demlight/geo/plugin/oiio_plugin.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr int kVersion = 3;

/// The font of demlight_oiio_text_size and _draw_text: Debian's fonts-dejavu-core.
constexpr const char* kFont = "DejaVuSans";
constexpr const char* kFontMissing =
    "OpenImageIO cannot draw text in DejaVu Sans (install Debian's fonts-dejavu-core)";

int failWith(const std::string& message, char* err, std::size_t errSize) {
    if (err && errSize > 0) {
        const std::size_t n = std::min(message.size(), errSize - 1);
        std::memcpy(err, message.data(), n);
        err[n] = '\0';
    }
    return 1;
}

/// The RGB channels of an RGBA image, for formats without alpha.
std::vector<std::uint8_t> rgbOf(const std::uint8_t* rgba, std::size_t width, std::size_t height) {
    std::vector<std::uint8_t> rgb(width * height * 3);
    for (std::size_t i = 0; i < width * height; ++i) std::copy_n(rgba + 4 * i, 3, rgb.data() + 3 * i);
    return rgb;
}

/// Empty when `path` reads back whole as a `width` x `height` picture, else why not.
std::string readBackProblem(const char* path, std::size_t width, std::size_t height) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return OIIO::geterror().empty() ? std::string("cannot open it") : OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    if (static_cast<std::size_t>(spec.width) != width || static_cast<std::size_t>(spec.height) != height)
        return "its size is " + std::to_string(spec.width) + " x " + std::to_string(spec.height);
    std::vector<std::uint8_t> pixels(width * height * static_cast<std::size_t>(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data())) {
        const std::string e = in->geterror();
        return e.empty() ? std::string("its pixels cannot be read") : e;
    }
    return {};
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

int demlight_oiio_check(const char* ext, char* err, std::size_t errSize) {
    if (!OIIO::ImageOutput::create(ext))
        return failWith(std::string("OpenImageIO cannot write '.") + ext + "' files", err, errSize);
    return 0;
}

int demlight_oiio_write(const char* path, const char* ext, const std::uint8_t* rgba, std::size_t width,
                        std::size_t height, char* err, std::size_t errSize) {
    auto out = OIIO::ImageOutput::create(ext);
    if (!out) return failWith(std::string("OpenImageIO cannot write '.") + ext + "' files", err, errSize);
    const bool alpha = out->supports("alpha");
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), alpha ? 4 : 3, OIIO::TypeDesc::UINT8);
    if (alpha) spec.alpha_channel = 3;
    const std::vector<std::uint8_t> rgb = alpha ? std::vector<std::uint8_t>() : rgbOf(rgba, width, height);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, alpha ? rgba : rgb.data()) ||
        !out->close())
        return failWith(out->geterror(), err, errSize);
    // Some of OpenImageIO's writers (GIF, through giflib) do not check their writes or fclose: a
    // file cut short by a full disk or a file size limit is reported as written. Reading the
    // whole picture back is what tells.
    const std::string unreadable = readBackProblem(path, width, height);
    if (!unreadable.empty()) return failWith("the file written is unreadable (" + unreadable + ")", err, errSize);
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

int demlight_oiio_gif_add(void* handle, const std::uint8_t* rgba, std::size_t width, std::size_t height, char* err,
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
    const std::vector<std::uint8_t> rgb = rgbOf(rgba, width, height);
    if (!gif.out->write_image(OIIO::TypeDesc::UINT8, rgb.data())) return failWith(gif.out->geterror(), err, errSize);
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

int demlight_oiio_text_size(const char* text, int sizePx, int* x0, int* y0, int* x1, int* y1, char* err,
                            std::size_t errSize) {
    const OIIO::ROI box = OIIO::ImageBufAlgo::text_size(text, sizePx, kFont);
    if (!box.defined()) return failWith(kFontMissing, err, errSize);
    *x0 = box.xbegin;
    *y0 = box.ybegin;
    *x1 = box.xend;
    *y1 = box.yend;
    return 0;
}

int demlight_oiio_draw_text(std::uint8_t* image, std::size_t width, std::size_t height, int x, int y, const char* text,
                            int sizePx, const std::uint8_t* rgba, char* err, std::size_t errSize) {
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 4, OIIO::TypeDesc::UINT8);
    spec.alpha_channel = 3;
    OIIO::ImageBuf buffer(spec, image);  // wraps the caller's pixels: drawn in place
    const float colour[4] = {rgba[0] / 255.0f, rgba[1] / 255.0f, rgba[2] / 255.0f, rgba[3] / 255.0f};
    if (!OIIO::ImageBufAlgo::render_text(buffer, x, y, text, sizePx, kFont, colour)) {
        const std::string why = buffer.geterror();
        return failWith(why.empty() ? std::string(kFontMissing) : kFontMissing + std::string(": ") + why, err, errSize);
    }
    return 0;
}
}
