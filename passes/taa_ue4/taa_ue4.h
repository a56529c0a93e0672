#pragma once
// UE4 temporal AA (Karis, "High Quality Temporal Supersampling", SIGGRAPH 2014: seed
// 002_2de9285e58f4d8b6.txt; aa-facts §5.1) on the pass framework. Readings and choices where the
// talk gives no number: docs/temporal.md "UE4 TAA".
//
//   frame colour (linear RGBA float, HDR), depth, velocity (px, current - previous), object id
//   jitter schedule halton8 (PassInfo::jitter; FrameInputs::jitter is this frame's offset)
//
//   taa-ue4/resolve   full-screen PS, every pixel, one dispatch per frame:
//     1. 3x3 colour loads (coordinates clamped to the screen): the jittered current samples
//     2. 3x3 depth loads -> the front-most (smallest depth) neighbour; its velocity (1 load)
//        (seed 002 "Dilate velocity: take front most velocity")
//     3. reconstruction: sum W(o + jitter) w_luma c / sum W w_luma over the 3x3, with
//        W(x) = e^(-2.29 x²) (seed 002 "Gaussian fit to Blackman-Harris 3.3") at the distance
//        from neighbour o's jittered sample to this pixel's centre, w_luma = 1 / (1 + luma)
//     4. history: 5-tap Catmull-Rom (passes/temporal, the renormalised form) at the pixel centre
//        minus the velocity, in the previous frame's history; off the screen, or on frame 0 of a
//        sequence (no history yet), the reconstructed colour is taken as the history
//     5. constraint (setting): none; the 3x3 RGB min/max clamp (seed 002 "Neighborhood
//        clamping"); or (default) the clip of the segment from the neighbourhood's YCoCg mean
//        to the history against the shaped YCoCg box, the average of the 3x3 and '+' min/max
//        boxes (seed 002 "Shaped neighborhood clamp", "YCoCg box", "Clip instead of clamp")
//     6. blend: current weight alpha (responsive pixels: responsive_alpha, seed 002 "Responsive
//        AA"), reduced near the box's luma faces (anti-flicker, seed 002), then the luma-weighted
//        exponential blend h + beta (c - h), beta = alpha w_c / (alpha w_c + (1 - alpha) w_h)
//     7. store: the new history, RGBA16_FLOAT (W x H), ping-pong with the previous one
//
// Resources: two RGBA16_FLOAT history targets (8 bytes per texel, read through a bilinear view
// and written by the PS); the pass output is the new history (a host copy in PassOutput, the
// same values). Counters: taa-ue4/history_clipped (pixels whose history the constraint moved),
// taa-ue4/history_offscreen (reprojected off the screen), taa-ue4/responsive_pixels.
// No layers.
//
// Strategies: the stencil (full-screen) one only. Every pixel is work for a TAA resolve, so the
// stencil would pass everywhere and a queue would add an append per pixel and an indirect
// dispatch for nothing (the copy pass measures exactly that overhead); the pass runs a single
// full-screen pixel shader with no stencil test and reports every pixel as its work set.

#include <memory>

#include "passes/pass.h"

namespace passes::taa_ue4 {

const PassInfo& Info();
std::unique_ptr<Pass> Make(const PassSettings& settings);

}  // namespace passes::taa_ue4
