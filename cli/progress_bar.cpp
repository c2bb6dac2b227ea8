#include "cli/progress_bar.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unistd.h>

namespace demlight::cli {
namespace {

// Constant-initialised and lock-free: the signal handler may store to it at any moment.
std::atomic<bool> gCancelRequested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

double steadySeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The time left for the rest of a stage at its rate so far, or empty while too little is done
/// to tell.
std::string timeLeft(double fraction, double elapsedS) {
    if (fraction < kMinEstimateFraction || elapsedS < kMinEstimateSeconds || fraction >= 1.0) return {};
    std::string text = "~";
    text += formatSpan(elapsedS * (1.0 - fraction) / fraction);
    text += " left";
    return text;
}

/// Whole per cent done, with a margin so that 0.7 (69.99999...) reads as 70.
int wholePercent(double fraction) {
    return static_cast<int>(std::floor(std::clamp(fraction, 0.0, 1.0) * 100.0 + 1e-9));
}

}  // namespace

void requestCancel() noexcept { gCancelRequested.store(true, std::memory_order_relaxed); }

bool cancelRequested() noexcept { return gCancelRequested.load(std::memory_order_relaxed); }

std::string formatSpan(double seconds) {
    char buf[32];
    seconds = std::max(0.0, seconds);
    if (seconds < 9.95) {
        std::snprintf(buf, sizeof buf, "%.1f s", seconds);
        return buf;
    }
    const long long s = std::llround(seconds);
    if (s < 60) {
        std::snprintf(buf, sizeof buf, "%lld s", s);
    } else if (s < 3600) {
        std::snprintf(buf, sizeof buf, "%lld min %02lld s", s / 60, s % 60);
    } else {
        const long long m = (s + 30) / 60;  // minutes, rounded
        std::snprintf(buf, sizeof buf, "%lld h %02lld min", m / 60, m % 60);
    }
    return buf;
}

ProgressBar::ProgressBar(bool enabled)
    : ProgressBar(enabled, stderr, ::isatty(STDERR_FILENO) != 0, steadySeconds, &gCancelRequested) {}

ProgressBar::ProgressBar(bool enabled, std::FILE* out, bool isTerminal, Clock clock,
                         const std::atomic<bool>* cancel)
    : enabled_(enabled), out_(out), isTerminal_(isTerminal), clock_(std::move(clock)), cancel_(cancel),
      stageStartS_(clock_()) {}

ProgressBar::~ProgressBar() { finish(); }

ProgressFn ProgressBar::callback() {
    return [this](double fraction, const std::string& stage) {
        if (enabled_) report(fraction, stage);
        return !cancel_->load(std::memory_order_relaxed);
    };
}

void ProgressBar::report(double fraction, const std::string& stage) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double nowS = clock_();
    // A stage whose count goes on from where the last one stopped (the next tile of a tiled job,
    // "tile 3/8: sky" after "tile 2/8: sky") is the same count under a new name: it keeps the
    // clock, so the time left is the whole job's.
    const bool continues = inStage_ && fraction > 0 && fraction >= lastFraction_ && lastFraction_ < 1;
    if (!inStage_ || (stage != stage_ && !continues)) startStage(stage);
    stage_ = stage;
    lastReportS_ = nowS;
    lastFraction_ = fraction;
    const double elapsedS = nowS - stageStartS_;
    if (isTerminal_) {
        drawBar(fraction, elapsedS);
    } else {
        writeLine(fraction, elapsedS);
    }
}

void ProgressBar::startStage(const std::string& stage) {
    // The first stage runs from the bar's construction; a later one from the previous stage's
    // last report, the best guess at when it started.
    if (inStage_) stageStartS_ = lastReportS_;
    if (drawn_) std::fputc('\n', out_);  // keep the finished stage's bar on screen
    drawn_ = false;
    drawnChars_ = 0;
    inStage_ = true;
    stage_ = stage;
    linesStep_ = 0;
}

void ProgressBar::drawBar(double fraction, double elapsedS) {
    constexpr int kWidth = 30;
    const double f = std::clamp(fraction, 0.0, 1.0);
    const int filled = static_cast<int>(f * kWidth + 0.5);
    const std::string left = timeLeft(f, elapsedS);
    char buf[160];
    const int n = std::snprintf(buf, sizeof buf, "%-22.22s [%.*s%*s] %3d%% %s%s%s", stage_.c_str(), filled,
                                "##############################", kWidth - filled, "",
                                static_cast<int>(f * 100 + 0.5), formatSpan(elapsedS).c_str(),
                                left.empty() ? "" : ", ", left.c_str());
    const std::size_t chars = static_cast<std::size_t>(std::clamp(n, 0, static_cast<int>(sizeof buf) - 1));
    // Blank what the previous, longer drawing leaves behind.
    std::fprintf(out_, "\r%s%*s", buf, static_cast<int>(drawnChars_ > chars ? drawnChars_ - chars : 0), "");
    std::fflush(out_);
    drawn_ = true;
    drawnChars_ = std::max(drawnChars_, chars);
}

void ProgressBar::writeLine(double fraction, double elapsedS) {
    const int percent = wholePercent(fraction);
    const int step = percent / kLineStepPercent * kLineStepPercent;
    if (step <= linesStep_) return;
    linesStep_ = step;
    const std::string left = timeLeft(fraction, elapsedS);
    std::fprintf(out_, "%s: %d %% after %s%s%s\n", stage_.c_str(), percent, formatSpan(elapsedS).c_str(),
                 left.empty() ? "" : ", ", left.c_str());
    std::fflush(out_);
}

void ProgressBar::finish() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (drawn_) std::fputc('\n', out_);
    drawn_ = false;
    drawnChars_ = 0;
}

}  // namespace demlight::cli
