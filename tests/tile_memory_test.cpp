// The memory budget of tiled runs (--memory-limit): the tile plan keeps its estimate within the
// limit and uses it (no tile needlessly small), and a run of the CLI on a DEM whose one-piece run
// would not fit stays under the limit, measured as the child process's peak resident set.
#include "cli_runner.h"
#include "geo/raster.h"
#include "products/aperture.h"
#include "products/sky.h"
#include "products/tiles.h"
#include "src/grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;

// ---- The plan ------------------------------------------------------------------------------

struct PlanCase {
    std::size_t side;      ///< square extent (cells)
    std::size_t halo;      ///< cells
    TileBytes bytes;
    double limitMB;
};

/// The plan's memory for a tile of `tile` cells: the read window (tile + 2 halo)^2 at
/// perReadCell, the tile at perTileCell, plus the block cache and the process.
double plannedBytes(const PlanCase& c, std::size_t tile) {
    const double read = static_cast<double>(tile + 2 * c.halo);
    const double cells = static_cast<double>(tile);
    return read * read * c.bytes.perReadCell + cells * cells * c.bytes.perTileCell +
           rasterCacheBytes(c.limitMB * 1e6) + kProcessBytes;
}

TEST(TilePlan, TilesFitTheMemoryLimitAndNoFewerEqualTilesWould) {
    const PlanCase cases[] = {
        // The 40 000^2 benchmark (halo of its 31.7 km search at 1" cells): sky, aperture, sun.
        {40000, 1563, skyTileBytes(SkyRequest{}), 4000},
        {40000, 1563, apertureTileBytes(), 4000},
        {40000, 1563, productTileBytes(2), 4000},
        {40000, 1563, skyTileBytes(SkyRequest{}), 12000},
        // Small limits and halos; a halo larger than the tile.
        {2400, 201, skyTileBytes(SkyRequest{}), 200},
        {2400, 201, productTileBytes(2), 200},
        {10000, 3000, skyTileBytes(SkyRequest{}), 2000},
        {7777, 50, productTileBytes(4), 500},
    };
    for (const PlanCase& c : cases) {
        const CellWindow extent{0, 0, c.side, c.side};
        const std::size_t tile = automaticTileCells(extent, c.halo, c.bytes, tileMemoryBytes(c.limitMB * 1e6));
        const std::string what = std::to_string(c.side) + "^2, halo " + std::to_string(c.halo) + ", " +
                                 std::to_string(c.limitMB) + " MB: tile " + std::to_string(tile);
        ASSERT_GT(tile, 0u) << what;
        ASSERT_LT(tile, c.side) << what << " (the case is meant to need tiles)";
        EXPECT_LE(plannedBytes(c, tile), c.limitMB * 1e6) << what;
        // Equal tiles: the extent is cut into `count` tiles of (nearly) the same size.
        const std::size_t count = (c.side + tile - 1) / tile;
        EXPECT_GT(c.side - (count - 1) * tile + count, tile) << what << ": a thin last tile";
        // One tile fewer, of equal size, would not fit.
        const std::size_t fewer = (c.side + count - 2) / (count - 1);
        EXPECT_GT(plannedBytes(c, fewer), c.limitMB * 1e6) << what << ": " << count - 1 << " tiles of " << fewer;
    }
}

TEST(TilePlan, AWholeExtentThatFitsIsOnePiece) {
    const CellWindow extent{0, 0, 1000, 800};
    EXPECT_EQ(automaticTileCells(extent, 100, skyTileBytes(SkyRequest{}), tileMemoryBytes(4000e6)), 1000u);
}

// ---- A run, measured --------------------------------------------------------------------------

const char* const kUtm10Wkt =
    R"(PROJCS["WGS 84 / UTM zone 10N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",-123],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1],AUTHORITY["EPSG","32610"]])";

/// Runs the demlight binary with `args` (no shell, so the child is the process measured) and
/// returns its peak resident set (bytes), or -1 when it did not exit 0; its stderr goes to
/// `errPath`.
double peakRssOfRun(const std::vector<std::string>& args, const std::string& errPath) {
    std::vector<char*> argv;
    std::string program = DEMLIGHT_CLI_PATH;
    argv.push_back(program.data());
    std::vector<std::string> copies = args;
    for (std::string& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int fd = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) ::dup2(fd, 2);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    if (pid < 0) return -1;
    int status = 0;
    struct rusage usage {};
    if (::wait4(pid, &status, 0, &usage) != pid) return -1;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
    return static_cast<double>(usage.ru_maxrss) * 1024.0;  // Linux reports kilobytes
}

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

class MeasuredMemory : public ::testing::Test {
protected:
    void SetUp() override {
#if defined(__SANITIZE_ADDRESS__)
        GTEST_SKIP() << "AddressSanitizer's shadow memory and quarantine are outside the budget";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
        GTEST_SKIP() << "AddressSanitizer's shadow memory and quarantine are outside the budget";
#endif
#endif
        dir_ = fs::temp_directory_path() / ("demlight_tile_memory_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
        // Rolling hills, 10 m cells: 2400^2 cells, so that one piece of either product needs
        // more than the limit and the run must tile (docs/performance.md has the figures).
        Grid<float> h(kSide, kSide);
        for (std::size_t r = 0; r < kSide; ++r)
            for (std::size_t c = 0; c < kSide; ++c)
                h(c, r) = static_cast<float>(500.0 + 150.0 * std::sin(0.013 * static_cast<double>(c)) *
                                                         std::cos(0.011 * static_cast<double>(r)) +
                                             40.0 * std::sin(0.07 * static_cast<double>(c + 2 * r)));
        GeoReference ref;
        ref.geoTransform = {500000, 10, 0, 5200000, 0, -10};
        ref.crsWkt = kUtm10Wkt;
        writeRaster(path("dem.tif"), {{&h, nullptr, "height", "m"}}, ref, WriteOptions{});
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    static constexpr std::size_t kSide = 2400;
    static constexpr double kLimitMB = 200;
    fs::path dir_;
};

TEST_F(MeasuredMemory, SkyAndSunInTilesStayUnderTheMemoryLimit) {
    const std::string limit = std::to_string(static_cast<int>(kLimitMB));
    const std::vector<std::vector<std::string>> runs = {
        {"sky", path("dem.tif"), "--max-distance", "2000", "--sky-directions", "4", "--memory-limit", limit, "-o",
         path("sky.tif")},
        {"sun", path("dem.tif"), "--time", "2024-06-21T15:30:00Z", "--max-distance", "2000", "--memory-limit", limit,
         "-o", path("sun.tif")},
    };
    for (const auto& args : runs) {
        const double peak = peakRssOfRun(args, path("err.txt"));
        const std::string err = readText(path("err.txt"));
        ASSERT_GT(peak, 0) << args[0] << " failed: " << err;
        EXPECT_NE(err.find("tiles of up to"), std::string::npos) << args[0] << " ran in one piece: " << err;
        EXPECT_LE(peak, kLimitMB * 1e6) << args[0] << " peaked at " << peak / 1e6 << " MB";
    }
}

}  // namespace
}  // namespace demlight
