// The CLI's progress reporting (cli/progress_bar.h): lines for logs, a bar with the time left on
// a terminal, cancellation; and through the built binary, progress in a log, none with -q, and
// an interrupt that cancels with exit code 130.
#include "cli/progress_bar.h"
#include "cli_runner.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace demlight::cli {
namespace {

namespace fs = std::filesystem;

/// A memory FILE* and a clock the test sets, around one ProgressBar.
class Harness {
public:
    /// The bar is made at time startS.
    Harness(bool enabled, bool isTerminal, double startS = 0) : nowS(startS) {
        out_ = open_memstream(&buf_, &size_);
        bar_ = std::make_unique<ProgressBar>(enabled, out_, isTerminal, [this] { return nowS; }, &cancel);
        fn = bar_->callback();
    }
    ~Harness() {
        bar_.reset();
        std::fclose(out_);
        std::free(buf_);
    }
    /// Reports `fraction` of `stage` at time tS.
    bool report(double fraction, const std::string& stage, double tS) {
        nowS = tS;
        return fn(fraction, stage);
    }
    void finish() { bar_->finish(); }
    std::string text() {
        std::fflush(out_);
        return std::string(buf_, size_);
    }
    std::vector<std::string> lines() {
        std::vector<std::string> v;
        std::istringstream in(text());
        for (std::string line; std::getline(in, line);) v.push_back(line);
        return v;
    }

    double nowS = 0;
    std::atomic<bool> cancel{false};
    ProgressFn fn;

private:
    char* buf_ = nullptr;
    std::size_t size_ = 0;
    std::FILE* out_ = nullptr;
    std::unique_ptr<ProgressBar> bar_;
};

TEST(ProgressBar, WithoutTerminalWritesOneLinePerTenPercent) {
    Harness h(true, false);
    // 1 % per call at 0.1 s each, as ProgressCounter's 100 updates of a 10 s stage.
    for (int i = 1; i <= 100; ++i) EXPECT_TRUE(h.report(i / 100.0, "sun", i / 10.0));
    const std::vector<std::string> expected = {
        "sun: 10 % after 1.0 s, ~9.0 s left", "sun: 20 % after 2.0 s, ~8.0 s left",
        "sun: 30 % after 3.0 s, ~7.0 s left", "sun: 40 % after 4.0 s, ~6.0 s left",
        "sun: 50 % after 5.0 s, ~5.0 s left", "sun: 60 % after 6.0 s, ~4.0 s left",
        "sun: 70 % after 7.0 s, ~3.0 s left", "sun: 80 % after 8.0 s, ~2.0 s left",
        "sun: 90 % after 9.0 s, ~1.0 s left", "sun: 100 % after 10 s"};
    EXPECT_EQ(h.lines(), expected);
    h.finish();
    const std::string all = h.text();
    EXPECT_EQ(all.find('\r'), std::string::npos) << all;
    EXPECT_EQ(all.back(), '\n');
    EXPECT_EQ(all.size(), all.find("10 s\n") + 5) << "finish() adds nothing to a log";
}

TEST(ProgressBar, WithoutTerminalAJumpGivesOneLineWithTheActualPercent) {
    Harness h(true, false);
    h.report(0.05, "sky", 0.5);
    h.report(0.35, "sky", 3.5);  // crosses 10, 20 and 30 %
    h.report(0.36, "sky", 3.6);
    h.report(0.40, "sky", 4.0);
    h.report(0.39, "sky", 4.1);  // a late report from another thread
    const std::vector<std::string> expected = {"sky: 35 % after 3.5 s, ~6.5 s left",
                                               "sky: 40 % after 4.0 s, ~6.0 s left"};
    EXPECT_EQ(h.lines(), expected);
}

TEST(ProgressBar, ANewStageStartsTheCountAndTheClockAfresh) {
    Harness h(true, false, 100);  // the clock's origin is arbitrary
    for (int i = 1; i <= 10; ++i) h.report(i / 10.0, "sky", 100 + i * 0.5);   // 5 s
    for (int i = 1; i <= 10; ++i) h.report(i / 10.0, "sunhours", 105 + i);    // 10 s
    const std::vector<std::string> lines = h.lines();
    ASSERT_EQ(lines.size(), 20u) << h.text();
    EXPECT_EQ(lines[0], "sky: 10 % after 0.5 s");  // under a second: no estimate yet
    EXPECT_EQ(lines[1], "sky: 20 % after 1.0 s, ~4.0 s left");
    EXPECT_EQ(lines[9], "sky: 100 % after 5.0 s");
    // The second stage is timed from the first one's last report.
    EXPECT_EQ(lines[10], "sunhours: 10 % after 1.0 s, ~9.0 s left");
    EXPECT_EQ(lines[19], "sunhours: 100 % after 10 s");
}

// Tiles of one job (demlight/products/tiles.h tileProgress) report the job's fraction under a stage named
// by the tile: the clock and the ten-per-cent lines run over the whole job, not per tile.
TEST(ProgressBar, TilesOfOneJobKeepTheJobsClock) {
    Harness h(true, false, 0);
    for (int tile = 0; tile < 4; ++tile)
        for (int i = 1; i <= 5; ++i) {
            const double f = (tile + i / 5.0) / 4.0;
            h.report(f, "tile " + std::to_string(tile + 1) + "/4: sky", tile * 10.0 + i * 2.0);
        }
    const std::vector<std::string> lines = h.lines();
    ASSERT_EQ(lines.size(), 10u) << h.text();
    EXPECT_EQ(lines[0], "tile 1/4: sky: 10 % after 4.0 s, ~36 s left");
    EXPECT_EQ(lines[2], "tile 2/4: sky: 30 % after 12 s, ~28 s left");
    EXPECT_EQ(lines[9], "tile 4/4: sky: 100 % after 40 s");
}

TEST(ProgressBar, OnATerminalRedrawsOneLineWithTheTimeLeft) {
    Harness h(true, true);
    h.report(0.01, "sun", 2.0);  // under 2 %: no estimate
    std::string t = h.text();
    EXPECT_EQ(t.front(), '\r');
    EXPECT_NE(t.find("sun"), std::string::npos) << t;
    EXPECT_NE(t.find("  1%"), std::string::npos) << t;
    EXPECT_EQ(t.find("left"), std::string::npos) << t;
    h.report(0.5, "sun", 0.5);  // half done but under a second: no estimate
    EXPECT_EQ(h.text().find("left"), std::string::npos) << h.text();
    h.report(0.25, "sun", 30.0);
    t = h.text();
    EXPECT_NE(t.find("[########"), std::string::npos) << t;
    EXPECT_NE(t.find(" 25% 30 s, ~1 min 30 s left"), std::string::npos) << t;
    EXPECT_EQ(t.find('\n'), std::string::npos) << "no newline while the bar runs";
    h.finish();
    EXPECT_EQ(h.text().back(), '\n');
    h.finish();
    EXPECT_EQ(h.text().find('\n'), h.text().size() - 1) << "a second finish() adds nothing";
}

TEST(ProgressBar, OnATerminalAShorterRedrawBlanksTheRest) {
    Harness h(true, true);
    h.report(0.5, "sun", 600.0);  // "10 min 00 s, ~10 min 00 s left"
    h.report(0.99, "sun", 601.0);  // much shorter estimate
    const std::string t = h.text();
    const std::size_t second = t.rfind('\r');
    ASSERT_NE(second, std::string::npos);
    EXPECT_EQ(t.size() - second, second) << "both drawings are as long:\n" << t;
}

TEST(ProgressBar, OnATerminalANewStageKeepsTheFinishedBar) {
    Harness h(true, true);
    h.report(1.0, "sky", 1.0);
    h.report(0.5, "sunhours", 2.0);
    const std::string t = h.text();
    const std::size_t nl = t.find('\n');
    ASSERT_NE(nl, std::string::npos) << t;
    EXPECT_NE(t.substr(0, nl).find("sky"), std::string::npos) << t;
    EXPECT_NE(t.substr(nl).find("\rsunhours"), std::string::npos) << t;
}

TEST(ProgressBar, QuietWritesNothingButStillCancels) {
    Harness h(false, false);
    for (int i = 1; i <= 100; ++i) EXPECT_TRUE(h.report(i / 100.0, "sun", i));
    h.finish();
    EXPECT_EQ(h.text(), "");
    h.cancel = true;
    EXPECT_FALSE(h.report(1.0, "sun", 101));
}

TEST(ProgressBar, CallbackReturnsFalseOnceCancelled) {
    for (const bool terminal : {false, true}) {
        Harness h(true, terminal);
        EXPECT_TRUE(h.report(0.1, "sun", 1));
        h.cancel = true;
        EXPECT_FALSE(h.report(0.2, "sun", 2));
        EXPECT_FALSE(h.report(0.3, "sun", 3));
    }
}

// The library's cancellation path through ProgressCounter: the bar's false stops the counter.
TEST(ProgressBar, CancelStopsAProgressCounter) {
    Harness h(true, false);
    ProgressCounter counter(h.fn, "sun", 100, 100);
    EXPECT_TRUE(counter.advance(10));
    h.cancel = true;
    EXPECT_FALSE(counter.advance(10));
    EXPECT_THROW(counter.throwIfCancelled(), Cancelled);
}

TEST(ProgressBar, FormatSpanReadsAsAPersonWouldSayIt) {
    const std::vector<std::pair<double, std::string>> cases = {
        {0.0, "0.0 s"},       {4.24, "4.2 s"},        {9.94, "9.9 s"},      {9.96, "10 s"},
        {12.4, "12 s"},       {59.4, "59 s"},         {59.6, "1 min 00 s"}, {185, "3 min 05 s"},
        {3599.4, "59 min 59 s"}, {3600, "1 h 00 min"}, {4830, "1 h 21 min"}, {-3, "0.0 s"}};
    for (const auto& [s, text] : cases) EXPECT_EQ(formatSpan(s), text) << s;
}

// --- through the built binary ---

const std::string kRocky = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

TEST(ProgressCli, ALogGetsPercentLines) {
    const fs::path dir = freshDir("demlight_progress_log");
    // The sun on this small DEM is one sweep, reported once when done.
    const auto r = testing::runDemlight("sun " + kRocky + " -o " + (dir / "x.tif").string() +
                                        " --time 2024-06-21T12:00Z");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("sun: 100 % after "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
}

// Sun hours run two stages, the sky factors then the instants: each counts up to 100 % afresh.
TEST(ProgressCli, EachStageCountsToAHundred) {
    const fs::path dir = freshDir("demlight_progress_stages");
    const auto r = testing::runDemlight("sunhours " + kRocky + " -o " + (dir / "x.tif").string() +
                                        " --date 2024-06-21 --tz America/Denver");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
    std::vector<std::pair<std::string, int>> seen;  // stage, per cent
    std::istringstream in(r.err);
    for (std::string line; std::getline(in, line);) {
        const std::size_t colon = line.find(": "), pct = line.find(" % after ");
        if (colon == std::string::npos || pct == std::string::npos) continue;
        seen.emplace_back(line.substr(0, colon), std::stoi(line.substr(colon + 2, pct - colon - 2)));
    }
    ASSERT_FALSE(seen.empty()) << r.err;
    std::vector<std::string> stages;
    for (std::size_t i = 0; i < seen.size(); ++i) {
        if (i == 0 || seen[i].first != seen[i - 1].first) {
            stages.push_back(seen[i].first);
            EXPECT_LE(seen[i].second, 20) << "a stage starts low: " << r.err;
        } else {
            EXPECT_GT(seen[i].second, seen[i - 1].second) << r.err;
            EXPECT_GE(seen[i].second / kLineStepPercent, seen[i - 1].second / kLineStepPercent + 1)
                << "one line per step crossed: " << r.err;
        }
        if (i + 1 == seen.size() || seen[i + 1].first != seen[i].first) {
            EXPECT_EQ(seen[i].second, 100) << r.err;
        }
    }
    EXPECT_EQ(stages, (std::vector<std::string>{"sky", "sunhours"})) << r.err;
}

TEST(ProgressCli, QuietGetsNoProgress) {
    const fs::path dir = freshDir("demlight_progress_quiet");
    const auto r = testing::runDemlight("-q sun " + kRocky + " -o " + (dir / "x.tif").string() +
                                        " --time 2024-06-21T12:00Z");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find('%'), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(dir / "x.tif"));
}

/// Starts demlight with `args`, waits for its first progress line on stderr, sends `sig`, and
/// returns the wait status and all of stderr.
std::pair<int, std::string> interruptAfterFirstProgress(const std::vector<std::string>& args, int sig) {
    int pipeFd[2];
    if (::pipe(pipeFd) != 0) return {-1, "pipe failed"};
    // argv before fork(): the child of a threaded process may only make async-signal-safe calls.
    std::string exe = DEMLIGHT_CLI_PATH;
    std::vector<std::string> copy = args;
    std::vector<char*> argv{exe.data()};
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(pipeFd[1], STDERR_FILENO);
        ::close(pipeFd[0]);
        ::close(pipeFd[1]);
        ::execv(exe.c_str(), argv.data());
        ::_exit(127);
    }
    ::close(pipeFd[1]);
    std::string err;
    bool sent = false;
    char buf[4096];
    for (ssize_t n; (n = ::read(pipeFd[0], buf, sizeof buf)) > 0;) {
        err.append(buf, static_cast<std::size_t>(n));
        if (!sent && err.find(" % after ") != std::string::npos) {
            ::kill(pid, sig);
            sent = true;
        }
    }
    ::close(pipeFd[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (!sent) err += "\n(test: no progress line came, nothing was sent)";
    return {status, err};
}

TEST(ProgressCli, AnInterruptCancelsWithExitCode130AndNoOutput) {
    for (const int sig : {SIGINT, SIGTERM}) {
        const fs::path dir = freshDir("demlight_progress_interrupt");
        // The reference ray march: seconds of work with a progress report per row.
        const auto [status, err] = interruptAfterFirstProgress(
            {"horizon", kRocky, "-o", (dir / "h.tif").string(), "--method", "reference", "--directions", "16",
             "--threads", "1"},
            sig);
        ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << "\n" << err;
        EXPECT_EQ(WEXITSTATUS(status), 130) << err;
        EXPECT_NE(err.find("demlight: cancelled"), std::string::npos) << err;
        EXPECT_NE(err.find("stopping"), std::string::npos) << err;
        EXPECT_TRUE(fs::is_empty(dir)) << "no output or temporary file left";
    }
}

}  // namespace
}  // namespace demlight::cli
