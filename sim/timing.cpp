#include "sim/timing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace sim {
namespace {

// GCN whitepaper: a SIMD is 16 lanes wide, so one wave64 VALU instruction occupies it for
// 64 / 16 = 4 cycles.
constexpr double kCyclesPerValuInstruction = 4.0;
// 1 GB/s = 1e9 bytes per second = 1e3 bytes per microsecond.
constexpr double kBytesPerMicrosecondPerGBps = 1e3;

}  // namespace

TimeEstimate EstimateTime(const GpuConfig& gpu, const WorkEstimate& work) {
  if (!std::isfinite(work.valuInstructionsPerWave) || work.valuInstructionsPerWave < 0.0) {
    throw std::invalid_argument("timing estimate: VALU instructions per wave must be finite and >= 0, found " +
                                std::to_string(work.valuInstructionsPerWave));
  }
  if (work.waves > 0 && work.occupancy.wavesPerSimd < 1) {
    throw std::invalid_argument("timing estimate: " + std::to_string(work.waves) +
                                " waves need an occupancy of at least 1 wave per SIMD");
  }
  const auto waves = static_cast<double>(work.waves);
  const double seClocksPerMicrosecond = gpu.shaderEngines * gpu.clockMhz;
  TimeEstimate estimate;

  // ---- ALU: every SIMD of the GPU busy with VALU work ----
  const double simds = static_cast<double>(gpu.computeUnits) * gpu.simdsPerCu;
  estimate.aluMicroseconds = waves * work.valuInstructionsPerWave * kCyclesPerValuInstruction / simds / gpu.clockMhz;

  // ---- Memory: DRAM bandwidth, derated when too few waves per SIMD hide the latency ----
  const double efficiency =
      work.waves == 0 ? 1.0 : std::min(1.0, work.occupancy.wavesPerSimd / gpu.wavesPerSimdToHideLatency);
  estimate.memoryMicroseconds =
      static_cast<double>(work.dramBytes) / (gpu.dramGBytesPerSecond * kBytesPerMicrosecondPerGBps) / efficiency;

  // ---- Front end: wave launch and the scan converter / hi-stencil, per shader engine ----
  estimate.launchMicroseconds = waves / (gpu.waveLaunchesPerClockPerSe * seClocksPerMicrosecond);
  estimate.rasterMicroseconds =
      static_cast<double>(work.rasterPixels) / (gpu.rasterPixelsPerClockPerSe * seClocksPerMicrosecond) +
      static_cast<double>(work.hiStencilTiles) / (gpu.hiStencilTilesPerClockPerSe * seClocksPerMicrosecond);

  // ---- Total and the bound; the first of equal terms wins ----
  estimate.overheadMicroseconds = gpu.dispatchOverheadMicroseconds;
  const std::array<std::pair<double, std::string_view>, 5> terms = {{
      {estimate.aluMicroseconds, "ALU"},
      {estimate.memoryMicroseconds, "memory"},
      {estimate.launchMicroseconds, "wave launch"},
      {estimate.rasterMicroseconds, "raster"},
      {estimate.overheadMicroseconds, "overhead"},
  }};
  const auto slowest = std::ranges::max_element(terms, {}, &std::pair<double, std::string_view>::first);
  estimate.bound = slowest->second;
  estimate.totalMicroseconds =
      std::max({estimate.aluMicroseconds, estimate.memoryMicroseconds, estimate.launchMicroseconds,
                estimate.rasterMicroseconds}) +
      estimate.overheadMicroseconds;
  return estimate;
}

}  // namespace sim
