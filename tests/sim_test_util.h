#pragma once
// Shared helpers for the machine tests: the PS4-class machine, a light kernel, report comparison
// for determinism checks, draw targets.

#include <gtest/gtest.h>

#include <span>

#include "raster/depth_stencil.h"
#include "raster/sample_pattern.h"
#include "sim/dispatch.h"

namespace sim::testing {

inline Machine TestMachine() { return Machine(GpuConfigByName("ps4-class")); }

// A kernel light enough that occupancy never limits the tests' waves.
inline KernelInfo SmallKernel() {
  return {.vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 10};
}

// The single-triangle draws' target: w x h, 4 samples all anchored, the standard pattern.
inline raster::DepthStencilSurface FourSampleDepth(int w, int h) {
  raster::DepthSurfaceConfig config;
  config.width = w;
  config.height = h;
  config.coverageSamples = 4;
  config.depthSamples = 4;
  return raster::DepthStencilSurface(config, raster::MakeBuiltinPattern("standard", 4));
}

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
