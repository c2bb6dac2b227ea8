// demlight run as an attacker would run it, and as an unlucky user does (docs/outputs.md
// "Security"):
//  - no file name, folder name or other user string reaches a shell or an interpreter: a DEM or
//    an output folder named with shell and gnuplot code runs none of it (the payload would make a
//    marker file);
//  - a link planted at any name a temporary file could have is never written through: the
//    temporary files live in private folders made by mkdtemp;
//  - a picture or chart cut short by a full disk or a file size limit is an error, never a file
//    under its final name with exit 0;
//  - two time-lapses into one folder: the second is refused while the first runs, and a run that
//    fails keeps only the frames it finished;
//  - a signal in the first milliseconds of the process is answered as one (exit 130).
#include "child_process.h"
#include "cli_runner.h"
#include "demlight/geo/output_file.h"
#include "demlight/core/error.h"
#include "demlight/core/process.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <set>
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
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

fs::path scratch(const std::string& suffix = {}) {
    const fs::path dir = fs::temp_directory_path() /
                         ("demlight_security_" + std::to_string(::getpid()) + "_" +
                          std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + suffix);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string quoted(const fs::path& p) {
    std::string q = "'";
    for (char c : p.string()) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

using testing::namesIn;

std::string joined(const std::set<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

std::string readText(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

bool anyTemporaryIn(const fs::path& dir) {
    for (const auto& n : namesIn(dir))
        if (n.find(".tmp") != std::string::npos) return true;
    return false;
}

// ---- No user string reaches an interpreter ---------------------------------------------------

// The bench chart's title is the DEM's name: it reaches gnuplot as an argument (ARG2), never as
// code. Before, it was pasted into `gnuplot -e "name='...'"`, and this name ran `touch`.
TEST(Security, BenchRunsNoGnuplotCodeFromTheDemsName) {
    if (!findProgram("gnuplot")) GTEST_SKIP() << "gnuplot is not installed";
    const fs::path dir = scratch();
    const fs::path dem = dir / "x'.system(\"touch PWNED\").'.dem";
    fs::copy_file(kHelens, dem);
    const fs::path out = dir / "bench";
    const auto r = runDemlight("-q bench " + quoted(dem) + " -o " + quoted(out) +
                               " --crop 48 --sample 10 --directions 4 --repeats 1");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(fs::exists(out / "PWNED")) << "gnuplot ran code from the DEM's name";
    EXPECT_FALSE(fs::exists("PWNED")) << "gnuplot ran code from the DEM's name";
    EXPECT_TRUE(fs::exists(out / "bench.png"));
    EXPECT_TRUE(fs::exists(out / "bench.svg"));
    // The title is the name as it is, drawn as text.
    EXPECT_NE(readText(out / "bench.svg").find("system"), std::string::npos);
    EXPECT_FALSE(anyTemporaryIn(dir)) << joined(namesIn(dir));
}

// The MP4 encoder starts from an argument vector: a folder name with `$(...)` and quotes in it is
// a name. Before, ffmpeg was started through the shell with the name in single quotes.
TEST(Security, TimelapseMp4RunsNoCommandFromTheFoldersName) {
    if (!findProgram("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed";
    const fs::path dir = scratch();
    const fs::path out = dir / "tl'$(touch PWNED)'%d";
    const auto r = runDemlight("-q timelapse " + kHelens + " --start 2024-06-21T08:00-07:00 --end 2024-06-21T09:00-07:00"
                               " --step 30m --formats mp4 -o " + quoted(out),
                               "cd " + quoted(dir) + " && ");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(fs::exists(dir / "PWNED")) << "the shell ran code from the folder's name";
    EXPECT_TRUE(fs::is_regular_file(out / "timelapse.mp4")) << joined(namesIn(dir));
    EXPECT_GT(fs::file_size(out / "timelapse.mp4"), 0u);
    EXPECT_FALSE(anyTemporaryIn(dir)) << joined(namesIn(dir));
}

TEST(Security, RunProgramPassesArgumentsAsTheyAre) {
    const fs::path dir = scratch();
    const std::string payload = "$(touch PWNED1); `touch PWNED2`; ' \" \\ %d";
    const ProgramExit run = runProgram({{"/bin/sh", "-c", "printf '%s' \"$1\" > arg.txt", "sh", payload}, dir.string(), {}});
    ASSERT_TRUE(run.ok()) << run.why;
    EXPECT_EQ(readText(dir / "arg.txt"), payload);
    EXPECT_FALSE(fs::exists(dir / "PWNED1"));
    EXPECT_FALSE(fs::exists(dir / "PWNED2"));
    const ProgramExit missing = runProgram({{"demlight-no-such-program"}, {}, {}});
    EXPECT_FALSE(missing.ok());
    EXPECT_FALSE(missing.why.empty());
}

// ---- No write through a planted link ---------------------------------------------------------

/// Plants, for every process id a run started now may get, a link at each temporary name an
/// earlier demlight used beside `finalPath` ("NAME.tmpPID", ".NAME.tmpPID") pointing at `victim`.
void plantLinks(const fs::path& finalPath, const fs::path& victim) {
    long last = 0;
    std::ifstream("/proc/sys/kernel/ns_last_pid") >> last;
    const std::string name = finalPath.filename().string();
    for (long pid = last + 1; pid <= last + 400; ++pid)
        for (const std::string& link : {name + ".tmp" + std::to_string(pid), "." + name + ".tmp" + std::to_string(pid)})
            fs::create_symlink(victim, finalPath.parent_path() / link);
}

TEST(Security, PlantedLinksAtTemporaryNamesAreNotFollowed) {
    struct Case {
        std::string args;  ///< OUT is replaced by the output path
        std::string output;
        std::vector<std::string> alsoWritten;  ///< other files the run writes beside its output
    };
    const std::vector<Case> cases = {
        {"sun " + kHelens + " --time " + kTime + " -o OUT", "o.tif", {}},
        {"sun " + kHelens + " --time " + kTime + " --of COG -o OUT", "o.tif", {"o.tif.stream.tif"}},
        {"render " + kHelens + " --time " + kTime + " -o OUT", "o.png", {}},
        {"render " + kHelens + " --time " + kTime + " -o OUT", "o.gif", {}},
        {"render " + kHelens + " --time " + kTime + " -o OUT", "o.jpg", {}},
        {"horizon " + kHelens + " --directions 4 -o OUT", "h.tif", {"h.truncated.tif"}},
    };
    for (const Case& c : cases) {
        const fs::path dir = scratch();
        const fs::path victim = dir / "victim.txt";
        std::ofstream(victim) << "precious";
        const fs::path out = dir / c.output;
        plantLinks(out, victim);
        for (const std::string& other : c.alsoWritten) plantLinks(dir / other, victim);
        std::string args = c.args;
        args.replace(args.find("OUT"), 3, out.string());
        SCOPED_TRACE(args);
        const auto r = runDemlight("-q " + args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(readText(victim), "precious") << "a write followed a planted link";
        EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(out))) << "the output is not a file of its own";
        for (const auto& e : fs::directory_iterator(dir))
            if (fs::is_directory(fs::symlink_status(e.path()))) ADD_FAILURE() << "left a folder: " << e.path();
    }
}

// A link at the final name is replaced by the output, not written through.
TEST(Security, ALinkAtTheOutputsNameIsReplacedNotFollowed) {
    const fs::path dir = scratch();
    const fs::path victim = dir / "victim.txt";
    std::ofstream(victim) << "precious";
    for (const std::string name : {"o.tif", "o.png"}) {
        fs::create_symlink(victim, dir / name);
        const auto r = runDemlight("-q " + std::string(name.ends_with("png") ? "render " : "sun ") + kHelens +
                                   " --time " + kTime + " -o " + (dir / name).string());
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / name)));
    }
    EXPECT_EQ(readText(victim), "precious");
}

// The private folder: made exclusively, mode 0700, the file inside under the final name; gone
// after commit and after discard. One a killed process left is removed by the next writer.
TEST(Security, TemporaryFilesLiveInAPrivateFolder) {
    const fs::path dir = scratch();
    const fs::path final = dir / "out.tif";
    {
        TemporaryFile tmp(final.string());
        const fs::path folder = fs::path(tmp.path()).parent_path();
        EXPECT_EQ(folder.parent_path(), dir);
        EXPECT_EQ(fs::path(tmp.path()).filename(), "out.tif");
        EXPECT_TRUE(folder.filename().string().starts_with(".out.tif.tmp" + std::to_string(::getpid()) + "-"));
        struct stat st {};
        ASSERT_EQ(::lstat(folder.c_str(), &st), 0);
        EXPECT_TRUE(S_ISDIR(st.st_mode));
        EXPECT_EQ(st.st_mode & 0777, 0700u);
        std::ofstream(tmp.path()) << "x";
        std::ofstream(tmp.path() + ".ovr.tmp") << "scratch";  // as GDAL's COG driver makes
        tmp.commit();
        EXPECT_FALSE(fs::exists(folder));
    }
    EXPECT_EQ(readText(final), "x");
    {
        TemporaryFile tmp(final.string());
        std::ofstream(tmp.path()) << "y";
    }  // discarded
    EXPECT_EQ(namesIn(dir), (std::set<std::string>{"out.tif"}));

    // In a folder this process has not written into yet: a private folder left by a process that
    // no longer runs (pid 2^22 + 1 is above Linux's pid_max) is removed by the first writer there;
    // one of a process that runs (this one) stays, as it may be writing; other names stay.
    const fs::path other = scratch("_other");
    const fs::path stale = other / ".other.tif.tmp4194305-AbC123";
    fs::create_directory(stale);
    std::ofstream(stale / "other.tif") << "partial";
    const fs::path live = other / (".busy.tif.tmp" + std::to_string(::getpid()) + "-XyZ789");
    fs::create_directory(live);
    std::ofstream(other / "notes.tmp4194305") << "a user's file";
    { TemporaryFile tmp((other / "next.tif").string()); }
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(live));
    EXPECT_TRUE(fs::exists(other / "notes.tmp4194305"));
}

TEST(Security, TemporaryNamesAreRecognised) {
    std::string final;
    EXPECT_TRUE(isTemporaryName(".out.tif.tmp123-AbC123", &final));
    EXPECT_EQ(final, "out.tif");
    EXPECT_TRUE(isTemporaryName("out.tif.tmp123", &final));
    EXPECT_EQ(final, "out.tif");
    EXPECT_FALSE(isTemporaryName("out.tif"));
    EXPECT_FALSE(isTemporaryName("notes.tmpl"));
    EXPECT_FALSE(isTemporaryName(".out.tif.tmp123-toolong1"));
}

// ---- No truncated file with exit 0 -----------------------------------------------------------

std::string fileSizeLimit(int blocks) { return "trap '' XFSZ; ulimit -f " + std::to_string(blocks) + "; "; }

// render's GIF (OpenImageIO's writer reports no failed write) and bench's chart (gnuplot exits 0
// with its picture cut short) under a file size limit: exit 1 naming the problem, no picture.
TEST(Security, PicturesCutShortAreErrorsNotFiles) {
    const fs::path dir = scratch();
    auto r = runDemlight("-q render " + kHelens + " --time " + kTime + " -o " + (dir / "r.gif").string(),
                         fileSizeLimit(100));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("cannot write"), std::string::npos) << r.err;
    EXPECT_TRUE(namesIn(dir).empty()) << joined(namesIn(dir));

    if (!findProgram("gnuplot")) GTEST_SKIP() << "gnuplot is not installed";
    const fs::path bench = dir / "bench";
    // 40 blocks (20 KB): the CSVs fit, the PNG chart does not.
    r = runDemlight("-q bench " + kHelens + " -o " + bench.string() + " --crop 48 --sample 10 --directions 4 --repeats 1",
                    fileSizeLimit(40));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("bench.png"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(bench / "bench.png"));
    EXPECT_FALSE(fs::exists(bench / "bench.svg"));
    EXPECT_FALSE(anyTemporaryIn(dir)) << joined(namesIn(dir));
}

// ---- Time-lapse folders ----------------------------------------------------------------------

// Two time-lapses into one new folder: while the first writes, the second is refused and
// changes nothing; the folder then holds the first run's set alone.
TEST(Security, ASecondTimelapseIntoTheSameFolderIsRefused) {
    const fs::path dir = scratch();
    const fs::path tl = dir / "tl";
    const std::vector<std::string> args = {"-q", "timelapse", kHelens, "--date", "2024-06-21", "--tz",
                                           "America/Los_Angeles", "--step", "10m", "-o", tl.string()};
    Child first(args, dir / "first.err");
    ASSERT_TRUE(first.started());
    // Wait until the first has started writing into the folder.
    const auto start = std::chrono::steady_clock::now();
    while (first.running() && !(fs::exists(tl) && !fs::is_empty(tl)) &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(first.running()) << "the first run ended before the second could start: " << readText(dir / "first.err");
    const auto second = runDemlight("-q timelapse " + kHelens + " --date 2024-06-21 --tz America/Los_Angeles --step 1h -o " +
                                    tl.string());
    EXPECT_EQ(second.exitCode, 1) << second.err;
    EXPECT_NE(second.err.find("being written by another demlight run"), std::string::npos) << second.err;
    const int status = first.wait();
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << readText(dir / "first.err");
    // The first run's frames only: its count at 10-minute steps, all listed in its frames.csv.
    std::size_t frames = 0;
    for (const auto& n : namesIn(tl)) frames += n.starts_with("frame_") && n.ends_with(".tif");
    const std::string index = readText(tl / "frames.csv");
    const auto rows = static_cast<std::size_t>(std::count(index.begin(), index.end(), '\n')) - 1;
    EXPECT_EQ(frames, rows);
    EXPECT_GT(frames, 24u);  // sunrise to sunset in 10-minute steps
    // And after it ended, a run without --overwrite is refused as the folder is not empty.
    const auto third = runDemlight("-q timelapse " + kHelens + " --date 2024-06-21 --tz America/Los_Angeles --step 1h -o " +
                                   tl.string());
    EXPECT_EQ(third.exitCode, 1);
    EXPECT_NE(third.err.find("not empty"), std::string::npos) << third.err;
}

// Stopped by a signal, a time-lapse keeps the frames it finished and nothing else: no sky_k.tif.
TEST(Security, AStoppedTimelapseKeepsOnlyItsFinishedFrames) {
    const fs::path dir = scratch();
    const fs::path tl = dir / "tl";
    Child run({"-q", "timelapse", kHelens, "--date", "2024-06-21", "--tz", "America/Los_Angeles", "--step", "5m", "-o",
               tl.string()},
              dir / "run.err");
    ASSERT_TRUE(run.started());
    const auto start = std::chrono::steady_clock::now();
    while (run.running() && !fs::exists(tl / "frame_002.tif") &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ASSERT_TRUE(run.running()) << "the run ended before it could be stopped";
    run.signal(SIGTERM);
    const int status = run.wait();
    ASSERT_TRUE(WIFEXITED(status)) << readText(dir / "run.err");
    EXPECT_EQ(WEXITSTATUS(status), 130) << readText(dir / "run.err");
    for (const auto& n : namesIn(tl)) {
        SCOPED_TRACE(n);
        EXPECT_TRUE(n.starts_with("frame_")) << "kept a file that is not a finished frame";
    }
    EXPECT_TRUE(fs::exists(tl / "frame_000.tif"));
}

// ---- Early signals ---------------------------------------------------------------------------

/// Whether process `pid` has SIGTERM blocked (its SigBlk mask in /proc), or has already moved on
/// to the program proper (demlight-core, which releases it).
bool sigtermBlocked(pid_t pid) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.starts_with("SigBlk:")) {
            const unsigned long long mask = std::stoull(line.substr(7), nullptr, 16);
            if (mask & (1ull << (SIGTERM - 1))) return true;
        }
    std::error_code ec;
    return fs::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec).filename() == "demlight-core";
}

// SIGTERM at once after the start, while the libraries load: exit 130 ("cancelled"), not killed
// by the signal (status 143 in a shell) as before main() installed its handlers.
TEST(Security, ASignalInTheFirstMillisecondsIsAnsweredAsOne) {
    const fs::path dir = scratch();
    int answered = 0, killed = 0;
    for (int i = 0; i < 20; ++i) {
        Child child({"sun", kHelens, "--time", kTime, "-o", (dir / "o.tif").string()}, dir / "err.txt");
        ASSERT_TRUE(child.started());
        // From the launcher's first instruction on (before it, no program can answer a signal):
        // its SIGTERM is blocked, as /proc shows.
        const auto start = std::chrono::steady_clock::now();
        while (!sigtermBlocked(child.pid()) && child.running() &&
               std::chrono::steady_clock::now() - start < std::chrono::seconds(10))
            std::this_thread::yield();
        std::this_thread::sleep_for(std::chrono::microseconds(2000 * i));
        child.signal(SIGTERM);
        const int status = child.wait();
        if (WIFSIGNALED(status)) {
            ++killed;
            continue;
        }
        ASSERT_TRUE(WIFEXITED(status));
        // 130 when the signal came before the run ended (0 only if it had already finished).
        if (WEXITSTATUS(status) == 130) ++answered;
        else EXPECT_EQ(WEXITSTATUS(status), 0) << readText(dir / "err.txt");
    }
    EXPECT_EQ(killed, 0) << "signals that ended the process before its handlers were installed";
    EXPECT_GT(answered, 0);
    EXPECT_FALSE(anyTemporaryIn(dir)) << joined(namesIn(dir));
}

}  // namespace
}  // namespace demlight
