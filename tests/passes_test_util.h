#pragma once
// Helpers of the pass tests: synthetic images (grey levels given as 8-bit sRGB codes, stored
// linear: what an 8-bit sRGB target decodes back to the same codes), a pass counter's value and a
// layer's values.

#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include <glm/vec4.hpp>

#include "passes/pass.h"
#include "sim/dispatch.h"
#include "sim/formats.h"
#include "sim/resources.h"

namespace passes::testing {

using Codes = std::function<int(int x, int y)>;

inline sim::Texture2D<glm::vec4> GreyImage(int width, int height, const Codes& code) {
  sim::Texture2D<glm::vec4> image("input", width, height, 16);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float linear = sim::Srgb8ToFloat(static_cast<std::uint8_t>(code(x, y)));
      image.At(x, y) = glm::vec4(linear, linear, linear, 1.0f);
    }
  }
  return image;
}

// The value of pass counter `name` of the first report of `dispatch`; throws when there is none.
inline std::uint64_t PassCounterValue(std::span<const sim::DispatchReport> reports, std::string_view dispatch,
                                      std::string_view name) {
  for (const sim::DispatchReport& report : reports) {
    if (report.name != dispatch) continue;
    for (const sim::PassCounter& counter : report.passCounters) {
      if (counter.name == name) return counter.value;
    }
  }
  throw std::logic_error("no counter " + std::string(name));
}

// The output layer called `name`; throws when there is none.
inline const PassLayer& LayerNamed(const PassOutput& output, std::string_view name) {
  for (const PassLayer& layer : output.layers) {
    if (layer.name == name) return layer;
  }
  throw std::logic_error("no layer " + std::string(name));
}

// Channel `channel` of the layer at (x, y).
inline float LayerValue(const PassLayer& layer, int x, int y, int channel = 0) {
  const std::size_t pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(layer.width) + static_cast<std::size_t>(x);
  const std::size_t at = pixel * layer.channels.size() + static_cast<std::size_t>(channel);
  if (at >= layer.Size()) throw std::out_of_range("layer " + layer.name + ": no value " + std::to_string(at));
  return layer.Value(at);
}

}  // namespace passes::testing
