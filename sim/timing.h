#pragma once
// A first-order ESTIMATE of how long a dispatch would take on the modelled GPU, from counts the
// simulation measured (waves, DRAM bytes, pixels scanned, hi-stencil tiles) and one number the
// kernel author declares (VALU instructions per wave). It is a roofline: each unit's time at its
// peak rate, the slowest one wins, plus a fixed launch overhead. It is not a cycle simulation,
// and every output that shows it labels it "estimate" (docs/timing-model.md).
//
// The estimate's terms, in microseconds (clock in MHz = cycles per microsecond):
//   ALU       waves * valuInstructionsPerWave * 4 / (computeUnits * simdsPerCu) / clockMhz
//             (a wave64 VALU instruction occupies a SIMD16 for 4 cycles: GCN whitepaper)
//   memory    dramBytes / (dramGBytesPerSecond * 1e3) / efficiency, where
//             efficiency = min(1, occupancy.wavesPerSimd / wavesPerSimdToHideLatency)
//             (1 when there are no waves: nothing waits on memory)
//   launch    waves / (waveLaunchesPerClockPerSe * shaderEngines * clockMhz)
//   raster    rasterPixels / (rasterPixelsPerClockPerSe * shaderEngines * clockMhz)
//             + hiStencilTiles / (hiStencilTilesPerClockPerSe * shaderEngines * clockMhz)
//   total     max(ALU, memory, launch, raster) + dispatchOverheadMicroseconds
// The launch, raster and latency-hiding rates are assumptions of the model (GpuConfig).

#include <cstdint>
#include <string_view>

#include "sim/gpu_config.h"
#include "sim/occupancy.h"

namespace sim {

// What one dispatch did, as the timing estimate needs it.
struct WorkEstimate {
  std::uint64_t waves = 0;
  double valuInstructionsPerWave = 0;  // declared by the kernel author, not measured
  std::uint64_t dramBytes = 0;
  std::uint64_t rasterPixels = 0;
  std::uint64_t hiStencilTiles = 0;
  Occupancy occupancy;  // of the kernel; needed whenever waves > 0
};

// Each term of the estimate in microseconds. `bound` names the largest of ALU, memory, wave
// launch, raster and the fixed overhead ("ALU", "memory", "wave launch", "raster",
// "overhead"); on a tie the earlier name in that list wins.
struct TimeEstimate {
  double aluMicroseconds = 0;
  double memoryMicroseconds = 0;
  double launchMicroseconds = 0;
  double rasterMicroseconds = 0;
  double overheadMicroseconds = 0;
  double totalMicroseconds = 0;
  std::string_view bound = "overhead";
  // The total with the declared VALU count halved and doubled: how much of the estimate rests on
  // the kernel author's instruction count (KernelInfo::source says where it comes from).
  double totalValuHalvedMicroseconds = 0;
  double totalValuDoubledMicroseconds = 0;
};

// Throws std::invalid_argument (one line) for a negative or non-finite VALU count, or for waves
// without an occupancy (occupancy.wavesPerSimd < 1).
TimeEstimate EstimateTime(const GpuConfig& gpu, const WorkEstimate& work);

}  // namespace sim
