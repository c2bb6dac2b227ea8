// A fast PNG encoder for large 8-bit RGBA pictures (time-lapse previews, renders): filter type 0
// rows compressed in one zlib stream by libdeflate at level 1. On a 3601 x 3601 preview that is
// about 0.17 s and a file ~10 % smaller than libpng's adaptive filters with zlib level 1 through
// OpenImageIO (0.45-0.6 s). Any PNG reader decodes it (tests/png_writer_test.cpp reads it back
// through OpenImageIO).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace demlight {

/// A picture's PNG pixel data: its rows, filtered (type 0) and compressed into one zlib stream.
/// Written under several names with their own text, a picture that repeats is compressed once
/// (time-lapse night frames).
struct PngPixels {
    std::size_t width = 0, height = 0;
    std::vector<std::uint8_t> zlib;
};

/// The PNG pixel data of `rgba` (width * height * 4 bytes, rows top to bottom, straight alpha).
/// Throws Error, its message starting with `path` (the file, or what the picture is), when the
/// size is invalid.
PngPixels compressPngRgba(const std::string& path, std::span<const std::uint8_t> rgba, std::size_t width,
                          std::size_t height);

/// Writes `pixels` to `path` as an 8-bit RGBA PNG, with `text` as tEXt chunks (keyword 1-79
/// printable Latin-1 characters, text without NUL). Throws Error when the file cannot be written
/// or a keyword is invalid.
void writePng(const std::string& path, const PngPixels& pixels,
              const std::vector<std::pair<std::string, std::string>>& text = {});

/// Writes `rgba` (width * height * 4 bytes, rows top to bottom, straight alpha) to `path` as an
/// 8-bit RGBA PNG, with `text` as tEXt chunks (keyword 1-79 printable Latin-1 characters, text
/// without NUL). Throws Error when the file cannot be written, the size or a keyword is invalid.
void writePngRgba(const std::string& path, std::span<const std::uint8_t> rgba, std::size_t width,
                  std::size_t height, const std::vector<std::pair<std::string, std::string>>& text = {});

}  // namespace demlight
