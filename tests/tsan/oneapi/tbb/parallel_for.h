#pragma once
// ThreadSanitizer builds only (AASIM_TSAN, cmake/AasimCompilerOptions.cmake puts tests/tsan first
// on every target's include path): tbb::parallel_for on std::threads, so TSan sees every
// hand-off between the thread that starts a loop and the threads that run its iterations.
// Debian's libtbb is not instrumented and passes tasks through atomics TSan cannot see, which
// buries any real race under hundreds of false reports (docs/fuzzing.md "ThreadSanitizer").
// Only the overloads aasim calls exist; everything else of oneTBB (blocked_range,
// global_control, info, task_arena, enumerable_thread_specific) is the real library. aasim's
// loops must not depend on how iterations are split or ordered, so a different split is a test.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>

namespace tbb {
namespace aasim_tsan {

// task(i) for every i in [0, count) on up to max_allowed_parallelism threads, the caller one of
// them; indices are handed out through one atomic counter. The first exception stops the hand-out
// and is rethrown after every thread has joined, as oneTBB rethrows a task's exception.
template <typename Task>
void RunIndexed(std::size_t count, const Task& task) {
  const std::size_t limit = global_control::active_value(global_control::max_allowed_parallelism);
  const std::size_t threads = std::min(std::max<std::size_t>(limit, 1), count);
  std::atomic<std::size_t> next{0};
  std::mutex failureMutex;
  std::exception_ptr failure;
  const auto work = [&] {
    for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      try {
        task(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failureMutex);
        if (!failure) failure = std::current_exception();
        next.store(count);
      }
    }
  };
  std::vector<std::thread> helpers;
  for (std::size_t t = 1; t < threads; ++t) helpers.emplace_back(work);
  work();
  for (std::thread& helper : helpers) helper.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace aasim_tsan

template <typename Index, typename Body>
void parallel_for(Index first, Index last, const Body& body) {
  if (!(first < last)) return;
  aasim_tsan::RunIndexed(static_cast<std::size_t>(last - first),
                         [&](std::size_t i) { body(static_cast<Index>(first + static_cast<Index>(i))); });
}

template <typename Value, typename Body>
void parallel_for(const blocked_range<Value>& range, const Body& body) {
  if (range.empty()) return;
  const std::size_t grain = std::max<std::size_t>(range.grainsize(), 1);
  const std::size_t size = range.size();
  aasim_tsan::RunIndexed((size + grain - 1) / grain, [&](std::size_t chunk) {
    const Value begin = static_cast<Value>(range.begin() + static_cast<Value>(chunk * grain));
    const Value end = static_cast<Value>(range.begin() + static_cast<Value>(std::min(size, (chunk + 1) * grain)));
    body(blocked_range<Value>(begin, end, grain));
  });
}

}  // namespace tbb
