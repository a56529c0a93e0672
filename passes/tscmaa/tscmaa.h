#pragma once
// TSCMAA, temporally stable CMAA (Intel; seed 003_d97583e795468cd4.txt, aa-facts §4.5): CMAA2 with
// TSCMAA's edge thresholds, then TAA on half of CMAA's edge candidates only, blended 0.8 with
// history; the history is the TSCMAA output. Readings and choices: docs/temporal.md "TSCMAA".
//
//   frame colour, velocity (px, current - previous)
//
//   cmaa2/*                    CMAA2 v2.3 as the cmaa2 pass runs it (passes/cmaa2/cmaa2.h), under
//                              the same strategy, with threshold 1/22 and local contrast
//                              adaptation 0.5 (seed 003 SetEdgeThresholds defaults, CMAA2's
//                              "tscmaa" preset): its targets cmaa2/colour (RGBA8_SRGB, after the
//                              deferred apply) and cmaa2/edges (R8_UINT, two pixels per texel),
//                              which the kernels below bind directly (cmaa2::Stage)
//   tscmaa/taa-candidates      (detect) per pixel: CMAA2's codes -> the new history (UNORM
//                              views, bit for bit: non-candidates keep CMAA2's pixel), then
//                              CMAA2's candidate test on its edges (two edges meeting at a
//                              corner), and the pixel among the chosen fraction
//                              (`taa_fraction`, default 0.5: a fixed 32-bit hash of (x, y) below
//                              fraction x 2^32; seed 003 "50 percent of CMAA edge candidates")
//                              stencil: full-screen PS; queue: compute 8x8, append
//   tscmaa/queue-args          (queue only) count -> indirect arguments
//   tscmaa/taa                 (consume, studied) per TAA candidate: history at the pixel centre
//                              minus its velocity through Intel's 5-tap Catmull-Rom
//                              (passes/temporal, aa-facts §5.3; seed 003 "five-tap approximation
//                              for a Hermite/Catmull-Rom bicubic"), clipped towards the current
//                              colour against the variance box mean ± gamma sigma of CMAA2's 3x3
//                              in YCoCg (seed 003 "variance clipping in YCoCg"), blended
//                              lerp(current, history, 0.8) (seed 003), stored into the new history
//                              (RGBA8_SRGB). Frame 0 of a sequence, a changed size, or a history
//                              position off the screen: the CMAA2 pixel unchanged
//
// History: two RGBA8_SRGB targets (W x H, ping-pong), the TSCMAA output of the previous frame
// (seed 003 "the output of TAA becomes a history frame"); the pass output is the new one.
// Counters: tscmaa/history_clipped, tscmaa/history_offscreen. Layers: CMAA2's "edges" and
// "candidates", and "taa-candidates" (1 = the TAA ran on the pixel).

#include <cstdint>
#include <memory>

#include "passes/pass.h"

namespace passes::tscmaa {

const PassInfo& Info();
std::unique_ptr<Pass> Make(const PassSettings& settings);

// A fixed 32-bit mix of the pixel position (Wellons' "lowbias32" integer hash on x | y << 16):
// neighbouring pixels get unrelated values, so any shape of candidates (a diagonal staircase
// included, which a checkerboard or ordered-dither choice would take all or nothing of) keeps
// about `fraction` of its pixels, the same ones every frame.
constexpr std::uint32_t PixelHash(int x, int y) {
  std::uint32_t h = static_cast<std::uint32_t>(x) | static_cast<std::uint32_t>(y) << 16;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}
// Whether a CMAA candidate at (x, y) is also a TAA candidate: its hash below fraction x 2^32.
constexpr bool ChosenForTaa(int x, int y, double fraction) {
  return static_cast<double>(PixelHash(x, y)) < fraction * 4294967296.0;
}

}  // namespace passes::tscmaa
