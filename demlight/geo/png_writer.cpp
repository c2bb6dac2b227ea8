// PNG encoder; see png_writer.h. Chunk layout from the PNG specification (ISO/IEC 15948):
// signature, IHDR, IDAT..., IEND; each chunk is length, type, data, CRC-32 of type and data.
#include "demlight/geo/png_writer.h"

#include "demlight/core/error.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

namespace demlight {
namespace {

/// libdeflate level: 1 is its fastest, and already smaller than zlib's level 1.
constexpr int kCompressionLevel = 1;
/// IDAT chunks are cut at this many bytes (any size up to 2^31 - 1 is valid; moderate chunks
/// suit streaming readers).
constexpr std::size_t kIdatChunkBytes = 1 << 20;

void putU32(std::uint8_t* p, std::uint32_t v) {
    p[0] = static_cast<std::uint8_t>(v >> 24);
    p[1] = static_cast<std::uint8_t>(v >> 16);
    p[2] = static_cast<std::uint8_t>(v >> 8);
    p[3] = static_cast<std::uint8_t>(v);
}

struct FileCloser {
    void operator()(std::FILE* f) const {
        if (f) std::fclose(f);
    }
};

/// The reason a stdio call on `path` failed, from errno ("No space left on device").
std::string failure(const std::string& path, const char* what) {
    return path + ": " + what + " (" + std::strerror(errno) + ")";
}

class ChunkWriter {
public:
    ChunkWriter(std::FILE* f, const std::string& path) : f_(f), path_(path) {}

    void raw(const void* data, std::size_t n) {
        if (n > 0 && std::fwrite(data, 1, n, f_) != n) throw Error(failure(path_, "cannot write PNG"));
    }

    void chunk(const char type[4], const std::uint8_t* data, std::size_t n) {
        std::uint8_t head[8];
        putU32(head, static_cast<std::uint32_t>(n));
        std::memcpy(head + 4, type, 4);
        std::uint32_t crc = libdeflate_crc32(0, head + 4, 4);
        if (n > 0) crc = libdeflate_crc32(crc, data, n);  // a NULL buffer would restart the CRC at 0
        std::uint8_t tail[4];
        putU32(tail, crc);
        raw(head, 8);
        raw(data, n);
        raw(tail, 4);
    }

private:
    std::FILE* f_;
    const std::string& path_;
};

}  // namespace

PngPixels compressPngRgba(const std::string& path, std::span<const std::uint8_t> rgba, std::size_t width,
                          std::size_t height) {
    constexpr std::size_t kMaxSide = std::numeric_limits<std::int32_t>::max();
    if (width == 0 || height == 0 || width > kMaxSide || height > kMaxSide || rgba.size() != width * height * 4)
        throw Error(path + ": invalid PNG image size " + std::to_string(width) + " x " + std::to_string(height));
    // Scanlines: a filter-type byte (0, none) before each row.
    const std::size_t stride = width * 4;
    std::vector<std::uint8_t> scanlines((stride + 1) * height);
    for (std::size_t r = 0; r < height; ++r) {
        std::uint8_t* line = scanlines.data() + r * (stride + 1);
        line[0] = 0;
        std::memcpy(line + 1, rgba.data() + r * stride, stride);
    }
    const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
        libdeflate_alloc_compressor(kCompressionLevel), &libdeflate_free_compressor);
    if (!compressor) throw Error(path + ": out of memory for the PNG compressor");
    PngPixels out{width, height, std::vector<std::uint8_t>(libdeflate_zlib_compress_bound(compressor.get(), scanlines.size()))};
    const std::size_t zsize = libdeflate_zlib_compress(compressor.get(), scanlines.data(), scanlines.size(),
                                                       out.zlib.data(), out.zlib.size());
    if (zsize == 0) throw Error(path + ": PNG compression failed");
    out.zlib.resize(zsize);
    return out;
}

void writePng(const std::string& path, const PngPixels& pixels,
              const std::vector<std::pair<std::string, std::string>>& text) {
    constexpr std::size_t kMaxKeyword = 79;  // PNG 1.2, 11.3.4.1
    for (const auto& [key, value] : text)
        if (key.empty() || key.size() > kMaxKeyword || key.find('\0') != std::string::npos ||
            value.find('\0') != std::string::npos)
            throw Error(path + ": invalid PNG text keyword '" + key + "'");
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
    if (!file) throw Error(failure(path, "cannot open for writing"));
    ChunkWriter out(file.get(), path);
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    out.raw(kSignature, sizeof kSignature);
    std::uint8_t ihdr[13];
    putU32(ihdr, static_cast<std::uint32_t>(pixels.width));
    putU32(ihdr + 4, static_cast<std::uint32_t>(pixels.height));
    ihdr[8] = 8;   // bit depth
    ihdr[9] = 6;   // colour type: RGBA
    ihdr[10] = 0;  // compression: deflate
    ihdr[11] = 0;  // filter method 0
    ihdr[12] = 0;  // no interlace
    out.chunk("IHDR", ihdr, sizeof ihdr);
    for (const auto& [key, value] : text) {
        std::vector<std::uint8_t> t(key.begin(), key.end());
        t.push_back(0);  // keyword separator
        t.insert(t.end(), value.begin(), value.end());
        out.chunk("tEXt", t.data(), t.size());
    }
    const std::size_t zsize = pixels.zlib.size();
    for (std::size_t at = 0; at < zsize; at += kIdatChunkBytes)
        out.chunk("IDAT", pixels.zlib.data() + at, std::min(kIdatChunkBytes, zsize - at));
    out.chunk("IEND", nullptr, 0);
    if (std::fflush(file.get()) != 0) throw Error(failure(path, "cannot write PNG"));
    // fclose can still fail (a deferred write error on some file systems): a PNG is only
    // written when it succeeds.
    if (std::fclose(file.release()) != 0) throw Error(failure(path, "cannot write PNG"));
}

void writePngRgba(const std::string& path, std::span<const std::uint8_t> rgba, std::size_t width,
                  std::size_t height, const std::vector<std::pair<std::string, std::string>>& text) {
    writePng(path, compressPngRgba(path, rgba, width, height), text);
}

}  // namespace demlight
