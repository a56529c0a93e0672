#pragma once
// Neighbourhood colour boxes the temporal passes bound their history with, in whatever space the
// caller fetches (YCoCg in every pass here: aa-facts §5.2, §5.3, Lottes in §5.4):
//   min/max boxes over the 3x3 or the 5-tap '+' neighbourhood, and their average (Playdead's
//   "MinMax3x3Rounded", UE4's shaped box, aa-facts §5.1/§5.2);
//   the variance box mean ± gamma·sigma over the same neighbourhoods (Salvi, aa-facts §5.3);
// and the two ways to bring a history colour into a box: clamp per channel, or clip along the
// segment towards a point inside it (the box centre is Playdead's fast path, aa-facts §5.2; the
// current colour is Intel's ray intersection, aa-facts §5.3).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace passes::temporal {

struct ColourBox {
  glm::vec3 min, max;
  glm::vec3 Centre() const { return (min + max) * 0.5f; }
};

enum class Neighbourhood { Box3x3, Plus };

// The neighbourhood's offsets, centre first.
inline constexpr std::array<glm::ivec2, 9> kOffsets3x3{
    {{0, 0}, {-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}}};
inline constexpr std::array<glm::ivec2, 5> kOffsetsPlus{{{0, 0}, {0, -1}, {-1, 0}, {1, 0}, {0, 1}}};

// Calls visit(offset) for each offset of the neighbourhood, centre first.
template <typename Visit>
void ForEachOffset(Neighbourhood neighbourhood, Visit&& visit) {
  if (neighbourhood == Neighbourhood::Box3x3) {
    for (const glm::ivec2 offset : kOffsets3x3) visit(offset);
  } else {
    for (const glm::ivec2 offset : kOffsetsPlus) visit(offset);
  }
}

// The min/max box of fetch(offset) over the neighbourhood; fetch returns the colour in box space.
template <typename Fetch>
ColourBox MinMaxBox(Neighbourhood neighbourhood, Fetch&& fetch) {
  ColourBox box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
  ForEachOffset(neighbourhood, [&](glm::ivec2 offset) {
    const glm::vec3 colour = fetch(offset);
    box.min = glm::min(box.min, colour);
    box.max = glm::max(box.max, colour);
  });
  return box;
}

// The average of two boxes' corners: the shaped box of the 3x3 and '+' boxes (aa-facts §5.1/§5.2),
// which rounds the 3x3 box's corners off towards the '+' one.
inline ColourBox AverageBox(const ColourBox& a, const ColourBox& b) {
  return {(a.min + b.min) * 0.5f, (a.max + b.max) * 0.5f};
}

// First and second moments of a neighbourhood (Salvi's variance clipping, aa-facts §5.3).
struct Moments {
  glm::vec3 sum{0.0f}, sumOfSquares{0.0f};
  int count = 0;
  void Add(const glm::vec3& colour) {
    sum += colour;
    sumOfSquares += colour * colour;
    ++count;
  }
};
template <typename Fetch>
Moments MomentsOf(Neighbourhood neighbourhood, Fetch&& fetch) {
  Moments moments;
  ForEachOffset(neighbourhood, [&](glm::ivec2 offset) { moments.Add(fetch(offset)); });
  return moments;
}
// mean ± gamma·sigma per channel; a negative variance from rounding counts as 0.
inline ColourBox VarianceBox(const Moments& moments, float gamma) {
  const float n = static_cast<float>(moments.count);
  const glm::vec3 mean = moments.sum / n;
  const glm::vec3 sigma = glm::sqrt(glm::max(moments.sumOfSquares / n - mean * mean, glm::vec3(0.0f)));
  return {mean - gamma * sigma, mean + gamma * sigma};
}

inline glm::vec3 ClampToBox(const glm::vec3& colour, const ColourBox& box) {
  return glm::clamp(colour, box.min, box.max);
}

// The point of the segment from `target` (inside the box) to `colour` that is nearest to
// `colour` and inside the box: `colour` itself when inside, else where the segment leaves the box.
inline glm::vec3 ClipTowards(const glm::vec3& colour, const ColourBox& box, const glm::vec3& target) {
  const glm::vec3 v = colour - target;
  // The largest t <= 1 keeping target + t v inside, per channel; a channel the segment does not
  // move along never limits it.
  float t = 1.0f;
  for (int c = 0; c < 3; ++c) {
    if (colour[c] > box.max[c] && v[c] > 0.0f) t = std::min(t, (box.max[c] - target[c]) / v[c]);
    if (colour[c] < box.min[c] && v[c] < 0.0f) t = std::min(t, (box.min[c] - target[c]) / v[c]);
  }
  return t < 1.0f ? target + v * std::max(t, 0.0f) : colour;
}

// Playdead's fast path (aa-facts §5.2): clip towards the box centre.
inline glm::vec3 ClipTowardsCentre(const glm::vec3& colour, const ColourBox& box) {
  return ClipTowards(colour, box, box.Centre());
}

}  // namespace passes::temporal
