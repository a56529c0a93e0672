#pragma once
// Shared helpers for the machine tests: report comparison for determinism checks.

#include <gtest/gtest.h>

#include "sim/dispatch.h"

namespace sim::testing {

// Everything a report says about the simulated machine; host wall time is not part of it.
inline void ExpectSameReport(const DispatchReport& a, const DispatchReport& b) {
  SCOPED_TRACE(a.name);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.lanes, b.lanes);
  ASSERT_EQ(a.resources.size(), b.resources.size());
  for (std::size_t i = 0; i < a.resources.size(); ++i) {
    EXPECT_EQ(a.resources[i].name, b.resources[i].name);
    EXPECT_EQ(a.resources[i].bytesRead, b.resources[i].bytesRead);
    EXPECT_EQ(a.resources[i].bytesWritten, b.resources[i].bytesWritten);
    EXPECT_EQ(a.resources[i].fetches, b.resources[i].fetches);
    EXPECT_EQ(a.resources[i].atomics, b.resources[i].atomics);
    EXPECT_EQ(a.resources[i].linesRead, b.resources[i].linesRead);
    EXPECT_EQ(a.resources[i].linesWritten, b.resources[i].linesWritten);
  }
  EXPECT_EQ(a.heat, b.heat);
  EXPECT_EQ(a.raster, b.raster);
  EXPECT_EQ(a.fragments, b.fragments);
  EXPECT_EQ(a.occupancy.wavesPerSimd, b.occupancy.wavesPerSimd);
  EXPECT_EQ(a.time.totalMicroseconds, b.time.totalMicroseconds);
}

inline void ExpectSameReports(std::span<const DispatchReport> a, std::span<const DispatchReport> b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ExpectSameReport(a[i], b[i]);
}

}  // namespace sim::testing
