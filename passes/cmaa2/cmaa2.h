#pragma once
// CMAA2 v2.3 (Intel, GameTechDev/CMAA2 Projects/CMAA2/CMAA2/CMAA2.hlsl and vaCMAA2DX11.cpp;
// aa-facts §4), 1x, LDR, on the pass framework. Defines followed: cmaa2_kernels.h; the readings
// (thread mapping, determinism, overflow policy, the tscmaa preset) in docs/cmaa2.md.
//
//   frame colour-srgb8 ──copy──► colour RGBA8_SRGB (W x H): read through its sRGB view (linear
//                           values, the reference's UNORM_SRGB SRV) and written in place at the end
//
//   cmaa2/edge-detection      (detect) per pixel: 3x3 lumas dot(sqrt(linear), Rec. 601), the four
//     EdgesColor2x2CS         contrasts minus amount x the largest perpendicular contrast at their
//                             ends, > threshold -> 4 edge bits; a pixel with two edges meeting at a
//                             corner is a candidate. Even-x lanes store the texel of their pixel
//                             pair: edges R8_UINT ((W+1)/2 x H, low nibble = even x; every pixel,
//                             0 included). A quad's top-left lane resets the quad's list head to
//                             0xFFFFFFFF when one of the 2x2 block's 12 contrasts is non-zero.
//                             stencil: full-screen PS loading its window, stencil = 1 on candidates
//                             queue:   compute 8x8, an 11x11 luma tile in LDS (484 bytes) behind a
//                                      barrier, appends candidates to the work-set queue
//   cmaa2/queue-args          (queue only) candidate count -> indirect arguments
//     ComputeDispatchArgsCS (2,1,1)
//   cmaa2/process-candidates  (consume, studied) per candidate: the simple-shape blend (3x3 edges,
//     ProcessCandidatesCS     0.8-weight item), Z detection, line tracing up to 86 px, the Z's
//                             per-pixel lerps (1.8-weight items). Each item: InterlockedAdd on the
//                             control buffer's item counter, InterlockedExchange into the quad's
//                             head (heads R32_UINT, (W+1)/2 x (H+1)/2), item list uint2 (next,
//                             R11G11B10 E4 colour); a quad's first item appends its location
//                             (qx << 16 | qy). Serial chunks (returned atomics).
//                             stencil: PS at stencil == 1; queue: indirect compute, 64 per group
//   cmaa2/dispatch-args       2 groups of 1 thread (Dispatch(1,2,1)): group y == 1 clamps the
//     ComputeDispatchArgsCS   location count to its capacity, writes {1, ceil(n/32), 1} and the
//                             count, clears the item and location counters (both strategies)
//   cmaa2/deferred-colour-apply  indirect compute, 4 x 32 threads ("threadgroup swap"): thread
//     DeferredColorApply2x2CS    (i, q) walks quad q's list, averages the items of pixel i
//                             (weights 0.8 / 1.8), converts to sRGB and stores the 8-bit codes
//                             (+0.5 rounding) through the colour's UNORM view; pixels without
//                             items are not written (both strategies)
//
// Buffers (aa-facts §4.1): control 16 x u32, indirect args 4 x u32 (our queue-args has its own),
// items and locations sized by the `reference_buffers` setting (docs/cmaa2.md "Queue sizing").
// Layers: "edges" (the 4-bit value per pixel) and "candidates" (1 = a candidate).

#include <cstdint>
#include <memory>

#include "passes/pass.h"

namespace passes::cmaa2 {

const PassInfo& Info();
std::unique_ptr<Pass> Make(const PassSettings& settings);

// CMAA2 as the first stage of another pass (TSCMAA): the same dispatches, with the targets left
// for the caller's kernels to bind, as a renderer's next pass binds them.
class Stage {
 public:
  virtual ~Stage() = default;
  struct Targets {
    const sim::Texture2D<glm::vec4>& colour;      // RGBA8_SRGB, the frame after the deferred apply
    const sim::Texture2D<std::uint32_t>& edges;   // R8_UINT, (W+1)/2 x H: LoadEdge reads a pixel's bits
    WorkSetShape workSet;                         // the candidates
  };
  // The diagram above on one frame. The targets live until the next call.
  virtual Targets Process(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) = 0;
  // The last frame's layers "edges" and "candidates" (of the strategy it ran).
  virtual PassLayer EdgesLayer() const = 0;
  virtual PassLayer CandidatesLayer(Strategy strategy) const = 0;
};
std::unique_ptr<Stage> MakeStage(const PassSettings& settings);

}  // namespace passes::cmaa2
