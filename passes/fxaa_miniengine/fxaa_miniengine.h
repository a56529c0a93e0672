#pragma once
// MiniEngine's compute FXAA (aa-facts §3; microsoft/DirectX-Graphics-Samples MiniEngine/Core/
// FXAA.cpp, Shaders/FXAAPass1CS.hlsli, FXAAResolveWorkQueueCS.hlsl, FXAAPass2CS.hlsli): FXAA 3.11
// re-derived for work queues, with its own luma and step tables (docs/fxaa-miniengine.md lists
// every difference from FXAA 3.11). Its queue layout is the work set's packed layout
// (passes/work_set.h): the deferred-queue strategy is MiniEngine's structure, the stencil
// strategy runs the same maths as full-screen pixel shaders; both give the same image.
//
//   frame colour ──store──► colour R11G11B10_FLOAT (W x H; MiniEngine's g_SceneColorBuffer,
//                           DefaultHdrColorFormat), modified in place; luma R8_UNORM (W x H,
//                           g_LumaBuffer) cleared to 0 once per frame
//
//   for each quadrant (W/2 x H/2 blocks, x outer, y inner: FXAA.cpp), origin StartPixel:
//   fxaa-miniengine/pass1       (detect) per pixel of the quadrant's 8x8 groups: log2 luma of the
//                               3x3 neighbourhood; range < ContrastThreshold -> none; else the
//                               edge orientation, gradient side and sub-pixel shift packed as
//                               Y << 20 | X << 8 | subpix | dir, and the neighbour across the
//                               edge's colour (the colour queue, R11G11B10 packed).
//                               queue:   compute 8x8, a 10x10 float luma LDS tile (400 bytes;
//                                        50 threads load 2 pixels each and also store their
//                                        lumas to the luma UAV), horizontal items from the front
//                                        and vertical items from the back of ONE queue
//                               stencil: full-screen PS over the quadrant, 9 colour loads; stencil
//                                        = 1 (horizontal) or 2 (vertical), item and colour in two
//                                        R32 targets; a full-screen PS "fxaa-miniengine/luma"
//                                        over the quadrant and its 1 px apron stores the lumas
//                                        the compute tile stores, first
//   fxaa-miniengine/resolve-work-queue  (queue only) one group of 64: pads each end to a multiple
//                               of 64 with 0xFFFFFFFF, writes {H/64, 1, 1} and {V/64, 1, 1},
//                               resets both counters
//   fxaa-miniengine/pass2-h     (consume 1, studied) per horizontal item: end search along x on
//                               the luma (SampleLevel, bilinear R8), blend with the queued colour
//                               by max(subpix, edge shift) if > 0.01. queue: indirect compute, one
//                               item per thread, dummy items' stores dropped out of bounds
//   fxaa-miniengine/pass2-v     (consume 2, studied) the same for vertical items, item i read at
//                               LastQueueIndex - i
//
// The queue holds W*H/4 + 128 slots (created once). Quadrant regions are the blocks rounded up
// to whole 8x8 groups (Dispatch2D launches whole groups and pass 1 has no bounds check), clipped
// to the screen: threads past the screen run the LDS fill but not the classification.
// Layers: "luma" (the luma target after the last quadrant), "items" (1 horizontal, 2 vertical).

#include <memory>

#include "passes/pass.h"

namespace passes::fxaa_miniengine {

const PassInfo& Info();
std::unique_ptr<Pass> Make(const PassSettings& settings);

}  // namespace passes::fxaa_miniengine
