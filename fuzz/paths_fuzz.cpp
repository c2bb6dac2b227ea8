// libFuzzer target: output file names (demlight/geo/output_file.h). Input: a file name (any bytes but '/'
// and NUL; cut at 200). In a scratch folder with a planted link at every name an earlier
// demlight's temporary file could have had, each input is written through a TemporaryFile and
// committed, then written again and discarded. Properties checked on every input:
//  - the planted links' target is never written;
//  - after the commit the folder holds the planted links, the output under the exact name given
//    (a regular file with what was written) and nothing else: no private folder is left;
//  - after the discard the output is unchanged and still nothing else is left;
//  - isTemporaryName agrees with the private folder's name, and gives back the final name.
// Refusals must be demlight::Error; anything else escaping is a finding.
#include "demlight/geo/output_file.h"
#include "demlight/core/error.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const char* what, const std::string& name) {
    std::fprintf(stderr, "paths_fuzz: %s for name '%s'\n", what, name.c_str());
    std::abort();
}

std::string readText(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

const fs::path& scratch() {
    static const fs::path dir = [] {
        const fs::path d = fs::temp_directory_path() / ("demlight_paths_fuzz_" + std::to_string(::getpid()));
        fs::remove_all(d);
        fs::create_directories(d / "out");
        std::ofstream(d / "victim") << "precious";
        return d;
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace demlight;
    std::string name(reinterpret_cast<const char*>(data), std::min<std::size_t>(size, 200));
    std::erase(name, '/');
    std::erase(name, '\0');
    if (name.empty() || name == "." || name == "..") return 0;
    const fs::path out = scratch() / "out";
    const fs::path victim = scratch() / "victim";
    fs::remove_all(out);
    fs::create_directories(out);
    std::set<std::string> planted;
    const std::string pid = std::to_string(::getpid());
    for (const std::string& link : {name + ".tmp" + pid, "." + name + ".tmp" + pid}) {
        if (link.size() > 255) continue;
        std::error_code ec;
        fs::create_symlink(victim, out / link, ec);
        if (!ec) planted.insert(link);
    }
    const fs::path final = out / name;
    try {
        {
            TemporaryFile tmp(final.string());
            const std::string folder = fs::path(tmp.path()).parent_path().filename().string();
            std::string back;
            if (!isTemporaryName(folder, &back) || back != name) fail("the private folder's name is not recognised", name);
            std::ofstream(tmp.path(), std::ios::binary) << "first";
            tmp.commit();
        }
        {
            TemporaryFile tmp(final.string());
            std::ofstream(tmp.path(), std::ios::binary) << "second";
        }
    } catch (const Error&) {
        return 0;  // a name too long for the file system
    }
    if (readText(victim) != "precious") fail("a write followed a planted link", name);
    if (!fs::is_regular_file(fs::symlink_status(final)) || readText(final) != "first")
        fail("the output is not the committed file", name);
    std::set<std::string> left;
    for (const auto& e : fs::directory_iterator(out)) left.insert(e.path().filename().string());
    planted.insert(name);
    if (left != planted) fail("something besides the output and the planted links is left", name);
    return 0;
}
