// Strategy names and layers (see pass.h).

#include "passes/pass.h"

#include <algorithm>

#include "sim/formats.h"
#include "sim/parallel.h"

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

glm::vec2 PatternJitter(const raster::SamplePattern& pattern) {
  const raster::SampleOffset offset = pattern.Offset(0, 0);
  return glm::vec2(static_cast<float>(offset.x), static_cast<float>(offset.y)) / 16.0f;
}

FrameInputs FrameInputsOf(const sim::FramePipeline& frame) {
  return {.colour = &frame.Colour(),
          .depth = &frame.Depth(),
          .normal = &frame.Normal(),
          .objectId = &frame.ObjectId(),
          .velocity = &frame.Velocity(),
          .eqaa = &frame.Eqaa(),
          .pattern = &frame.Settings().pattern,
          .frameIndex = frame.FrameIndex(),
          .jitter = PatternJitter(frame.Settings().pattern)};
}

PassLayer LayerOf(std::string name, const sim::Texture2D<float>& texture) {
  const std::span<const float> texels = texture.Texels();
  return {std::move(name), {"Y"}, texture.Width(), texture.Height(), {texels.begin(), texels.end()}};
}

namespace {
// Per-texel host conversions of a whole frame, by rows on the worker threads (independent
// texels: the result does not depend on the thread count).
template <typename Convert>
void ConvertTexels(std::span<const glm::vec4> in, std::span<glm::vec4> out, int width, Convert convert) {
  const auto row = static_cast<std::size_t>(width);
  sim::ParallelFor(in.size() / row, [&](std::size_t y) {
    for (std::size_t i = y * row; i < (y + 1) * row; ++i) out[i] = convert(in[i]);
  });
}
}  // namespace

sim::Texture2D<glm::vec4> Srgb8ColourTarget(std::string name, const sim::Texture2D<glm::vec4>& linear) {
  sim::Texture2D<glm::vec4> target(std::move(name), linear.Width(), linear.Height(), sim::Format::RGBA8Srgb);
  ConvertTexels(linear.Texels(), target.Texels(), linear.Width(),
                [](const glm::vec4& texel) { return sim::Quantize(sim::Format::RGBA8Srgb, texel); });
  return target;
}

void StoreSrgb8(const sim::Texture2D<glm::vec4>& linear, sim::Texture2D<glm::vec4>& target) {
  ConvertTexels(linear.Texels(), target.Texels(), linear.Width(),
                [](const glm::vec4& texel) { return sim::Quantize(sim::Format::RGBA8Srgb, texel); });
}

sim::Texture2D<glm::vec4> DecodedSrgb8(std::string name, const sim::Texture2D<glm::vec4>& target) {
  sim::Texture2D<glm::vec4> linear(std::move(name), target.Width(), target.Height(), 4);
  ConvertTexels(target.Texels(), linear.Texels(), target.Width(),
                [](const glm::vec4& texel) { return sim::Decode(sim::Format::RGBA8Srgb, texel); });
  return linear;
}

}  // namespace passes
