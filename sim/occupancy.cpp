#include "sim/occupancy.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sim/wave.h"

namespace sim {
namespace {

int RoundUp(int value, int granule) { return (value + granule - 1) / granule * granule; }
int DivideCeil(int value, int divisor) { return (value + divisor - 1) / divisor; }

void Require(bool valid, const std::string& what, int value, const std::string& range) {
  if (!valid) throw std::invalid_argument(what + " = " + std::to_string(value) + " is out of range " + range);
}

}  // namespace

std::string_view LimiterName(OccupancyLimiter limiter) {
  switch (limiter) {
    case OccupancyLimiter::WaveSlots: return "wave slots";
    case OccupancyLimiter::Vgpr: return "VGPR";
    case OccupancyLimiter::Sgpr: return "SGPR";
    case OccupancyLimiter::Lds: return "LDS";
    case OccupancyLimiter::GroupsPerCu: return "groups per CU";
  }
  return "unknown";
}

Occupancy TheoreticalOccupancy(const GpuConfig& gpu, const KernelResources& kernel) {
  // ---- Validate against the per-wave and per-group maxima of the GPU ----
  Require(kernel.vgprs >= 1 && kernel.vgprs <= gpu.maxVgprsPerWave, "VGPRs", kernel.vgprs,
          "1.." + std::to_string(gpu.maxVgprsPerWave));
  Require(kernel.sgprs >= 0 && kernel.sgprs <= gpu.maxSgprsPerWave, "SGPRs", kernel.sgprs,
          "0.." + std::to_string(gpu.maxSgprsPerWave));
  Require(kernel.ldsBytesPerGroup >= 0 && kernel.ldsBytesPerGroup <= gpu.maxLdsBytesPerGroup, "LDS bytes per group",
          kernel.ldsBytesPerGroup, "0.." + std::to_string(gpu.maxLdsBytesPerGroup));
  Require(kernel.threadsPerGroup >= 1 && kernel.threadsPerGroup <= gpu.maxThreadsPerGroup, "threads per group",
          kernel.threadsPerGroup, "1.." + std::to_string(gpu.maxThreadsPerGroup));

  const int slots = gpu.waveSlotsPerSimd;
  Occupancy result;
  result.maxWavesPerSimd = slots;
  result.wavesPerGroup = DivideCeil(kernel.threadsPerGroup, kWaveLanes);
  // Waves per SIMD that `groups` whole groups per CU occupy; the CU spreads a group's waves over
  // its SIMDs, so the busiest SIMD holds the ceiling.
  const auto wavesFromGroups = [&](int groups) {
    return std::min(slots, DivideCeil(groups * result.wavesPerGroup, gpu.simdsPerCu));
  };

  // ---- Per-SIMD register limits ----
  result.vgprsAllocated = RoundUp(kernel.vgprs, gpu.vgprGranule);
  result.byVgpr = std::min(slots, gpu.vgprsPerSimdLane / result.vgprsAllocated);
  result.sgprsAllocated = RoundUp(kernel.sgprs, gpu.sgprGranule);
  result.bySgpr = kernel.sgprs == 0 ? slots : std::min(slots, gpu.sgprsPerSimd / result.sgprsAllocated);

  // ---- Per-CU group limits ----
  result.ldsBytesAllocated = RoundUp(kernel.ldsBytesPerGroup, gpu.ldsGranuleBytes);
  result.byLds = kernel.ldsBytesPerGroup == 0 ? slots : wavesFromGroups(gpu.ldsBytesPerCu / result.ldsBytesAllocated);
  const int groupsThatFit = gpu.simdsPerCu * std::min(result.byVgpr, result.bySgpr) / result.wavesPerGroup;
  if (groupsThatFit < 1) {
    throw std::invalid_argument("a group of " + std::to_string(kernel.threadsPerGroup) + " threads (" +
                                std::to_string(result.wavesPerGroup) + " waves) does not fit on one CU with " +
                                std::to_string(kernel.vgprs) + " VGPRs and " + std::to_string(kernel.sgprs) +
                                " SGPRs per wave");
  }
  const int groupsByBarrier = result.wavesPerGroup > 1 ? gpu.maxGroupsPerCu : groupsThatFit;
  result.byGroups = wavesFromGroups(std::min(groupsThatFit, groupsByBarrier));

  // ---- Minimum and limiter; ties resolve in this order ----
  result.wavesPerSimd = std::min({result.byVgpr, result.bySgpr, result.byLds, result.byGroups});
  if (result.wavesPerSimd < slots) {
    if (result.byVgpr == result.wavesPerSimd) {
      result.limiter = OccupancyLimiter::Vgpr;
    } else if (result.bySgpr == result.wavesPerSimd) {
      result.limiter = OccupancyLimiter::Sgpr;
    } else if (result.byLds == result.wavesPerSimd) {
      result.limiter = OccupancyLimiter::Lds;
    } else {
      result.limiter = OccupancyLimiter::GroupsPerCu;
    }
  }
  return result;
}

}  // namespace sim
