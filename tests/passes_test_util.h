#pragma once
// Synthetic images for pass tests: grey levels given as 8-bit sRGB codes, stored linear (what an
// 8-bit sRGB target decodes back to the same codes).

#include <cstdint>
#include <functional>

#include <glm/vec4.hpp>

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

}  // namespace passes::testing
