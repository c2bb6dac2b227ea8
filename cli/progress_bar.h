// A terminal progress bar for long work, drawn on stderr; silent when stderr is not a terminal
// or --quiet is given (then only the final summary lines are printed by the commands).
#pragma once

#include "src/progress.h"

#include <chrono>
#include <string>

namespace demlight::cli {

class ProgressBar {
public:
    explicit ProgressBar(bool enabled);
    ~ProgressBar();
    /// A callback for the library.
    ProgressFn callback();
    /// Ends the current line.
    void finish();

private:
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace demlight::cli
