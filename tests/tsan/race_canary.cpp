// Built only into aasim_tsan_tests (tests/CMakeLists.txt): proves the ThreadSanitizer run can
// fail. A loop body on sim::ParallelFor (the machine's chunk loop) increments one int from two
// threads without synchronisation; the child process must die with TSan's report. If the loops
// ran on a pool TSan cannot follow, or on one thread, the child would exit 0 and this test fail.

#include <gtest/gtest.h>

#include <cstdlib>

#include <oneapi/tbb/global_control.h>

#include "sim/parallel.h"

namespace {

TEST(TsanCanary, AnUnsynchronisedWriteInsideAParallelLoopIsReported) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        const tbb::global_control twoThreads(tbb::global_control::max_allowed_parallelism, 2);
        int shared = 0;
        sim::ParallelFor(256, [&](std::size_t) { shared = shared + 1; });
        std::exit(shared > 0 ? 0 : 1);
      },
      testing::ExitedWithCode(66), "ThreadSanitizer: data race");
}

}  // namespace
