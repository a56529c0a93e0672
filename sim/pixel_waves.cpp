// Pixel-wave formation (see pixel_waves.h).

#include "sim/pixel_waves.h"

namespace sim {

void PackPixelWaves(std::span<const raster::QuadFragment> quads, WaveFlush flush, PackedWaves& out,
                    LaneCounters& counters) {
  out.quads.clear();
  out.waveStarts.clear();
  bool waveOpen = false;
  std::size_t waveBegin = 0;
  int primitivesInWave = 0;
  std::uint32_t previousPrimitive = 0;
  auto closeWave = [&] {
    ++counters.wavesByPrimitives[static_cast<std::size_t>(primitivesInWave)];
    waveOpen = false;
  };
  for (std::size_t i = 0; i < quads.size(); ++i) {
    const raster::QuadFragment& quad = quads[i];
    const int live = quad.passed.LivePixelCount();
    ++counters.quadsByLivePixels[static_cast<std::size_t>(live)];
    if (live == 0) {
      ++counters.quadsCulled;
      continue;
    }
    bool samePrimitive = waveOpen && quad.primitiveId == previousPrimitive;
    const bool full = waveOpen && out.quads.size() - waveBegin == static_cast<std::size_t>(kQuadsPerWave);
    if (full || (waveOpen && flush == WaveFlush::OnePrimitivePerWave && !samePrimitive)) closeWave();
    if (!waveOpen) {
      waveOpen = true;
      waveBegin = out.quads.size();
      out.waveStarts.push_back(static_cast<std::uint32_t>(waveBegin));
      primitivesInWave = 0;
      samePrimitive = false;
      ++counters.waves;
    }
    // hw-facts §6.1: the wave's first quad, and each quad with a new_prim_mask bit, starts a
    // primitive (at most 16 per wave).
    if (!samePrimitive) ++primitivesInWave;
    previousPrimitive = quad.primitiveId;
    out.quads.push_back(static_cast<std::uint32_t>(i));
    ++counters.quadsLaunched;
  }
  if (waveOpen) closeWave();
  if (!out.waveStarts.empty()) out.waveStarts.push_back(static_cast<std::uint32_t>(out.quads.size()));
}

QuadLaneKinds ClassifyQuad(const raster::QuadFragment& quad, DispatchKind kind) {
  constexpr unsigned kAllPixels = (1u << raster::kQuadPixels) - 1u;
  const unsigned passed = quad.passed.LivePixels();
  const unsigned dead = kind == DispatchKind::FullScreen ? quad.covered.LivePixels() & ~passed & kAllPixels : 0u;
  return {.active = passed, .helper = ~passed & ~dead & kAllPixels, .deadStencil = dead};
}

}  // namespace sim
