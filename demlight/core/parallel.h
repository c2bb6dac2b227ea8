// One parallel-for abstraction (TBB underneath). Work items must be independent; results are
// deterministic when each item writes only its own outputs.
#pragma once

#include <cstddef>
#include <functional>

namespace demlight {

/// Most worker threads a request may ask for. Far more than any machine's cores; beyond it TBB
/// cannot make the arena (65537 crashed it), so requests above are refused, not clamped.
inline constexpr int kMaxThreads = 1024;

/// Number of worker threads to use: `requested` if > 0, else all hardware threads.
int resolveThreadCount(int requested);

/// Calls body(i) for every i in [begin, end) on up to `threads` threads (0 = all cores), and
/// never on more than the machine (or the process's CPU affinity) runs at once.
/// `grain` is the smallest chunk handed to one thread.
void parallelFor(std::size_t begin, std::size_t end, int threads,
                 const std::function<void(std::size_t)>& body, std::size_t grain = 1);

}  // namespace demlight
