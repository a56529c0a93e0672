// Strategy names and layers (see pass.h).

#include "passes/pass.h"

#include <algorithm>
#include <stdexcept>

#include "sim/check.h"
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

glm::vec2 PatternJitter(const raster::SamplePattern& pattern) {
  const raster::SampleOffset offset = pattern.Offset(0, 0);
  return glm::vec2(static_cast<float>(offset.x), static_cast<float>(offset.y)) / 16.0f;
}

FrameInputs FrameInputsOf(const sim::FramePipeline& frame) {
  return {.colour = &frame.Colour(),
          .colourSrgb8 = &frame.ColourSrgb8(),
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
  if (texture.KeepsCodes()) {
    return CodesLayer(std::move(name), {"Y"}, texture.Width(), texture.Height(), texture.Codes(), 1, 1);
  }
  const std::span<const float> texels = texture.Texels();
  return {std::move(name), {"Y"}, texture.Width(), texture.Height(), {texels.begin(), texels.end()}, {}, 0};
}

PassLayer MembershipLayer(std::string name, std::span<const std::uint8_t> joined, int width, int height) {
  AASIM_CHECK_EQ(joined.size(), static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  PassLayer layer{std::move(name), {"Y"}, width, height, std::vector<float>(joined.size()), {}, 0};
  ByRows(width, height, [&](std::size_t i) { layer.values[i] = joined[i]; });
  return layer;
}

PassLayer CodesLayer(std::string name, std::vector<std::string> channels, int width, int height,
                     std::span<const std::uint8_t> codes, int codeChannels, int components) {
  AASIM_CHECK_EQ(channels.size(), static_cast<std::size_t>(components));
  return {.name = std::move(name), .channels = std::move(channels), .width = width, .height = height, .values = {},
          .codes = {codes.begin(), codes.end()}, .codeChannels = codeChannels};
}

std::vector<float> PassLayer::Floats() const {
  if (codeChannels == 0) return values;
  std::vector<float> floats(Size());
  for (std::size_t i = 0; i < floats.size(); ++i) floats[i] = Value(i);
  return floats;
}

sim::Texture2D<glm::vec4> Srgb8ColourTarget(std::string name, const sim::Texture2D<glm::vec4>& linear) {
  sim::Texture2D<glm::vec4> target(std::move(name), linear.Width(), linear.Height(), sim::Format::RGBA8Srgb);
  sim::StoreSrgb8(linear, target);
  return target;
}

const sim::Texture2D<glm::vec4>& FrameInputs::ColourSrgb8() const {
  if (colourSrgb8 == nullptr) throw std::logic_error("frame inputs without colourSrgb8: this pass reads the 8-bit frame");
  if (colourSrgb8->Width() != Width() || colourSrgb8->Height() != Height() ||
      colourSrgb8->TexelFormat() != sim::Format::RGBA8Srgb) {
    throw std::logic_error("frame inputs: colourSrgb8 is not an RGBA8 sRGB texture of the colour's size");
  }
  return *colourSrgb8;
}

void CopySrgb8Frame(const FrameInputs& frame, sim::Texture2D<glm::vec4>& target) {
  const std::span<const std::uint8_t> codes = frame.ColourSrgb8().Codes();
  AASIM_CHECK(target.TexelFormat() == sim::Format::RGBA8Srgb && target.Codes().size() == codes.size());
  std::ranges::copy(codes, target.Codes().begin());
}

sim::Texture2D<glm::vec4> DecodedSrgb8(std::string name, const sim::Texture2D<glm::vec4>& target) {
  sim::Texture2D<glm::vec4> linear(std::move(name), target.Width(), target.Height(), 4);
  const std::uint8_t* const codes = target.Codes().data();
  const std::span<glm::vec4> out = linear.Texels();
  ByRows(target.Width(), target.Height(),
         [&](std::size_t i) { out[i] = sim::DecodeCodes<glm::vec4>(codes + 4 * i, 4, true); });
  return linear;
}

}  // namespace passes
