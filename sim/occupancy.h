#pragma once
// Theoretical occupancy by GCN rules: how many waves of one kernel fit on a SIMD at once, given
// its VGPR, SGPR and LDS use and its group size, and which resource sets the limit. This is the
// "A/B waves per SIMD" and "limiting factor" RGP reports per event (hw-facts §6.3); the timing
// estimate (sim/timing.h) uses it for latency hiding.
//
// The rules (docs/timing-model.md works examples; GpuConfig fields in brackets):
//   1. Registers are allocated in granules [vgprGranule, sgprGranule] from per-SIMD files
//      [vgprsPerSimdLane, sgprsPerSimd] (LLVM AMDGPUBaseInfo.cpp getVGPRAllocGranule,
//      getSGPRAllocGranule, getTotalNumVGPRs, getTotalNumSGPRs):
//        byVgpr = min(slots, floor(vgprsPerSimdLane / roundUp(vgprs, vgprGranule)))
//        bySgpr = min(slots, floor(sgprsPerSimd / roundUp(sgprs, sgprGranule)))  (0 SGPRs: slots)
//      where slots = waveSlotsPerSimd (GCN whitepaper: 10 waves per SIMD).
//   2. A group of N threads is wavesPerGroup = ceil(N / 64) waves on one CU (hw-facts §6.2), so
//      the remaining limits count whole groups per CU:
//        LDS:     floor(ldsBytesPerCu / roundUp(lds, ldsGranuleBytes))  (0 bytes: none; Mesa
//                 ac_gpu_info.c lds_alloc_granularity)
//        barrier: maxGroupsPerCu when wavesPerGroup > 1; single-wave groups use no barrier
//                 (LLVM getMaxWorkGroupsPerCU)
//        fit:     floor(simdsPerCu * min(byVgpr, bySgpr) / wavesPerGroup): a group's waves must
//                 all be resident at once
//      and a per-CU group count G becomes min(slots, ceil(G * wavesPerGroup / simdsPerCu)) waves
//      per SIMD.
//   3. Occupancy is the minimum of byVgpr, bySgpr, byLds and byGroups (barrier and fit). The
//      limiter is the resource giving it; ties go to VGPR, SGPR, LDS, groups per CU in that
//      order, and it is "wave slots" when no limit is below the slot count.

#include <cstdint>
#include <string_view>

#include "sim/gpu_config.h"

namespace sim {

struct KernelResources {
  int vgprs = 0;
  int sgprs = 0;
  int ldsBytesPerGroup = 0;
  int threadsPerGroup = 64;
};

enum class OccupancyLimiter : std::uint8_t { WaveSlots, Vgpr, Sgpr, Lds, GroupsPerCu };

// "wave slots", "VGPR", "SGPR", "LDS", "groups per CU".
std::string_view LimiterName(OccupancyLimiter limiter);

// All counts in waves per SIMD unless the name says otherwise.
struct Occupancy {
  int wavesPerSimd = 0;     // the theoretical occupancy, "A" of RGP's "A/B"
  int maxWavesPerSimd = 0;  // waveSlotsPerSimd, "B"
  OccupancyLimiter limiter = OccupancyLimiter::WaveSlots;
  int byVgpr = 0;
  int bySgpr = 0;
  int byLds = 0;     // the slot count when the kernel uses no LDS
  int byGroups = 0;  // barrier and whole-group fit; the slot count when neither binds
  int wavesPerGroup = 0;
  int vgprsAllocated = 0;     // per lane, after the granule
  int sgprsAllocated = 0;     // per wave, after the granule
  int ldsBytesAllocated = 0;  // per group, after the granule
};

// Throws std::invalid_argument (one line) for vgprs < 1 or > maxVgprsPerWave, sgprs < 0 or
// > maxSgprsPerWave, LDS < 0 or > maxLdsBytesPerGroup, threads < 1 or > maxThreadsPerGroup, and
// for a group whose waves cannot all be resident on one CU under the register limits.
Occupancy TheoreticalOccupancy(const GpuConfig& gpu, const KernelResources& kernel);

}  // namespace sim
