// Report pictures (see report_images.h).

#include "cli/report_images.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "cli/image_io.h"

namespace cli {
namespace {

// matplotlib's magma colour map at t = 0, 0.1, ..., 1 (sRGB): perceptually uniform and readable
// in greyscale, the map the FLIP paper shows its error images in.
constexpr std::array<std::array<std::uint8_t, 3>, 11> kMagma{{
    {0x00, 0x00, 0x04}, {0x14, 0x0e, 0x36}, {0x3b, 0x0f, 0x70}, {0x64, 0x1a, 0x80},
    {0x8c, 0x29, 0x81}, {0xb7, 0x37, 0x79}, {0xde, 0x49, 0x68}, {0xf7, 0x70, 0x5c},
    {0xfe, 0x9f, 0x6d}, {0xfe, 0xcf, 0x92}, {0xfc, 0xfd, 0xbf},
}};

void PushMagma(std::vector<std::uint8_t>& rgb, float t) {
  const float at = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(kMagma.size() - 1);
  const auto lower = std::min(static_cast<std::size_t>(at), kMagma.size() - 2);
  const float f = at - static_cast<float>(lower);
  for (std::size_t c = 0; c < 3; ++c) {
    const float value = static_cast<float>(kMagma[lower][c]) * (1.0f - f) + static_cast<float>(kMagma[lower + 1][c]) * f;
    rgb.push_back(static_cast<std::uint8_t>(std::lround(value)));
  }
}

// Calls emit(sum, count) for every factor x factor block in row-major order.
template <typename T, typename Emit>
void ForEachBlock(std::span<const T> values, int width, int height, int factor, T zero, Emit&& emit) {
  for (int by = 0; by < height; by += factor) {
    for (int bx = 0; bx < width; bx += factor) {
      T sum = zero;
      int count = 0;
      for (int y = by; y < std::min(by + factor, height); ++y) {
        for (int x = bx; x < std::min(bx + factor, width); ++x) {
          sum += values[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
          ++count;
        }
      }
      emit(sum, count);
    }
  }
}

int Blocks(int size, int factor) { return (size + factor - 1) / factor; }

void PushSrgb(std::vector<std::uint8_t>& rgb, const glm::vec4& linear) {
  rgb.push_back(EncodeSrgb8(linear.r));
  rgb.push_back(EncodeSrgb8(linear.g));
  rgb.push_back(EncodeSrgb8(linear.b));
}

}  // namespace

int PreviewFactor(int width, int maxWidth) { return std::max(1, (width + maxWidth - 1) / maxWidth); }

RgbImage Preview(std::span<const glm::vec4> linear, int width, int height, int factor) {
  RgbImage image{Blocks(width, factor), Blocks(height, factor), {}};
  image.rgb.reserve(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
  ForEachBlock(linear, width, height, factor, glm::vec4(0.0f),
               [&](const glm::vec4& sum, int count) { PushSrgb(image.rgb, sum / static_cast<float>(count)); });
  return image;
}

RgbImage Crop(std::span<const glm::vec4> linear, int width, const PixelRect& rect) {
  RgbImage image{rect.width, rect.height, {}};
  image.rgb.reserve(static_cast<std::size_t>(rect.width) * static_cast<std::size_t>(rect.height) * 3);
  for (int y = rect.y; y < rect.y + rect.height; ++y) {
    for (int x = rect.x; x < rect.x + rect.width; ++x) {
      PushSrgb(image.rgb, linear[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]);
    }
  }
  return image;
}

RgbImage ErrorPreview(std::span<const float> values, int width, int height, float maxValue, int factor) {
  RgbImage image{Blocks(width, factor), Blocks(height, factor), {}};
  image.rgb.reserve(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
  ForEachBlock(values, width, height, factor, 0.0f,
               [&](float sum, int count) { PushMagma(image.rgb, sum / static_cast<float>(count) / maxValue); });
  return image;
}

std::vector<PixelRect> HardestRegions(std::span<const float> score, int width, int height, int size,
                                      int count) {
  struct Window {
    double sum;
    PixelRect rect;
  };
  std::vector<Window> windows;
  const int step = std::max(1, size / 2);
  for (int y = 0; y + size <= height; y += step) {
    for (int x = 0; x + size <= width; x += step) {
      double sum = 0.0;
      for (int v = y; v < y + size; ++v) {
        for (int u = x; u < x + size; ++u) {
          sum += static_cast<double>(score[static_cast<std::size_t>(v) * static_cast<std::size_t>(width) + static_cast<std::size_t>(u)]);
        }
      }
      if (sum > 0.0) windows.push_back({sum, {x, y, size, size}});
    }
  }
  // Stable: equal sums keep row-major (top-left first) order.
  std::stable_sort(windows.begin(), windows.end(), [](const Window& a, const Window& b) { return a.sum > b.sum; });
  std::vector<PixelRect> chosen;
  for (const Window& window : windows) {
    if (static_cast<int>(chosen.size()) == count) break;
    const bool overlaps = std::any_of(chosen.begin(), chosen.end(), [&](const PixelRect& r) {
      return window.rect.x < r.x + r.width && r.x < window.rect.x + window.rect.width &&
             window.rect.y < r.y + r.height && r.y < window.rect.y + window.rect.height;
    });
    if (!overlaps) chosen.push_back(window.rect);
  }
  return chosen;
}

}  // namespace cli
