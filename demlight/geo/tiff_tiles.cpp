#include "demlight/geo/tiff_tiles.h"

#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <tiffio.h>
#include <zstd.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <strings.h>

namespace demlight::detail {

std::atomic<bool> encodeTiles{true};
std::atomic<std::size_t> tilesWritten{0};

namespace {

bool equalsIgnoringCase(const std::string& a, const char* b) { return strcasecmp(a.c_str(), b) == 0; }

/// A whole-string integer, or nothing.
std::optional<int> parseInt(const std::string& s) {
    if (s.empty()) return std::nullopt;
    char* end = nullptr;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (*end != '\0' || v < -1000000 || v > 1000000) return std::nullopt;
    return static_cast<int>(v);
}

}  // namespace

std::optional<TileEncoding> tileEncoding(const std::vector<std::string>& creationOptions, TileSamples samples) {
    TileEncoding e;
    e.samples = samples;
    bool tiled = false, zstd = false, samplesPredictor = false, bandInterleave = false;
    for (const std::string& kv : creationOptions) {
        const std::size_t eq = kv.find('=');
        if (eq == std::string::npos) return std::nullopt;
        const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
        if (equalsIgnoringCase(key, "TILED")) {
            tiled = equalsIgnoringCase(value, "YES") || equalsIgnoringCase(value, "TRUE") || value == "1" ||
                    equalsIgnoringCase(value, "ON");
        } else if (equalsIgnoringCase(key, "COMPRESS")) {
            zstd = equalsIgnoringCase(value, "ZSTD");
        } else if (equalsIgnoringCase(key, "PREDICTOR")) {
            samplesPredictor = value == (samples == TileSamples::Float32 ? "3" : "2");
        } else if (equalsIgnoringCase(key, "INTERLEAVE")) {
            bandInterleave = equalsIgnoringCase(value, "BAND");
        } else if (equalsIgnoringCase(key, "ZSTD_LEVEL")) {
            const std::optional<int> level = parseInt(value);
            if (!level || *level < 1 || *level > 22) return std::nullopt;  // GDAL's range; it refuses the rest
            e.zstdLevel = *level;
        } else if (equalsIgnoringCase(key, "NUM_THREADS")) {
            if (equalsIgnoringCase(value, "ALL_CPUS")) {
                e.threads = 0;
            } else if (const std::optional<int> n = parseInt(value); n && *n >= 1) {
                e.threads = std::min(*n, kMaxThreads);
            } else {
                return std::nullopt;
            }
        } else if (equalsIgnoringCase(key, "BIGTIFF") || equalsIgnoringCase(key, "BLOCKXSIZE") ||
                   equalsIgnoringCase(key, "BLOCKYSIZE")) {
            // The file's layout: GDAL applies them at Create, the writer reads the tile size
            // and offset width from the file.
        } else {
            return std::nullopt;
        }
    }
    if (!(tiled && zstd && samplesPredictor && bandInterleave)) return std::nullopt;
    return e;
}

void predictFloatRow(const float* row, std::size_t n, std::uint8_t* out) {
    // Kept per thread: a row of a 256-wide tile is 1 KiB.
    if (n == 0) return;
    thread_local std::vector<std::uint8_t> planes;
    planes.resize(4 * n);
    std::uint8_t* p = planes.data();
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t v;
        std::memcpy(&v, row + i, 4);
        p[i] = static_cast<std::uint8_t>(v >> 24);
        p[n + i] = static_cast<std::uint8_t>(v >> 16);
        p[2 * n + i] = static_cast<std::uint8_t>(v >> 8);
        p[3 * n + i] = static_cast<std::uint8_t>(v);
    }
    // Differences of bytes in a row across the planes (TN3: the row is one sequence of bytes).
    out[0] = p[0];
    for (std::size_t k = 1; k < 4 * n; ++k) out[k] = static_cast<std::uint8_t>(p[k] - p[k - 1]);
}

void predictInt16Row(const std::int16_t* row, std::size_t n, std::uint8_t* out) {
    std::uint16_t previous = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const auto v = static_cast<std::uint16_t>(row[i]);
        const auto d = static_cast<std::uint16_t>(i == 0 ? v : v - previous);
        out[2 * i] = static_cast<std::uint8_t>(d);
        out[2 * i + 1] = static_cast<std::uint8_t>(d >> 8);
        previous = v;
    }
}

namespace {

/// One tile's rows predicted into `raw` (sizeof(T) * tileW bytes a row): `rows` rows of `cols`
/// cells from `first` (`stride` cells apart), zeros past the raster's edges (no reader sees
/// them). Whole rows are predicted from the raster itself, the others from a padded copy.
template <class T>
void predictTile(const T* first, std::size_t stride, std::size_t cols, std::size_t rows, std::size_t tileW,
                 std::size_t tileH, std::uint8_t* raw, void (*predictRow)(const T*, std::size_t, std::uint8_t*)) {
    thread_local std::vector<T> padded;
    padded.assign(tileW, T{});  // copies below fill [0, cols) only: the rest stays zero
    for (std::size_t r = 0; r < tileH; ++r) {
        std::uint8_t* out = raw + sizeof(T) * tileW * r;
        if (r < rows && cols == tileW) {
            predictRow(first + r * stride, tileW, out);
            continue;
        }
        if (r < rows) {
            std::copy_n(first + r * stride, cols, padded.begin());
        } else {
            std::fill(padded.begin(), padded.end(), T{});
        }
        predictRow(padded.data(), tileW, out);
    }
}

}  // namespace

struct TileWriter::State {
    TIFF* tif = nullptr;
    std::string path;
    std::size_t width = 0, height = 0, bands = 0;
    std::uint32_t tileW = 0, tileH = 0;
    TileEncoding encoding;
    std::string libtiffError;               // the first error libtiff reported
    std::vector<std::vector<std::uint8_t>> compressed;  // a strip's tiles

    /// The reason a write failed: libtiff's own when it gave one.
    Error failure(const std::string& what) const { return Error(libtiffError.empty() ? what : libtiffError); }
};

namespace {

/// libtiff's errors kept for the Error thrown; its warnings (GDAL's own tags, which libtiff
/// does not know) dropped.
int keepError(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
    auto* message = static_cast<std::string*>(user);
    if (message->empty()) {
        char text[512];
        std::vsnprintf(text, sizeof text, fmt, ap);
        *message = std::string(module ? module : "libtiff") + ": " + text;
    }
    return 1;
}

int dropWarning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

struct ZstdContextFree {
    void operator()(ZSTD_CCtx* c) const { ZSTD_freeCCtx(c); }
};

}  // namespace

TileWriter::TileWriter(const std::string& path, std::size_t width, std::size_t height, std::size_t bands,
                                 TileEncoding encoding)
    : state_(std::make_unique<State>()) {
    State& st = *state_;
    st.path = path;
    st.width = width;
    st.height = height;
    st.bands = bands;
    st.encoding = encoding;
    TIFFOpenOptions* opts = TIFFOpenOptionsAlloc();
    TIFFOpenOptionsSetErrorHandlerExtR(opts, keepError, &st.libtiffError);
    TIFFOpenOptionsSetWarningHandlerExtR(opts, dropWarning, nullptr);
    st.tif = TIFFOpenExt(path.c_str(), "r+", opts);
    TIFFOpenOptionsFree(opts);
    if (!st.tif) throw st.failure("cannot open the GeoTIFF to write its tiles");

    // The layout GDAL made from the creation options this writer was chosen for.
    std::uint32_t w = 0, h = 0;
    std::uint16_t bits = 0, format = 0, predictor = 0, compression = 0, planar = 0, samples = 0;
    const bool ok = TIFFIsTiled(st.tif) && TIFFGetField(st.tif, TIFFTAG_IMAGEWIDTH, &w) &&
                    TIFFGetField(st.tif, TIFFTAG_IMAGELENGTH, &h) && TIFFGetField(st.tif, TIFFTAG_TILEWIDTH, &st.tileW) &&
                    TIFFGetField(st.tif, TIFFTAG_TILELENGTH, &st.tileH) &&
                    TIFFGetField(st.tif, TIFFTAG_BITSPERSAMPLE, &bits) &&
                    TIFFGetField(st.tif, TIFFTAG_SAMPLEFORMAT, &format) &&
                    TIFFGetField(st.tif, TIFFTAG_PREDICTOR, &predictor) &&
                    TIFFGetField(st.tif, TIFFTAG_COMPRESSION, &compression) &&
                    TIFFGetField(st.tif, TIFFTAG_PLANARCONFIG, &planar) &&
                    TIFFGetField(st.tif, TIFFTAG_SAMPLESPERPIXEL, &samples);
    const bool asEncoded = encoding.samples == TileSamples::Float32
                               ? bits == 32 && format == SAMPLEFORMAT_IEEEFP && predictor == PREDICTOR_FLOATINGPOINT
                               : bits == 16 && format == SAMPLEFORMAT_INT && predictor == PREDICTOR_HORIZONTAL &&
                                     !TIFFIsByteSwapped(st.tif);  // predictInt16Row writes little-endian
    if (!ok || !asEncoded || w != width || h != height || compression != COMPRESSION_ZSTD ||
        (samples > 1 && planar != PLANARCONFIG_SEPARATE) || samples != bands || st.tileW == 0 || st.tileH == 0) {
        TIFFClose(st.tif);
        st.tif = nullptr;
        throw st.failure("internal: the GeoTIFF's layout is not the one its tiles are encoded for");
    }
}

TileWriter::~TileWriter() {
    if (state_ && state_->tif) TIFFClose(state_->tif);  // after an error: the caller removes the file
}

std::size_t TileWriter::tileHeight() const { return state_->tileH; }

void TileWriter::writeRows(std::size_t band, std::size_t row0, std::size_t rows, const void* values) {
    State& st = *state_;
    if (!st.tif || band >= st.bands || row0 % st.tileH != 0 || row0 + rows > st.height ||
        (rows % st.tileH != 0 && row0 + rows != st.height))
        throw st.failure("internal: rows not on the tiles");
    const std::size_t tileW = st.tileW, tileH = st.tileH;
    const std::size_t across = (st.width + tileW - 1) / tileW;
    const std::size_t tileRows = (rows + tileH - 1) / tileH;
    const std::size_t tiles = across * tileRows;
    st.compressed.resize(std::max(st.compressed.size(), tiles));
    const int level = st.encoding.zstdLevel;
    std::atomic<bool> failed{false};
    const bool floats = st.encoding.samples == TileSamples::Float32;
    const std::size_t sampleBytes = floats ? 4 : 2;
    // Tiles are independent: each thread predicts and compresses whole tiles into its own buffer.
    parallelFor(0, tiles, [&](std::size_t t) {
        thread_local std::unique_ptr<ZSTD_CCtx, ZstdContextFree> cctx;
        thread_local std::vector<std::uint8_t> raw;
        if (!cctx) cctx.reset(ZSTD_createCCtx());
        const std::size_t ty = t / across, tx = t % across;
        const std::size_t x0 = tx * tileW, cols = std::min(tileW, st.width - x0);
        const std::size_t inTile = std::min(tileH, rows - ty * tileH), first = ty * tileH * st.width + x0;
        raw.resize(sampleBytes * tileW * tileH);
        if (floats) {
            predictTile(static_cast<const float*>(values) + first, st.width, cols, inTile, tileW, tileH, raw.data(),
                        predictFloatRow);
        } else {
            predictTile(static_cast<const std::int16_t*>(values) + first, st.width, cols, inTile, tileW, tileH,
                        raw.data(), predictInt16Row);
        }
        std::vector<std::uint8_t>& out = st.compressed[t];
        out.resize(ZSTD_compressBound(raw.size()));
        const std::size_t n = cctx ? ZSTD_compressCCtx(cctx.get(), out.data(), out.size(), raw.data(), raw.size(), level)
                                   : 0;
        if (!cctx || ZSTD_isError(n)) {
            failed = true;  // any thread's failure fails the strip
            out.clear();
            return;
        }
        out.resize(n);
    });
    if (failed) throw st.failure("ZSTD could not compress a tile");
    // In file order: the tiles of a band row by row, as GDAL writes them.
    for (std::size_t t = 0; t < tiles; ++t) {
        const std::size_t ty = row0 / tileH + t / across, tx = t % across;
        const std::uint32_t index = TIFFComputeTile(st.tif, static_cast<std::uint32_t>(tx * tileW),
                                                    static_cast<std::uint32_t>(ty * tileH), 0,
                                                    static_cast<std::uint16_t>(band));
        std::vector<std::uint8_t>& data = st.compressed[t];
        if (TIFFWriteRawTile(st.tif, index, data.data(), static_cast<tmsize_t>(data.size())) !=
            static_cast<tmsize_t>(data.size()))
            throw st.failure("libtiff could not append a tile");
    }
    tilesWritten += tiles;
}

void TileWriter::close() {
    State& st = *state_;
    if (!st.tif) return;
    // TIFFFlush rewrites only the tile offsets and byte counts (in place) when nothing else of the
    // directory changed; TIFFClose cannot report a failure, so flush first.
    const int flushed = TIFFFlush(st.tif);
    TIFFClose(st.tif);
    st.tif = nullptr;
    if (!flushed || !st.libtiffError.empty()) throw st.failure("libtiff could not write the tile offsets");
}

}  // namespace demlight::detail
