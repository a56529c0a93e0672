#pragma once
// FXAA 3.11 "PC quality" (NVIDIA Fxaa3_11.h, Timothy Lottes; FXAA_PC 1, luma in alpha) with the
// header's own integration (its "INTEGRATION - RGBL AND COLORSPACE" notes) and its work set, the
// pixels past the early exit, under both dispatch strategies:
//
//   frame colour-srgb8 RGBA8_SRGB (W x H; the frame's 8-bit sRGB target, FrameInputs::colourSrgb8)
//
//   fxaa/luma          full-screen PS: colour through a UNORM view (gamma codes) -> rgbl RGBA8
//                      UNORM: rgb the codes unchanged, a = dot(rgb, (0.299, 0.587, 0.114))
//                      rounded to 8 bits by the store (the pass before FXAA "outputs RGBL")
//   fxaa/early-exit    rgbl: the centre texel and its 4 neighbours' alpha (point fetches at
//     (detect)         texel centres); range < max(edge_threshold_min, rangeMax x edge_threshold)
//                      writes rgbyM to the output and leaves the pixel out of the work set (the
//                      header's `return rgbyM`)
//                      stencil:  full-screen PS, stencil = 1 on work-set pixels
//                      queue:    compute 8x8, appends work-set pixels
//   fxaa/queue-args    (queue only) append count -> indirect arguments
//   fxaa/edge-search   the rest of FxaaPixelShader on work-set pixels: the 5 texels again and
//     (consume,        the 4 diagonals, sub-pixel amount, span direction, gradient side, the end
//      studied)        search on both sides with the preset's step table (bilinear alpha
//                      fetches on the edge line, fixed point), the final offset and one bilinear
//                      colour fetch -> output RGBA8 UNORM (rgb, a = lumaM)
//                      stencil:  full-screen PS, stencil == 1, hi-stencil
//                      queue:    indirect compute, one work-set pixel per thread
//
// The output holds gamma codes; the pass's output colour is their sRGB decode (alpha: the
// frame's). Settings subpix, edge_threshold, edge_threshold_min (FxaaPixelShader's inputs, the
// header's defaults and documented ranges) and quality_preset (FXAA_QUALITY__PRESET, default
// 12); presets "10".."15", "20".."29", "39" set quality_preset. Layers: "luma" (rgbl's alpha as
// k / 255) and "span" (direction: 0 outside the work set, 1 horizontal span, 2 vertical; dstN,
// dstP: the search's reach in pixels; offset: the blend offset in pixels, negative towards N or W), the latter an
// inspection record of the consume, not a machine resource.

#include <memory>

#include "passes/pass.h"

namespace passes::fxaa {

const PassInfo& Info();
std::unique_ptr<Pass> Make(const PassSettings& settings);

}  // namespace passes::fxaa
