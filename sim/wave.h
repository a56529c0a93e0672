#pragma once
// The fixed shape of the machine's work units: 64-lane waves, 2x2 quads, lane kinds and the
// dispatch kinds (hw-facts §6). Everything that counts lanes agrees on these names.

#include <cstdint>
#include <string_view>

#include "raster/limits.h"

namespace sim {

// hw-facts §6.1: GCN waves are 64 lanes; a pixel wave holds up to 16 quads.
inline constexpr int kWaveLanes = 64;
inline constexpr int kQuadsPerWave = kWaveLanes / raster::kQuadPixels;
// hw-facts §6.2: at most 1024 invocations per compute group.
inline constexpr int kMaxGroupThreads = 1024;
// hw-facts §5.3: hi-stencil and the heat maps work on 8x8-pixel tiles.
inline constexpr int kTileSize = raster::kTileSize;
// GCN memory requests are tracked in 64-byte lines (the L2 line size of the GCN whitepaper);
// distinct lines touched per dispatch are the compulsory DRAM traffic of the timing estimate.
inline constexpr int kCacheLineBytes = 64;

static_assert(kQuadsPerWave == 16, "hw-facts §6.1: 16 quads per wave64");

// What a launched lane did (each launched lane is exactly one of these).
enum class LaneKind : std::uint8_t {
  Active,        // ran the kernel for a pixel or thread
  Helper,        // ran for derivatives only (uncovered pixel of a live quad); stores dropped
  DeadStencil,   // pixel of a live quad that failed the stencil test: launched, never ran
  DeadEmpty,     // empty lane of a partial wave: no quad, thread outside the grid or item count
};

enum class DispatchKind : std::uint8_t { Draw, FullScreen, Compute, IndirectCompute };

constexpr std::string_view DispatchKindName(DispatchKind kind) {
  switch (kind) {
    case DispatchKind::Draw: return "draw";
    case DispatchKind::FullScreen: return "full-screen PS";
    case DispatchKind::Compute: return "compute";
    case DispatchKind::IndirectCompute: return "indirect compute";
  }
  return "unknown";
}

// How the pixel-wave packer closes a wave (hw-facts §6.1: a wave may mix primitives; the SPI's
// real rule is not public, §9). Waves never span 32x32 scan-converter bins.
enum class WaveFlush : std::uint8_t {
  MixPrimitives,        // close a wave only when 16 quads are in or the bin ends
  OnePrimitivePerWave,  // also close it when the next quad belongs to another primitive
};

}  // namespace sim
