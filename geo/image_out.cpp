// Picture output; see image_out.h.
#include "geo/image_out.h"

#include "geo/oiio_loader.h"
#include "geo/png_writer.h"
#include "src/error.h"

#include <algorithm>
#include <cmath>
#include <cctype>
#include <filesystem>
#include <memory>
#include <utility>
#include <unistd.h>

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

/// A hidden temporary name beside `path`, so the rename stays on one file system.
fs::path tempPathFor(const std::string& path) {
    const fs::path p(path);
    std::string name = ".";
    name += p.filename().string();
    name += ".tmp";
    name += std::to_string(::getpid());
    return p.parent_path() / name;
}

void commit(const fs::path& tmp, const std::string& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error(path + ": cannot write: rename failed");
    }
}

[[noreturn]] void fail(const char* why, const fs::path& tmp, const std::string& path) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write image: " + why);
}

}  // namespace

void checkImagePath(const std::string& path) { checkFormat(path, extensionOf(path)); }

void writeImage(const std::string& path, const Image8& image) {
    if (extensionOf(path) == "png") {
        // PNG through libdeflate (geo/png_writer.h): ~3x faster than libpng for time-lapse frames.
        const fs::path tmp = tempPathFor(path);
        try {
            writePngRgba(tmp.string(), image.rgba, image.width, image.height, image.text);
        } catch (const Error& e) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw Error(path + ": cannot write image: " + e.what());
        }
        commit(tmp, path);
        return;
    }
    const std::string ext = extensionOf(path);
    if (ext.empty()) checkFormat(path, ext);  // throws, naming the missing extension
    const fs::path tmp = tempPathFor(path);
    char err[512];
    if (oiioPlugin().write(tmp.string().c_str(), ext.c_str(), image.rgba.data(), image.width, image.height, err,
                           sizeof err) != 0)
        fail(err, tmp, path);
    commit(tmp, path);
}

struct GifWriter::Impl {
    void* gif = nullptr;
    fs::path tmp;
};

GifWriter::GifWriter(std::string path, int framesPerSecond)
    : path_(std::move(path)), fps_(framesPerSecond), impl_(std::make_unique<Impl>()) {
    impl_->tmp = tempPathFor(path_);
    char err[512];
    impl_->gif = oiioPlugin().gifOpen(impl_->tmp.string().c_str(), fps_, err, sizeof err);
    if (!impl_->gif) throw Error(path_ + ": " + err);
}

GifWriter::~GifWriter() {
    if (impl_ && impl_->gif) {
        oiioPlugin().gifFree(impl_->gif);
        std::error_code ec;
        fs::remove(impl_->tmp, ec);
    }
}

void GifWriter::add(const Image8& frame) {
    char err[512];
    if (oiioPlugin().gifAdd(impl_->gif, frame.rgba.data(), frame.width, frame.height, err, sizeof err) != 0)
        fail(err, impl_->tmp, path_);
    ++frames_;
}

void GifWriter::finish() {
    if (frames_ == 0) throw Error(path_ + ": no frames to write");
    char err[512];
    const int closed = oiioPlugin().gifClose(impl_->gif, err, sizeof err);
    oiioPlugin().gifFree(impl_->gif);
    impl_->gif = nullptr;
    if (closed != 0) fail(err, impl_->tmp, path_);
    commit(impl_->tmp, path_);
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

}  // namespace demlight
