// Inputs and options chosen to break demlight: a header declaring a vast grid (opening must
// cost the same whatever the declared size, and answer a signal at once), creation options
// asking for blocks no writer can hold, and a long thin DEM (its tiles' halos cannot reach past
// it, so it runs in one piece).
#include "cli_runner.h"
#include "demlight/geo/dem.h"
#include "demlight/geo/raster.h"
#include "demlight/core/error.h"
#include "demlight/core/grid.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace demlight {
namespace {

namespace fs = std::filesystem;
using testing::runDemlight;

const char* const kUtm10Wkt =
    R"(PROJCS["WGS 84 / UTM zone 10N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",-123],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1],AUTHORITY["EPSG","32610"]])";

bool underAddressSanitizer() {
#if defined(__SANITIZE_ADDRESS__)
    return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    return true;
#endif
#endif
    return false;
}

class HostileInput : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("demlight_hostile_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    /// A 64 x 64 UTM DEM of 10 m cells (hills), and a VRT declaring `cols` x `rows` cells of
    /// `cellM` metres over it, each source cell stretched over as many as it takes.
    std::string hugeVrt(std::size_t cols, std::size_t rows, double cellM) const {
        Grid<float> h(64, 64);
        for (std::size_t r = 0; r < 64; ++r)
            for (std::size_t c = 0; c < 64; ++c)
                h(c, r) = static_cast<float>(300 + 50 * std::sin(0.2 * static_cast<double>(c)) * std::cos(0.15 * static_cast<double>(r)));
        GeoReference ref;
        ref.geoTransform = {500000, 10, 0, 5200000, 0, -10};
        ref.crsWkt = kUtm10Wkt;
        writeRaster(path("small.tif"), {{&h, nullptr, "height", "m"}}, ref, WriteOptions{});
        std::ofstream vrt(path("huge.vrt"));
        vrt << "<VRTDataset rasterXSize=\"" << cols << "\" rasterYSize=\"" << rows << "\">\n"
            << "  <SRS>EPSG:32610</SRS>\n"
            << "  <GeoTransform>500000, " << cellM << ", 0, 5200000, 0, " << -cellM << "</GeoTransform>\n"
            << "  <VRTRasterBand dataType=\"Float32\" band=\"1\">\n"
            << "    <SimpleSource><SourceFilename relativeToVRT=\"1\">small.tif</SourceFilename><SourceBand>1</SourceBand>\n"
            << "      <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"64\" ySize=\"64\"/>"
            << "<DstRect xOff=\"0\" yOff=\"0\" xSize=\"" << cols << "\" ySize=\"" << rows << "\"/></SimpleSource>\n"
            << "  </VRTRasterBand>\n</VRTDataset>\n";
        return path("huge.vrt");
    }

    fs::path dir_;
};

// ---- A header declaring a vast grid -------------------------------------------------------------

TEST(ConvergenceLattice, StaysAtSixtyFourCellsOnRealDemsAndBoundedOnVastOnes) {
    // Every DEM of up to 65 000 cells a side keeps its lattice (and so its outputs' bits).
    EXPECT_EQ(convergenceStepCells(3601, 3601), 64u);
    EXPECT_EQ(convergenceStepCells(40000, 40000), 64u);
    EXPECT_EQ(convergenceStepCells(100000, 1), 64u);
    for (const std::size_t side : {70000ul, 1000000ul, 4194304ul}) {
        const std::size_t step = convergenceStepCells(side, side);
        const std::size_t nodes = ((side - 1) / step + 2) * ((side - 1) / step + 2);
        EXPECT_LE(nodes, std::size_t{1} << 20) << side;
        EXPECT_GT(((side - 1) / (step / 2) + 2) * ((side - 1) / (step / 2) + 2), std::size_t{1} << 20)
            << side << ": a finer lattice would have fitted";
    }
}

// The lattice of a vast DEM is coarser, and still gives the convergence PROJ gives at any cell.
TEST_F(HostileInput, AVastDemHasABoundedLatticeThatStillGivesTheConvergence) {
    const std::size_t side = 200000;
    const Dem dem = openDem(hugeVrt(side, side, 0.5), {});
    const ConvergenceField& g = dem.terrain.convergence;
    EXPECT_LE(g.gammaDeg.size(), std::size_t{1} << 20);
    EXPECT_EQ(dem.terrain.rowLatitudeDeg.size(), side);
    const auto& gt = dem.band.ref.geoTransform;
    for (const auto& [col, row] : std::vector<std::pair<double, double>>{{0.5, 0.5}, {77777.5, 123456.5}, {199999.5, 199999.5}, {100000.5, 3.5}}) {
        // gamma from PROJ at this very cell: the grid direction of a step north.
        const auto [lat, lon] = cellLatLon(dem, col, row);
        const auto [x2, y2] = crsPointOfWgs84(dem, lat + 1e-4, lon);
        const double x = gt[0] + col * gt[1], y = gt[3] + row * gt[5];
        const double gammaDeg = -std::atan2(x2 - x, y2 - y) * 180.0 / M_PI;
        // The lattice's stated accuracy (demlight/geo/dem.cpp): far below 0.001 degrees.
        EXPECT_NEAR(g.at(col, row), gammaDeg, 1e-3) << col << ", " << row;
    }
}

// Opening reports its work and stops when asked, not after it.
TEST_F(HostileInput, OpeningAVastDemStopsWhenAsked) {
    const std::string vrt = hugeVrt(1000000, 1000000, 0.01);
    int calls = 0;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW(openDem(vrt, {},
                         [&](double fraction, const std::string& stage) {
                             EXPECT_EQ(stage, "opening DEM");
                             EXPECT_GE(fraction, 0.0);
                             return ++calls < 3;
                         }),
                 Cancelled);
    EXPECT_EQ(calls, 3);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

TEST_F(HostileInput, AHeaderDeclaringBillionsOfRowsIsRefused) {
    try {
        openDem(hugeVrt(100, 2000000000, 0.001), {});
        FAIL() << "opened";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("2000000000 cells"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("at most 4194304 cells a side"), std::string::npos) << e.what();
    }
}

/// The demlight binary started with `args` (SIGINT at its default disposition), stderr to
/// `errPath`.
pid_t startDemlight(const std::vector<std::string>& args, const std::string& errPath) {
    std::vector<std::string> copies = args;
    std::string program = DEMLIGHT_CLI_PATH;
    std::vector<char*> argv = {program.data()};
    for (std::string& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::signal(SIGINT, SIG_DFL);
        const int fd = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) ::dup2(fd, 2);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    return pid;
}

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// SIGINT at several moments of a run on a 10^6 x 10^6 UTM VRT (inside the opening, in its pass
// over the heights) is answered at once: exit 130 after cleanup, and no gigabyte held meanwhile.
TEST_F(HostileInput, ASignalWhileOpeningAVastDemIsAnsweredAtOnce) {
    const std::string vrt = hugeVrt(1000000, 1000000, 0.01);
    // From 1 s: a signal in the first instants, before main() installs its handler, is another
    // matter (tests/output_safety_test.cpp).
    for (const double delayS : {1.0, 2.0, 4.0}) {
        SCOPED_TRACE("SIGINT after " + std::to_string(delayS) + " s");
        const pid_t pid = startDemlight({"sun", vrt, "--time", "2024-06-21T20:00Z", "-o", path("out.tif")}, path("err.txt"));
        ASSERT_GT(pid, 0);
        std::this_thread::sleep_for(std::chrono::duration<double>(delayS));
        ::kill(pid, SIGINT);
        const auto signalled = std::chrono::steady_clock::now();
        int status = 0;
        struct rusage usage {};
        pid_t ended = 0;
        // Generous for a loaded machine; before the fix it ran on for minutes.
        constexpr double kDeadlineS = 10;
        while ((ended = ::wait4(pid, &status, WNOHANG, &usage)) == 0 &&
               std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count() < kDeadlineS)
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        const double answeredS = std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
        if (ended == 0) {
            ::kill(pid, SIGKILL);
            ::wait4(pid, &status, 0, &usage);
            FAIL() << "still running " << kDeadlineS << " s after SIGINT: " << readText(path("err.txt"));
        }
        ASSERT_TRUE(WIFEXITED(status)) << readText(path("err.txt"));
        EXPECT_EQ(WEXITSTATUS(status), 130) << readText(path("err.txt"));
        EXPECT_NE(readText(path("err.txt")).find("demlight: cancelled"), std::string::npos);
        EXPECT_LT(answeredS, kDeadlineS);
        if (!underAddressSanitizer()) {
            EXPECT_LT(static_cast<double>(usage.ru_maxrss) * 1024.0, 400e6) << "peak resident set";
        }
        EXPECT_FALSE(fs::exists(path("out.tif")));
    }
}

// ---- Creation options asking for blocks no writer can hold -----------------------------------

TEST_F(HostileInput, CreationOptionsWithBlocksBeyondReachAreRefusedBeforeAnyWork) {
    const std::string dem = std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem";
    const auto r = runDemlight("sun '" + dem + "' --time 2024-06-21T20:00Z -o '" + path("o.tif") +
                               "' --co BLOCKXSIZE=1000000000 --co BLOCKYSIZE=1000000000");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("BLOCKXSIZE=1000000000"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("1 to 4096"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("o.tif")));
    for (const std::string co : {"BLOCKSIZE=0", "BLOCKYSIZE=4097", "BLOCKXSIZE=-256", "BLOCKXSIZE=1e9"}) {
        const auto bad = runDemlight("-q sun '" + dem + "' --time 2024-06-21T20:00Z -o '" + path("o.tif") + "' --co " + co);
        EXPECT_EQ(bad.exitCode, 2) << co << ": " << bad.err;
        EXPECT_NE(bad.err.find(co), std::string::npos) << bad.err;
    }
    // The largest blocks allowed are written.
    const auto ok = runDemlight("-q sun '" + dem + "' --time 2024-06-21T20:00Z -o '" + path("o.tif") +
                                "' --co BLOCKXSIZE=4096 --co BLOCKYSIZE=4096");
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
}

// The library refuses them too (Python's write, a caller of writeRaster), naming the option.
TEST_F(HostileInput, TheWriterRefusesBlocksBeyondReach) {
    Grid<float> v(40, 30, 1.0f);
    GeoReference ref;
    ref.geoTransform = {500000, 10, 0, 5200000, 0, -10};
    ref.crsWkt = kUtm10Wkt;
    for (const std::string format : {"GTiff", "COG"}) {
        WriteOptions o;
        o.format = format;
        o.creationOptions = {format == "COG" ? "BLOCKSIZE=1000000000" : "BLOCKXSIZE=1000000000"};
        try {
            writeRaster(path("w.tif"), {{&v, nullptr, "v", ""}}, ref, o);
            ADD_FAILURE() << format << ": written";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(o.creationOptions.front()), std::string::npos) << e.what();
        }
        EXPECT_THROW(checkCreationOptions(format, o.creationOptions), Error);
        EXPECT_FALSE(fs::exists(path("w.tif")));
    }
}

// ---- A long thin DEM --------------------------------------------------------------------------

// 20 000 x 1 cells whose search reaches across it: halos cannot read past the DEM, so one piece
// holds no more than a tile would, and the run is one piece (it was 79 tiles, each reading
// and sweeping the whole DEM).
TEST_F(HostileInput, ALongThinDemRunsInOnePiece) {
    Grid<float> h(20000, 1);
    for (std::size_t c = 0; c < h.width(); ++c) h(c, 0) = static_cast<float>(500 + 400 * std::sin(0.001 * static_cast<double>(c)));
    GeoReference ref;
    ref.geoTransform = {500000, 1, 0, 5200000, 0, -1};
    ref.crsWkt = kUtm10Wkt;
    writeRaster(path("thin.tif"), {{&h, nullptr, "height", "m"}}, ref, WriteOptions{});
    const auto r = runDemlight("sun '" + path("thin.tif") + "' --time 2024-06-21T20:00Z --memory-limit 2000 -o '" +
                               path("o.tif") + "'");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("tiles of up to"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(path("o.tif")));
}

}  // namespace
}  // namespace demlight
