// Progress reporting: the library calls a passed-in callback; it never prints.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace demlight {

/// Called with the fraction done in [0, 1] and a short stage label. Return false to cancel;
/// the library then throws demlight::Cancelled at the next safe point.
using ProgressFn = std::function<bool(double fraction, const std::string& stage)>;

/// Counts finished work items from any thread and forwards to a ProgressFn at most every
/// `1/updates` of the total. Thread-safe.
class ProgressCounter {
public:
    ProgressCounter(ProgressFn fn, std::string stage, std::size_t total, int updates = 100);
    /// Record `n` finished items. Returns false once the callback asked to cancel.
    bool advance(std::size_t n = 1);
    bool cancelled() const { return cancelled_.load(); }
    /// Throws Cancelled if the callback asked to stop.
    void throwIfCancelled() const;

private:
    ProgressFn fn_;
    std::string stage_;
    std::size_t total_;
    std::size_t step_;
    std::atomic<std::size_t> done_{0};
    std::atomic<std::size_t> nextReport_{0};
    std::atomic<bool> cancelled_{false};
    std::mutex callbackMutex_;  // serialises calls into the user's callback
};

}  // namespace demlight
