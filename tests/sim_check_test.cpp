// sim/check.h: failed checks print the expression and both operands and abort; DCHECKs run only
// in debug and sanitizer builds and are not evaluated otherwise.

#include <gtest/gtest.h>

#include <string>

#include "sim/check.h"

namespace sim {
namespace {

TEST(SimCheckDeathTest, AFailedCheckPrintsBothOperandsAndAborts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const int two = 2;
  EXPECT_DEATH(AASIM_CHECK_EQ(two, 3), "check failed at .*sim_check_test.cpp:[0-9]+: two == 3 \\(2 vs 3\\)");
  const std::size_t slot = 7, slots = 3;
  EXPECT_DEATH(AASIM_CHECK_LT(slot, slots), "slot < slots \\(7 vs 3\\)");
  EXPECT_DEATH(AASIM_CHECK_NE(std::string("demo/blend"), "demo/blend"),
               "\\(\"demo/blend\" vs \"demo/blend\"\\)");
  EXPECT_DEATH(AASIM_CHECK_GE(-1.5, 0.25), "\\(-1.5 vs 0.25\\)");
  EXPECT_DEATH(AASIM_CHECK(two > 5), "check failed at .*: two > 5");
}

TEST(SimCheck, PassingChecksEvaluateEachOperandOnce) {
  int evaluated = 0;
  AASIM_CHECK_EQ(++evaluated, 1);
  AASIM_CHECK_LT(0, ++evaluated);
  AASIM_CHECK(++evaluated == 3);
  EXPECT_EQ(evaluated, 3);
}

TEST(SimCheckDeathTest, DchecksRunOnlyInDebugAndSanitizerBuilds) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  int evaluated = 0;
  if (AASIM_DCHECKS_ACTIVE) {
    EXPECT_DEATH(AASIM_DCHECK_LT(5, 3), "5 < 3 \\(5 vs 3\\)");
    AASIM_DCHECK_EQ(++evaluated, 1);
    EXPECT_EQ(evaluated, 1);
  } else {
    AASIM_DCHECK_LT(++evaluated, 0);
    AASIM_DCHECK(++evaluated < 0);
    EXPECT_EQ(evaluated, 0);
  }
}

}  // namespace
}  // namespace sim
