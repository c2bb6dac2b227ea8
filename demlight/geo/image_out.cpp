// Picture output; see image_out.h.
#include "demlight/geo/image_out.h"

#include "demlight/geo/oiio_loader.h"
#include "demlight/geo/output_file.h"
#include "demlight/geo/png_writer.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <cmath>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>

namespace demlight {
namespace {

namespace fs = std::filesystem;

std::string extensionOf(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

/// Throws unless `ext` (the file's lower-case extension) names a format demlight can write: PNG
/// natively, anything else through the OpenImageIO plugin.
void checkFormat(const std::string& path, const std::string& ext) {
    if (ext.empty()) throw Error(path + ": the output needs an image extension (.png, .jpg, .exr, .gif)");
    if (ext == "png") return;
    char err[512];
    if (oiioPlugin().check(ext.c_str(), err, sizeof err) != 0) throw Error(path + ": " + err);
}

/// Walks a GIF's block structure (GIF89a specification, sections 17-27: header, logical screen
/// descriptor and colour table, then extension and image blocks of sub-blocks, then the trailer)
/// and counts its images. OpenImageIO's GIF writer does not report failed writes (a full disk
/// gave a GIF cut off without its trailer, reported as written), so the finished file is read
/// back: empty when it is whole with `frames` images, else what is wrong.
std::string checkGif(const std::string& path, std::size_t frames) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return "cannot read it back";
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(f, &std::fclose);
    const auto skip = [&](long n) { return std::fseek(f, n, SEEK_CUR) == 0; };
    const auto byte = [&]() { return std::fgetc(f); };
    const auto colourTableBytes = [](int packed) { return (packed & 0x80) ? 3L << ((packed & 7) + 1) : 0L; };
    const auto cutOff = [&](std::size_t images) {
        return "cut off after " + std::to_string(images) + (images == 1 ? " frame" : " frames");
    };
    const auto subBlocks = [&]() {
        for (int n = byte(); n != 0; n = byte())
            if (n == EOF || !skip(n)) return false;
        return true;
    };
    char header[6];
    if (std::fread(header, 1, 6, f) != 6 || std::memcmp(header, "GIF8", 4) != 0) return "no GIF header";
    unsigned char screen[7];
    if (std::fread(screen, 1, 7, f) != 7 || !skip(colourTableBytes(screen[4]))) return "cut off in its header";
    std::size_t images = 0;
    for (;;) {
        const int block = byte();
        if (block == 0x3B) break;  // trailer
        if (block == 0x21) {        // extension: label, then sub-blocks
            if (byte() == EOF || !subBlocks()) return cutOff(images);
        } else if (block == 0x2C) {  // image: descriptor, local colour table, LZW code size, data
            unsigned char desc[9];
            if (std::fread(desc, 1, 9, f) != 9 || !skip(colourTableBytes(desc[8])) || byte() == EOF || !subBlocks())
                return cutOff(images);
            ++images;
        } else {
            return block == EOF ? cutOff(images) + " (no trailer)" : "corrupt after " + std::to_string(images) + " frames";
        }
    }
    if (byte() != EOF) return "data after its trailer";
    if (images != frames) return std::to_string(images) + " frames instead of " + std::to_string(frames);
    return {};
}

[[noreturn]] void fail(const std::string& why, TemporaryFile& tmp, const std::string& path) {
    const std::string message = writeFailureMessage("image '" + path + "'", tmp.path(), why);
    tmp.discard();
    throw Error(message);
}

/// Writes `path` under a temporary name through write(temporaryPath), renaming it into place
/// when that returns; its Error becomes a failure naming `path`.
template <class Write>
void writeThroughTemporary(const std::string& path, Write&& write) {
    TemporaryFile tmp(path);
    try {
        write(tmp.path());
    } catch (const Error& e) {
        // Its message starts with the temporary name; the final one is what the user gave.
        std::string why = e.what();
        if (why.starts_with(tmp.path() + ": ")) why.erase(0, tmp.path().size() + 2);
        fail(why, tmp, path);
    }
    tmp.commit();
}

}  // namespace

void checkImagePath(const std::string& path) { checkFormat(path, extensionOf(path)); }

void writeImage(const std::string& path, const Image8& image) {
    checkOutputFile(path);
    const std::string ext = extensionOf(path);
    if (ext.empty()) checkFormat(path, ext);  // throws, naming the missing extension
    if (ext == "png") {
        // PNG through libdeflate (demlight/geo/png_writer.h): ~3x faster than libpng for time-lapse frames.
        writeThroughTemporary(path, [&](const std::string& tmp) {
            writePngRgba(tmp, image.rgba, image.width, image.height, image.text);
        });
        return;
    }
    writeThroughTemporary(path, [&](const std::string& tmp) {
        char err[512];
        if (oiioPlugin().write(tmp.c_str(), ext.c_str(), image.rgba.data(), image.width, image.height, err,
                               sizeof err) != 0)
            throw Error(tmp + ": " + err);
        // OpenImageIO's GIF writer reports no failed write, and its reader takes a GIF cut short:
        // the file is walked block by block to its trailer.
        if (ext == "gif")
            if (const std::string broken = checkGif(tmp, 1); !broken.empty())
                throw Error(tmp + ": the GIF written is " + broken);
    });
}

PngPixels encodePng(const Image8& image) {
    return compressPngRgba("the picture", image.rgba, image.width, image.height);  // (no file yet to name)
}

void writeImage(const std::string& path, const PngPixels& pixels,
                const std::vector<std::pair<std::string, std::string>>& text) {
    checkOutputFile(path);
    if (extensionOf(path) != "png") throw Error(path + ": PNG pixel data goes to a .png file");
    writeThroughTemporary(path, [&](const std::string& tmp) { writePng(tmp, pixels, text); });
}

struct GifWriter::Impl {
    void* gif = nullptr;
    std::optional<TemporaryFile> tmp;
};

GifWriter::GifWriter(std::string path, int framesPerSecond)
    : path_(std::move(path)), fps_(framesPerSecond), impl_(std::make_unique<Impl>()) {
    checkOutputFile(path_);
    impl_->tmp.emplace(path_);
    char err[512];
    impl_->gif = oiioPlugin().gifOpen(impl_->tmp->path().c_str(), fps_, err, sizeof err);
    if (!impl_->gif) throw Error(path_ + ": " + err);
}

GifWriter::~GifWriter() {
    if (impl_ && impl_->gif) oiioPlugin().gifFree(impl_->gif);
    // impl_->tmp, unless committed, removes the file
}

void GifWriter::add(const Image8& frame) {
    char err[512];
    if (oiioPlugin().gifAdd(impl_->gif, frame.rgba.data(), frame.width, frame.height, err, sizeof err) != 0)
        fail(err, *impl_->tmp, path_);
    ++frames_;
}

void GifWriter::finish() {
    if (frames_ == 0) throw Error(path_ + ": no frames to write");
    char err[512];
    const int closed = oiioPlugin().gifClose(impl_->gif, err, sizeof err);
    oiioPlugin().gifFree(impl_->gif);
    impl_->gif = nullptr;
    if (closed != 0) fail(err, *impl_->tmp, path_);
    const std::string broken = checkGif(impl_->tmp->path(), frames_);
    if (!broken.empty()) fail("the GIF written is " + broken, *impl_->tmp, path_);
    impl_->tmp->commit();
}

Image8 downsample(const Image8& image, std::size_t maxSide) {
    const std::size_t longer = std::max(image.width, image.height);
    if (maxSide == 0 || longer <= maxSide) return image;
    const std::size_t f = (longer + maxSide - 1) / maxSide;
    Image8 out;
    out.width = (image.width + f - 1) / f;
    out.height = (image.height + f - 1) / f;
    out.rgba.assign(out.width * out.height * 4, 0);
    for (std::size_t r = 0; r < out.height; ++r)
        for (std::size_t c = 0; c < out.width; ++c) {
            unsigned sum[4] = {0, 0, 0, 0};
            unsigned n = 0, all = 0;
            for (std::size_t y = r * f; y < std::min(image.height, (r + 1) * f); ++y)
                for (std::size_t x = c * f; x < std::min(image.width, (c + 1) * f); ++x) {
                    const std::uint8_t* p = image.rgba.data() + (y * image.width + x) * 4;
                    ++all;
                    if (p[3] == 0) continue;
                    for (int k = 0; k < 4; ++k) sum[k] += p[k];
                    ++n;
                }
            std::uint8_t* q = out.rgba.data() + (r * out.width + c) * 4;
            if (n == 0) {
                q[0] = q[1] = q[2] = kNodataGrey;
                q[3] = 0;
                continue;
            }
            for (int k = 0; k < 3; ++k) q[k] = static_cast<std::uint8_t>((sum[k] + n / 2) / n);
            q[3] = static_cast<std::uint8_t>((sum[3] + all / 2) / all);
        }
    return out;
}

TextBox measureText(const std::string& text, int sizePx) {
    TextBox box;
    char err[512];
    if (oiioPlugin().textSize(text.c_str(), sizePx, &box.x0, &box.y0, &box.x1, &box.y1, err, sizeof err) != 0)
        throw Error(err);
    return box;
}

void drawText(Image8& image, int x, int y, const std::string& text, int sizePx, const std::array<std::uint8_t, 4>& rgba) {
    char err[512];
    if (oiioPlugin().drawText(image.rgba.data(), image.width, image.height, x, y, text.c_str(), sizePx, rgba.data(), err,
                              sizeof err) != 0)
        throw Error(err);
}

}  // namespace demlight
