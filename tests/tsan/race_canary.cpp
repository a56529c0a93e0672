// Built only into aasim_tsan_tests (tests/CMakeLists.txt): proves the ThreadSanitizer run can
// fail. Two iterations of a loop on sim::ParallelFor (the machine's chunk loop) increment one int
// on two threads without synchronisation; the child process must die with TSan's report. If the
// loops ran on a pool TSan cannot follow, or on one thread, the child would exit 0 and this test
// fail.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <thread>

#include <oneapi/tbb/global_control.h>

#include "sim/parallel.h"

namespace {

TEST(TsanCanary, AnUnsynchronisedWriteInsideAParallelLoopIsReported) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        const tbb::global_control twoThreads(tbb::global_control::max_allowed_parallelism, 2);
        alignas(64) int shared = 0;
        // Two iterations that wait for each other, so they run on two threads (one thread could
        // otherwise take both before the second starts, and there would be no race); the wait is
        // relaxed, so TSan sees no happens-before in it, and gives up after 10 s. The second
        // writes 50 ms after the first: TSan can miss two accesses made at the same instant.
        // `shared` and `arrived` each get a 64-byte line of their own: TSan keeps four accesses
        // per 8 bytes of memory and evicts one at random when they are full, so with the two ints
        // side by side the spinning loads of `arrived` could evict the first write to `shared`
        // before the second came, and the race went unreported (CI at stop 26; 6 runs in 40
        // here, against none in 70 with the alignment).
        alignas(64) std::atomic<int> arrived{0};
        sim::ParallelFor(2, [&](std::size_t index) {
          arrived.fetch_add(1, std::memory_order_relaxed);
          const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(10);
          while (arrived.load(std::memory_order_relaxed) < 2 && std::chrono::steady_clock::now() < giveUp) {
          }
          if (index == 1) std::this_thread::sleep_for(std::chrono::milliseconds(50));
          shared = shared + 1;
        });
        std::exit(shared > 0 ? 0 : 1);
      },
      testing::ExitedWithCode(66), "ThreadSanitizer: data race");
}

}  // namespace
