#pragma once
// The post passes the main job runs, in order: each takes the frame's resolved colour (and, as
// later passes need them, its other targets) and runs under every dispatch strategy it has, so
// the report can put the strategies side by side. A pass joins the study by adding one entry to
// the table in post_passes.cpp.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

#include "passes/demo_edge_blend.h"
#include "sim/dispatch.h"
#include "sim/frame.h"

namespace cli {

struct PostPassOutput {
  sim::Texture2D<glm::vec4> image;
  sim::Texture2D<float> edges;  // the pixels the pass worked on (0/1)
  std::uint64_t edgePixels = 0;
};

struct PostPass {
  std::string_view name;         // "demo"
  std::string_view description;  // one line for --help and the report
  // The dispatch the strategies exist for, compared side by side ("demo/blend").
  std::string_view studiedDispatch;
  std::vector<passes::Strategy> strategies;
  // Appends its dispatches to the machine's report list.
  std::function<PostPassOutput(sim::Machine&, const sim::FramePipeline&, passes::Strategy)> run;
};

const std::vector<PostPass>& PostPasses();
std::vector<std::string> PostPassNames();
// Throws std::invalid_argument listing the names.
const PostPass& PostPassByName(std::string_view name);

}  // namespace cli
