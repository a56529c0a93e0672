#pragma once
// SMAA 1x's three shaders as kernels on the machine, in the reference's float32 arithmetic
// (iryoku/smaa SMAA.hlsl; aa-facts §1.3-§1.5 and §1.9). Every fetch is the reference's fetch:
// point samples where it point-samples, the machine's fixed-point bilinear on the 8-bit edge,
// area and search textures where it samples them bilinearly (the pseudo-gather and the 0.25/0.75
// crossing-edge reads depend on it), float bilinear on the sRGB colour view. `mad` is a multiply
// then an add, two roundings (aa-facts §1.9); passes/CMakeLists.txt turns off FP contraction so
// the compiler cannot fuse them.
//
// One deliberate choice: the reference's vertex shader outputs (texcoord and the search offsets)
// are interpolated across a full-screen triangle; here they are computed per pixel from the
// pixel centre, texcoord = (x + 0.5) / W in float32, then offset with the reference's mad
// sequence. Interpolation on a GPU can differ in the last bit; no decision below sits within a
// bit of a texel boundary except the search loop ends, which this keeps in the reference order.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "sim/views.h"

namespace passes::smaa {

enum class EdgeMode : std::uint8_t { Luma, Colour, Depth };

// SMAA.hlsl's configuration macros as run-time values (aa-facts §1.2).
struct Config {
  EdgeMode edges = EdgeMode::Luma;
  bool predication = false;                // luma/colour only: thresholds from a second buffer
  float threshold = 0.1f;                  // SMAA_THRESHOLD
  float localContrastFactor = 2.0f;        // SMAA_LOCAL_CONTRAST_ADAPTATION_FACTOR
  int maxSearchSteps = 16;                 // SMAA_MAX_SEARCH_STEPS (2 px per step)
  int maxSearchStepsDiag = 8;              // SMAA_MAX_SEARCH_STEPS_DIAG, 0 disables diagonals
  float cornerRounding = 25.0f;            // SMAA_CORNER_ROUNDING, 100 disables corner detection
  float predicationThreshold = 0.01f;      // SMAA_PREDICATION_THRESHOLD
  float predicationScale = 2.0f;           // SMAA_PREDICATION_SCALE
  float predicationStrength = 0.4f;        // SMAA_PREDICATION_STRENGTH
  // (vertical ortho, horizontal ortho, diagonal 1, diagonal 2) AreaTex stripes: 0 for SMAA 1x,
  // per frame or sample for T2x/S2x/4x (aa-facts §1.8).
  glm::vec4 subsampleIndices{0.0f};

  // SMAA_DEPTH_THRESHOLD = 0.1 * SMAA_THRESHOLD (aa-facts §1.2).
  float DepthThreshold() const { return 0.1f * threshold; }
  bool Diagonals() const { return maxSearchStepsDiag > 0; }
  bool Corners() const { return cornerRounding < 100.0f; }
};

// SMAA_RT_METRICS = (1/W, 1/H, W, H).
struct Metrics {
  float invWidth, invHeight, width, height;
  static Metrics Of(int width, int height) {
    return {1.0f / static_cast<float>(width), 1.0f / static_cast<float>(height), static_cast<float>(width),
            static_cast<float>(height)};
  }
  glm::vec2 Texcoord(int x, int y) const {
    return {(static_cast<float>(x) + 0.5f) / width, (static_cast<float>(y) + 0.5f) / height};
  }
};

// Two roundings, as the reference's mad on the measured path (aa-facts §1.9).
template <typename T, typename U, typename V>
inline auto Mad(const T& a, const U& b, const V& c) {
  return a * b + c;
}
// HLSL step(edge, x): 1 where x >= edge (equality counts, aa-facts §1.3).
inline float Step(float edge, float x) { return x >= edge ? 1.0f : 0.0f; }
inline glm::vec2 Step(glm::vec2 edge, glm::vec2 x) { return {Step(edge.x, x.x), Step(edge.y, x.y)}; }
inline float Saturate(float v) { return std::clamp(v, 0.0f, 1.0f); }
// GLSL round on the measured path rounds halves to even; SMAA's rounded values never tie.
inline float Round(float v) { return std::nearbyint(v); }

// ---- Pass 1: edge detection (SMAA*EdgeDetectionPS, aa-facts §1.3) ----

// Reads the colour through a UNORM view of the sRGB colour target (gamma values: "luma edge
// detection requires gamma-corrected colors") or the depth; the predication buffer is the
// frame's depth. Returns (left edge, top edge) as 0/1; (0, 0) is the reference's discard.
class EdgeDetection {
 public:
  EdgeDetection(const Config& config, const Metrics& metrics, std::optional<sim::TextureView<glm::vec4>> colour,
                std::optional<sim::TextureView<float>> depth)
      : config_(config), metrics_(metrics), colour_(std::move(colour)), depth_(std::move(depth)) {}

  glm::vec2 operator()(const sim::LaneBase& lane, int x, int y) const {
    switch (config_.edges) {
      case EdgeMode::Luma: return LumaEdges(lane, x, y);
      case EdgeMode::Colour: return ColourEdges(lane, x, y);
      case EdgeMode::Depth: return DepthEdges(lane, x, y);
    }
    return {0.0f, 0.0f};
  }

 private:
  // The reference point-samples at texcoord + whole-pixel offsets with clamp addressing: the
  // neighbour's texel, clamped to the image.
  glm::vec3 Colour(const sim::LaneBase& lane, int x, int y) const {
    return glm::vec3(colour_->Load(lane, std::clamp(x, 0, colour_->Width() - 1),
                                   std::clamp(y, 0, colour_->Height() - 1)));
  }
  // dot(rgb, (0.2126, 0.7152, 0.0722)) evaluated as x*wx + (y*wy + z*wz) (aa-facts §1.9).
  static float Luma(const glm::vec3& rgb) { return rgb.x * 0.2126f + (rgb.y * 0.7152f + rgb.z * 0.0722f); }
  static float MaxChannelDelta(const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 t = glm::abs(a - b);
    return std::max(std::max(t.r, t.g), t.b);
  }
  // SMAAGatherNeighbours with gather: one gather4 at texcoord - (0.5, 0.5) px, components
  // .g, .r, .b = (P, Pleft, Ptop).
  glm::vec3 GatherNeighbours(const sim::LaneBase& lane, const sim::TextureView<float>& texture, int x, int y) const {
    const glm::vec2 tc = metrics_.Texcoord(x, y);
    const glm::vec4 g = texture.Gather(lane, tc + glm::vec2(metrics_.invWidth, metrics_.invHeight) * -0.5f);
    return {g.y, g.x, g.z};
  }
  glm::vec2 Threshold(const sim::LaneBase& lane, int x, int y) const {
    if (!config_.predication) return glm::vec2(config_.threshold);
    // SMAACalculatePredicatedThreshold: 0.2 where the predication buffer has no edge, 0.12 where
    // it has one, with the defaults (aa-facts §1.3).
    const glm::vec3 n = GatherNeighbours(lane, *depth_, x, y);
    const glm::vec2 delta = glm::abs(glm::vec2(n.x) - glm::vec2(n.y, n.z));
    const glm::vec2 edges = Step(glm::vec2(config_.predicationThreshold), delta);
    return config_.predicationScale * config_.threshold * (1.0f - config_.predicationStrength * edges);
  }
  glm::vec2 LumaEdges(const sim::LaneBase& lane, int x, int y) const;
  glm::vec2 ColourEdges(const sim::LaneBase& lane, int x, int y) const;
  glm::vec2 DepthEdges(const sim::LaneBase& lane, int x, int y) const;
  glm::vec2 AdaptLocalContrast(glm::vec2 edges, glm::vec4 delta, glm::vec2 farDelta) const;

  Config config_;
  Metrics metrics_;
  std::optional<sim::TextureView<glm::vec4>> colour_;
  std::optional<sim::TextureView<float>> depth_;
};

inline glm::vec2 EdgeDetection::AdaptLocalContrast(glm::vec2 edges, glm::vec4 delta, glm::vec2 farDelta) const {
  const glm::vec2 maxDelta = glm::max(glm::max(glm::vec2(delta.x, delta.y), glm::vec2(delta.z, delta.w)), farDelta);
  const float finalDelta = std::max(maxDelta.x, maxDelta.y);
  return edges * Step(glm::vec2(finalDelta), config_.localContrastFactor * glm::vec2(delta.x, delta.y));
}

inline glm::vec2 EdgeDetection::LumaEdges(const sim::LaneBase& lane, int x, int y) const {
  const glm::vec2 threshold = Threshold(lane, x, y);
  const float l = Luma(Colour(lane, x, y));
  const float left = Luma(Colour(lane, x - 1, y)), top = Luma(Colour(lane, x, y - 1));
  glm::vec4 delta(std::fabs(l - left), std::fabs(l - top), 0.0f, 0.0f);
  const glm::vec2 edges = Step(threshold, glm::vec2(delta.x, delta.y));
  if (edges.x + edges.y == 0.0f) return edges;
  delta.z = std::fabs(l - Luma(Colour(lane, x + 1, y)));
  delta.w = std::fabs(l - Luma(Colour(lane, x, y + 1)));
  // The luma path measures the far deltas from the neighbour (aa-facts §1.3).
  const glm::vec2 farDelta(std::fabs(left - Luma(Colour(lane, x - 2, y))),
                           std::fabs(top - Luma(Colour(lane, x, y - 2))));
  return AdaptLocalContrast(edges, delta, farDelta);
}

inline glm::vec2 EdgeDetection::ColourEdges(const sim::LaneBase& lane, int x, int y) const {
  const glm::vec2 threshold = Threshold(lane, x, y);
  const glm::vec3 c = Colour(lane, x, y);
  glm::vec4 delta(MaxChannelDelta(c, Colour(lane, x - 1, y)), MaxChannelDelta(c, Colour(lane, x, y - 1)), 0.0f,
                  0.0f);
  const glm::vec2 edges = Step(threshold, glm::vec2(delta.x, delta.y));
  if (edges.x + edges.y == 0.0f) return edges;
  delta.z = MaxChannelDelta(c, Colour(lane, x + 1, y));
  delta.w = MaxChannelDelta(c, Colour(lane, x, y + 1));
  // The colour path measures the far deltas from the centre pixel (aa-facts §1.3).
  const glm::vec2 farDelta(MaxChannelDelta(c, Colour(lane, x - 2, y)), MaxChannelDelta(c, Colour(lane, x, y - 2)));
  return AdaptLocalContrast(edges, delta, farDelta);
}

// No local contrast adaptation on depth (aa-facts §1.3).
inline glm::vec2 EdgeDetection::DepthEdges(const sim::LaneBase& lane, int x, int y) const {
  const glm::vec3 n = GatherNeighbours(lane, *depth_, x, y);
  const glm::vec2 delta = glm::abs(glm::vec2(n.x) - glm::vec2(n.y, n.z));
  return Step(glm::vec2(config_.DepthThreshold()), delta);
}

}  // namespace passes::smaa

namespace passes::smaa {

// ---- Pass 3: neighbourhood blending (SMAANeighborhoodBlendingPS, aa-facts §1.5) ----

// SMAA_REPROJECTION's velocity length in alpha, a = sqrt(5 |v|) with v in UV units (aa-facts
// §1.8): the temporal resolve compares the current and previous frames' a.
inline float PackedVelocityLength(glm::vec2 velocity) { return std::sqrt(5.0f * glm::length(velocity)); }

// Reads the weights (RGBA8) and the colour through an sRGB view (linear values, filtered in float
// after decoding); blends along one axis only, with two bilinear fetches. With a velocity view
// (SMAA_REPROJECTION, T2x/4x) the velocity is blended with the colour's weights at the colour's
// coordinates and its packed length replaces alpha.
class NeighbourhoodBlending {
 public:
  NeighbourhoodBlending(const Metrics& metrics, sim::TextureView<glm::vec4> colour, sim::TextureView<glm::vec4> weights,
                        std::optional<sim::TextureView<glm::vec2>> velocity = std::nullopt)
      : metrics_(metrics), colour_(std::move(colour)), weights_(std::move(weights)), velocity_(std::move(velocity)) {}

  // Inlined into the dispatch's lambda: called, GCC built the returned vec4 on the stack and
  // reloaded it in halves for every pixel (docs/PERFORMANCE.md, "Stop 28").
  [[gnu::always_inline]] glm::vec4 operator()(const sim::LaneBase& lane, int x, int y) const {
    const glm::vec2 uv = metrics_.Texcoord(x, y);
    const glm::vec2 pixel(metrics_.invWidth, metrics_.invHeight);
    const glm::vec4 offset = Mad(glm::vec4(pixel, pixel), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f), glm::vec4(uv, uv));
    // Weights towards (right, bottom, left, top): the right pixel's A and the lower pixel's G
    // (their weights towards this pixel), this pixel's B and R (aa-facts §1.5).
    const glm::vec4 here = weights_.SampleBilinear(lane, uv);
    const glm::vec4 a(weights_.SampleBilinear(lane, {offset.x, offset.y}).w,
                      weights_.SampleBilinear(lane, {offset.z, offset.w}).y, here.z, here.x);
    if (a.x + a.y + a.z + a.w < 1e-5f) {
      glm::vec4 colour = colour_.SampleBilinear(lane, uv);
      if (velocity_) colour.a = PackedVelocityLength(velocity_->SampleBilinear(lane, uv));
      return colour;
    }
    const bool horizontal = std::max(a.x, a.z) > std::max(a.y, a.w);
    const glm::vec4 blendingOffset = horizontal ? glm::vec4(a.x, 0.0f, a.z, 0.0f) : glm::vec4(0.0f, a.y, 0.0f, a.w);
    glm::vec2 blendingWeight = horizontal ? glm::vec2(a.x, a.z) : glm::vec2(a.y, a.w);
    blendingWeight /= blendingWeight.x + blendingWeight.y;
    const glm::vec4 coord = Mad(blendingOffset, glm::vec4(pixel, -pixel), glm::vec4(uv, uv));
    glm::vec4 colour = blendingWeight.x * colour_.SampleBilinear(lane, {coord.x, coord.y});
    colour += blendingWeight.y * colour_.SampleBilinear(lane, {coord.z, coord.w});
    if (velocity_) {
      glm::vec2 velocity = blendingWeight.x * velocity_->SampleBilinear(lane, {coord.x, coord.y});
      velocity += blendingWeight.y * velocity_->SampleBilinear(lane, {coord.z, coord.w});
      colour.a = PackedVelocityLength(velocity);
    }
    return colour;
  }

 private:
  Metrics metrics_;
  sim::TextureView<glm::vec4> colour_;
  sim::TextureView<glm::vec4> weights_;
  std::optional<sim::TextureView<glm::vec2>> velocity_;
};

}  // namespace passes::smaa
