// Outputs that survive odd paths, full disks and Ctrl-C (docs/design.md §8):
//  - a device, a fifo or a directory as an output is refused before any work and stays what it
//    was (the library's writers refuse it too);
//  - a write that fails (the file size limit, `ulimit -f`, stands in for a full disk: tests cannot
//    mount a small tmpfs) exits non-zero naming the problem and leaves no file under a final name
//    and no temporary file; the GIF writer notices a file cut short;
//  - SIGINT at any moment, once (stop at the next safe point) or twice (quit at once), leaves
//    no temporary file and no partial output;
//  - a time-lapse into a non-empty folder is refused unless --overwrite, which removes the
//    earlier run's files first;
//  - COG overviews are resampled per band by what it holds;
//  - --threads beyond kMaxThreads is refused, beyond the cores quietly capped; exit codes follow
//    the documented table;
//  - smaller ones: a date needs a time zone, a raster is named .tif, the horizon's mask follows
//    --of, years outside SPA's are refused, a missing input reads the same in every command.
#include "child_process.h"
#include "cli_runner.h"
#include "demlight/geo/image_out.h"
#include "demlight/geo/raster.h"
#include "demlight/geo/solar_position.h"
#include "demlight/geo/time.h"
#include "demlight/products/product.h"
#include "shared_dem.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <set>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace demlight {
namespace {

namespace fs = std::filesystem;
using testing::Child;
using testing::runDemlight;

const std::string kSamples = DEMLIGHT_SAMPLES_DIR;
const std::string kHelens = kSamples + "/mount_st_helens_1980_usgs.dem";
const std::string kTime = "2024-06-21T17:00Z";

/// An empty scratch folder named after the running test.
fs::path scratch(const std::string& suffix = {}) {
    const fs::path dir = fs::temp_directory_path() /
                         ("demlight_safety_" + std::to_string(::getpid()) + "_" +
                          std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + suffix);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

using testing::namesIn;

std::string joined(const std::set<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

/// Names of temporary files: "x.tmp1234", ".x.png.tmp1234", GDAL's "x.tmp1234.ovr.tmp".
bool isTemporary(const std::string& name) { return name.find(".tmp") != std::string::npos; }

/// Every file left in `dir` is whole: rasters read back through GDAL, pictures have their end.
void expectOnlyCompleteFiles(const fs::path& dir) {
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        const std::string name = e.path().filename().string();
        SCOPED_TRACE(name);
        EXPECT_FALSE(isTemporary(name)) << "temporary file left";
        EXPECT_GT(e.file_size(), 0u) << "empty file under a final name";
        if (e.path().extension() == ".tif") {
            EXPECT_NO_THROW(readRasterBands(e.path().string())) << "partial raster under a final name";
        } else if (e.path().extension() == ".png") {
            // A whole PNG ends with the IEND chunk and its CRC.
            std::ifstream f(e.path(), std::ios::binary);
            f.seekg(-12, std::ios::end);
            char tail[12] = {};
            f.read(tail, 12);
            EXPECT_EQ(std::string(tail + 4, 4), "IEND") << "partial PNG under a final name";
        } else if (e.path().extension() == ".gif") {
            std::ifstream f(e.path(), std::ios::binary);
            f.seekg(-1, std::ios::end);
            EXPECT_EQ(f.get(), 0x3B) << "GIF without its trailer";
        }
    }
}

bool isFifo(const fs::path& p) { return fs::status(p).type() == fs::file_type::fifo; }
bool isCharDevice(const fs::path& p) { return fs::status(p).type() == fs::file_type::character; }

// ---- Non-regular outputs -----------------------------------------------------------------------

/// The outputs of every command, as "command ... -o ", for a path to be appended.
std::vector<std::string> rasterCommands() {
    return {"sun " + kHelens + " --time " + kTime + " -o ",
            "sky " + kHelens + " -o ",
            "aperture " + kHelens + " -o ",
            "horizon " + kHelens + " --azimuth 90 -o ",
            "light " + kHelens + " --time " + kTime + " -o ",
            "sunhours " + kHelens + " --date 2024-06-21 --tz America/Los_Angeles --step 2h -o ",
            "render " + kHelens + " --time " + kTime + " -o "};
}

TEST(OutputSafety, NonRegularOutputsAreRefusedAndStayWhatTheyWere) {
    const fs::path dir = scratch();
    const fs::path fifo = dir / "pipe.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // A null device node of our own (as /dev/null, major 1 minor 3): the real one must not be
    // at stake if the refusal ever breaks. Needs root; without it only the fifo is tried.
    const fs::path device = dir / "null.tif";
    const bool haveDevice = ::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
    for (const std::string& command : rasterCommands()) {
        for (const fs::path& node : {fifo, device}) {
            if (node == device && !haveDevice) continue;
            SCOPED_TRACE(command + node.string());
            const auto start = std::chrono::steady_clock::now();
            const auto r = runDemlight("-q " + command + node.string());
            EXPECT_EQ(r.exitCode, 1);
            EXPECT_NE(r.err.find("'" + node.string() + "' is a"), std::string::npos) << r.err;
            EXPECT_NE(r.err.find("not a regular file; demlight writes files (a temporary file renamed into place)"),
                      std::string::npos)
                << r.err;
            EXPECT_TRUE(node == fifo ? isFifo(node) : isCharDevice(node)) << "the node was replaced";
            // Refused before any work: no progress, no result notes.
            EXPECT_EQ(r.err.find("wrote"), std::string::npos) << r.err;
            EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
        }
    }
    // The horizon's truncation mask beside its output is checked as well, before any work.
    const fs::path maskFifo = dir / "h.truncated.tif";
    ASSERT_EQ(::mkfifo(maskFifo.c_str(), 0600), 0);
    auto r = runDemlight("-q horizon " + kHelens + " --azimuth 90 -o " + (dir / "h.tif").string());
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("is a fifo (named pipe), not a regular file"), std::string::npos) << r.err;
    EXPECT_TRUE(isFifo(maskFifo));
    EXPECT_FALSE(fs::exists(dir / "h.tif"));
    // A time-lapse folder must be a folder or not exist.
    for (const fs::path& node : {fifo, device}) {
        if (node == device && !haveDevice) continue;
        r = runDemlight("-q timelapse " + kHelens + " --start 2024-06-21T08:00-07:00 --end 2024-06-21T09:00-07:00 -o " +
                        node.string());
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_NE(r.err.find("not a folder"), std::string::npos) << r.err;
        EXPECT_TRUE(node == fifo ? isFifo(node) : isCharDevice(node));
    }
    std::set<std::string> expected = {"pipe.png", "h.truncated.tif"};
    if (haveDevice) expected.insert("null.tif");
    EXPECT_EQ(namesIn(dir), expected);
}

// The library's writers refuse them too, whoever calls them.
TEST(OutputSafety, WritersRefuseNonRegularFiles) {
    const fs::path dir = scratch();
    Grid<float> z(4, 4, 1.0f);
    Image8 image;
    image.width = image.height = 4;
    image.rgba.assign(4 * 4 * 4, 128);
    for (const std::string name : {"a.tif", "a.png", "a.gif"}) {
        const fs::path fifo = dir / name;
        ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
        SCOPED_TRACE(name);
        if (name == "a.tif") {
            EXPECT_THROW(writeRaster(fifo.string(), {{&z, nullptr, "v", ""}}, GeoReference{}, WriteOptions{}), Error);
            WriteOptions cog;
            cog.format = "COG";
            EXPECT_THROW(writeRaster(fifo.string(), {{&z, nullptr, "v", ""}}, GeoReference{}, cog), Error);
        } else if (name == "a.png") {
            EXPECT_THROW(writeImage(fifo.string(), image), Error);
        } else {
            EXPECT_THROW(GifWriter(fifo.string(), 8), Error);
        }
        EXPECT_TRUE(isFifo(fifo));
    }
    EXPECT_EQ(namesIn(dir), (std::set<std::string>{"a.tif", "a.png", "a.gif"}));
}

// ---- Full disk ------------------------------------------------------------------------------------

/// `ulimit -f BLOCKS` (512-byte blocks in sh) with SIGXFSZ ignored: a write past the limit fails
/// with EFBIG, as one on a full disk fails with ENOSPC, and the process lives to report it.
std::string fileSizeLimit(int blocks) { return "trap '' XFSZ; ulimit -f " + std::to_string(blocks) + "; "; }

struct FullDiskCase {
    std::string args;     ///< after "-q "; OUT is replaced by the scratch folder
    int blocks;           ///< the file size limit
    std::string message;  ///< expected in stderr
};

TEST(OutputSafety, FullDiskLeavesNoFileAndNamesTheProblem) {
    // St Helens outputs are 0.2-2 MB; 100 blocks (51 200 bytes) stops each of them.
    const std::string tl = "timelapse " + kHelens + " --start 2024-06-21T08:00-07:00 --end 2024-06-21T12:00-07:00 --step 1h";
    const std::vector<FullDiskCase> cases = {
        {"sun " + kHelens + " --time " + kTime + " -o OUT/o.tif", 100, "file too large"},
        {"sky " + kHelens + " -o OUT/o.tif", 100, "file too large"},
        {"sky " + kHelens + " --of COG -o OUT/o.tif", 100, "file too large"},
        {"sky " + kHelens + " --of COG --co RESAMPLING=CUBIC --co BLOCKSIZE=128 -o OUT/o.tif", 100, "cannot write"},
        {"aperture " + kHelens + " -o OUT/o.tif", 100, "file too large"},
        {"horizon " + kHelens + " --directions 8 -o OUT/o.tif", 100, "file too large"},
        {"light " + kHelens + " --time " + kTime + " -o OUT/o.tif", 100, "file too large"},
        {"sunhours " + kHelens + " --date 2024-06-21 --tz America/Los_Angeles --step 2h -o OUT/o.tif", 100,
         "file too large"},
        {"render " + kHelens + " --time " + kTime + " -o OUT/o.png", 100, "file too large"},
        // OpenImageIO's GIF writer reports no failed write: the read-back does.
        {"render " + kHelens + " --time " + kTime + " -o OUT/o.gif", 100, "file too large"},
        // libjpeg ends the process itself on a write error (exit 1, its own message).
        {"render " + kHelens + " --time " + kTime + " -o OUT/o.jpg", 40, "write error"},
        // sky_k.tif (~410 KB) fails, or (880 blocks) passes and the first frame (~480 KB) fails.
        {tl + " -o OUT/tl", 100, "file too large"},
        {tl + " -o OUT/tl", 880, "file too large"},
        // The GIF alone: OpenImageIO reports no failed write, the read-back check does.
        {"timelapse " + kHelens + " --start 2024-06-21T08:00-07:00 --end 2024-06-21T18:00-07:00 --step 30m"
         " --formats gif -o OUT/tg",
         100, "file too large"},
    };
    for (const auto& c : cases) {
        const fs::path dir = scratch();
        std::string args = c.args;
        for (auto at = args.find("OUT"); at != std::string::npos; at = args.find("OUT")) args.replace(at, 3, dir.string());
        SCOPED_TRACE(args + " under ulimit -f " + std::to_string(c.blocks));
        const auto r = runDemlight("-q " + args, fileSizeLimit(c.blocks));
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        for (const auto& name : namesIn(dir)) {
            EXPECT_FALSE(isTemporary(name)) << name;
            // A time-lapse keeps the frames it finished (none here), not the shared sky_k.tif.
            EXPECT_TRUE(name == "tl" || name == "tg") << name;
        }
        // A time-lapse that wrote nothing whole leaves no empty folder of its own making.
        if (c.args.starts_with("timelapse") && c.blocks == 100 && c.args.ends_with("OUT/tl")) {
            EXPECT_FALSE(fs::exists(dir / "tl"));
        }
        expectOnlyCompleteFiles(dir);
    }
}

// demlight ignores SIGXFSZ itself: under a file size limit (no trap in the shell) the write
// fails and is reported, instead of the process being killed with its temporary file left.
TEST(OutputSafety, FileSizeLimitIsReportedNotFatal) {
    const fs::path dir = scratch();
    const auto r = runDemlight("-q sky " + kHelens + " -o " + (dir / "o.tif").string(), "ulimit -f 100; ");
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("file too large"), std::string::npos) << r.err;
    EXPECT_TRUE(namesIn(dir).empty()) << joined(namesIn(dir));
}

// ---- Signals -----------------------------------------------------------------------------------


bool anyTemporaryIn(const fs::path& dir) {
    const auto names = namesIn(dir);
    return std::any_of(names.begin(), names.end(), isTemporary);
}

std::string readText(const fs::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

/// When to interrupt: `delayS` after the start, or after the first temporary file appears
/// (writing has begun); `signals` SIGINTs 50 ms apart.
struct Interrupt {
    bool afterWritingStarts;
    double delayS;
    int signals;
};

/// Runs `args` (with -o into `dir`), interrupts it as `when` says, and checks the folder holds
/// no temporary and only complete files, and that the exit status is one the table allows.
void interruptAndCheck(const std::vector<std::string>& args, const fs::path& dir, const Interrupt& when) {
    SCOPED_TRACE((when.afterWritingStarts ? "after writing starts + " : "after start + ") +
                 std::to_string(when.delayS) + " s, " + std::to_string(when.signals) + " SIGINT");
    const fs::path errPath = dir.parent_path() / (dir.filename().string() + ".stderr");
    Child child(args, errPath);
    ASSERT_TRUE(child.started());
    const auto start = std::chrono::steady_clock::now();
    if (when.afterWritingStarts) {
        while (child.running() && !anyTemporaryIn(dir)) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(when.delayS));
    const bool signalled = child.running();
    for (int i = 0; i < when.signals && child.running(); ++i) {
        if (i > 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
        child.signal(SIGINT);
    }
    const int status = child.wait();
    const std::string err = readText(errPath);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    SCOPED_TRACE("stderr: " + err + " after " + std::to_string(seconds) + " s");
    if (signalled && when.signals == 2 && WIFSIGNALED(status)) {
        EXPECT_EQ(WTERMSIG(status), SIGINT);  // the second signal ends it at once, as SIGINT
    } else if (signalled && WIFSIGNALED(status) && WTERMSIG(status) == SIGINT && namesIn(dir).empty()) {
        // On a loaded machine the signal can arrive while the process is still starting, before
        // main() installs its handlers: the default action ends it with nothing written.
    } else {
        ASSERT_TRUE(WIFEXITED(status));
        // 130: cancelled by the first signal; 0: it finished before the signal took effect.
        EXPECT_TRUE(WEXITSTATUS(status) == 130 || WEXITSTATUS(status) == 0) << WEXITSTATUS(status);
        if (WEXITSTATUS(status) == 130) {
            EXPECT_NE(err.find("demlight: cancelled"), std::string::npos);
        }
    }
    EXPECT_FALSE(anyTemporaryIn(dir)) << joined(namesIn(dir));
    expectOnlyCompleteFiles(dir);
}

// Writing a big output takes seconds (DEFLATE level 9 on the 3601² tile): SIGINT while it
// writes, once or twice, at several moments, and during the compute before it.
TEST(OutputSafety, SigintAtAnyMomentLeavesNoTemporaryFile) {
    const std::string big = sharedDemPath("N48W125_srtm1.tif");
    if (!fs::exists(big)) GTEST_SKIP() << "shared DEM " << big << " absent";
    const std::vector<Interrupt> moments = {{false, 0.3, 1}, {false, 1.0, 2}, {true, 0.0, 1}, {true, 0.5, 1},
                                            {true, 0.0, 2},  {true, 1.0, 2}};
    int run = 0;
    for (const auto& when : moments) {
        const fs::path dir = scratch("_" + std::to_string(run++));
        interruptAndCheck({"-q", "sun", big, "--time", "2024-06-21T20:00Z", "--co", "COMPRESS=DEFLATE", "--co",
                           "ZLEVEL=9", "-o", (dir / "out.tif").string()},
                          dir, when);
    }
    // COG: overviews built in memory, then GDAL's copy into the file (and its own .ovr.tmp when
    // told to resample every band alike).
    for (const auto& when : {Interrupt{true, 0.2, 1}, Interrupt{true, 0.2, 2}, Interrupt{false, 2.5, 2}}) {
        const fs::path dir = scratch("_" + std::to_string(run++));
        interruptAndCheck({"-q", "sun", big, "--time", "2024-06-21T20:00Z", "--of", "COG", "-o", (dir / "out.tif").string()},
                          dir, when);
        const fs::path dir2 = scratch("_" + std::to_string(run++));
        interruptAndCheck({"-q", "sun", big, "--time", "2024-06-21T20:00Z", "--of", "COG", "--co", "RESAMPLING=CUBIC",
                           "-o", (dir2 / "out.tif").string()},
                          dir2, when);
    }
}

// A time-lapse writes frames, the GIF and the index while it computes: interrupted, it keeps
// only whole frames, and neither the GIF nor frames.csv of an unfinished run.
TEST(OutputSafety, SigintDuringATimelapseLeavesNoTemporaryFile) {
    int run = 0;
    for (const auto& when : {Interrupt{true, 0.3, 1}, Interrupt{true, 0.3, 2}, Interrupt{true, 1.0, 2}}) {
        const fs::path dir = scratch("_" + std::to_string(run++));
        interruptAndCheck({"-q", "timelapse", kHelens, "--date", "2024-06-21", "--tz", "America/Los_Angeles", "--step",
                           "5m", "-o", (dir / "tl").string()},
                          dir, when);
        if (fs::exists(dir / "tl" / "frames.csv")) {
            // It finished: then the whole set is there.
            EXPECT_TRUE(fs::exists(dir / "tl" / "timelapse.gif"));
        } else {
            EXPECT_FALSE(fs::exists(dir / "tl" / "timelapse.gif"));
        }
    }
}

// The writer's own cancellation (WriteOptions::progress), as a library caller sees it.
TEST(OutputSafety, CancelledWriteRemovesItsTemporaryFile) {
    const fs::path dir = scratch();
    Grid<float> a(600, 700, 0.5f), b(600, 700, 0.25f);
    for (const std::string format : {"GTiff", "COG"}) {
        SCOPED_TRACE(format);
        WriteOptions o;
        o.format = format;
        int calls = 0;
        bool sawFile = false;
        // GTiff: stop at the second batch of tile rows (the second band's: the first band's tiles
        // are in the file); COG: once GDAL's copy has begun the file.
        o.progress = [&](double, const std::string&) {
            ++calls;
            sawFile = sawFile || anyTemporaryIn(dir);
            return format == "GTiff" ? calls < 2 : !sawFile;
        };
        const std::string out = (dir / "out.tif").string();
        EXPECT_THROW(writeRaster(out, {{&a, nullptr, "a", ""}, {&b, nullptr, "b", ""}}, GeoReference{}, o), Cancelled);
        EXPECT_TRUE(sawFile);
        EXPECT_TRUE(namesIn(dir).empty()) << joined(namesIn(dir));
    }
}

// ---- Time-lapse folders ----------------------------------------------------------------------------

TEST(OutputSafety, TimelapseIntoANonEmptyFolderNeedsOverwrite) {
    const fs::path dir = scratch();
    const fs::path tl = dir / "tl";
    const std::string base = "-q timelapse " + kHelens + " -o " + tl.string() + " --step 1h --formats tif,png,gif";
    auto r = runDemlight(base + " --start 2024-06-21T08:00-07:00 --end 2024-06-21T11:00-07:00 --fit-degree 1");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_TRUE(fs::exists(tl / "frame_003.png"));
    std::ofstream(tl / "notes.txt") << "mine\n";
    const std::set<std::string> before = namesIn(tl);

    // A second run with fewer frames would leave frame_002/003 of the first beside its own.
    const std::string second = base + " --start 2024-06-21T09:00-07:00 --end 2024-06-21T10:00-07:00";
    r = runDemlight(second);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--overwrite not given, and the folder '" + tl.string() + "' is not empty"), std::string::npos)
        << r.err;
    EXPECT_EQ(namesIn(tl), before) << "the folder changed";

    r = runDemlight(second + " --overwrite");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(namesIn(tl), (std::set<std::string>{"frame_000.tif", "frame_001.tif", "frame_000.png", "frame_001.png",
                                                  "sky_k.tif", "frames.csv", "timelapse.gif", "notes.txt"}));
    const std::string index = readText(tl / "frames.csv");
    EXPECT_EQ(std::count(index.begin(), index.end(), '\n'), 3) << index;  // header + 2 frames
    EXPECT_NE(index.find("2024-06-21T09:00"), std::string::npos) << index;
    EXPECT_EQ(readText(tl / "notes.txt"), "mine\n");
}

// ---- COG overviews ----------------------------------------------------------------------------------

/// The distinct values of a band (NaN left out).
std::set<float> valuesOf(const Grid<float>& g) {
    std::set<float> out;
    for (float v : g.values())
        if (!std::isnan(v)) out.insert(v);
    return out;
}

/// Writes `command` as a COG with 128-cell tiles (the samples are smaller than the default
/// 512, which would give them no overviews) and returns the full bands and overview 0.
std::pair<std::vector<Grid<float>>, std::vector<Grid<float>>> cogWithOverviews(const std::string& command,
                                                                                const fs::path& out) {
    const auto r = runDemlight("-q " + command + " --of COG --co BLOCKSIZE=128 -o " + out.string());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const RasterSummary s = inspectRaster(out.string());
    EXPECT_EQ(s.imageStructure.at("LAYOUT"), "COG");
    EXPECT_GE(s.overviews, 1u);
    return {readRasterBands(out.string()), readRasterOverview(out.string(), 0)};
}

TEST(OutputSafety, CogOverviewsKeepEachBandsValues) {
    const fs::path dir = scratch();
    // Fractions and irradiance (average): within the full band's range, in particular a
    // visibility in [0, 1] (cubic gave -0.24 .. 1.19).
    {
        const auto [full, ovr] = cogWithOverviews("sun " + kHelens + " --time 2024-06-21T13:30Z", dir / "sun.tif");
        ASSERT_EQ(full.size(), 2u);
        for (std::size_t b = 0; b < 2; ++b) {
            SCOPED_TRACE("sun band " + std::to_string(b + 1));
            const auto all = valuesOf(full[b]);
            const auto coarse = valuesOf(ovr[b]);
            ASSERT_FALSE(coarse.empty());
            EXPECT_GE(*coarse.begin(), *all.begin());
            EXPECT_LE(*coarse.rbegin(), *all.rbegin());
        }
        EXPECT_GE(*valuesOf(ovr[0]).begin(), 0.0f);
        EXPECT_LE(*valuesOf(ovr[0]).rbegin(), 1.0f);
    }
    {
        const auto [full, ovr] = cogWithOverviews("sky " + kHelens, dir / "sky.tif");
        for (std::size_t b = 0; b < full.size(); ++b) {
            SCOPED_TRACE("sky band " + std::to_string(b + 1));
            const auto all = valuesOf(full[b]);
            const auto coarse = valuesOf(ovr[b]);
            EXPECT_GE(*coarse.begin(), *all.begin());
            EXPECT_LE(*coarse.rbegin(), *all.rbegin());
        }
    }
    // Markers (nearest): every overview value is one of the band's own, -1 "never lit" kept as
    // such; no blend like -0.4 or 2 a.m.
    {
        const auto [full, ovr] = cogWithOverviews(
            "sunhours " + kHelens + " --date 2024-12-21 --tz America/Los_Angeles --step 30m", dir / "sh.tif");
        ASSERT_EQ(full.size(), 5u);
        for (std::size_t b : {3u, 4u}) {  // first_lit, last_lit
            SCOPED_TRACE("sunhours band " + std::to_string(b + 1));
            const auto all = valuesOf(full[b]);
            ASSERT_TRUE(all.count(-1.0f)) << "no never-lit cell: the test needs one";
            for (float v : valuesOf(ovr[b])) EXPECT_TRUE(all.count(v)) << v;
        }
    }
    {
        // Scan lines only (--near-field 0): cells on the DEM's edge looking out see no terrain
        // (-90), a marker to keep. (With the near field they see the edge's outer half cell.)
        const auto [full, ovr] =
            cogWithOverviews("horizon " + kHelens + " --directions 4 --near-field 0", dir / "hz.tif");
        for (std::size_t b = 0; b < full.size(); ++b) {
            SCOPED_TRACE("horizon band " + std::to_string(b + 1));
            const auto all = valuesOf(full[b]);
            for (float v : valuesOf(ovr[b])) EXPECT_TRUE(all.count(v)) << v;
        }
        EXPECT_TRUE(valuesOf(full[0]).count(-90.0f)) << "no 'no terrain' cell: the test needs one";
    }
}

// ---- Threads, exit codes --------------------------------------------------------------------------

TEST(OutputSafety, ThreadsBeyondTheMaximumAreRefused) {
    const fs::path dir = scratch();
    const std::string threads = " --threads " + std::to_string(kMaxThreads * 64 + 1);  // 65537 crashed TBB
    for (const std::string& command : std::vector<std::string>{"sky " + kHelens + " -o " + (dir / "o.tif").string(), "aperture " + kHelens + " -o " + (dir / "o.tif").string(),
          "sunhours " + kHelens + " --date 2024-06-21 --tz UTC -o " + (dir / "o.tif").string(),
          "render " + kHelens + " --time " + kTime + " -o " + (dir / "o.png").string(),
          "sun " + kHelens + " --time " + kTime + " -o " + (dir / "o.tif").string()}) {
        SCOPED_TRACE(command);
        const auto r = runDemlight("-q " + command + threads);
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_NE(r.err.find("--threads 65537: must be in [0, 1024]"), std::string::npos) << r.err;
    }
    EXPECT_TRUE(namesIn(dir).empty());
    // The library names the field.
    SearchRequest search;
    search.threads = 65537;
    const Terrain flat = [] {
        Terrain t;
        t.heightsM = Grid<float>(4, 4, 0.0f);
        return t;
    }();
    try {
        planFor(search, flat);
        ADD_FAILURE() << "65537 threads accepted";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "threads");
    }
}

TEST(OutputSafety, ExitCodesFollowTheTable) {
    const fs::path dir = scratch();
    const std::string out = " -o " + (dir / "o.tif").string();
    struct Case {
        std::string args;
        int code;
        std::string message;
    };
    const std::vector<Case> cases = {
        {"sun " + kHelens + " -o '' --time " + kTime, 1, "-o: the output path is empty"},
        {"sky " + kHelens + " -o ''", 1, "-o: the output path is empty"},
        {"render " + kHelens + " -o '' --time " + kTime, 1, "-o: the output path is empty"},
        {"timelapse " + kHelens + " -o '' --date 2024-06-21 --tz UTC", 1, "-o: the output folder path is empty"},
        {"sky /nonexistent/dem.tif" + out, 1, "no such file"},
        {"sky " + kHelens + out + " --no-such-option", 2, "--no-such-option"},
        {"sky" + out, 2, "DEM is required"},
        {"sky " + kHelens + out + " --albedo 2", 2, "--albedo"},
        {"skyy " + kHelens + out, 2, "unknown command 'skyy'"},
        {"--help", 0, ""},
        {"sky --help", 0, ""},
        {"--version", 0, ""},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.args);
        const auto r = runDemlight("-q " + c.args);
        EXPECT_EQ(r.exitCode, c.code) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    }
    // The table is in the help of every command.
    const auto help = runDemlight("sun --help");
    EXPECT_NE(help.out.find("Exit codes: 0 done, 1 error"), std::string::npos) << help.out;
}

// ---- Smaller ones ------------------------------------------------------------------------------

// A date alone has times too (its day runs midnight to midnight in some zone, first_lit and
// last_lit are clock times), so without --tz it is refused like a time without a zone; it was
// silently UTC.
TEST(OutputSafety, DatesWithoutATimeZoneAreRefused) {
    const fs::path dir = scratch();
    const std::string out = (dir / "sh.tif").string();
    for (const std::string& command :
         {"sunhours " + kHelens + " --date 2024-06-21 -o " + out,
          "sunhours " + kHelens + " --start 2024-06-21 --end 2024-06-22 -o " + out,
          "timelapse " + kHelens + " --date 2024-06-21 --formats tif -o " + (dir / "tl").string()}) {
        SCOPED_TRACE(command);
        const auto r = runDemlight("-q " + command);
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find("--tz missing: a date is a day from midnight to midnight in some time zone"),
                  std::string::npos)
            << r.err;
    }
    EXPECT_TRUE(namesIn(dir).empty()) << joined(namesIn(dir));
    // The library names the field; "UTC" is an explicit zone.
    try {
        zoneOfDays("");
        ADD_FAILURE() << "a day without a zone accepted";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "zone");
    }
    EXPECT_EQ(zoneOfDays("UTC").offsetAt(UtcInstant{}), std::chrono::seconds(0));
    const auto r = runDemlight("-q sunhours " + kHelens + " --date 2024-06-21 --tz UTC --step 2h -o " + out);
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

// sun -o out.png wrote a GeoTIFF named .png (readers take it for a picture).
TEST(OutputSafety, RastersNamedAsAnotherFormatAreRefused) {
    const fs::path dir = scratch();
    for (const std::string name : {"out.png", "out.jpg", "out.gif"}) {
        for (const std::string& command : rasterCommands()) {
            if (command.starts_with("render")) continue;  // render writes pictures
            SCOPED_TRACE(command + name);
            const auto r = runDemlight("-q " + command + (dir / name).string());
            EXPECT_EQ(r.exitCode, 1) << r.err;
            EXPECT_NE(r.err.find("its extension '" + fs::path(name).extension().string() +
                                 "' names another format, and this output is a GeoTIFF; name it .tif or .tiff"),
                      std::string::npos)
                << r.err;
        }
    }
    EXPECT_TRUE(namesIn(dir).empty()) << joined(namesIn(dir));
    // The library refuses it too; .tif and .TIFF are GeoTIFF names, and so is a name without one.
    const Grid<float> z(2, 2, 0.0f);
    EXPECT_THROW(writeRaster((dir / "x.png").string(), {{&z, nullptr, "v", ""}}, GeoReference{}, WriteOptions{}), Error);
    for (const std::string name : {"a.tif", "b.TIFF", "c"})
        EXPECT_NO_THROW(writeRaster((dir / name).string(), {{&z, nullptr, "v", ""}}, GeoReference{}, WriteOptions{}))
            << name;
}

// The truncation mask beside the horizons stayed a plain GTiff under --of COG.
TEST(OutputSafety, HorizonMaskFollowsTheOutputFormat) {
    const fs::path dir = scratch();
    const auto r = runDemlight("-q horizon " + kHelens + " --directions 2 --of COG -o " + (dir / "h.tif").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const std::string name : {"h.tif", "h.truncated.tif"}) {
        SCOPED_TRACE(name);
        const RasterSummary s = inspectRaster((dir / name).string());
        const auto layout = s.imageStructure.find("LAYOUT");
        ASSERT_NE(layout, s.imageStructure.end()) << "not a COG";
        EXPECT_EQ(layout->second, "COG");
    }
}

// --threads above the cores made TBB print "TBB Warning: The number of workers is currently
// limited to ..." on stderr, -q or not.
TEST(OutputSafety, ThreadsBeyondTheCoresPrintNothingUnderQuiet) {
    const fs::path dir = scratch();
    for (const std::string& command :
         {"sun " + kHelens + " --time " + kTime + " -o " + (dir / "o.tif").string(),
          "sky " + kHelens + " --sky-directions 8 -o " + (dir / "o.tif").string()}) {
        SCOPED_TRACE(command);
        const auto r = runDemlight("-q " + command + " --threads " + std::to_string(kMaxThreads));
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(r.err, "");
    }
}

// A year past SPA's validity (6000) was accepted and its sun shown as exactly as any other.
TEST(OutputSafety, YearsOutsideSpaAreRefused) {
    const fs::path dir = scratch();
    const std::string message = "outside the years -2000 to 6000 the solar position algorithm (NREL SPA) is valid for";
    for (const std::string& command :
         {"sun " + kHelens + " --time 6001-06-21T12:00Z -o " + (dir / "o.tif").string(),
          "light " + kHelens + " --time 9999-06-21T12:00Z -o " + (dir / "o.tif").string(),
          "sunhours " + kHelens + " --date 6001-06-21 --tz UTC -o " + (dir / "o.tif").string(),
          "timelapse " + kHelens + " --start 6001-06-21T12:00Z --end 6001-06-21T14:00Z --step 1h -o " +
              (dir / "tl").string(),
          "timelapse " + kHelens + " --date 6001-06-21 --tz UTC -o " + (dir / "tl").string(),
          std::string("sunpos --time 6001-01-01T00:00Z --lat 46 --lon 7")}) {
        SCOPED_TRACE(command);
        const auto r = runDemlight("-q " + command);
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    }
    EXPECT_TRUE(namesIn(dir).empty()) << joined(namesIn(dir));
    EXPECT_EQ(runDemlight("-q sunpos --time 6000-12-31T23:00Z --lat 46 --lon 7").exitCode, 0);
    // The library's bounds are inclusive years of UTC.
    const auto at = [](int year) {
        return UtcInstant{std::chrono::sys_days{std::chrono::year{year} / 6 / 21}};
    };
    EXPECT_NO_THROW(solarPosition(SolarSite{}, at(kSpaFirstYear)));
    EXPECT_NO_THROW(solarPosition(SolarSite{}, at(kSpaLastYear)));
    EXPECT_THROW(solarPosition(SolarSite{}, at(kSpaFirstYear - 1)), Error);
    EXPECT_THROW(solarPosition(SolarSite{}, at(kSpaLastYear + 1)), Error);
    EXPECT_THROW(sunEvents(SolarSite{}, at(kSpaLastYear + 1)), Error);
}

// info and every other command say the same about a missing input.
TEST(OutputSafety, MissingInputReadsTheSameInEveryCommand) {
    const fs::path dir = scratch();
    const std::string missing = (dir / "absent.tif").string();
    const std::string expected = "demlight: error: cannot open '" + missing + "': no such file\n";
    std::vector<std::string> commands = {"info " + missing,
                                         "timelapse " + missing + " --date 2024-06-21 --tz UTC -o " + (dir / "tl").string(),
                                         "sequence " + missing + " --time " + kTime + " -o " + (dir / "s.tif").string()};
    for (std::string command : rasterCommands()) {
        command.replace(command.find(kHelens), kHelens.size(), missing);
        commands.push_back(command + (dir / (command.starts_with("render") ? "o.png" : "o.tif")).string());
    }
    for (const std::string& command : commands) {
        SCOPED_TRACE(command);
        const auto r = runDemlight("-q " + command);
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_EQ(r.err, expected);
    }
    EXPECT_TRUE(namesIn(dir).empty()) << joined(namesIn(dir));
}

}  // namespace
}  // namespace demlight
