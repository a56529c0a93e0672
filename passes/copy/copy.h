#pragma once
// The strategies' floor: every pixel joins the work set and the consume kernel copies the colour.
// What a pass costs under each strategy when nothing is culled, and the smallest registered pass
// (the template a new pass starts from).
//
//   stencil-culled   copy/mark   full-screen PS: stencil = 1 everywhere
//                    copy/copy   full-screen PS, stencil == 1: colour -> output
//   deferred queue   copy/mark   compute 8x8 groups: append every pixel
//                    copy/queue-args, copy/copy (indirect compute, one pixel per thread)
//
// Inputs: colour. Output: the colour, bit for bit. No layers.

#include <memory>

#include "passes/pass.h"

namespace passes::copy {

const PassInfo& Info();
std::unique_ptr<Pass> Make(const PassSettings& settings);

}  // namespace passes::copy
