#pragma once
// Pixel-wave formation: the quads a scan-converter bin produced, in rasterization order, packed
// 16 per wave64 (hw-facts §6.1). Quads with no pixel passing depth/stencil are culled before
// packing; a wave may mix primitives unless the flush rule says otherwise; a bin's last wave
// may be partial. Which lane of a launched quad does what is decided here too.

#include <cstdint>
#include <span>
#include <vector>

#include "raster/rasterizer.h"
#include "sim/counters.h"
#include "sim/wave.h"

namespace sim {

struct PackedWaves {
  std::vector<std::uint32_t> quads;       // indices into the bin's quad list, launched quads only
  std::vector<std::uint32_t> waveStarts;  // wave w holds quads[waveStarts[w] .. waveStarts[w+1])

  std::size_t WaveCount() const { return waveStarts.empty() ? 0 : waveStarts.size() - 1; }
};

// Fills `out` and counts waves, quads launched and culled, quads by live pixels and waves by
// primitives into `counters`.
void PackPixelWaves(std::span<const raster::QuadFragment> quads, WaveFlush flush, PackedWaves& out,
                    LaneCounters& counters);

// A launched quad's lanes by kind, one bit per quad pixel (bit p: pixel p); the three masks
// partition the quad's four pixels.
struct QuadLaneKinds {
  unsigned active = 0;
  unsigned helper = 0;
  unsigned deadStencil = 0;

  LaneKind Of(int quadPixel) const {
    if ((active >> quadPixel & 1u) != 0) return LaneKind::Active;
    return (deadStencil >> quadPixel & 1u) != 0 ? LaneKind::DeadStencil : LaneKind::Helper;
  }
};

// A pixel that passed depth/stencil is active. One that was covered but failed is a dead lane in
// a full-screen pass (the stencil culled it: seed 000 "Stencil Culling Inefficiencies") and a
// helper in a draw (whole-quad mode runs it for derivatives, hw-facts §6.1); an uncovered pixel
// of a launched quad is always a helper.
QuadLaneKinds ClassifyQuad(const raster::QuadFragment& quad, DispatchKind kind);

}  // namespace sim
