// Strategy names and layers (see pass.h).

#include "passes/pass.h"

#include <algorithm>

#include "sim/formats.h"

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

sim::Texture2D<glm::vec4> Srgb8ColourTarget(std::string name, const sim::Texture2D<glm::vec4>& linear) {
  sim::Texture2D<glm::vec4> target(std::move(name), linear.Width(), linear.Height(), sim::Format::RGBA8Srgb);
  std::span<glm::vec4> out = target.Texels();
  std::span<const glm::vec4> in = linear.Texels();
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = sim::Quantize(sim::Format::RGBA8Srgb, in[i]);
  return target;
}

sim::Texture2D<glm::vec4> DecodedSrgb8(std::string name, const sim::Texture2D<glm::vec4>& target) {
  sim::Texture2D<glm::vec4> linear(std::move(name), target.Width(), target.Height(), 4);
  std::span<glm::vec4> out = linear.Texels();
  std::span<const glm::vec4> in = target.Texels();
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = sim::Decode(sim::Format::RGBA8Srgb, in[i]);
  return linear;
}

}  // namespace passes
