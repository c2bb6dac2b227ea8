#include "demlight/core/progress.h"

#include "demlight/core/error.h"

#include <algorithm>

namespace demlight {

ProgressCounter::ProgressCounter(ProgressFn fn, std::string stage, std::size_t total, int updates)
    : fn_(std::move(fn)),
      stage_(std::move(stage)),
      total_(std::max<std::size_t>(total, 1)),
      step_(std::max<std::size_t>(total_ / static_cast<std::size_t>(std::max(updates, 1)), 1)) {}

bool ProgressCounter::advance(std::size_t n) {
    const std::size_t done = done_.fetch_add(n) + n;
    if (!fn_) return true;
    std::size_t next = nextReport_.load();
    if (done >= next || done >= total_) {
        if (nextReport_.compare_exchange_strong(next, done + step_)) {
            std::lock_guard<std::mutex> lock(callbackMutex_);
            if (!fn_(std::min(1.0, static_cast<double>(done) / static_cast<double>(total_)), stage_))
                cancelled_ = true;
        }
    }
    return !cancelled_;
}

void ProgressCounter::throwIfCancelled() const {
    if (cancelled_) throw Cancelled();
}

}  // namespace demlight
