#pragma once
// CMAA2 v2.3's kernels (GameTechDev/CMAA2 Projects/CMAA2/CMAA2/CMAA2.hlsl; aa-facts §4), templated
// on the lane type so the stencil strategy's pixel shaders and the queue strategy's compute
// kernels run the same arithmetic. Defines followed: CMAA2_STATIC_QUALITY_PRESET (the settings),
// CMAA2_EDGE_DETECTION_LUMA_PATH 1, CMAA2_EXTRA_SHARPNESS 0, CMAA2_SUPPORT_HDR_COLOR_RANGE 0,
// CMAA_MSAA_SAMPLE_COUNT 1, CMAA_PACK_SINGLE_SAMPLE_EDGE_TO_HALF_WIDTH 1,
// CMAA2_COLLECT_EXPAND_BLEND_ITEMS 1 (its 10-bit lerp quantisation; see docs/cmaa2.md),
// CMAA2_UAV_STORE_TYPED 0 with CMAA2_UAV_STORE_UNTYPED_FORMAT 1 and CMAA2_UAV_STORE_CONVERT_TO_SRGB
// 1, CMAA2_USE_HALF_FLOAT_PRECISION 0. Float32 throughout, in the shader's operator order (the
// passes library is built with -ffp-contract=off: a mad is two roundings).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "passes/cmaa2/e4_colour.h"
#include "sim/dispatch.h"
#include "sim/formats.h"

namespace passes::cmaa2 {

struct Config {
  float edgeThreshold = 0.07f;             // g_CMAA2_EdgeThreshold, HIGH (aa-facts §4.2)
  float localContrastAdaptation = 0.10f;   // g_CMAA2_LocalContrastAdaptationAmount (aa-facts §4.2)
  bool referenceBufferSizes = false;       // the reference's "99.99% safe" sizes (aa-facts §4.1)
};

// Edge bits of one pixel (CMAA2.hlsl PackEdges; aa-facts §4.1).
inline constexpr std::uint32_t kEdgeRight = 0x01, kEdgeBelow = 0x02, kEdgeLeft = 0x04, kEdgeAbove = 0x08;

inline constexpr float kSimpleShapeBlurriness = 0.10f;  // g_CMAA2_SimpleShapeBlurinessAmount (aa-facts §4.3)
inline constexpr int kMaxLineLength = 86;               // c_maxLineLength (aa-facts §4.3)
inline constexpr float kSymmetryCorrectionOffset = 0.22f;  // c_symmetryCorrectionOffset
inline constexpr float kDampeningEffect = 0.15f;           // c_dampeningEffect
inline constexpr int kApplyMaxLoops = 32;                  // DeferredColorApply2x2CS's maxLoops (1x)
inline constexpr std::uint32_t kEmptyList = 0xFFFFFFFFu;
inline constexpr std::uint32_t kItemIndexMask = (1u << 26) - 1u;  // the pointer word's 26-bit index

// ---- Edge detection (EdgesColor2x2CS) ----------------------------------------------------------

// RGBToLumaForEdges: Rec. 601 weights on sqrt(linear) ("just very roughly approximate RGB curve");
// dot as x*wx + (y*wy + z*wz) (aa-facts §1.9).
inline float LumaForEdges(const glm::vec3& linear) {
  return std::sqrt(linear.r) * 0.299f + (std::sqrt(linear.g) * 0.587f + std::sqrt(linear.b) * 0.114f);
}

// The pixel at window offset (0, 0)'s four edges from its 3x3 luma window (`luma(dx, dy)`, dx and
// dy in -1..1). Each edge is the thread-independent arithmetic of EdgesColor2x2CS: the contrast
// |a - b| (ComputeEdgeLuma) minus amount x the largest of the four perpendicular contrasts touching
// its two ends (ComputeLocalContrastH / V), strictly above the threshold.
template <typename Luma>
std::uint32_t EdgesOf(Luma&& luma, const Config& config) {
  // horizontalNeighbour(dx, dy): between (dx, dy) and (dx + 1, dy); below(dx, dy): (dx, dy), (dx, dy + 1).
  const auto across = [&](int dx, int dy) { return std::fabs(luma(dx, dy) - luma(dx + 1, dy)); };
  const auto below = [&](int dx, int dy) { return std::fabs(luma(dx, dy) - luma(dx, dy + 1)); };
  const auto max4 = [](float a, float b, float c, float d) { return std::max(std::max(a, b), std::max(c, d)); };
  const float amount = config.localContrastAdaptation, threshold = config.edgeThreshold;
  const float right = across(0, 0), left = across(-1, 0), bottom = below(0, 0), top = below(0, -1);
  const auto on = [&](float contrast, float perpendicular) { return contrast - perpendicular * amount > threshold; };
  std::uint32_t bits = 0;
  if (on(right, max4(top, bottom, below(1, -1), below(1, 0)))) bits |= kEdgeRight;
  if (on(bottom, max4(left, right, across(-1, 1), across(0, 1)))) bits |= kEdgeBelow;
  if (on(left, max4(below(-1, -1), below(-1, 0), top, bottom))) bits |= kEdgeLeft;
  if (on(top, max4(across(-1, -1), across(0, -1), left, right))) bits |= kEdgeAbove;
  return bits;
}

// EdgesColor2x2CS's "someNonZeroEdges" for the 2x2 block whose top-left pixel is at window offset
// (0, 0) (`luma(dx, dy)`, dx in -1..2, dy in -1..2): one of its 12 contrasts (right and bottom of
// its four pixels, left of its left column, top of its top row) is non-zero. Such a block resets
// its quad's list head.
template <typename Luma>
bool BlockHasContrast(Luma&& luma) {
  for (int dy = 0; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (luma(dx, dy) != luma(dx + 1, dy)) return true;  // left, inner, right contrasts
    }
  }
  for (int dx = 0; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      if (luma(dx, dy) != luma(dx, dy + 1)) return true;  // top, inner, bottom contrasts
    }
  }
  return false;
}

// "at least one two edge corner": R*G + G*B + B*A + A*R != 0 on the 0/1 edges.
constexpr bool IsCandidate(std::uint32_t bits) {
  const bool r = bits & kEdgeRight, g = bits & kEdgeBelow, b = bits & kEdgeLeft, a = bits & kEdgeAbove;
  return (r && g) || (g && b) || (b && a) || (a && r);
}

// LoadEdge on the half-width R8_UINT edges texture: pixel x lives in texel x / 2, nibble x % 2.
// A negative x wraps to a huge uint in the shader: out of bounds, 0 (as Load does here).
template <typename Lane, typename EdgesTexture>
std::uint32_t LoadEdge(const Lane& lane, const EdgesTexture& edges, int x, int y) {
  const std::uint32_t texel = edges.Load(lane, x < 0 ? -1 : x / 2, y);
  return (texel >> (static_cast<std::uint32_t>(x < 0 ? 1 : x % 2) * 4u)) & 0xFu;
}

// ---- The deferred blend's linked lists (StoreColorSample) ---------------------------------------

// Appends one blended colour to its quad's list. The counters are the control buffer's words 8
// (locations) and 12 (items). Overflow policy (docs/cmaa2.md): an item past the item list's
// capacity is neither linked nor stored (the reference would link an index it cannot store) and is
// counted; a quad whose location does not fit is counted (its items are never applied).
struct BlendItemWriter {
  sim::RwBufferView<std::uint32_t> control;
  sim::RwBufferView<std::uint32_t> heads;       // ((W + 1) / 2) x ((H + 1) / 2), row-major
  sim::RwBufferView<glm::uvec2> items;          // (next pointer, packed colour)
  sim::RwBufferView<std::uint32_t> locations;   // qx << 16 | qy
  sim::CounterView stored, itemsDropped, locationsDropped;
  int headsWidth = 0;

  template <typename Lane>
  void Store(const Lane& lane, int x, int y, const glm::vec3& colour, bool complexShape) const {
    const std::uint32_t index = control.InterlockedAdd(lane, 12, 1u);
    if (index >= items.Size()) {
      itemsDropped.Add(lane);
      return;
    }
    const int qx = x / 2, qy = y / 2;
    const auto offsetXY = static_cast<std::uint32_t>((y % 2) * 2 + x % 2);
    const std::uint32_t header = offsetXY << 30 | static_cast<std::uint32_t>(complexShape) << 26;
    const std::uint32_t previous =
        heads.InterlockedExchange(lane, static_cast<std::size_t>(qy) * static_cast<std::size_t>(headsWidth) + qx,
                                  index | header);
    items.Store(lane, index, glm::uvec2(previous, PackR11G11B10E4(colour)));
    stored.Add(lane);
    if (previous != kEmptyList) return;
    const std::uint32_t location = control.InterlockedAdd(lane, 8, 1u);
    if (location >= locations.Size()) {
      locationsDropped.Add(lane);
      return;
    }
    locations.Store(lane, location, static_cast<std::uint32_t>(qx) << 16 | static_cast<std::uint32_t>(qy));
  }
};

// ---- Process candidates (ProcessCandidatesCS) ---------------------------------------------------

struct EdgeSet {
  float r = 0, g = 0, b = 0, a = 0;  // right, below, left, above as 0/1 (UnpackEdgesFlt)
  static EdgeSet Of(std::uint32_t bits) {
    return {static_cast<float>((bits & kEdgeRight) != 0), static_cast<float>((bits & kEdgeBelow) != 0),
            static_cast<float>((bits & kEdgeLeft) != 0), static_cast<float>((bits & kEdgeAbove) != 0)};
  }
  // .argb: the edges rotated 90 degrees counter-clockwise, so vertical Zs reuse the horizontal test.
  EdgeSet Rotated() const { return {a, r, g, b}; }
};

// dot(v, (1, 1, 1, 1)) in the order x + (y + (z + w)) (aa-facts §1.9's dot, extended to four).
inline float Sum4(float x, float y, float z, float w) { return x + (y + (z + w)); }

// ComputeSimpleShapeBlendValues with dontTestShapeValidity = true, as ProcessCandidatesCS calls it:
// weights (from left, above, right, below).
inline glm::vec4 SimpleShapeBlendValues(const EdgeSet& e, const EdgeSet& left, const EdgeSet& right,
                                        const EdgeSet& top, const EdgeSet& bottom) {
  float fromRight = e.r, fromBelow = e.g, fromLeft = e.b, fromAbove = e.a;
  float blurCoeff = kSimpleShapeBlurriness;
  const float numberOfEdges = Sum4(e.r, e.g, e.b, e.a);
  // dot(left.bga + right.rga + top.rba + bottom.rgb, (1, 1, 1)): small integers, exact.
  const float around = (left.b + right.r + top.r + bottom.r) +
                       ((left.g + right.g + top.b + bottom.g) + (left.a + right.a + top.a + bottom.b));
  if (numberOfEdges == 2.0f) {
    blurCoeff *= 0.75f;
    const float k = 0.9f;  // the L-shape continuation terms
    fromRight += k * (e.g * top.r * (1.0f - left.g) + e.a * bottom.r * (1.0f - left.a));
    fromBelow += k * (e.b * right.g * (1.0f - top.b) + e.r * left.g * (1.0f - top.r));
    fromLeft += k * (e.a * bottom.b * (1.0f - right.a) + e.g * top.b * (1.0f - right.g));
    fromAbove += k * (e.r * left.a * (1.0f - bottom.r) + e.b * right.a * (1.0f - bottom.b));
  }
  blurCoeff *= std::clamp(1.30f - around / 10.0f, 0.0f, 1.0f);
  return glm::vec4(fromLeft, fromAbove, fromRight, fromBelow) * blurCoeff;
}

struct ZScores {
  float inverted = 0, normal = 0;
};

// DetectZsHorizontal: edges of the pixel, its left, right and second-right neighbours.
inline ZScores DetectZsHorizontal(const EdgeSet& e, const EdgeSet& m1, const EdgeSet& p1, const EdgeSet& p2) {
  ZScores s;
  s.inverted = e.r * e.g * p1.a;
  s.inverted *= 2.0f + (m1.g + p2.a) - (e.a + p1.g) - 0.7f * (((p2.g + m1.a) + e.b) + p1.r);
  s.normal = e.r * e.a * p1.g;
  s.normal *= 2.0f + (m1.a + p2.g) - (e.g + p1.a) - 0.7f * (((p2.a + m1.g) + e.b) + p1.r);
  return s;
}

struct ZShape {
  bool found = false, horizontal = true, inverted = false;
  float score = 0;
};

// The best positive Z score, horizontal first; vertical wins only with a strictly higher score.
inline ZShape DetectZ(const EdgeSet& e, const EdgeSet& left, const EdgeSet& right, const EdgeSet& right2,
                      const EdgeSet& bottom, const EdgeSet& top, const EdgeSet& top2) {
  ZShape z;
  const ZScores h = DetectZsHorizontal(e, left, right, right2);
  z.score = std::max(h.inverted, h.normal);
  if (z.score > 0.0f) z.inverted = h.inverted > h.normal;
  const ZScores v = DetectZsHorizontal(e.Rotated(), bottom.Rotated(), top.Rotated(), top2.Rotated());
  const float vertical = std::max(v.inverted, v.normal);
  if (vertical > z.score) {
    z.score = vertical;
    z.horizontal = false;
    z.inverted = v.inverted > v.normal;
  }
  z.found = z.score > 0.0f;
  return z;
}

struct LineLengths {
  float left = 1, right = 1;
};

// FindZLineLengths: trace the Z's top (bottom) edge leftwards and its bottom (top) edge rightwards
// until either pattern ends; stop once the longer side is ahead of 1.25 x the shorter - 0.25, or at
// c_maxLineLength, or when both have stopped.
template <typename Lane, typename EdgesTexture>
LineLengths FindZLineLengths(const Lane& lane, const EdgesTexture& edges, int x, int y, bool horizontal,
                             bool inverted) {
  std::uint32_t maskLeft = horizontal ? kEdgeAbove : kEdgeLeft;
  std::uint32_t maskRight = horizontal ? kEdgeBelow : kEdgeRight;
  if (inverted) std::swap(maskLeft, maskRight);
  const glm::ivec2 stepRight = horizontal ? glm::ivec2(1, 0) : glm::ivec2(0, -1);
  bool continueLeft = true, continueRight = true;
  LineLengths length;
  for (;;) {
    const glm::ivec2 l = glm::ivec2(x, y) - stepRight * static_cast<int>(length.left);
    const glm::ivec2 r = glm::ivec2(x, y) + stepRight * (static_cast<int>(length.right) + 1);
    const std::uint32_t edgeLeft = LoadEdge(lane, edges, l.x, l.y);
    const std::uint32_t edgeRight = LoadEdge(lane, edges, r.x, r.y);
    continueLeft = continueLeft && (edgeLeft & maskLeft) == maskLeft;
    continueRight = continueRight && (edgeRight & maskRight) == maskRight;
    length.left += static_cast<float>(continueLeft);
    length.right += static_cast<float>(continueRight);
    float maxLR = std::max(length.right, length.left);
    if (!continueLeft && !continueRight) maxLR = static_cast<float>(kMaxLineLength);
    if (maxLR >= std::min(static_cast<float>(kMaxLineLength), 1.25f * std::min(length.right, length.left) - 0.25f)) {
      return length;
    }
  }
}

// One pixel of a Z's blend as CollectBlendZs encodes it and the expand loop decodes it: the step
// along the line, the source offset across it and the lerp factor in 10 bits.
struct ZItem {
  int step = 0, sourceOffset = 0;
  float lerpK = 0;
};

// CollectBlendZs's loop over the line, calling `emit(ZItem)` per pixel.
template <typename Emit>
void ForEachZItem(float shapeQualityScore, float lengthLeft, float lengthRight, Emit&& emit) {
  const float leftOdd = kSymmetryCorrectionOffset * std::fmod(lengthLeft, 2.0f);
  const float rightOdd = kSymmetryCorrectionOffset * std::fmod(lengthRight, 2.0f);
  const float dampenEffect = std::clamp((lengthLeft + lengthRight - shapeQualityScore) * kDampeningEffect, 0.0f, 1.0f);
  const float loopFrom = -std::floor((lengthLeft + 1.0f) / 2.0f) + 1.0f;
  const float loopTo = std::floor((lengthRight + 1.0f) / 2.0f);
  const float totalLength = (loopTo - loopFrom) + 1.0f - leftOdd - rightOdd;
  const float lerpStep = 1.0f / totalLength;
  const float lerpFromK = (0.5f - leftOdd - loopFrom) * lerpStep;
  for (float i = loopFrom; i <= loopTo; i += 1.0f) {
    const float secondPart = static_cast<float>(i > 0.0f);
    const float srcOffset = 1.0f - secondPart * 2.0f;
    float lerpK = (lerpStep * i + lerpFromK) * srcOffset + secondPart;
    lerpK *= dampenEffect;
    // uint(saturate(lerpK) * 1023 + 0.5), decoded as (bits & 0x3FF) / 1023.0.
    const auto bits = static_cast<std::uint32_t>(std::clamp(lerpK, 0.0f, 1.0f) * 1023.0f + 0.5f);
    emit(ZItem{static_cast<int>(i), static_cast<int>(srcOffset), static_cast<float>(bits) / 1023.0f});
  }
}

// lerp(a, b, t) = a + t * (b - a), two roundings per channel.
inline glm::vec3 Lerp(const glm::vec3& a, const glm::vec3& b, float t) { return a + (b - a) * t; }

// ProcessCandidatesCS for one candidate pixel: the simple-shape item, then a complex Z shape's
// items. `colour` reads the frame through its sRGB view (linear values, as the reference's
// UNORM_SRGB SRV); out-of-range loads read 0 as Texture2D.Load does.
template <typename ColourTexture, typename EdgesTexture>
struct ProcessCandidates {
  ColourTexture colour;
  EdgesTexture edges;
  BlendItemWriter writer;
  sim::CounterView zShapes;

  template <typename Lane>
  void operator()(const Lane& lane, int x, int y) const {
    const auto edgesAt = [&](int dx, int dy) { return EdgeSet::Of(LoadEdge(lane, edges, x + dx, y + dy)); };
    const auto colourAt = [&](int px, int py) { return glm::vec3(colour.Load(lane, px, py)); };
    const EdgeSet e = edgesAt(0, 0), left = edgesAt(-1, 0), right = edgesAt(1, 0), bottom = edgesAt(0, 1),
                  top = edgesAt(0, -1);
    SimpleShape(lane, x, y, e, left, right, top, bottom, colourAt);
    const ZShape z = DetectZ(e, left, right, edgesAt(2, 0), bottom, top, edgesAt(0, -2));
    if (!z.found) return;
    zShapes.Add(lane);
    const float shapeQualityScore = std::floor(std::clamp(4.0f - z.score, 0.0f, 3.0f));
    LineLengths length = FindZLineLengths(lane, edges, x, y, z.horizontal, z.inverted);
    length.left -= shapeQualityScore;
    length.right -= shapeQualityScore;
    if (length.left + length.right < 5.0f) return;
    const glm::ivec2 stepRight = z.horizontal ? glm::ivec2(1, 0) : glm::ivec2(0, -1);
    const glm::ivec2 blendDir = (z.horizontal ? glm::ivec2(0, -1) : glm::ivec2(-1, 0)) * (z.inverted ? -1 : 1);
    ForEachZItem(shapeQualityScore, length.left, length.right, [&](const ZItem& item) {
      const glm::ivec2 p = glm::ivec2(x, y) + stepRight * item.step;
      const glm::ivec2 from = p + blendDir * item.sourceOffset;
      writer.Store(lane, p.x, p.y, Lerp(colourAt(p.x, p.y), colourAt(from.x, from.y), item.lerpK), true);
    });
  }

 private:
  template <typename Lane, typename ColourAt>
  void SimpleShape(const Lane& lane, int x, int y, const EdgeSet& e, const EdgeSet& left, const EdgeSet& right,
                   const EdgeSet& top, const EdgeSet& bottom, ColourAt& colourAt) const {
    const glm::vec4 blend = SimpleShapeBlendValues(e, left, right, top, bottom);
    const float centreWeight = 1.0f - Sum4(blend.x, blend.y, blend.z, blend.w);
    glm::vec3 out = colourAt(x, y) * centreWeight;
    if (blend.x > 0.0f) out += blend.x * colourAt(x - 1, y);
    if (blend.y > 0.0f) out += blend.y * colourAt(x, y - 1);
    if (blend.z > 0.0f) out += blend.z * colourAt(x + 1, y);
    if (blend.w > 0.0f) out += blend.w * colourAt(x, y + 1);
    writer.Store(lane, x, y, out, false);
  }
};

// ---- Deferred colour apply (DeferredColorApply2x2CS) --------------------------------------------

// LINEAR_to_SRGB, per channel, in float.
inline float LinearToSrgb(float value) {
  if (value < 0.0031308f) return value * 12.92f;
  return 1.055f * std::pow(std::fabs(value), 1.0f / 2.4f) - 0.055f;
}

// FLOAT4_to_R8G8B8A8_UNORM's per-channel code: uint(saturate(x) * 255 + 0.5).
inline std::uint8_t UntypedUnorm8(float value) {
  return static_cast<std::uint8_t>(static_cast<std::uint32_t>(std::clamp(value, 0.0f, 1.0f) * 255.0f + 0.5f));
}

// The weighted mean of one pixel's items: 0.8 per simple-shape item, 1.8 per complex-shape item.
// The items are summed in the order of their (complex flag, packed colour) keys, not in list
// order: the list order is the order the atomics ran in, which differs between the strategies
// (docs/cmaa2.md "Determinism"). Returns alpha = the weight sum (0: no item).
inline glm::vec4 WeightedMean(std::vector<std::uint64_t>& keys) {
  std::sort(keys.begin(), keys.end());
  glm::vec4 sum(0.0f);
  for (const std::uint64_t key : keys) {
    const glm::vec3 colour = UnpackR11G11B10E4(static_cast<std::uint32_t>(key));
    const float weight = 0.8f + 1.0f * static_cast<float>(key >> 32);
    sum += glm::vec4(colour * weight, weight);
  }
  return sum;
}

struct DeferredColourApply {
  sim::BufferView<std::uint32_t> control;     // word 3: the clamped location count
  sim::BufferView<std::uint32_t> locations;
  sim::BufferView<std::uint32_t> heads;
  sim::BufferView<glm::uvec2> items;
  sim::RwTextureView<glm::vec4> output;       // the colour target through its UNORM view
  sim::CounterView longLists;
  int headsWidth = 0;

  // 4 x 32 threads per group ("threadgroup swap"): thread x is the pixel in the quad, y the quad.
  void operator()(sim::ComputeLane& lane) const {
    const auto quad = static_cast<std::uint32_t>(lane.threadId.y);
    if (quad >= control.Load(lane, 3)) return;
    const std::uint32_t location = locations.Load(lane, quad);
    const int qx = static_cast<int>(location >> 16), qy = static_cast<int>(location & 0xFFFFu);
    const auto offsetXY = static_cast<std::uint32_t>(lane.localId.x);
    const int x = qx * 2 + static_cast<int>(offsetXY % 2), y = qy * 2 + static_cast<int>(offsetXY / 2);
    std::uint32_t pointer = heads.Load(lane, static_cast<std::size_t>(qy) * static_cast<std::size_t>(headsWidth) + qx);
    std::vector<std::uint64_t> keys;
    std::size_t walked = 0;
    // Items are linked only when stored, so every list ends; the item count bounds a walk anyway.
    while (pointer != kEmptyList && walked < items.Size()) {
      const glm::uvec2 item = items.Load(lane, pointer & kItemIndexMask);
      if ((pointer >> 30) == offsetXY) keys.push_back(std::uint64_t{(pointer >> 26) & 1u} << 32 | item.y);
      pointer = item.x;
      ++walked;
    }
    if (walked > static_cast<std::size_t>(kApplyMaxLoops)) longLists.Add(lane);
    const glm::vec4 sum = WeightedMean(keys);
    if (sum.a == 0.0f) return;
    const glm::vec3 mean = glm::vec3(sum) / sum.a;
    const auto code = [&](float channel) { return sim::Unorm8ToFloat(UntypedUnorm8(LinearToSrgb(channel))); };
    output.Store(lane, x, y, glm::vec4(code(mean.r), code(mean.g), code(mean.b), 1.0f));
  }
};

}  // namespace passes::cmaa2
