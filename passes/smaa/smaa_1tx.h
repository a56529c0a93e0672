#pragma once
// SMAA 1TX (Sousa 2013, as seed 000 "SMAA 1TX [Sousa2013]" gives it; aa-facts §2): SMAA 1x with
// no jitter, then a spatial-contrast exponential history: more history where the frame's local
// contrast is high (keeps texture detail stable in motion), a clamp of the reprojected history to
// the four diagonal neighbours' range.
//
//   frame colour-srgb8 RGBA8_SRGB (W x H; FrameInputs::colourSrgb8)
//   frame velocity ──store──► velocity RG16F (W x H, UV units; smaa_temporal.h "Velocity")
//   smaa-1tx/{edge-detection,        SMAA 1x (smaa.h's diagram; subsample indices 0; both
//     blending-weights,              strategies through the work set)
//     neighbourhood-blending}        -> smaa RGBA8_SRGB (W x H)
//   smaa-1tx/temporal                full-screen PS: smaa through an sRGB view (the centre texel and
//                                    four bilinear taps at (+-0.5, +-0.5) px, each the mean of a 2x2
//                                    block), history[previous] (bilinear at uv - v_uv), velocity
//                                    -> history[current] RGBA8_SRGB (W x H), this frame's output
//
// Per channel, in linear colour (the sRGB views' values), with c_TL..c_BR the diagonal taps:
//   c_acc = clamp(history(p - v), min(c_TL..c_BR), max(c_TL..c_BR))
//   w_k   = |(c_TL + c_TR + c_BL + c_BR) / 4 - c_M|
//   w     = clamp(1 / (K_lowfreq (1 - w_k) + K_hifreq w_k), 0, 1)
//   c     = c_acc (1 - w) + c_M w
// K_lowfreq = 2 and K_hifreq = 6 are "frames to keep in history" in low- and high-contrast areas:
// the seed gives no values; these are CryEngine's defaults (r_AntialiasingTAAFalloffLowFreq 2.0,
// r_AntialiasingTAAFalloffHiFreq 6.0, its PostAA shader's SMAA 1TX mode) and are settings.
// w is the CURRENT frame's weight: the seed's slide writes c = c_M (1 - w) + c_acc w, which read
// literally gives the history the weight 1/K, i.e. LESS history where contrast is high, against
// its own bullet ("blend with history more strongly on high contrast areas") and against K as
// frames kept in history (an exponential average with current weight 1/K spans ~K frames,
// aa-facts §5.4); CryEngine's shader blends lerp(c_acc, c_M, 1/K) as here. The diagonal taps'
// positions (half a pixel, bilinear) are CryEngine's too; the seed says "diagonals only". The clamp
// range is the four taps' (the seed), not including c_M. Colour space: linear (the seed is silent;
// CryEngine squares its gamma values, an approximation of the same).
//
// History: two RGBA8 sRGB targets swapped every frame (each frame's output is the next frame's
// history), read through the views like any target. Frame 0 (or a size change) has no history:
// the history read is this frame's SMAA output, as CryEngine's PostAA stage binds the current frame
// when its history is stale (its pPrevRT choice): c_acc is then c_M clamped to its neighbours.
// Layers: SMAA 1x's "edges" and "weights".

#include <memory>

#include <glm/vec3.hpp>

#include "passes/pass.h"

namespace passes::smaa {

// K_lowfreq, K_hifreq defaults (CryEngine's, see above).
inline constexpr float kOneTxLowFrequencyFrames = 2.0f, kOneTxHighFrequencyFrames = 6.0f;

// The formula above for one pixel: centre c_M, diagonal taps (TL, TR, BL, BR), the reprojected
// history; returns c.
glm::vec3 SpatialContrastBlend(const glm::vec3& centre, const glm::vec3 (&diagonals)[4], const glm::vec3& history,
                               float lowFrequencyFrames, float highFrequencyFrames);

const PassInfo& OneTxInfo();
std::unique_ptr<Pass> MakeOneTx(const PassSettings& settings);

}  // namespace passes::smaa
