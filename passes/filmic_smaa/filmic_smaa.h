#pragma once
// Filmic SMAA's morphological part (seed 000, "Morphological Antialiasing Improvements";
// aa-facts §2) on SMAA 1x's searches and tables (passes/smaa/), with its work set under both
// dispatch strategies. The readings of the seed's unformulated ideas are in docs/filmic-smaa.md.
//
//   frame colour-srgb8 RGBA8_SRGB (W x H; FrameInputs::colourSrgb8), and a copy of it as the
//                           output target
//
//   filmic-smaa/edge-detection  colour through a UNORM view (gamma luma), a 6x6 window per pixel
//     (detect)                  (3 px left/up, 2 px right/down). Morphological edge suppression
//                               replaces local contrast adaptation (seed 000, Morphological:
//                               the best two-edge pattern through the edge must beat the best
//                               one not through it and 2 x threshold). Each pixel picks its
//                               higher-contrast boundary (left on ties) and keeps it only if it
//                               beats its neighbours along the blending axis that picked the
//                               same direction ("I've more contrast, I win!"). Writes edges RG8
//                               (every kept edge: what the searches read; cleared to 0).
//                               stencil: full-screen PS, loads; stencil = 1 (vertical item) or
//                                        2 (horizontal item)
//                               queue:   compute 8x8; a 14x14 luma tile in LDS (784 bytes)
//                                        filled with 3 gather4 (R, G, B) per 2x2 texels ("LDS
//                                        preloading via Gather4"); appends to the vertical or
//                                        the horizontal queue
//   filmic-smaa/queue-args      (queue only) both counts -> two indirect argument triples
//   filmic-smaa/vertical-edges  per vertical item P: SMAA's vertical search and AreaTex lookup
//     (consume 1, studied)      for P's left edge (edges RG8 bilinear, AreaTex RG8, SearchTex
//                               R8), then writes BOTH P and its left neighbour: each lerped
//                               towards the other by its weight (read and written through the
//                               output's sRGB view; scattered RW stores, only where the weight is
//                               non-zero). stencil: PS at stencil == 1; queue: indirect compute
//   filmic-smaa/horizontal-edges the same for horizontal items (SMAA's diagonal patterns first,
//     (consume 2, studied)       then the horizontal search) writing P and the pixel above; runs
//                               after the vertical dispatch ("serialize execution: vertical edges
//                               then horizontal"), so it blends the vertically blended colours.
//                               stencil: PS at stencil == 2; queue: indirect compute
//
// No weights texture and no neighbourhood-blending pass: the output differs from SMAA 1x by
// design. Silhouette line detection and U-shape smoothing are named by the seed without a
// formula and are not implemented. Settings and presets are SMAA's (aa-facts §1.2) without the
// local contrast adaptation factor. Layers: "edges" (R, G as k / 255) and "items" (1 = a vertical
// item, 2 = a horizontal item, 0 = none).

#include <memory>

#include "passes/pass.h"

namespace passes::filmic_smaa {

const PassInfo& Info();
std::unique_ptr<Pass> Make(const PassSettings& settings);

}  // namespace passes::filmic_smaa
