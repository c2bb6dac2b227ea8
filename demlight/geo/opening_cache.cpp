#include "demlight/geo/opening_cache.h"

#include "demlight/geo/raster.h"
#include "demlight/core/error.h"

#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace demlight {
namespace {

namespace fs = std::filesystem;

constexpr const char* kHeader = "demlight opening pass 1";
/// Larger files are not cache files of ours (a key lists a VRT's sources: ~100 bytes each).
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{64} << 20;

std::string hexBits(std::uint64_t bits, int digits) {
    char text[17];
    std::snprintf(text, sizeof text, "%0*llx", digits, static_cast<unsigned long long>(bits));
    return text;
}

/// FNV-1a, 64 bits: the file name of a key (the key itself is checked when read back).
std::uint64_t fnv1a(const std::string& text) {
    std::uint64_t h = 14695981039346656037ull;
    for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
    return h;
}

/// The key: what the pass's results depend on. Empty when the files cannot be listed.
std::string keyOf(const std::string& path, const HeightOptions& heights) {
    std::vector<std::string> files;
    try {
        files = rasterFiles(path);
    } catch (const Error&) {
        return {};
    }
    if (files.empty()) return {};
    std::ostringstream key;
    std::error_code ec;
    const fs::path absolute = fs::absolute(path, ec);
    key << kHeader << "\npath " << (ec ? path : absolute.lexically_normal().string()) << "\nz-unit " << heights.zUnit
        << "\nz-factor " << hexBits(std::bit_cast<std::uint64_t>(heights.zFactor), 16) << "\n";
    for (const std::string& f : files) {
        struct stat st {};
        if (::stat(f.c_str(), &st) != 0) return {};
        key << "file " << st.st_size << ' ' << st.st_mtim.tv_sec << '.' << st.st_mtim.tv_nsec << ' ' << f << "\n";
    }
    return key.str();
}

std::string fileFor(const std::string& folder, const std::string& key) {
    return (fs::path(folder) / ("opening-" + hexBits(fnv1a(key), 16) + ".txt")).string();
}

/// Reads "NAME HEX" into `bits` (`digits` hexadecimal digits).
bool readHex(std::istream& in, const char* name, int digits, std::uint64_t& bits) {
    std::string word, hex;
    if (!(in >> word >> hex) || word != name || hex.size() != static_cast<std::size_t>(digits)) return false;
    char* end = nullptr;
    errno = 0;
    bits = std::strtoull(hex.c_str(), &end, 16);
    return errno == 0 && end == hex.c_str() + hex.size();
}

bool readCount(std::istream& in, const char* name, std::size_t& value) {
    std::string word, digits;
    if (!(in >> word >> digits) || word != name || digits.empty() || digits.size() > 19 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
        return false;
    value = static_cast<std::size_t>(std::stoull(digits));
    return true;
}

}  // namespace

OpeningCache OpeningCache::fromEnvironment() {
    OpeningCache cache;
    if (const char* off = std::getenv("DEMLIGHT_CACHE"); off && std::string(off) == "off") return cache;
    if (const char* dir = std::getenv("DEMLIGHT_CACHE_DIR")) {
        cache.folder = dir;
    } else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/') {
        cache.folder = std::string(xdg) + "/demlight";
    } else if (const char* home = std::getenv("HOME"); home && *home == '/') {
        cache.folder = std::string(home) + "/.cache/demlight";
    }
    return cache;
}

std::optional<OpeningPass> OpeningCache::find(const std::string& path, const HeightOptions& heights) const {
    if (folder.empty()) return std::nullopt;
    const std::string key = keyOf(path, heights);
    if (key.empty()) return std::nullopt;
    const std::string file = fileFor(folder, key);
    std::error_code ec;
    const std::uintmax_t bytes = fs::file_size(file, ec);
    if (ec || bytes > kMaxFileBytes || bytes <= key.size()) return std::nullopt;
    std::ifstream in(file, std::ios::binary);
    std::string text(static_cast<std::size_t>(bytes), '\0');
    if (!in.read(text.data(), static_cast<std::streamsize>(bytes))) return std::nullopt;
    if (text.compare(0, key.size(), key) != 0) return std::nullopt;  // another DEM's, or files changed
    std::istringstream values(text.substr(key.size()));
    OpeningPass p;
    std::uint64_t low = 0, high = 0, mean = 0, steep = 0;
    std::string end;
    if (!readCount(values, "width", p.width) || !readCount(values, "height", p.height) ||
        !readHex(values, "low", 8, low) || !readHex(values, "high", 8, high) ||
        !readCount(values, "valid", p.validCells) || !readHex(values, "mean", 16, mean) ||
        !readHex(values, "steep", 16, steep) || !(values >> end) || end != "end" || (values >> end))
        return std::nullopt;
    p.lowM = std::bit_cast<float>(static_cast<std::uint32_t>(low));
    p.highM = std::bit_cast<float>(static_cast<std::uint32_t>(high));
    p.meanHeightM = std::bit_cast<double>(mean);
    p.steepStepShare = std::bit_cast<double>(steep);
    if (p.validCells == 0 || p.validCells > p.width * p.height || !(p.lowM <= p.highM)) return std::nullopt;
    return p;
}

void OpeningCache::keep(const std::string& path, const HeightOptions& heights, const OpeningPass& pass) const {
    if (folder.empty() || pass.width * pass.height < minCells) return;
    const std::string key = keyOf(path, heights);
    if (key.empty()) return;
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) return;
    ::chmod(folder.c_str(), 0700);
    std::ostringstream text;
    text << key << "width " << pass.width << "\nheight " << pass.height << "\nlow "
         << hexBits(std::bit_cast<std::uint32_t>(pass.lowM), 8) << "\nhigh "
         << hexBits(std::bit_cast<std::uint32_t>(pass.highM), 8) << "\nvalid " << pass.validCells << "\nmean "
         << hexBits(std::bit_cast<std::uint64_t>(pass.meanHeightM), 16) << "\nsteep "
         << hexBits(std::bit_cast<std::uint64_t>(pass.steepStepShare), 16) << "\nend\n";
    const std::string body = text.str();
    std::string tmp = (fs::path(folder) / ".opening.tmpXXXXXX").string();
    const int fd = ::mkstemp(tmp.data());  // mode 0600, a new name: no link is followed
    if (fd < 0) return;
    bool ok = ::write(fd, body.data(), body.size()) == static_cast<ssize_t>(body.size());
    ok = (::close(fd) == 0) && ok;
    if (!ok || std::rename(tmp.c_str(), fileFor(folder, key).c_str()) != 0) ::unlink(tmp.c_str());
}

}  // namespace demlight
