#pragma once
// SMAA 1x, the reference implementation's three passes (iryoku/smaa SMAA.hlsl; aa-facts §1),
// with its work set (the edge pixels) under both dispatch strategies:
//
//   frame colour-srgb8 RGBA8_SRGB (W x H; the frame's 8-bit sRGB target, FrameInputs::colourSrgb8)
//   [frame depth R32F] ─────────────────────────────────────┐ (depth edges, or predication)
//                                                           ▼
//   smaa/edge-detection      colour through a UNORM view (gamma values), point samples; depth
//     (detect)               gathers. Writes edges RG8 (R = edge on the left side of the pixel,
//                            G = on its top side; cleared to 0, nothing written where no edge)
//                            stencil:  full-screen PS, stencil = 1 on edge pixels
//                            queue:    compute 8x8, appends edge pixels
//   smaa/queue-args          (queue only) append count -> indirect arguments
//   smaa/blending-weights    edges RG8 (fixed-point bilinear), AreaTex RG8 160x560, SearchTex
//     (consume)              R8 64x16 -> weights RGBA8 (cleared to 0; aa-facts §1.5 channels)
//                            stencil:  full-screen PS, stencil == 1, hi-stencil
//                            queue:    indirect compute, one edge pixel per thread
//   smaa/neighbourhood-      colour through an sRGB view (linear, float bilinear), weights ->
//     blending               output RGBA8_SRGB; full-screen PS on every pixel, both strategies
//
// Registered variants (one registry line each): smaa (luma edges), smaa-colour, smaa-depth,
// smaa-predicated (luma edges, thresholds predicated by the frame's depth) and smaa-s2x (luma
// SMAA 1x on each sample of a 2-sample EQAA surface, separated by a smaa-s2x/separate full-screen
// pass reading the surface through the shader fetch path, with the subsample indices of
// aa-facts §1.8; the second sample's neighbourhood blending blends onto the first's with factor
// 0.5; dispatches smaa-s2x/s<k>/...). Presets low, medium,
// high, ultra are SMAA.hlsl's (aa-facts §1.2); the defaults are HIGH's. Layers: "edges" (R, G)
// and "weights" (R, G, B, A), the 8-bit texels as k / 255. The temporal modes on these runs are
// separate passes: SMAA T2x and 4x (smaa_temporal.h), SMAA 1TX (smaa_1tx.h).

#include <memory>
#include <string_view>
#include <vector>

#include "passes/pass.h"
#include "passes/smaa/smaa_kernels.h"

namespace passes::smaa {

enum class Variant { Luma, Colour, Depth, LumaPredicated, S2x };

// SMAA.hlsl's threshold and search settings (threshold, max_search_steps, max_search_steps_diag,
// corner_rounding) and its presets LOW..ULTRA over them (aa-facts §1.2), for every pass built on
// SMAA's searches; `thresholdDoc` says what the threshold means to that pass.
std::vector<SettingInfo> SearchSettings(std::string_view thresholdDoc);
std::vector<Preset> SearchPresets();

// A variant's settings (SearchSettings plus its own) and the kernels' configuration from them,
// for the passes built on a variant (T2x and 4x on luma SMAA).
std::vector<SettingInfo> SettingsOf(Variant variant);
Config ConfigOf(Variant variant, const PassSettings& settings);

template <Variant V>
const PassInfo& Info();
template <Variant V>
std::unique_ptr<Pass> Make(const PassSettings& settings);

}  // namespace passes::smaa
