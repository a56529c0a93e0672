#pragma once
// Pictures for the HTML report, made from the study's float images: previews scaled down to fit
// the page, nearest-neighbour crops of the hardest regions, and error maps in a perceptual colour
// map. All are 8-bit sRGB RGB; the full-resolution data stays in the EXR files beside the report.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

namespace cli {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3, sRGB
};

struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// The integer factor that brings `width` to at most `maxWidth` (1 if it already fits).
int PreviewFactor(int width, int maxWidth);

// Linear RGBA averaged over factor x factor blocks (in linear light, before the sRGB encode);
// partial blocks at the right and bottom edges average what they hold.
RgbImage Preview(std::span<const glm::vec4> linear, int width, int height, int factor);
RgbImage Crop(std::span<const glm::vec4> linear, int width, const PixelRect& rect);

// Values in [0, maxValue] through matplotlib's magma map (dark = no error), averaged over blocks
// like Preview; the map is the same for every image so the report compares like with like.
RgbImage ErrorPreview(std::span<const float> values, int width, int height, float maxValue, int factor);

// The `count` non-overlapping size x size windows (on a grid of size / 2 steps) with the largest
// sum of `score`, best first; ties go to the window nearer the top-left. Fewer if the image has
// fewer windows with a positive sum.
std::vector<PixelRect> HardestRegions(std::span<const float> score, int width, int height, int size,
                                      int count);

}  // namespace cli
