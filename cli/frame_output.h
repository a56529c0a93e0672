#pragma once
// Images of a rendered frame shared by `aasim frame` and `aasim run`: sRGB previews of linear
// colour, 0/1 masks, and frame.exr with the frame pipeline's pixel targets as named layers.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "sim/frame.h"

namespace cli {

// 8-bit sRGB RGB of linear RGBA texels (alpha dropped).
std::vector<std::uint8_t> SrgbImage(std::span<const glm::vec4> texels);
// 8-bit grey of a 0/1 mask: black and white come out exactly.
std::vector<std::uint8_t> MaskImage(std::span<const float> mask);

// Where two same-sized images differ bit for bit: how many pixels, and the first in row order.
// Bitwise, so -0 against +0 or two NaN payloads count: the dispatch strategies promise identical
// bits, not equal values.
struct ImageDifference {
  std::uint64_t pixels = 0;
  int x = 0, y = 0;
};
template <typename T>
ImageDifference BitwiseDifference(const sim::Texture2D<T>& a, const sim::Texture2D<T>& b) {
  ImageDifference difference;
  for (int y = 0; y < a.Height(); ++y) {
    for (int x = 0; x < a.Width(); ++x) {
      if (std::memcmp(&a.At(x, y), &b.At(x, y), sizeof(T)) == 0) continue;
      if (difference.pixels++ == 0) {
        difference.x = x;
        difference.y = y;
      }
    }
  }
  return difference;
}

// Channels R, G, B (resolved colour), depth, normal.X/Y/Z, objectId (-1 for the background),
// velocity.X/Y. Throws OutputError naming the path.
void WriteFrameExr(const std::filesystem::path& path, const sim::FramePipeline& pipeline);

}  // namespace cli
