// Pictures: single images (PNG natively; JPEG, EXR, ... chosen by
// extension, through the OpenImageIO plugin, demlight/geo/oiio_loader.h)
// and animated GIFs. Files are written under a temporary name and renamed on success.
#pragma once

#include "demlight/geo/png_writer.h"
#include "demlight/core/image.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace demlight {

/// Fails early if `path`'s extension names no format demlight can write.
void checkImagePath(const std::string& path);

/// Writes an 8-bit RGBA image; formats without alpha (JPEG) get RGB (nodata shows as the
/// neutral grey the renderer put there). Throws Error naming the path on failure.
void writeImage(const std::string& path, const Image8& image);

/// The PNG pixel data of `image`, for the writeImage below: a picture written under several
/// names (a time-lapse's repeated night picture) is compressed once.
PngPixels encodePng(const Image8& image);

/// writeImage of a PNG (`path` ends in .png) whose pixels encodePng compressed, with `text` as
/// its tEXt chunks.
void writeImage(const std::string& path, const PngPixels& pixels,
                const std::vector<std::pair<std::string, std::string>>& text);

/// Streams an animated GIF frame by frame (so long sequences of big frames never sit in
/// memory together). Written under a temporary name; finish() renames it into place, and
/// destruction without finish() removes it.
class GifWriter {
public:
    GifWriter(std::string path, int framesPerSecond);
    ~GifWriter();
    GifWriter(const GifWriter&) = delete;
    GifWriter& operator=(const GifWriter&) = delete;
    /// Adds a frame; every frame must have the first frame's size. Alpha is dropped (GIF keeps RGB).
    void add(const Image8& frame);
    void finish();
    std::size_t frames() const { return frames_; }

private:
    struct Impl;
    std::string path_;
    int fps_;
    std::size_t frames_ = 0;
    std::unique_ptr<Impl> impl_;
};

/// Where text drawn by drawText lies, relative to the left end of its baseline (pixels; y down:
/// y0 < 0 is above the baseline).
struct TextBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
};

/// The box of `text` (UTF-8) drawn `sizePx` pixels high in DejaVu Sans, through the OpenImageIO
/// plugin. Throws Error when the plugin or the font (Debian's fonts-dejavu-core) is missing.
TextBox measureText(const std::string& text, int sizePx);

/// Draws `text` over `image` in colour `rgba`, composited over what is there, the left end of
/// its baseline at (x, y). Throws Error as measureText.
void drawText(Image8& image, int x, int y, const std::string& text, int sizePx, const std::array<std::uint8_t, 4>& rgba);

/// Box-filtered copy of `image` whose longer side is at most maxSide pixels (integer factor;
/// returned unchanged when already small enough). Transparent pixels are left out of the mean.
Image8 downsample(const Image8& image, std::size_t maxSide);

}  // namespace demlight
