// Loads libdemlight_oiio.so; see oiio_loader.h.
#include "demlight/geo/oiio_loader.h"

#include "demlight/core/error.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <string>

namespace demlight {
namespace {

constexpr const char* kPluginName = "libdemlight_oiio.so";
constexpr int kPluginVersion = 3;  // demlight_oiio_version() of the plugin this build expects

template <class Fn>
Fn symbol(void* handle, const char* name, const std::string& path) {
    void* address = ::dlsym(handle, name);
    if (!address) throw Error("picture output: " + path + " has no " + name + " (a plugin from another build?)");
    return reinterpret_cast<Fn>(address);
}

OiioPlugin load() {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::string path = ec ? std::string(kPluginName) : (self.parent_path() / kPluginName).string();
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = ::dlerror();
        throw Error("picture output needs " + path + ", built and installed beside demlight (" +
                    (why ? why : "not found") + "); PNG output works without it");
    }
    const auto version = symbol<decltype(&demlight_oiio_version)>(handle, "demlight_oiio_version", path);
    if (version() != kPluginVersion)
        throw Error("picture output: " + path + " is version " + std::to_string(version()) + ", demlight needs " +
                    std::to_string(kPluginVersion));
    return {symbol<decltype(&demlight_oiio_check)>(handle, "demlight_oiio_check", path),
            symbol<decltype(&demlight_oiio_write)>(handle, "demlight_oiio_write", path),
            symbol<decltype(&demlight_oiio_gif_open)>(handle, "demlight_oiio_gif_open", path),
            symbol<decltype(&demlight_oiio_gif_add)>(handle, "demlight_oiio_gif_add", path),
            symbol<decltype(&demlight_oiio_gif_close)>(handle, "demlight_oiio_gif_close", path),
            symbol<decltype(&demlight_oiio_gif_free)>(handle, "demlight_oiio_gif_free", path),
            symbol<decltype(&demlight_oiio_text_size)>(handle, "demlight_oiio_text_size", path),
            symbol<decltype(&demlight_oiio_draw_text)>(handle, "demlight_oiio_draw_text", path)};
}

}  // namespace

const OiioPlugin& oiioPlugin() {
    // Loaded once and kept for the process (never dlclose'd: OpenImageIO keeps threads).
    static std::once_flag once;
    static OiioPlugin plugin;
    static std::string failure;
    std::call_once(once, [] {
        try {
            plugin = load();
        } catch (const Error& e) {
            failure = e.what();
        }
    });
    if (!failure.empty()) throw Error(failure);
    return plugin;
}

}  // namespace demlight
