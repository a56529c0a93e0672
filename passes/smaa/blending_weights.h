#pragma once
// SMAA's second pass, SMAABlendingWeightCalculationPS (aa-facts §1.4), on edge pixels: diagonal
// searches first (a diagonal found skips the orthogonal work), else the horizontal search along
// a top edge; then the vertical search along a left edge. Searches, crossing-edge reads and the
// AreaTex/SearchTex lookups sample exactly where the reference does, in float32 with its
// operation order (see smaa_kernels.h).

#include <cmath>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "passes/smaa/smaa_kernels.h"
#include "sim/views.h"

namespace passes::smaa {

// SMAA.hlsl's non-configurable defines (aa-facts §1.2).
inline constexpr float kAreaTexMaxDistance = 16.0f;
inline constexpr float kAreaTexMaxDistanceDiag = 20.0f;
inline constexpr float kAreaTexSubtexSize = 1.0f / 7.0f;
inline const glm::vec2 kAreaTexPixelSize = 1.0f / glm::vec2(160.0f, 560.0f);
// A pseudo-gathered e.g above 53/64 means both pixels of the pair carry the edge (aa-facts §1.4).
inline constexpr float kBothEdges = 0.8281f;
// SearchTex holds 0, 127 or 254: x 255/127 gives 0, 1 or 2 pixels (aa-facts §1.4, §1.7).
inline constexpr float kSearchTexScale = 255.0f / 127.0f;

struct BlendingWeightViews {
  sim::TextureView<glm::vec2> edges;  // RG8
  sim::TextureView<glm::vec2> area;   // RG8, AreaTex
  sim::TextureView<float> search;     // R8, SearchTex
  sim::CounterView searchSteps;       // orthogonal and diagonal loop iterations
};

class BlendingWeights {
 public:
  BlendingWeights(const Config& config, const Metrics& metrics, BlendingWeightViews views)
      : config_(config), metrics_(metrics), v_(std::move(views)) {}

  glm::vec4 operator()(const sim::LaneBase& lane, int x, int y) const;

  // The pixel's two edges one at a time, as the pixel above processes them (Filmic SMAA's dual
  // edge blending runs each on its own): the edges texel at the pixel's centre; the top edge's
  // (R, G) weights, diagonal patterns first, then the horizontal search (a diagonal found skips
  // the left edge); the left edge's (B, A) weights from the vertical search (aa-facts §1.4, §1.5).
  struct TopEdge {
    glm::vec2 weights;
    bool diagonal;
  };
  glm::vec2 EdgesAt(const sim::LaneBase& lane, int x, int y) const { return Edges(lane, metrics_.Texcoord(x, y)); }
  TopEdge TopEdgeWeights(const sim::LaneBase& lane, int x, int y, glm::vec2 e) const;
  glm::vec2 LeftEdgeWeights(const sim::LaneBase& lane, int x, int y) const;

 private:
  glm::vec2 Edges(const sim::LaneBase& lane, glm::vec2 uv, glm::ivec2 offset = {0, 0}) const {
    return v_.edges.SampleBilinear(lane, uv, sim::AddressMode::Clamp, offset);
  }
  glm::vec2 Pixel() const { return {metrics_.invWidth, metrics_.invHeight}; }
  // The vertex shader's loop end offset[2] = mad(pixel, +-2 S, mad(pixel, start, texcoord)), as
  // llvmpipe evaluates it: its compiler sums the two constant products first, texcoord +
  // (start * pixel + (+-2 S) * pixel), one rounding fewer than the source order (measured against
  // the reference: docs/smaa.md "Against the reference"). Whether a search takes one more step at
  // its limit depends on it.
  float LoopEnd(float texcoord, float start, float sign, float pixel) const {
    const float steps = sign * 2.0f * static_cast<float>(config_.maxSearchSteps);
    return texcoord + (start * pixel + steps * pixel);
  }

  // Orthogonal searches (SMAASearchXLeft/XRight/YUp/YDown).
  float SearchXLeft(const sim::LaneBase& lane, glm::vec2 uv, float end) const;
  float SearchXRight(const sim::LaneBase& lane, glm::vec2 uv, float end) const;
  float SearchYUp(const sim::LaneBase& lane, glm::vec2 uv, float end) const;
  float SearchYDown(const sim::LaneBase& lane, glm::vec2 uv, float end) const;
  float SearchLength(const sim::LaneBase& lane, glm::vec2 e, float offset) const;
  glm::vec2 Area(const sim::LaneBase& lane, glm::vec2 distance, float e1, float e2, float offset) const;
  glm::vec2 HorizontalWeights(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 pixcoord) const;
  glm::vec2 VerticalWeights(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 pixcoord) const;
  void RoundHorizontalCorners(const sim::LaneBase& lane, glm::vec2& weights, glm::vec2 uv, glm::vec2 d) const;
  void RoundVerticalCorners(const sim::LaneBase& lane, glm::vec2& weights, glm::vec2 uv, glm::vec2 d) const;

  // Diagonal searches (SMAASearchDiag1/2, SMAACalculateDiagWeights).
  glm::vec2 SearchDiag1(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 dir, glm::vec2& e) const;
  glm::vec2 SearchDiag2(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 dir, glm::vec2& e) const;
  glm::vec2 AreaDiag(const sim::LaneBase& lane, glm::vec2 distance, glm::vec2 e, float offset) const;
  glm::vec2 DiagonalWeights(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 e) const;

  Config config_;
  Metrics metrics_;
  BlendingWeightViews v_;
};

// ---- Orthogonal searches ----

// @PSEUDO_GATHER4: uv sits at (-0.25, -0.125) px from a pixel pair, so one fixed-point bilinear
// fetch returns four edge bits as distinct values; the loop stops at the end of the top edge or
// at a crossing (left) edge, two pixels per step.
inline float BlendingWeights::SearchXLeft(const sim::LaneBase& lane, glm::vec2 uv, float end) const {
  glm::vec2 e(0.0f, 1.0f);
  while (uv.x > end && e.y > kBothEdges && e.x == 0.0f) {
    e = Edges(lane, uv);
    uv = Mad(-glm::vec2(2.0f, 0.0f), Pixel(), uv);
    v_.searchSteps.Add(lane);
  }
  const float offset = Mad(-kSearchTexScale, SearchLength(lane, e, 0.0f), 3.25f);
  return Mad(metrics_.invWidth, offset, uv.x);
}

inline float BlendingWeights::SearchXRight(const sim::LaneBase& lane, glm::vec2 uv, float end) const {
  glm::vec2 e(0.0f, 1.0f);
  while (uv.x < end && e.y > kBothEdges && e.x == 0.0f) {
    e = Edges(lane, uv);
    uv = Mad(glm::vec2(2.0f, 0.0f), Pixel(), uv);
    v_.searchSteps.Add(lane);
  }
  const float offset = Mad(-kSearchTexScale, SearchLength(lane, e, 0.5f), 3.25f);
  return Mad(-metrics_.invWidth, offset, uv.x);
}

inline float BlendingWeights::SearchYUp(const sim::LaneBase& lane, glm::vec2 uv, float end) const {
  glm::vec2 e(1.0f, 0.0f);
  while (uv.y > end && e.x > kBothEdges && e.y == 0.0f) {
    e = Edges(lane, uv);
    uv = Mad(-glm::vec2(0.0f, 2.0f), Pixel(), uv);
    v_.searchSteps.Add(lane);
  }
  const float offset = Mad(-kSearchTexScale, SearchLength(lane, glm::vec2(e.y, e.x), 0.0f), 3.25f);
  return Mad(metrics_.invHeight, offset, uv.y);
}

inline float BlendingWeights::SearchYDown(const sim::LaneBase& lane, glm::vec2 uv, float end) const {
  glm::vec2 e(1.0f, 0.0f);
  while (uv.y < end && e.x > kBothEdges && e.y == 0.0f) {
    e = Edges(lane, uv);
    uv = Mad(glm::vec2(0.0f, 2.0f), Pixel(), uv);
    v_.searchSteps.Add(lane);
  }
  const float offset = Mad(-kSearchTexScale, SearchLength(lane, glm::vec2(e.y, e.x), 0.5f), 3.25f);
  return Mad(-metrics_.invHeight, offset, uv.y);
}

// SearchTex is cropped from 66x33 to 64x16 and flipped; this scale and bias undo both, then a
// point sample reads it (aa-facts §1.7).
inline float BlendingWeights::SearchLength(const sim::LaneBase& lane, glm::vec2 e, float offset) const {
  const glm::vec2 ratio(66.0f / 64.0f, 33.0f / 16.0f);
  const glm::vec2 scale = ratio * glm::vec2(0.5f, -1.0f);
  const glm::vec2 bias = ratio * glm::vec2(offset, 1.0f);
  return v_.search.SamplePoint(lane, Mad(scale, e, bias));
}

// AreaTex is indexed by the square roots of the distances (quadratic compression) in the
// sub-texture of the crossing-edge codes round(4 e) (aa-facts §1.4, §1.6).
inline glm::vec2 BlendingWeights::Area(const sim::LaneBase& lane, glm::vec2 distance, float e1, float e2,
                                       float offset) const {
  glm::vec2 uv = Mad(kAreaTexMaxDistance, glm::vec2(Round(4.0f * e1), Round(4.0f * e2)), distance);
  uv = Mad(kAreaTexPixelSize, uv, 0.5f * kAreaTexPixelSize);
  uv.y = Mad(kAreaTexSubtexSize, offset, uv.y);
  return v_.area.SampleBilinear(lane, uv);
}

inline glm::vec2 BlendingWeights::HorizontalWeights(const sim::LaneBase& lane, glm::vec2 uv,
                                                    glm::vec2 pixcoord) const {
  // The blending-weight vertex shader's offsets (SMAABlendingWeightCalculationVS).
  const glm::vec4 offset0 = Mad(glm::vec4(Pixel(), Pixel()), glm::vec4(-0.25f, -0.125f, 1.25f, -0.125f),
                                glm::vec4(uv, uv));
  const glm::vec4 offset1 = Mad(glm::vec4(Pixel(), Pixel()), glm::vec4(-0.125f, -0.25f, -0.125f, 1.25f),
                                glm::vec4(uv, uv));
  const float endLeft = LoopEnd(uv.x, -0.25f, -1.0f, metrics_.invWidth);
  const float endRight = LoopEnd(uv.x, 1.25f, 1.0f, metrics_.invWidth);

  glm::vec2 coords(SearchXLeft(lane, {offset0.x, offset0.y}, endLeft), offset1.y);
  glm::vec2 d(coords.x, 0.0f);
  // Crossing edges at -0.25 px in y (@CROSSING_OFFSET): the row above weighs 0.25, this one 0.75.
  const float e1 = Edges(lane, coords).x;
  coords.x = SearchXRight(lane, {offset0.z, offset0.w}, endRight);
  d.y = coords.x;
  d = Mad(metrics_.width, d, -pixcoord.x);
  const glm::vec2 sqrtD(std::sqrt(std::fabs(d.x)), std::sqrt(std::fabs(d.y)));
  const float e2 = Edges(lane, coords, {1, 0}).x;
  glm::vec2 weights = Area(lane, sqrtD, e1, e2, config_.subsampleIndices.y);
  RoundHorizontalCorners(lane, weights, uv, d);
  return weights;
}

inline glm::vec2 BlendingWeights::VerticalWeights(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 pixcoord) const {
  const glm::vec4 offset0 = Mad(glm::vec4(Pixel(), Pixel()), glm::vec4(-0.25f, -0.125f, 1.25f, -0.125f),
                                glm::vec4(uv, uv));
  const glm::vec4 offset1 = Mad(glm::vec4(Pixel(), Pixel()), glm::vec4(-0.125f, -0.25f, -0.125f, 1.25f),
                                glm::vec4(uv, uv));
  const float endUp = LoopEnd(uv.y, -0.25f, -1.0f, metrics_.invHeight);
  const float endDown = LoopEnd(uv.y, 1.25f, 1.0f, metrics_.invHeight);

  glm::vec2 coords(offset0.x, SearchYUp(lane, {offset1.x, offset1.y}, endUp));
  glm::vec2 d(coords.y, 0.0f);
  const float e1 = Edges(lane, coords).y;
  coords.y = SearchYDown(lane, {offset1.z, offset1.w}, endDown);
  d.y = coords.y;
  d = Mad(metrics_.height, d, -pixcoord.y);
  const glm::vec2 sqrtD(std::sqrt(std::fabs(d.x)), std::sqrt(std::fabs(d.y)));
  const float e2 = Edges(lane, coords, {0, 1}).y;
  glm::vec2 weights = Area(lane, sqrtD, e1, e2, config_.subsampleIndices.x);
  RoundVerticalCorners(lane, weights, uv, d);
  return weights;
}

// SMAADetectHorizontalCornerPattern: a crossing edge one row below or two rows above the nearer
// end rounds the corner off by (1 - rounding / 100) (aa-facts §1.4).
inline void BlendingWeights::RoundHorizontalCorners(const sim::LaneBase& lane, glm::vec2& weights, glm::vec2 uv,
                                                    glm::vec2 d) const {
  if (!config_.Corners()) return;
  const glm::vec4 coords = Mad(glm::vec4(d.x, 0.0f, d.y, 0.0f), glm::vec4(Pixel(), Pixel()), glm::vec4(uv, uv));
  const glm::vec2 leftRight = Step(glm::abs(d), glm::abs(glm::vec2(d.y, d.x)));
  glm::vec2 rounding = (1.0f - config_.cornerRounding / 100.0f) * leftRight;
  rounding /= leftRight.x + leftRight.y;
  glm::vec2 factor(1.0f);
  const glm::vec2 near(coords.x, coords.y), far(coords.z, coords.w);
  factor.x -= rounding.x * Edges(lane, near, {0, 1}).x;
  factor.x -= rounding.y * Edges(lane, far, {1, 1}).x;
  factor.y -= rounding.x * Edges(lane, near, {0, -2}).x;
  factor.y -= rounding.y * Edges(lane, far, {1, -2}).x;
  weights *= glm::vec2(Saturate(factor.x), Saturate(factor.y));
}

inline void BlendingWeights::RoundVerticalCorners(const sim::LaneBase& lane, glm::vec2& weights, glm::vec2 uv,
                                                  glm::vec2 d) const {
  if (!config_.Corners()) return;
  const glm::vec4 coords = Mad(glm::vec4(0.0f, d.x, 0.0f, d.y), glm::vec4(Pixel(), Pixel()), glm::vec4(uv, uv));
  const glm::vec2 leftRight = Step(glm::abs(d), glm::abs(glm::vec2(d.y, d.x)));
  glm::vec2 rounding = (1.0f - config_.cornerRounding / 100.0f) * leftRight;
  rounding /= leftRight.x + leftRight.y;
  glm::vec2 factor(1.0f);
  const glm::vec2 near(coords.x, coords.y), far(coords.z, coords.w);
  factor.x -= rounding.x * Edges(lane, near, {1, 0}).y;
  factor.x -= rounding.y * Edges(lane, far, {1, 1}).y;
  factor.y -= rounding.x * Edges(lane, near, {-2, 0}).y;
  factor.y -= rounding.y * Edges(lane, far, {-2, 1}).y;
  weights *= glm::vec2(Saturate(factor.x), Saturate(factor.y));
}

// ---- Diagonal searches ----

// One bilinear fetch at +0.25 px reads the left edge of the next pixel and the top edge of this
// one: 0.25/1.0 and 0.75/1.0 decode by round(e * |5 e - 3.75|) (SMAADecodeDiagBilinearAccess).
inline float DecodeDiagonalRed(float r) { return Round(r * std::fabs(5.0f * r - 5.0f * 0.75f)); }

inline glm::vec2 BlendingWeights::SearchDiag1(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 dir,
                                              glm::vec2& e) const {
  glm::vec4 coord(uv, -1.0f, 1.0f);
  while (coord.z < static_cast<float>(config_.maxSearchStepsDiag - 1) && coord.w > 0.9f) {
    const glm::vec3 xyz = Mad(glm::vec3(Pixel(), 1.0f), glm::vec3(dir, 1.0f), glm::vec3(coord));
    coord = glm::vec4(xyz, coord.w);
    e = Edges(lane, {coord.x, coord.y});
    coord.w = e.x * 0.5f + e.y * 0.5f;
    v_.searchSteps.Add(lane);
  }
  return {coord.z, coord.w};
}

inline glm::vec2 BlendingWeights::SearchDiag2(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 dir,
                                              glm::vec2& e) const {
  glm::vec4 coord(uv, -1.0f, 1.0f);
  coord.x += 0.25f * metrics_.invWidth;  // @SearchDiag2Optimization: two edges in one fetch
  while (coord.z < static_cast<float>(config_.maxSearchStepsDiag - 1) && coord.w > 0.9f) {
    const glm::vec3 xyz = Mad(glm::vec3(Pixel(), 1.0f), glm::vec3(dir, 1.0f), glm::vec3(coord));
    coord = glm::vec4(xyz, coord.w);
    e = Edges(lane, {coord.x, coord.y});
    e = glm::vec2(DecodeDiagonalRed(e.x), Round(e.y));
    coord.w = e.x * 0.5f + e.y * 0.5f;
    v_.searchSteps.Add(lane);
  }
  return {coord.z, coord.w};
}

// The diagonal half of AreaTex: 20x20 linear distances per 2-bit crossing code (aa-facts §1.6).
inline glm::vec2 BlendingWeights::AreaDiag(const sim::LaneBase& lane, glm::vec2 distance, glm::vec2 e,
                                           float offset) const {
  glm::vec2 uv = Mad(kAreaTexMaxDistanceDiag, e, distance);
  uv = Mad(kAreaTexPixelSize, uv, 0.5f * kAreaTexPixelSize);
  uv.x += 0.5f;
  uv.y += kAreaTexSubtexSize * offset;
  return v_.area.SampleBilinear(lane, uv);
}

inline glm::vec2 BlendingWeights::DiagonalWeights(const sim::LaneBase& lane, glm::vec2 uv, glm::vec2 e) const {
  glm::vec2 weights(0.0f);
  glm::vec4 d(0.0f);
  glm::vec2 end(0.0f);
  if (e.x > 0.0f) {
    const glm::vec2 found = SearchDiag1(lane, uv, {-1.0f, 1.0f}, end);
    d.x = found.x + (end.y > 0.9f ? 1.0f : 0.0f);
    d.z = found.y;
  }
  const glm::vec2 other = SearchDiag1(lane, uv, {1.0f, -1.0f}, end);
  d.y = other.x;
  d.w = other.y;
  if (d.x + d.y > 2.0f) {  // a line of more than 3 pixels
    const glm::vec4 coords = Mad(glm::vec4(-d.x + 0.25f, d.x, d.y, -d.y - 0.25f), glm::vec4(Pixel(), Pixel()),
                                 glm::vec4(uv, uv));
    const glm::vec2 a = Edges(lane, {coords.x, coords.y}, {-1, 0});
    const glm::vec2 b = Edges(lane, {coords.z, coords.w}, {1, 0});
    // c.yxwz = decode(c.xyzw): the decoded red lands in y (and w), the green in x (and z).
    const glm::vec4 c(Round(a.y), DecodeDiagonalRed(a.x), Round(b.y), DecodeDiagonalRed(b.x));
    glm::vec2 cc = Mad(2.0f, glm::vec2(c.x, c.z), glm::vec2(c.y, c.w));
    // An end not found (the search ran out on an edge) has no crossing edge.
    if (d.z >= 0.9f) cc.x = 0.0f;
    if (d.w >= 0.9f) cc.y = 0.0f;
    weights += AreaDiag(lane, {d.x, d.y}, cc, config_.subsampleIndices.z);
  }

  const glm::vec2 up = SearchDiag2(lane, uv, {-1.0f, -1.0f}, end);
  d = glm::vec4(up.x, 0.0f, up.y, 0.0f);
  if (Edges(lane, uv, {1, 0}).x > 0.0f) {
    const glm::vec2 down = SearchDiag2(lane, uv, {1.0f, 1.0f}, end);
    d.y = down.x + (end.y > 0.9f ? 1.0f : 0.0f);
    d.w = down.y;
  }
  if (d.x + d.y > 2.0f) {
    const glm::vec4 coords = Mad(glm::vec4(-d.x, -d.x, d.y, d.y), glm::vec4(Pixel(), Pixel()), glm::vec4(uv, uv));
    const glm::vec2 near(coords.x, coords.y), far(coords.z, coords.w);
    const glm::vec2 farEdges = Edges(lane, far, {1, 0});
    const glm::vec4 c(Edges(lane, near, {-1, 0}).y, Edges(lane, near, {0, -1}).x, farEdges.y, farEdges.x);
    glm::vec2 cc = Mad(2.0f, glm::vec2(c.x, c.z), glm::vec2(c.y, c.w));
    if (d.z >= 0.9f) cc.x = 0.0f;
    if (d.w >= 0.9f) cc.y = 0.0f;
    const glm::vec2 area = AreaDiag(lane, {d.x, d.y}, cc, config_.subsampleIndices.w);
    weights += glm::vec2(area.y, area.x);
  }
  return weights;
}

// ---- The pixel ----

inline BlendingWeights::TopEdge BlendingWeights::TopEdgeWeights(const sim::LaneBase& lane, int x, int y,
                                                                glm::vec2 e) const {
  const glm::vec2 uv = metrics_.Texcoord(x, y);
  glm::vec2 diagonal(0.0f);
  if (config_.Diagonals()) diagonal = DiagonalWeights(lane, uv, e);
  // Diagonals win: a diagonal found skips the horizontal and the vertical processing.
  if (diagonal.x != -diagonal.y) return {diagonal, true};
  return {HorizontalWeights(lane, uv, uv * glm::vec2(metrics_.width, metrics_.height)), false};
}

inline glm::vec2 BlendingWeights::LeftEdgeWeights(const sim::LaneBase& lane, int x, int y) const {
  const glm::vec2 uv = metrics_.Texcoord(x, y);
  return VerticalWeights(lane, uv, uv * glm::vec2(metrics_.width, metrics_.height));
}

inline glm::vec4 BlendingWeights::operator()(const sim::LaneBase& lane, int x, int y) const {
  glm::vec4 weights(0.0f);
  glm::vec2 e = EdgesAt(lane, x, y);
  if (e.y > 0.0f) {  // edge at the top
    const TopEdge top = TopEdgeWeights(lane, x, y, e);
    weights.x = top.weights.x;
    weights.y = top.weights.y;
    if (top.diagonal) e.x = 0.0f;
  }
  if (e.x > 0.0f) {  // edge at the left
    const glm::vec2 vertical = LeftEdgeWeights(lane, x, y);
    weights.z = vertical.x;
    weights.w = vertical.y;
  }
  return weights;
}

}  // namespace passes::smaa
