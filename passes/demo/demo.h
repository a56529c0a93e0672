#pragma once
// Demonstration post pass for the dispatch study: luma edge detection, then a 3x3 box blend on
// edge pixels only. Its work set is the edge pixels; passes/work_set.h runs it as
//
//   stencil-culled   demo/edge-detect  full-screen PS: edge mask, copy colour, stencil = 1 on edges
//                    demo/blend        full-screen PS, stencil == 1, hi-stencil pretest on
//   deferred queue   demo/edge-detect  compute 8x8 groups, 10x10 luma tile in LDS, appends edges
//                    demo/queue-args   one thread: append count -> indirect arguments
//                    demo/blend        indirect compute, one queued pixel per thread
//
// Inputs: colour (RGBA, linear, host float). Outputs: the blended colour and the "edges" layer
// (0/1). Both strategies run the same arithmetic in the same order, so their images are
// bit-identical; only the machine's work differs.

#include <memory>

#include "passes/pass.h"

namespace passes::demo {

const PassInfo& Info();
std::unique_ptr<Pass> Make(const PassSettings& settings);

}  // namespace passes::demo
