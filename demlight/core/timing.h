// Wall-clock helpers: elapsed seconds and the median of repeated runs, for the commands' time
// notes, `demlight bench` and the benchmarks (timings are printed or returned, never asserted).
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace demlight {

/// Seconds since t0 (steady clock).
inline double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Median wall time of `repeats` (at least one) calls of f (seconds).
inline double medianSeconds(int repeats, const std::function<void()>& f) {
    std::vector<double> s;
    for (int i = 0; i < std::max(1, repeats); ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        s.push_back(secondsSince(t0));
    }
    std::sort(s.begin(), s.end());
    return s[s.size() / 2];
}

}  // namespace demlight
