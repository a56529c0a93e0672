// Theoretical occupancy against hand-worked GCN examples (256 VGPRs per lane, 512 SGPRs,
// 64 KB LDS, 10 wave slots per SIMD), every limiter and tie rule, and every invalid input.

#include "sim/occupancy.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace sim {
namespace {

// The GFX7 values of sim/gpus/*.jsonc, typed here independently of the files.
GpuConfig Gcn() {
  GpuConfig gpu;
  gpu.name = "test-gcn";
  gpu.clockMhz = 800;
  gpu.shaderEngines = 2;
  gpu.computeUnits = 18;
  gpu.simdsPerCu = 4;
  gpu.waveSlotsPerSimd = 10;
  gpu.vgprsPerSimdLane = 256;
  gpu.vgprGranule = 4;
  gpu.maxVgprsPerWave = 256;
  gpu.sgprsPerSimd = 512;
  gpu.sgprGranule = 8;
  gpu.maxSgprsPerWave = 104;
  gpu.ldsBytesPerCu = 65536;
  gpu.ldsGranuleBytes = 512;
  gpu.maxLdsBytesPerGroup = 65536;
  gpu.maxGroupsPerCu = 16;
  gpu.maxThreadsPerGroup = 1024;
  gpu.dramGBytesPerSecond = 176;
  return gpu;
}

Occupancy OccupancyOf(int vgprs, int sgprs, int lds, int threads) {
  return TheoreticalOccupancy(Gcn(), {vgprs, sgprs, lds, threads});
}

TEST(SimOccupancy, VgprLimitsFollowTheRegisterFile) {
  struct Case {
    int vgprs;
    int waves;
    OccupancyLimiter limiter;
  };
  // floor(256 / roundUp(v, 4)), capped at 10 slots.
  const Case cases[] = {
      {24, 10, OccupancyLimiter::WaveSlots}, {32, 8, OccupancyLimiter::Vgpr},  {64, 4, OccupancyLimiter::Vgpr},
      {84, 3, OccupancyLimiter::Vgpr},       {128, 2, OccupancyLimiter::Vgpr}, {256, 1, OccupancyLimiter::Vgpr},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("vgprs " + std::to_string(c.vgprs));
    const Occupancy occupancy = OccupancyOf(c.vgprs, 16, 0, 64);
    EXPECT_EQ(occupancy.wavesPerSimd, c.waves);
    EXPECT_EQ(occupancy.byVgpr, c.waves);
    EXPECT_EQ(occupancy.limiter, c.limiter);
    EXPECT_EQ(occupancy.maxWavesPerSimd, 10);
  }
}

TEST(SimOccupancy, VgprsAreAllocatedInGranulesOfFour) {
  EXPECT_EQ(OccupancyOf(1, 16, 0, 64).vgprsAllocated, 4);
  EXPECT_EQ(OccupancyOf(21, 16, 0, 64).vgprsAllocated, 24);
  EXPECT_EQ(OccupancyOf(84, 16, 0, 64).vgprsAllocated, 84);
  // 85 -> 88 -> floor(256 / 88) = 2, where 84 still gives 3.
  EXPECT_EQ(OccupancyOf(85, 16, 0, 64).wavesPerSimd, 2);
}

TEST(SimOccupancy, SgprLimitsFollowTheRegisterFile) {
  // floor(512 / roundUp(s, 8)), capped at 10 slots.
  EXPECT_EQ(OccupancyOf(16, 48, 0, 64).wavesPerSimd, 10);
  EXPECT_EQ(OccupancyOf(16, 48, 0, 64).limiter, OccupancyLimiter::WaveSlots);
  EXPECT_EQ(OccupancyOf(16, 64, 0, 64).wavesPerSimd, 8);
  EXPECT_EQ(OccupancyOf(16, 64, 0, 64).limiter, OccupancyLimiter::Sgpr);
  EXPECT_EQ(OccupancyOf(16, 104, 0, 64).wavesPerSimd, 4);
  EXPECT_EQ(OccupancyOf(16, 104, 0, 64).bySgpr, 4);
  EXPECT_EQ(OccupancyOf(16, 57, 0, 64).sgprsAllocated, 64);
  // No SGPRs declared: no SGPR limit.
  EXPECT_EQ(OccupancyOf(16, 0, 0, 64).bySgpr, 10);
  EXPECT_EQ(OccupancyOf(16, 0, 0, 64).sgprsAllocated, 0);
}

TEST(SimOccupancy, LdsLimitsWholeGroupsPerCu) {
  // 256 threads = 4 waves; 64 KB / 32 KB = 2 groups per CU = 8 waves over 4 SIMDs = 2.
  const Occupancy big = OccupancyOf(16, 16, 32768, 256);
  EXPECT_EQ(big.wavesPerGroup, 4);
  EXPECT_EQ(big.byLds, 2);
  EXPECT_EQ(big.wavesPerSimd, 2);
  EXPECT_EQ(big.limiter, OccupancyLimiter::Lds);
  EXPECT_EQ(big.ldsBytesAllocated, 32768);

  // 64 threads with 16 KB: 4 groups = 4 waves per CU = 1 per SIMD.
  const Occupancy single = OccupancyOf(16, 16, 16384, 64);
  EXPECT_EQ(single.wavesPerSimd, 1);
  EXPECT_EQ(single.limiter, OccupancyLimiter::Lds);

  // 20000 bytes round up to 20480 (40 granules of 512): 3 groups, still 1 wave per SIMD.
  const Occupancy rounded = OccupancyOf(16, 16, 20000, 64);
  EXPECT_EQ(rounded.ldsBytesAllocated, 20480);
  EXPECT_EQ(rounded.wavesPerSimd, 1);
  EXPECT_EQ(rounded.limiter, OccupancyLimiter::Lds);

  // No LDS: no LDS limit.
  EXPECT_EQ(OccupancyOf(16, 16, 0, 256).byLds, 10);
}

TEST(SimOccupancy, LargestGroupFitsTwicePerCu) {
  // 1024 threads = 16 waves; 40 slots per CU hold 2 whole groups = 32 waves = 8 per SIMD.
  const Occupancy occupancy = OccupancyOf(16, 16, 0, 1024);
  EXPECT_EQ(occupancy.wavesPerGroup, 16);
  EXPECT_EQ(occupancy.byGroups, 8);
  EXPECT_EQ(occupancy.wavesPerSimd, 8);
  EXPECT_EQ(occupancy.limiter, OccupancyLimiter::GroupsPerCu);
}

TEST(SimOccupancy, GroupFitUsesTheRegisterLimit) {
  // 48 VGPRs: 5 waves per SIMD = 20 per CU, so one 16-wave group fits: 16 / 4 = 4 per SIMD.
  const Occupancy occupancy = OccupancyOf(48, 16, 0, 1024);
  EXPECT_EQ(occupancy.byVgpr, 5);
  EXPECT_EQ(occupancy.byGroups, 4);
  EXPECT_EQ(occupancy.wavesPerSimd, 4);
  EXPECT_EQ(occupancy.limiter, OccupancyLimiter::GroupsPerCu);
}

TEST(SimOccupancy, BarriersLimitMultiWaveGroupsOnly) {
  // 128 threads = 2 waves: 16 barriers -> 16 groups = 32 waves per CU = 8 per SIMD.
  const Occupancy pairs = OccupancyOf(16, 16, 0, 128);
  EXPECT_EQ(pairs.byGroups, 8);
  EXPECT_EQ(pairs.wavesPerSimd, 8);
  EXPECT_EQ(pairs.limiter, OccupancyLimiter::GroupsPerCu);
  // Single-wave groups use no barrier: all 10 slots.
  const Occupancy singles = OccupancyOf(16, 16, 0, 64);
  EXPECT_EQ(singles.byGroups, 10);
  EXPECT_EQ(singles.wavesPerSimd, 10);
  EXPECT_EQ(singles.limiter, OccupancyLimiter::WaveSlots);
  // A partial wave counts as a whole one: 65 threads = 2 waves.
  EXPECT_EQ(OccupancyOf(16, 16, 0, 65).wavesPerGroup, 2);
}

TEST(SimOccupancy, TiesPreferVgprThenSgprThenLds) {
  // 64 VGPRs -> 4; 104 SGPRs -> 4; 256 threads with 16 KB -> 4 groups = 16 waves = 4 per SIMD.
  EXPECT_EQ(OccupancyOf(64, 104, 16384, 256).limiter, OccupancyLimiter::Vgpr);
  EXPECT_EQ(OccupancyOf(16, 104, 16384, 256).limiter, OccupancyLimiter::Sgpr);
  EXPECT_EQ(OccupancyOf(16, 16, 16384, 256).limiter, OccupancyLimiter::Lds);
  EXPECT_EQ(OccupancyOf(16, 16, 16384, 256).wavesPerSimd, 4);
  // 128 threads with 8 KB: LDS allows 8 groups = 4 per SIMD, below the barrier's 8.
  EXPECT_EQ(OccupancyOf(16, 16, 8192, 128).limiter, OccupancyLimiter::Lds);
  EXPECT_EQ(OccupancyOf(16, 16, 8192, 128).wavesPerSimd, 4);
}

TEST(SimOccupancy, LimiterNames) {
  EXPECT_EQ(LimiterName(OccupancyLimiter::WaveSlots), "wave slots");
  EXPECT_EQ(LimiterName(OccupancyLimiter::Vgpr), "VGPR");
  EXPECT_EQ(LimiterName(OccupancyLimiter::Sgpr), "SGPR");
  EXPECT_EQ(LimiterName(OccupancyLimiter::Lds), "LDS");
  EXPECT_EQ(LimiterName(OccupancyLimiter::GroupsPerCu), "groups per CU");
}

TEST(SimOccupancy, InvalidResourcesThrowOneLine) {
  const KernelResources invalid[] = {
      {0, 16, 0, 64},      {257, 16, 0, 64},   {16, -1, 0, 64},  {16, 105, 0, 64}, {16, 16, -1, 64},
      {16, 16, 65537, 64}, {16, 16, 0, 0},     {16, 16, 0, 1025},
      {128, 16, 0, 1024},  // 2 waves per SIMD = 8 per CU: a 16-wave group never fits
  };
  for (const KernelResources& kernel : invalid) {
    SCOPED_TRACE(std::to_string(kernel.vgprs) + " " + std::to_string(kernel.sgprs) + " " +
                 std::to_string(kernel.ldsBytesPerGroup) + " " + std::to_string(kernel.threadsPerGroup));
    try {
      TheoreticalOccupancy(Gcn(), kernel);
      ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& error) {
      const std::string message = error.what();
      EXPECT_FALSE(message.empty());
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  // The limits themselves are valid.
  EXPECT_NO_THROW(OccupancyOf(256, 104, 65536, 1024 / 16));
  EXPECT_NO_THROW(OccupancyOf(16, 16, 0, 1024));
}

}  // namespace
}  // namespace sim
