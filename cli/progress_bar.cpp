#include "cli/progress_bar.h"

#include <cstdio>
#include <unistd.h>

namespace demlight::cli {

ProgressBar::ProgressBar(bool enabled)
    : enabled_(enabled && ::isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { finish(); }

ProgressFn ProgressBar::callback() {
    if (!enabled_) return {};
    return [this](double fraction, const std::string& stage) {
        constexpr int kWidth = 30;
        const int filled = static_cast<int>(fraction * kWidth + 0.5);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        std::fprintf(stderr, "\r%-22.22s [%.*s%*s] %3d%% %6.1fs", stage.c_str(), filled,
                     "##############################", kWidth - filled, "",
                     static_cast<int>(fraction * 100 + 0.5), seconds);
        std::fflush(stderr);
        drawn_ = true;
        return true;
    };
}

void ProgressBar::finish() {
    if (drawn_) std::fputc('\n', stderr);
    drawn_ = false;
}

}  // namespace demlight::cli
