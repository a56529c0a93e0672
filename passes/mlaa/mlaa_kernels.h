#pragma once
// PS3 MLAA's arithmetic (seed 004; aa-facts §7), as functions the kernels and the tests share:
// the discontinuity test with its three thresholdings, the gradient class that splits features,
// and the revectorised area of a pixel on a traced line. Everything is float32 on the 8-bit gamma
// codes read through a UNORM view (k / 255), as the SPUs read the 32-bit frame buffer.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "sim/formats.h"

namespace passes::mlaa {

enum class Thresholding : std::uint8_t { Absolute, Relative, Predicated };

struct Config {
  Thresholding thresholding = Thresholding::Relative;
  float threshold = 0.1f;              // absolute thresholding
  float scale = 0.2f;                  // relative: T(p) = max(lower bound, scale x max channel of p)
  float lowerBound = 0.04f;
  float predicationLowerBound = 0.01f; // depth edges, the same relative test on one channel
  float predicationRelative = 0.01f;
  float predicationScale = 2.0f;       // the colour threshold away from depth edges, x this
  float predicationStrength = 0.75f;   // and at depth edges x scale x (1 - strength)
  int maxSearch = 32;                  // pixels traced along a line on each side of a pixel
  bool featureSplitting = true;
  bool linearBlend = false;            // blend decoded linear values instead of the gamma codes
};

inline float MaxChannel(const glm::vec3& c) { return std::max(std::max(c.r, c.g), c.b); }
inline float MaxChannelDelta(const glm::vec3& a, const glm::vec3& b) { return MaxChannel(glm::abs(a - b)); }

// Seed 004, "Relative Thresholding": T(p) = max(lower bound, scale * maxcolor(p)).
inline float RelativeThreshold(const Config& config, const glm::vec3& c) {
  return std::max(config.lowerBound, config.scale * MaxChannel(c));
}

// Seed 004, "Two-Stage Predicated Thresholding": the same relative test on the non-colour
// buffer (the frame's depth, one channel), strict as the colour test is.
inline bool DepthEdge(const Config& config, float z0, float z1) {
  const auto t = [&](float z) { return std::max(config.predicationLowerBound, config.predicationRelative * z); };
  return std::fabs(z0 - z1) > std::min(t(z0), t(z1));
}

// The threshold a pair's largest channel difference must exceed. The discontinuity test is the
// seed's bonus slide ("discontinuity if (max(diff.R, diff.G, diff.B) > t)", t the smaller of
// the two thresholds); its "Edge(p0,p1) = min(T(p0), T(p1)) >= max(|p0 - p1|)" is the negation
// of that test (docs/mlaa.md). Predication is SMAA's form of it (aa-facts §1.3): the threshold
// is scaled by `predicationScale` and lowered by `predicationStrength` where the depth has an
// edge.
inline float PairThreshold(const Config& config, const glm::vec3& c0, const glm::vec3& c1, bool depthEdge) {
  if (config.thresholding == Thresholding::Absolute) return config.threshold;
  const float t = std::min(RelativeThreshold(config, c0), RelativeThreshold(config, c1));
  if (config.thresholding == Thresholding::Relative) return t;
  return t * config.predicationScale * (1.0f - config.predicationStrength * (depthEdge ? 1.0f : 0.0f));
}

inline bool IsEdge(const Config& config, const glm::vec3& c0, const glm::vec3& c1, bool depthEdge) {
  return MaxChannelDelta(c0, c1) > PairThreshold(config, c0, c1, depthEdge);
}

// Seed 004, "Color Gradients": the gradient across an edge on the sum of channels, from the
// upper (left) pixel to the lower (right) one, on the 8-bit codes so equal sums compare equal.
// Three classes, 0 (falls), 0.5 (flat), 1 (rises): a mirrored image swaps rising and falling and
// keeps flat, so splitting where the class changes is mirror-symmetric (docs/mlaa.md).
inline float GradientClass(const glm::vec3& c0, const glm::vec3& c1) {
  const auto sum = [](const glm::vec3& c) {
    return int{sim::FloatToUnorm8(c.r)} + int{sim::FloatToUnorm8(c.g)} + int{sim::FloatToUnorm8(c.b)};
  };
  const int g = sum(c1) - sum(c0);
  return g > 0 ? 1.0f : g < 0 ? 0.0f : 0.5f;
}

// The revectorisation height at a line end (aa-facts §7): the midpoint of the crossing edge,
// half a pixel into the side it turns to (+ towards the upper/left row, - towards the lower/right
// one); 0 at an end without exactly one crossing edge (none, both, the image border or the search
// limit), where the line is not revectorised.
inline float EndHeight(bool crossingPrev, bool crossingNext) {
  if (crossingPrev == crossingNext) return 0.0f;
  return crossingPrev ? 0.5f : -0.5f;
}

// Area cut from the pixel at `near` pixels from an end with height `h`, by the half-line from
// (0, h) to the line's midpoint (length / 2, 0): the integral of h (1 - 2t / length) over
// [near, min(near + 1, length / 2)]. Both halves use this from their own end, so a mirrored line
// gives bit-identical areas.
inline float HalfLineArea(float h, int near, int length) {
  const float d = static_cast<float>(length);
  const float t0 = static_cast<float>(near), t1 = std::min(t0 + 1.0f, 0.5f * d);
  if (t1 <= t0 || h == 0.0f) return 0.0f;
  return h * ((t1 - t0) - (t1 * t1 - t0 * t0) / d);
}

// The areas of one pixel of a line (`left` and `right` pixels to its ends, end heights hLeft and
// hRight): where the revectorised line runs on the upper/left side of the edge (`towardsNext`: the
// upper pixel takes that much of the lower one) and where it runs on the lower/right side
// (`towardsPrev`: the lower pixel takes that much of the upper one). An L has one non-zero end,
// a Z two of opposite signs, a U two of the same sign (aa-facts §7).
struct LineAreas {
  float towardsNext = 0.0f, towardsPrev = 0.0f;
};
inline LineAreas PixelAreas(int left, int right, float hLeft, float hRight) {
  const int length = left + right + 1;
  const float a = HalfLineArea(hLeft, left, length), b = HalfLineArea(hRight, right, length);
  return {std::max(a, 0.0f) + std::max(b, 0.0f), std::max(-a, 0.0f) + std::max(-b, 0.0f)};
}

}  // namespace passes::mlaa
