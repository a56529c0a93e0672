#pragma once
// PS3 MLAA (Berghoff & Perthuis, "MLAA on PS3", SIGGRAPH 2011 course; seed 004, aa-facts §7):
// Reshetov's MLAA with relative or predicated thresholding and feature splitting, as a horizontal
// pass then a vertical pass over the colour, each an edge detect and a line blend on its own work
// set (docs/mlaa.md has the talk's rules, quoted, and every choice the talk leaves open):
//
//   frame colour-srgb8 RGBA8_SRGB (W x H; the 8-bit frame buffer, FrameInputs::colourSrgb8, read
//   [frame depth R32F] ──┐   through a UNORM view: gamma codes, as the SPUs processed it)
//                        ▼ (predicated thresholding only)
//   mlaa/h-edges   (detect) colour -> edges-h RGBA8 (R: edge to the pixel below, G: to the right,
//                  B, A: their gradient class 0 / 0.5 / 1), every pixel written; copies the colour
//                  into horizontal RGBA8_SRGB. Work set: pixels with an edge above or below.
//                  stencil: full-screen PS, stencil = 1; queue: compute 8x8, appends
//   mlaa/h/queue-args (queue only)
//   mlaa/h-blend   (consume, studied) per pixel, each horizontal edge above and below it: trace
//                  the line left and right in edges-h (up to max_search px per side, split where
//                  the gradient class changes), classify its ends by their crossing edges (L, Z,
//                  U), blend the pixel with its neighbour across the edge by the revectorised
//                  area: colour -> horizontal (RGBA8 UNORM view), weights-h RG16F
//   mlaa/v-edges, mlaa/v/queue-args, mlaa/v-blend: the same transposed, on the horizontal pass's
//                  output (the PS3's in-place second pass): horizontal -> edges-v, output
//                  RGBA8_SRGB, weights-v RG16F (work set: pixels with an edge left or right)
//
// The framework's second consume takes a pixel in one consume only; a pixel on a horizontal and a
// vertical line needs both, so the two passes are two work sets, each with its own detect (which
// is also what the in-place PS3 pass did: the vertical pass detects on the horizontal pass's
// result). The work-set shape is the sum of the two. Layers: "edges-h", "edges-v" (R, G, B, A)
// and "weights-h" (R: from the pixel above, G: from below), "weights-v" (R: from the left, G:
// from the right). Registered as three variants of the thresholding: "mlaa" (relative, the talk's
// main test), "mlaa-absolute" and "mlaa-predicated" (depth), so one run compares them.

#include <memory>

#include "passes/mlaa/mlaa_kernels.h"
#include "passes/pass.h"

namespace passes::mlaa {

template <Thresholding T>
const PassInfo& Info();
template <Thresholding T>
std::unique_ptr<Pass> Make(const PassSettings& settings);

}  // namespace passes::mlaa
