// One parallel-for abstraction (TBB underneath). Work items must be independent; results are
// deterministic when each item writes only its own outputs.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <type_traits>

namespace demlight {

/// Most worker threads a request may ask for. Far more than any machine's cores; beyond it TBB
/// cannot make the arena (65537 crashed it), so requests above are refused, not clamped.
inline constexpr int kMaxThreads = 1024;

/// Number of worker threads to use: `requested` if > 0, else all hardware threads.
int resolveThreadCount(int requested);

/// Calls body(i) for every i in [begin, end) on the threads of the run it is called in: those of
/// the enclosing withThreads, else every core (at most the process's CPU affinity). `grain` is
/// the smallest chunk handed to one thread. No loop makes a thread pool of its own: a run sets
/// its thread count once, as pbrt-v4's ParallelFor owns its pool.
void parallelFor(std::size_t begin, std::size_t end, const std::function<void(std::size_t)>& body,
                 std::size_t grain = 1);

/// Runs `run` on a thread pool of `threads` threads (0 = all cores, at most the machine's):
/// every parallelFor inside it uses that pool. Enter it once per run (a product call, a tile
/// job), not per loop; entered again with the same count inside, it adds nothing.
void withThreads(int threads, const std::function<void()>& run);

/// The threads of the run it is called in: those of the enclosing withThreads, else every core.
int runThreads();

/// withThreads for work that returns a value.
template <class Work>
    requires(!std::is_void_v<std::invoke_result_t<Work&>>)
auto withThreads(int threads, Work&& work) -> std::invoke_result_t<Work&> {
    std::optional<decltype(work())> result;
    withThreads(threads, std::function<void()>([&] { result.emplace(work()); }));
    return std::move(*result);
}

}  // namespace demlight
