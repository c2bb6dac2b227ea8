// The C interface of libdemlight_oiio.so, the OpenImageIO side of picture output (JPEG, EXR,
// TIFF, GIF, ... by extension; PNG does not need it). demlight loads it with dlopen on the first
// picture that needs it (demlight/geo/oiio_loader.cpp): OpenImageIO pulls in many shared libraries that
// every process would map at start-up, whether it writes a picture or not
// (docs/measurements.md#clicmakeliststxt-and-geopluginoiio_pluginh-demlight_oiio).
// Every function returns 0 on success; on failure it writes a message into err (errSize bytes,
// NUL-terminated) and returns nonzero.
#pragma once

#include <cstddef>
#include <cstdint>

extern "C" {

/// Bumped whenever a signature below changes; the loader refuses a plugin of another version.
int demlight_oiio_version();

/// Whether OpenImageIO can write files with extension `ext` (lower case, no dot).
int demlight_oiio_check(const char* ext, char* err, std::size_t errSize);

/// Writes an 8-bit RGBA image to `path` in the format of `ext`; formats without alpha get RGB.
int demlight_oiio_write(const char* path, const char* ext, const std::uint8_t* rgba, std::size_t width,
                        std::size_t height, char* err, std::size_t errSize);

/// Animated GIF: open (returns a handle or null), add RGBA frames (all of the first one's size;
/// alpha is dropped), close (completes the file), free (discards an unclosed one).
void* demlight_oiio_gif_open(const char* path, int framesPerSecond, char* err, std::size_t errSize);
int demlight_oiio_gif_add(void* gif, const std::uint8_t* rgba, std::size_t width, std::size_t height, char* err,
                          std::size_t errSize);
int demlight_oiio_gif_close(void* gif, char* err, std::size_t errSize);
void demlight_oiio_gif_free(void* gif);

/// Text in the DejaVu Sans font (Debian's fonts-dejavu-core), `sizePx` pixels high, UTF-8.
/// text_size: the box of `text` drawn at (0, 0) with its baseline's left end there (x0 <= 0 < x1,
/// y0 < 0 above the baseline, y1 below it).
int demlight_oiio_text_size(const char* text, int sizePx, int* x0, int* y0, int* x1, int* y1, char* err,
                            std::size_t errSize);
/// draw_text: draws `text` over an 8-bit RGBA image in place, the baseline's left end at (x, y),
/// in colour `rgba` (4 bytes), composited over what is there.
int demlight_oiio_draw_text(std::uint8_t* image, std::size_t width, std::size_t height, int x, int y, const char* text,
                            int sizePx, const std::uint8_t* rgba, char* err, std::size_t errSize);
}
