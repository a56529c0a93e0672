// Temporal stability measures (see stability.h).

#include "study/stability.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <glm/common.hpp>

#include "sim/colour.h"
#include "sim/parallel.h"

namespace study {
namespace {

glm::vec3 CodesAt(const DisplayImage& image, int x, int y) {
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x));
  return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

double MeanAbs(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = glm::abs(a - b);
  return (static_cast<double>(d.r) + static_cast<double>(d.g) + static_cast<double>(d.b)) / 3.0;
}

// Per-row sums on the worker threads, added in row order: the total does not depend on the
// thread count.
template <typename PixelValue>
std::pair<double, std::uint64_t> SumOverPixels(int width, int height, PixelValue value) {
  std::vector<double> sums(static_cast<std::size_t>(height), 0.0);
  std::vector<std::uint64_t> counts(static_cast<std::size_t>(height), 0);
  sim::ParallelFor(static_cast<std::size_t>(height), [&](std::size_t y) {
    for (int x = 0; x < width; ++x) {
      const std::optional<double> v = value(x, static_cast<int>(y));
      if (!v) continue;
      sums[y] += *v;
      ++counts[y];
    }
  });
  return {std::accumulate(sums.begin(), sums.end(), 0.0), std::accumulate(counts.begin(), counts.end(), std::uint64_t{0})};
}

void CheckSameSize(const DisplayImage& a, const DisplayImage& b) {
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument("stability: images of different sizes");
}

// Bilinear on the codes, clamped at the border, pixel centres at x + 0.5.
glm::vec3 BilinearCodes(const DisplayImage& image, glm::vec2 at) {
  const glm::vec2 p = at - 0.5f;
  const glm::vec2 base = glm::floor(p);
  const glm::vec2 f = p - base;
  auto texel = [&](int dx, int dy) {
    return CodesAt(image, std::clamp(static_cast<int>(base.x) + dx, 0, image.width - 1),
                   std::clamp(static_cast<int>(base.y) + dy, 0, image.height - 1));
  };
  return glm::mix(glm::mix(texel(0, 0), texel(1, 0), f.x), glm::mix(texel(0, 1), texel(1, 1), f.x), f.y);
}

glm::ivec2 Nearest(glm::vec2 at) { return glm::ivec2(glm::floor(at)); }

}  // namespace

DisplayImage ToDisplay(const sim::Texture2D<glm::vec4>& linear) {
  DisplayImage image{linear.Width(), linear.Height(), std::vector<std::uint8_t>(linear.Texels().size() * 3)};
  const std::span<const glm::vec4> texels = linear.Texels();
  sim::ParallelFor(static_cast<std::size_t>(image.height), [&](std::size_t y) {
    const std::size_t row = y * static_cast<std::size_t>(image.width);
    for (std::size_t i = row; i < row + static_cast<std::size_t>(image.width); ++i) {
      for (int c = 0; c < 3; ++c) image.rgb[3 * i + static_cast<std::size_t>(c)] = sim::EncodeSrgb8(texels[i][c]);
    }
  });
  return image;
}

Reprojection Reproject(const sim::Texture2D<glm::vec2>& velocity, const sim::Texture2D<std::uint32_t>& objectId,
                       const sim::Texture2D<std::uint32_t>& previousObjectId) {
  const int width = velocity.Width(), height = velocity.Height();
  Reprojection result{width, height, {}, {}, 0};
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  result.source.resize(count);
  result.tracked.resize(count);
  sim::ParallelFor(static_cast<std::size_t>(height), [&](std::size_t y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = y * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      const glm::vec2 source = glm::vec2(static_cast<float>(x), static_cast<float>(y)) + 0.5f -
                               velocity.At(x, static_cast<int>(y));
      const glm::ivec2 nearest = Nearest(source);
      const bool onScreen = nearest.x >= 0 && nearest.y >= 0 && nearest.x < width && nearest.y < height;
      result.source[i] = source;
      result.tracked[i] = onScreen && previousObjectId.At(nearest.x, nearest.y) == objectId.At(x, static_cast<int>(y));
    }
  });
  result.disoccludedPixels = static_cast<std::uint64_t>(std::count(result.tracked.begin(), result.tracked.end(), 0));
  return result;
}

double CompensatedDifference(const DisplayImage& current, const DisplayImage& previous, const Reprojection& reprojection) {
  CheckSameSize(current, previous);
  if (current.width != reprojection.width || current.height != reprojection.height) {
    throw std::invalid_argument("stability: reprojection of another size");
  }
  const auto [sum, count] = SumOverPixels(reprojection.width, reprojection.height, [&](int x, int y) -> std::optional<double> {
    const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(reprojection.width) + static_cast<std::size_t>(x);
    if (!reprojection.tracked[i]) return std::nullopt;
    return MeanAbs(CodesAt(current, x, y), BilinearCodes(previous, reprojection.source[i]));
  });
  return count == 0 ? 0.0 : sum / static_cast<double>(count);
}

std::vector<std::uint8_t> AdvanceAges(const std::vector<std::uint8_t>& previousAges, const Reprojection& reprojection,
                                      std::uint8_t cap) {
  const std::size_t count = reprojection.tracked.size();
  if (previousAges.empty()) return std::vector<std::uint8_t>(count, cap);
  std::vector<std::uint8_t> ages(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!reprojection.tracked[i]) {
      ages[i] = 0;
      continue;
    }
    const glm::ivec2 from = Nearest(reprojection.source[i]);
    const std::uint8_t before = previousAges[static_cast<std::size_t>(from.y) * static_cast<std::size_t>(reprojection.width) +
                                             static_cast<std::size_t>(from.x)];
    ages[i] = static_cast<std::uint8_t>(std::min<int>(before + 1, cap));
  }
  return ages;
}

std::optional<double> YoungPixelError(const DisplayImage& image, const DisplayImage& reference,
                                      const std::vector<std::uint8_t>& ages, std::uint8_t young) {
  CheckSameSize(image, reference);
  const int width = image.width;
  const auto [sum, count] = SumOverPixels(width, image.height, [&](int x, int y) -> std::optional<double> {
    if (ages[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] >= young) return std::nullopt;
    return MeanAbs(CodesAt(image, x, y), CodesAt(reference, x, y));
  });
  if (count == 0) return std::nullopt;
  return sum / static_cast<double>(count);
}

double MeanCodeDifference(const DisplayImage& a, const DisplayImage& b, std::span<const float> mask) {
  CheckSameSize(a, b);
  const bool masked = std::any_of(mask.begin(), mask.end(), [](float m) { return m != 0.0f; });
  const auto [sum, count] = SumOverPixels(a.width, a.height, [&](int x, int y) -> std::optional<double> {
    if (masked && mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(a.width) + static_cast<std::size_t>(x)] == 0.0f) {
      return std::nullopt;
    }
    return MeanAbs(CodesAt(a, x, y), CodesAt(b, x, y));
  });
  return count == 0 ? 0.0 : sum / static_cast<double>(count);
}

std::optional<int> ConvergenceFrame(const std::vector<double>& distanceToFinal, double tolerance) {
  if (distanceToFinal.empty()) return std::nullopt;
  int frame = static_cast<int>(distanceToFinal.size());
  while (frame > 0 && distanceToFinal[static_cast<std::size_t>(frame - 1)] <= tolerance) --frame;
  return frame;
}

}  // namespace study
