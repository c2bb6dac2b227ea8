// Progress of long work on stderr, and stopping it with Ctrl-C.
//  - stderr a terminal: one bar per stage, redrawn in place, with the time left once it can be
//    estimated (at least kMinEstimateFraction done and kMinEstimateSeconds passed);
//  - stderr not a terminal (a log, a batch job): one line per kLineStepPercent crossed,
//    "sun: 30 % after 4.2 s, ~9.8 s left", no carriage returns;
//  - quiet: nothing.
// A new stage label (the library passes one with every call: "sky", then "sunhours") starts the
// bar, the line count and the time estimate afresh. In every mode the callback returns false
// once requestCancel() was called (on the first Ctrl-C: cli/main.cpp, demlight/geo/signals.h), so the
// library throws demlight::Cancelled at its next safe point. Writing outputs checks
// cancelRequested() between strips (RunContext::cancelled, demlight/run/runner.h); work that
// reports no progress (reading the DEM) is not interrupted, and a command that reaches no further
// progress call after the request finishes normally.
#pragma once

#include "demlight/core/progress.h"

#include <atomic>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

namespace demlight::cli {

/// Share of a stage done before the time left is estimated: earlier rates are mostly start-up.
inline constexpr double kMinEstimateFraction = 0.02;
/// Seconds of a stage before the time left is estimated.
inline constexpr double kMinEstimateSeconds = 1.0;
/// Without a terminal, a line each time the stage crosses a multiple of this many per cent.
inline constexpr int kLineStepPercent = 10;

/// Asks every ProgressBar callback to return false from now on. Async-signal-safe (it only
/// stores a lock-free atomic), so a signal handler may call it.
void requestCancel() noexcept;
/// Whether requestCancel() was called in this process.
bool cancelRequested() noexcept;

/// "4.2 s", "12 s", "3 min 05 s", "1 h 20 min": a time span for a person to read.
std::string formatSpan(double seconds);

class ProgressBar {
public:
    /// Monotonic time in seconds (any origin).
    using Clock = std::function<double()>;

    /// Progress on stderr (a bar on a terminal, lines otherwise); nothing when !enabled (quiet).
    /// The callback follows requestCancel() either way.
    explicit ProgressBar(bool enabled);
    /// Progress on `out`, drawn as on a terminal when isTerminal, timed by `clock`, cancelled
    /// once `*cancel` is true (tests drive these).
    ProgressBar(bool enabled, std::FILE* out, bool isTerminal, Clock clock, const std::atomic<bool>* cancel);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    /// A callback for the library; it refers to this bar, which must outlive its use.
    ProgressFn callback();
    /// Ends the current bar's line (terminal).
    void finish();

private:
    void report(double fraction, const std::string& stage);
    void startStage(const std::string& stage);
    void drawBar(double fraction, double elapsedS);
    void writeLine(double fraction, double elapsedS);

    bool enabled_;
    std::FILE* out_;
    bool isTerminal_;
    Clock clock_;
    const std::atomic<bool>* cancel_;

    std::mutex mutex_;  // a bar may be shared by counters on several threads
    bool drawn_ = false;            // a bar is on the current terminal line
    std::size_t drawnChars_ = 0;    // its length, to blank what a shorter redraw leaves
    bool inStage_ = false;
    std::string stage_;
    double stageStartS_ = 0;
    double lastReportS_ = 0;
    double lastFraction_ = 0;
    int linesStep_ = 0;  // the highest multiple of kLineStepPercent already written
};

}  // namespace demlight::cli
