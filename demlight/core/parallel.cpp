#include "demlight/core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <thread>

namespace demlight {

int resolveThreadCount(int requested) {
    if (requested > 0) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

void parallelFor(std::size_t begin, std::size_t end, int threads,
                 const std::function<void(std::size_t)>& body, std::size_t grain) {
    if (begin >= end) return;
    // More threads than the machine runs at once add nothing (results do not depend on the
    // count), and TBB would print a warning of its own on stderr for the workers it cannot add.
    const int n = std::min(resolveThreadCount(threads), tbb::info::default_concurrency());
    if (n <= 1) {
        for (std::size_t i = begin; i < end; ++i) body(i);
        return;
    }
    const auto loop = [&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, std::max<std::size_t>(grain, 1)),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t i = r.begin(); i < r.end(); ++i) body(i);
                          });
    };
    // The caller's arena (the process's default one, or one a run entered once for its thread
    // count) when it runs no more threads than asked: an arena made per call costs its set-up
    // and its workers' start on every loop, and a sweep runs two loops per region.
    if (n >= tbb::this_task_arena::max_concurrency()) {
        loop();
        return;
    }
    tbb::task_arena arena(n);
    arena.execute(loop);
}

void withThreads(int threads, const std::function<void()>& run) {
    const int n = std::min(resolveThreadCount(threads), tbb::info::default_concurrency());
    if (n == tbb::this_task_arena::max_concurrency()) {
        run();
        return;
    }
    tbb::task_arena arena(n);
    arena.execute(run);
}

}  // namespace demlight
