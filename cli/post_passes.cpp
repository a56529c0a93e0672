// The main job's post passes (see post_passes.h).

#include "cli/post_passes.h"

#include <stdexcept>

#include "cli/common_options.h"

namespace cli {
namespace {

PostPassOutput RunDemo(sim::Machine& machine, const sim::FramePipeline& frame,
                       passes::Strategy strategy) {
  passes::DemoEdgeBlendResult result = passes::RunDemoEdgeBlend(machine, frame.Colour(), strategy);
  return {std::move(result.output), std::move(result.edges), result.edgePixels};
}

}  // namespace

const std::vector<PostPass>& PostPasses() {
  static const std::vector<PostPass> passes{
      {"demo", "luma edge detection, then a 3x3 box blend on edge pixels (passes/demo_edge_blend.h)",
       "demo/blend", {passes::Strategy::StencilCulled, passes::Strategy::DeferredQueue}, RunDemo},
  };
  return passes;
}

std::vector<std::string> PostPassNames() { return Names(PostPasses()); }

const PostPass& PostPassByName(std::string_view name) {
  for (const PostPass& pass : PostPasses()) {
    if (pass.name == name) return pass;
  }
  throw std::invalid_argument("unknown post pass '" + std::string(name) + "' (passes: " +
                              JoinNames(PostPassNames()) + ")");
}

}  // namespace cli
