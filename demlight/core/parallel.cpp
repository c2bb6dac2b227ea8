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

void parallelFor(std::size_t begin, std::size_t end, const std::function<void(std::size_t)>& body,
                 std::size_t grain) {
    if (begin >= end) return;
    if (tbb::this_task_arena::max_concurrency() <= 1) {
        for (std::size_t i = begin; i < end; ++i) body(i);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, std::max<std::size_t>(grain, 1)),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i) body(i);
                      });
}

int runThreads() { return tbb::this_task_arena::max_concurrency(); }

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
