#pragma once
// Shared helpers for the machine tests: report comparison for determinism checks.

#include <gtest/gtest.h>

#include <span>

#include "sim/dispatch.h"

namespace sim::testing {

inline void ExpectSameReports(std::span<const DispatchReport> a, std::span<const DispatchReport> b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(a[i].SameSimulation(b[i])) << a[i].name;
    // SameSimulation must see a difference in any counter.
    DispatchReport changed = b[i];
    ++changed.lanes.lanesActive;
    EXPECT_FALSE(a[i].SameSimulation(changed)) << a[i].name;
  }
}

}  // namespace sim::testing
