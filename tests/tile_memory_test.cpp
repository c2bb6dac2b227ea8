// The memory budget of tiled runs (--memory-limit): the tile plan keeps its estimate within the
// limit and uses it (no tile needlessly small), and a run of the CLI on a DEM whose one-piece run
// would not fit stays under the limit, measured as the child process's peak resident set.
#include "cli_runner.h"
#include "demlight/geo/raster.h"
#include "demlight/products/aperture.h"
#include "demlight/products/sky.h"
#include "demlight/products/tiles.h"
#include "demlight/core/grid.h"

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

/// The plan's memory for a tile of `shape` on the case's square grid: the read window (the tile
/// and its halo, clipped to the grid) at perReadCell, the tile at perTileCell, plus the block
/// cache and the process.
double plannedBytes(const PlanCase& c, TileShape shape) {
    const double readCols = static_cast<double>(std::min(shape.cols + 2 * c.halo, c.side));
    const double readRows = static_cast<double>(std::min(shape.rows + 2 * c.halo, c.side));
    return readCols * readRows * c.bytes.perReadCell +
           static_cast<double>(shape.cols) * static_cast<double>(shape.rows) * c.bytes.perTileCell +
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
        const TilePlan plan = automaticTiles(extent, c.side, c.side, c.halo, c.bytes, tileMemoryBytes(c.limitMB * 1e6));
        const TileShape tile = plan.shape;
        const std::string what = std::to_string(c.side) + "^2, halo " + std::to_string(c.halo) + ", " +
                                 std::to_string(c.limitMB) + " MB: tile " + std::to_string(tile.cols) + " x " +
                                 std::to_string(tile.rows);
        ASSERT_GT(tile.cols, 0u) << what;
        ASSERT_GT(tile.rows, 0u) << what;
        ASSERT_LT(tile.cols * tile.rows, c.side * c.side) << what << " (the case is meant to need tiles)";
        EXPECT_LE(plannedBytes(c, tile), c.limitMB * 1e6) << what;
        EXPECT_LE(plan.smallestTileBytes, plannedBytes(c, tile)) << what;
        // Equal tiles along each cut axis: no thin last tile (it would read a whole halo for a
        // few cells), and one tile fewer, of equal size, would not fit.
        for (const bool alongCols : {true, false}) {
            const std::size_t size = alongCols ? tile.cols : tile.rows;
            if (size == c.side) continue;
            const std::size_t count = (c.side + size - 1) / size;
            EXPECT_GT(c.side - (count - 1) * size + count, size) << what << ": a thin last tile";
            const std::size_t fewer = (c.side + count - 2) / (count - 1);
            TileShape bigger = tile;
            (alongCols ? bigger.cols : bigger.rows) = fewer;
            if (tile.cols == tile.rows) bigger = {fewer, fewer};  // squares grow on both axes
            EXPECT_GT(plannedBytes(c, bigger), c.limitMB * 1e6) << what << ": " << count - 1 << " tiles of " << fewer;
        }
    }
}

TEST(TilePlan, AWholeExtentThatFitsIsOnePiece) {
    const CellWindow extent{0, 0, 1000, 800};
    const TilePlan plan = automaticTiles(extent, 1000, 800, 100, skyTileBytes(SkyRequest{}), tileMemoryBytes(4000e6));
    EXPECT_EQ(plan.shape, (TileShape{1000, 800}));
}

// A halo cannot read past the DEM: on a 100 000 x 1 DEM whose search reaches across it, a tile
// reads the whole DEM, so the whole DEM in one piece holds no more (it was 391 tiles of 256
// cells, each reading and sweeping all 100 000).
TEST(TilePlan, ALongThinDemWhoseHaloSpansItIsOnePiece) {
    for (const TileBytes& bytes : {productTileBytes(2), skyTileBytes(SkyRequest{})}) {
        const TilePlan plan = automaticTiles({0, 0, 100000, 1}, 100000, 1, 100000, bytes, tileMemoryBytes(200e6));
        EXPECT_EQ(plan.shape, (TileShape{100000, 1}));
    }
}

// A thin DEM too large for one piece is cut across its length only: strips its full height,
// whose halo reaches the DEM's edges on the short side anyway.
TEST(TilePlan, AThinDemTooLargeForOnePieceIsCutAcrossItsLength) {
    const CellWindow extent{0, 0, 100000, 300};
    const TileBytes bytes = productTileBytes(2);
    const double memory = tileMemoryBytes(1000e6);
    const TilePlan plan = automaticTiles(extent, 100000, 300, 2000, bytes, memory);
    EXPECT_EQ(plan.shape.rows, 300u);
    ASSERT_GT(plan.shape.cols, 0u);
    EXPECT_LT(plan.shape.cols, 100000u);
    EXPECT_LE(tileBytes(plan.shape, 2000, 100000, 300, bytes), memory);
    // The read window of a strip: its columns and halo by the DEM's 300 rows.
    EXPECT_DOUBLE_EQ(tileBytes(plan.shape, 2000, 100000, 300, bytes),
                     static_cast<double>(plan.shape.cols + 4000) * 300 * bytes.perReadCell);
    const std::vector<CellWindow> tiles = tilesOf(extent, plan.shape);
    EXPECT_EQ(tiles.size(), (100000 + plan.shape.cols - 1) / plan.shape.cols);
}

// When not even the smallest tile fits, the plan says so and what the smallest tile needs.
TEST(TilePlan, NoTileFittingIsReportedWithWhatTheSmallestNeeds) {
    const TileBytes bytes = productTileBytes(2);
    const TilePlan plan = automaticTiles({0, 0, 2400, 2400}, 2400, 2400, 200, bytes, tileMemoryBytes(100e6));
    EXPECT_EQ(plan.shape, (TileShape{0, 0}));
    // The smallest tile: 256 cells a side with its halo, 656^2 cells read.
    EXPECT_DOUBLE_EQ(plan.smallestTileBytes, 656.0 * 656.0 * bytes.perReadCell);
    EXPECT_GE(tileMemoryBytes(memoryBudgetFor(plan.smallestTileBytes)), plan.smallestTileBytes * (1 - 1e-12));
    EXPECT_LT(tileMemoryBytes(memoryBudgetFor(plan.smallestTileBytes) - 1e6), plan.smallestTileBytes);
}

// ---- A run, measured --------------------------------------------------------------------------

const char* const kUtm10Wkt =
    R"(PROJCS["WGS 84 / UTM zone 10N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",-123],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1],AUTHORITY["EPSG","32610"]])";

/// Runs the demlight binary with `args` and -v (no shell, so the child is the process measured)
/// and returns its peak resident set (bytes), as the command's own "peak memory" note gives it, or
/// -1 when it did not exit 0 (its exit status in `exitCode` when given); its stderr goes to
/// `errPath`. (Not the child's ru_maxrss: Linux counts in it what the child held before its exec,
/// a forked copy of this test process, itself larger than the command's runs here.)
double peakRssOfRun(const std::vector<std::string>& args, const std::string& errPath, int* exitCode = nullptr) {
    std::vector<char*> argv;
    std::string program = DEMLIGHT_CLI_PATH;
    argv.push_back(program.data());
    std::vector<std::string> copies = args;
    copies.push_back("-v");
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
    if (exitCode) *exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
    std::ifstream err(errPath);
    const std::string note = "peak memory: ";
    for (std::string line; std::getline(err, line);)
        if (line.rfind(note, 0) == 0) return std::atof(line.c_str() + note.size()) * 1e6;
    ADD_FAILURE() << "no peak memory note in " << errPath;
    return -1;
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

// A limit below what the run needs is refused, naming the smallest that works; that one is
// held (the whole process's peak, the pass over the DEM's heights included), in tiles. Before,
// 16 MB ran anyway and peaked at several times that.
TEST_F(MeasuredMemory, ALimitTooSmallIsRefusedNamingOneThatIsHeld) {
    const std::vector<std::vector<std::string>> runs = {
        {"sky", path("dem.tif"), "--max-distance", "2000", "--sky-directions", "4", "-o", path("sky.tif")},
        {"sun", path("dem.tif"), "--time", "2024-06-21T15:30:00Z", "--max-distance", "2000", "-o", path("sun.tif")},
    };
    for (const auto& run : runs) {
        std::vector<std::string> args = run;
        args.insert(args.end(), {"--memory-limit", "16"});
        int exitCode = 0;
        peakRssOfRun(args, path("err.txt"), &exitCode);
        const std::string err = readText(path("err.txt"));
        EXPECT_EQ(exitCode, 1) << run[0] << ": " << err;
        const std::string give = "give --memory-limit ";
        const std::size_t at = err.find(give);
        ASSERT_NE(at, std::string::npos) << run[0] << ": " << err;
        EXPECT_NE(err.find("2400 x 2400 DEM"), std::string::npos) << err;
        const double needMB = std::atof(err.c_str() + at + give.size());
        ASSERT_GT(needMB, 16) << err;
        EXPECT_LT(needMB, kLimitMB) << err;  // the smallest tile, not the one piece
        args = run;
        args.insert(args.end(), {"--memory-limit", std::to_string(static_cast<int>(needMB))});
        const double peak = peakRssOfRun(args, path("err.txt"));
        const std::string err2 = readText(path("err.txt"));
        ASSERT_GT(peak, 0) << run[0] << " at the limit it named, " << needMB << " MB: " << err2;
        EXPECT_NE(err2.find("tiles of up to"), std::string::npos) << run[0] << " ran in one piece: " << err2;
        EXPECT_LE(peak, needMB * 1e6) << run[0] << " peaked at " << peak / 1e6 << " MB under --memory-limit " << needMB;
    }
}

}  // namespace
}  // namespace demlight
