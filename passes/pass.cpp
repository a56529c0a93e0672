// Strategy names and layers (see pass.h).

#include "passes/pass.h"

#include <algorithm>

namespace passes {

std::string_view StrategyName(Strategy strategy) {
  return strategy == Strategy::StencilCulled ? "stencil" : "queue";
}

std::optional<Strategy> StrategyByName(std::string_view name) {
  const auto* found = std::find_if(std::begin(kAllStrategies), std::end(kAllStrategies),
                                   [&](Strategy strategy) { return StrategyName(strategy) == name; });
  if (found == std::end(kAllStrategies)) return std::nullopt;
  return *found;
}

FrameInputs FrameInputsOf(const sim::FramePipeline& frame) {
  return {.colour = &frame.Colour(),
          .depth = &frame.Depth(),
          .normal = &frame.Normal(),
          .objectId = &frame.ObjectId(),
          .velocity = &frame.Velocity(),
          .eqaa = &frame.Eqaa(),
          .frameIndex = frame.FrameIndex(),
          .jitter = glm::vec2(0.0f)};
}

PassLayer LayerOf(std::string name, const sim::Texture2D<float>& texture) {
  const std::span<const float> texels = texture.Texels();
  return {std::move(name), {"Y"}, texture.Width(), texture.Height(), {texels.begin(), texels.end()}};
}

}  // namespace passes
