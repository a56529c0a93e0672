// The timing estimate's formulas on hand-computed numbers (sim/timing.h, docs/timing-model.md):
// each term alone, the bound, latency hiding, the no-wave case and invalid inputs.

#include "sim/timing.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace sim {
namespace {

// A PS4-class machine typed here: 18 CUs x 4 SIMDs = 72 SIMDs, 2 SEs, 800 MHz, 176 GB/s.
GpuConfig Ps4Like() {
  GpuConfig gpu;
  gpu.name = "test-ps4";
  gpu.clockMhz = 800;
  gpu.shaderEngines = 2;
  gpu.computeUnits = 18;
  gpu.dramGBytesPerSecond = 176;
  gpu.waveLaunchesPerClockPerSe = 1;
  gpu.rasterPixelsPerClockPerSe = 16;
  gpu.hiStencilTilesPerClockPerSe = 1;
  gpu.wavesPerSimdToHideLatency = 4;
  gpu.dispatchOverheadMicroseconds = 1;
  return gpu;
}

WorkEstimate Work(std::uint64_t waves, int wavesPerSimd) {
  WorkEstimate work;
  work.waves = waves;
  work.occupancy.wavesPerSimd = wavesPerSimd;
  work.occupancy.maxWavesPerSimd = 10;
  return work;
}

TEST(SimTiming, AluTermIsFourCyclesPerInstructionOverAllSimds) {
  // 7200 waves * 100 instructions * 4 cycles / 72 SIMDs = 40000 cycles = 50 us at 800 MHz.
  WorkEstimate work = Work(7200, 10);
  work.valuInstructionsPerWave = 100;
  const TimeEstimate time = EstimateTime(Ps4Like(), work);
  EXPECT_DOUBLE_EQ(time.aluMicroseconds, 50.0);
  // 7200 launches / (1 per clock * 2 SEs * 800 MHz) = 4.5 us.
  EXPECT_DOUBLE_EQ(time.launchMicroseconds, 4.5);
  EXPECT_EQ(time.bound, "ALU");
  EXPECT_DOUBLE_EQ(time.totalMicroseconds, 51.0);
}

TEST(SimTiming, AluTermOnXboxOneClass) {
  GpuConfig gpu = Ps4Like();
  gpu.computeUnits = 12;
  gpu.clockMhz = 853;
  gpu.dramGBytesPerSecond = 68.3;
  // 4800 waves * 10 * 4 / 48 SIMDs = 4000 cycles at 853 MHz.
  WorkEstimate work = Work(4800, 10);
  work.valuInstructionsPerWave = 10;
  EXPECT_DOUBLE_EQ(EstimateTime(gpu, work).aluMicroseconds, 4000.0 / 853.0);
  // 68.3 GB/s = 68300 bytes per microsecond.
  work.valuInstructionsPerWave = 0;
  work.dramBytes = 683000;
  EXPECT_DOUBLE_EQ(EstimateTime(gpu, work).memoryMicroseconds, 10.0);
}

TEST(SimTiming, MemoryTermIsDeratedBelowTheLatencyHidingOccupancy) {
  // 176e6 bytes at 176 GB/s = 176e3 bytes per us -> 1000 us at full efficiency.
  for (int wavesPerSimd : {4, 8, 10}) {
    WorkEstimate work = Work(1000, wavesPerSimd);
    work.dramBytes = 176'000'000;
    EXPECT_DOUBLE_EQ(EstimateTime(Ps4Like(), work).memoryMicroseconds, 1000.0) << wavesPerSimd;
  }
  WorkEstimate work = Work(1000, 2);  // efficiency 2/4
  work.dramBytes = 176'000'000;
  const TimeEstimate half = EstimateTime(Ps4Like(), work);
  EXPECT_DOUBLE_EQ(half.memoryMicroseconds, 2000.0);
  EXPECT_EQ(half.bound, "memory");
  EXPECT_DOUBLE_EQ(half.totalMicroseconds, 2001.0);
  work.occupancy.wavesPerSimd = 1;  // efficiency 1/4
  EXPECT_DOUBLE_EQ(EstimateTime(Ps4Like(), work).memoryMicroseconds, 4000.0);
}

TEST(SimTiming, LaunchTermBoundsTinyWaves) {
  // 16000 waves / 1600 launches per us = 10 us; 1 instruction each = 16000*4/72/800 us.
  WorkEstimate work = Work(16000, 10);
  work.valuInstructionsPerWave = 1;
  const TimeEstimate time = EstimateTime(Ps4Like(), work);
  EXPECT_DOUBLE_EQ(time.launchMicroseconds, 10.0);
  EXPECT_DOUBLE_EQ(time.aluMicroseconds, 16000.0 * 4.0 / 72.0 / 800.0);
  EXPECT_EQ(time.bound, "wave launch");
  EXPECT_DOUBLE_EQ(time.totalMicroseconds, 11.0);
}

TEST(SimTiming, RasterTermAddsScanConversionAndHiStencilTiles) {
  // 1920x1080 pixels / (16 * 2 * 800 = 25600 per us) = 81 us; 32400 tiles / 1600 per us = 20.25 us.
  WorkEstimate work = Work(32400, 10);
  work.rasterPixels = 1920 * 1080;
  work.hiStencilTiles = 32400;
  const TimeEstimate time = EstimateTime(Ps4Like(), work);
  EXPECT_DOUBLE_EQ(time.rasterMicroseconds, 81.0 + 20.25);
  EXPECT_EQ(time.bound, "raster");
  EXPECT_DOUBLE_EQ(time.totalMicroseconds, 102.25);
}

TEST(SimTiming, NoWorkCostsOnlyTheOverhead) {
  const TimeEstimate time = EstimateTime(Ps4Like(), WorkEstimate{});
  EXPECT_DOUBLE_EQ(time.aluMicroseconds, 0.0);
  EXPECT_DOUBLE_EQ(time.memoryMicroseconds, 0.0);
  EXPECT_DOUBLE_EQ(time.launchMicroseconds, 0.0);
  EXPECT_DOUBLE_EQ(time.rasterMicroseconds, 0.0);
  EXPECT_DOUBLE_EQ(time.overheadMicroseconds, 1.0);
  EXPECT_DOUBLE_EQ(time.totalMicroseconds, 1.0);
  EXPECT_EQ(time.bound, "overhead");
}

TEST(SimTiming, NoWavesStillCountsTheFrontEnd) {
  // A full-screen pass whose every tile hi-stencil culled: no wave, but the tiles were walked.
  WorkEstimate work;
  work.hiStencilTiles = 3200;  // 2 us
  const TimeEstimate time = EstimateTime(Ps4Like(), work);
  EXPECT_DOUBLE_EQ(time.rasterMicroseconds, 2.0);
  EXPECT_EQ(time.bound, "raster");
  EXPECT_DOUBLE_EQ(time.totalMicroseconds, 3.0);
}

TEST(SimTiming, OverheadBoundsSmallDispatches) {
  // 64 waves: 0.04 us of launch, 64 * 10 * 4 / 72 / 800 = 0.0444 us of ALU.
  WorkEstimate work = Work(64, 10);
  work.valuInstructionsPerWave = 10;
  const TimeEstimate time = EstimateTime(Ps4Like(), work);
  EXPECT_DOUBLE_EQ(time.launchMicroseconds, 0.04);
  EXPECT_DOUBLE_EQ(time.aluMicroseconds, 64.0 * 10.0 * 4.0 / 72.0 / 800.0);
  EXPECT_EQ(time.bound, "overhead");
  EXPECT_DOUBLE_EQ(time.totalMicroseconds, 1.0 + time.aluMicroseconds);
}

TEST(SimTiming, TiesGoToTheEarlierTerm) {
  // ALU: 800 waves * 18 * 4 / 72 / 800 = 1 us; launch: 800 / 1600 = 0.5 us; memory 176000 B = 1 us.
  WorkEstimate work = Work(800, 10);
  work.valuInstructionsPerWave = 18;
  work.dramBytes = 176'000;
  const TimeEstimate time = EstimateTime(Ps4Like(), work);
  EXPECT_DOUBLE_EQ(time.aluMicroseconds, 1.0);
  EXPECT_DOUBLE_EQ(time.memoryMicroseconds, 1.0);
  EXPECT_EQ(time.bound, "ALU");
}

TEST(SimTiming, InvalidWorkThrows) {
  WorkEstimate negative = Work(10, 10);
  negative.valuInstructionsPerWave = -1;
  EXPECT_THROW(EstimateTime(Ps4Like(), negative), std::invalid_argument);
  // Waves without an occupancy cannot be derated for latency.
  EXPECT_THROW(EstimateTime(Ps4Like(), Work(10, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace sim
