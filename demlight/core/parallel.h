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
/// never on more than the machine (or the process's CPU affinity) runs at once, nor on more than
/// the threads of the run it is called in (withThreads). `grain` is the smallest chunk handed to
/// one thread. Runs in the caller's thread pool unless `threads` asks for fewer threads than it
/// has.
void parallelFor(std::size_t begin, std::size_t end, int threads,
                 const std::function<void(std::size_t)>& body, std::size_t grain = 1);

/// Runs `run` with a thread pool of `threads` threads (0 = all cores, at most the machine's):
/// every parallelFor inside it, with threads = 0 or that count, uses that pool instead of making
/// its own. Enter it once per run (a product, a tile job), not per loop.
void withThreads(int threads, const std::function<void()>& run);

}  // namespace demlight
