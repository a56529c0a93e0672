#pragma once
// Demonstration post pass for the dispatch study (DESIGN.md "Dispatch strategies"): luma edge
// detection, then a 3x3 box blend on edge pixels only, run either as
//
//   stencil-culled   demo/edge-detect  full-screen PS: edge mask, copy colour, stencil = 1 on edges
//                    demo/blend        full-screen PS, stencil == 1, hi-stencil pretest on
//   deferred queue   demo/edge-detect  compute 8x8 groups, 10x10 luma tile in LDS, appends edges
//                    demo/queue-args   one thread: append count -> indirect arguments
//                    demo/blend        indirect compute, one queued pixel per thread
//
// Inputs: colour (RGBA, linear). Outputs: the blended colour, the edge mask (0/1), and one
// DispatchReport per dispatch. Both strategies run the same arithmetic in the same order, so
// their images are bit-identical; only the machine's work differs.

#include <cstdint>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

#include "sim/dispatch.h"

namespace passes {

enum class Strategy : std::uint8_t { StencilCulled, DeferredQueue };
std::string_view StrategyName(Strategy strategy);  // "stencil", "queue"

struct DemoEdgeBlendSettings {
  // aa-facts §1.2: SMAA's default luma edge threshold.
  float threshold = 0.1f;
};

struct DemoEdgeBlendResult {
  sim::Texture2D<glm::vec4> output;
  sim::Texture2D<float> edges;
  std::uint64_t edgePixels = 0;
  std::vector<sim::DispatchReport> dispatches;
};

// Throws std::invalid_argument for a threshold outside (0, 1].
DemoEdgeBlendResult RunDemoEdgeBlend(sim::Machine& machine, const sim::Texture2D<glm::vec4>& colour,
                                     Strategy strategy, const DemoEdgeBlendSettings& settings = {});

}  // namespace passes
