#pragma once
// Filmic SMAA T2x (seed 000, "Filmic SMAA T2x" and "Temporal Antialiasing Improvements"; aa-facts
// §2): temporal supersampling (SMAA T2x's two-frame resolve, improved) separated from temporal
// filtering (an exponential history applied only on temporal edges, from a deferred queue).
//
//   frame colour-srgb8 ──copy──► colour RGBA8_SRGB, and a copy as this frame's morph target
//   frame velocity ──store──► velocity[N] RG16F (UV units, smaa_temporal.h "Velocity")
//
//   filmic-smaa-t2x/{edge-detection,   Filmic SMAA's morphological part (filmic_smaa.h, both
//     vertical-edges,                 strategies) with the frame's T2x subsample indices
//     horizontal-edges}               (frameIndex parity, aa-facts §1.8) -> morph[N] RGBA8_SRGB
//   filmic-smaa-t2x/store-luma        full-screen: gamma luma of morph[N] -> luma[N] R8 (a ring of
//                                     four: N..N-3, "we store luma for each frame")
//   filmic-smaa-t2x/depth-downsample  half-resolution NEAREST depth (min of each 2x2) -> depth[N]
//                                     R32F ceil(W/2) x ceil(H/2) (a ring of two)
//   filmic-smaa-t2x/supersample       full-screen PS, temporal supersampling of morph[N] with
//                                     morph[N-1] -> resolved RGBA8_SRGB:
//     - previous fetched at p - v plus the contrast-aware quincunx offset t * (j_N - j_{N-1})
//       (the jitter change: +-0.5 px diagonally, where one bilinear fetch averages the previous
//       frame's four samples around this frame's: quincunx); t = saturate(contrast /
//       quincunx_contrast), contrast = max - min of those four samples' luma (one gather of
//       luma[N-1]): low contrast (texture detail) stays 2x, high contrast (edges) goes quincunx;
//       the fetch's fraction goes through smoothstep ("fast smootheststep" resampling: snaps to
//       texel centres, keeps the quincunx's 0.5)
//     - weight = 0.5 * velocity weight * colour weight N/N-2 * colour weight N-1/N-3:
//       velocity weight = saturate(1 - sqrt(||v_N| - |v_{N-1}(p - v)||) * 30) (SMAA's, UV units);
//       colour weight = saturate(1 - SAD * colour_weight_scale), SAD of the 2x2 luma blocks one
//       gather each returns: luma[N] at p against luma[N-2] at p - 2v, luma[N-1] at p - v against
//       luma[N-3] at p - 3v (equal jitters; constant velocity assumed across the four frames)
//   filmic-smaa-t2x/temporal/...      the temporal filter's work set (both strategies):
//     temporal-edges (detect)         per pixel: the filtered history at p - v (bilinear), depth
//                                     test (depth[N] at p/2 against depth[N-1] at (p - v)/2: a
//                                     difference above depth_tolerance is a disocclusion), the
//                                     temporal contrast |luma(resolved) - luma(history)|. A pixel
//                                     with no history, a disocclusion or a contrast below
//                                     temporal_threshold is not filtered: the detect writes
//                                     resolved (which "resets the accumulation buffer"); the
//                                     others are temporal edges and join the work set
//     temporal-filter (consume)       the history through the 5-tap Catmull-Rom filter (seed 000's
//                                     SMAAFilterHistory, sharpness c: passes/temporal's
//                                     SampleHistoryFilmic), clamped to resolved's 3x3
//                                     min/max, out = history a + resolved (1 - a) with the
//                                     FPS-aware a = exp(-dt / convergence_time), dt =
//                                     FrameInputs::frameSeconds
//                                   -> filtered[N] RGBA16F (a ring of two; the output)
//
// History (machine textures, bytes counted by the views): morph[N-1], luma[N-1..N-3],
// velocity[N-1], depth[N-1] and filtered[N-1]. A sequence's first frame (or a size change) has
// none: the supersample weight is 0 (resolved = morph[N]) and no pixel is filtered; the colour
// weights whose older frames do not exist yet are 1.
//
// Not modelled: temporal spatial-contrast tracking (raising the convergence time where spatial
// contrast flickers; no formula in the seed), improved pixel matching (closest-match search), the
// 8-bit velocity encoding and half-resolution velocities (the study's options), temporal
// upsampling. Supersampling derivatives: see docs/temporal.md (our material kernel samples
// base-colour textures without mips, so an LOD bias has nothing to act on).
//
// Settings: SMAA's (morphological part, filmic_smaa.h) plus temporal_threshold, convergence_time,
// sharpness, depth_tolerance, quincunx_contrast, colour_weight_scale, reprojection_weight_scale.
// Layers: "edges" (R, G), "items" (morphological items), "temporal-edges" (1 where filtered).

#include <cmath>
#include <memory>

#include "passes/pass.h"

namespace passes::filmic_smaa {

// The FPS-aware exponential blend (seed 000 "FPS-aware temporal filtering"; aa-facts §2, §5.4):
// the weight the history keeps over dt seconds, a = exp(-dt / tau); the frame gets 1 - a. Frame
// rates compose: two frames of dt keep a(dt)^2 = a(2 dt).
inline float HistoryWeight(double frameSeconds, double convergenceSeconds) {
  return static_cast<float>(std::exp(-frameSeconds / convergenceSeconds));
}

const PassInfo& FilmicT2xInfo();
std::unique_ptr<Pass> MakeFilmicT2x(const PassSettings& settings);

}  // namespace passes::filmic_smaa
