#pragma once
// MiniEngine FXAA's arithmetic (aa-facts §3; microsoft/DirectX-Graphics-Samples
// MiniEngine/Core/Shaders/FXAAPass1CS.hlsli and FXAAPass2CS.hlsli), as host functions the kernels
// in fxaa_miniengine.cpp and the tests share. Float32 in the shaders' order; HLSL lerp(a, b, t)
// is a + t * (b - a) and mad is two roundings (the passes library builds with -ffp-contract=off).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sim/formats.h"

namespace passes::fxaa_miniengine {

// The work item: [12 bits Y | 12 bits X | 7 bits sub-pixel shift | 1 bit gradient direction]
// (FXAAPass1CS.hlsli "Packet header"). X and Y are the pixel's screen coordinates (pass 1 packs
// DTid + StartPixel, pass 2 adds nothing back), so a screen side is at most 4095 pixels and the
// padding item 0xFFFFFFFF decodes to pixel (4095, 4095), off every such screen.
inline constexpr int kMaxSide = 4095;
inline constexpr std::uint32_t kDummyItem = 0xFFFFFFFFu;

constexpr std::uint32_t PackWorkItem(int x, int y, std::uint32_t subpix, std::uint32_t gradientDir) {
  return static_cast<std::uint32_t>(y) << 20 | static_cast<std::uint32_t>(x) << 8 | subpix | gradientDir;
}
// Pass 2's decode: uint2(header >> 8, header >> 20) & 0xFFF.
constexpr glm::ivec2 WorkItemPixel(std::uint32_t item) {
  return {static_cast<int>((item >> 8) & 0xFFFu), static_cast<int>((item >> 20) & 0xFFFu)};
}
constexpr std::uint32_t WorkItemGradientDir(std::uint32_t item) { return item & 1u; }
// (header & 0xFE) / 254.0 * 0.5: seven bits for a shift in [0, 0.5].
inline float WorkItemSubpix(std::uint32_t item) { return static_cast<float>(item & 0xFEu) / 254.0f * 0.5f; }

// RGBToLogLuminance: log2(1 + 15 Y) / 4 of Rec. 709 luminance (FXAAPass1CS.hlsli; its header
// comment describes (1 - 2^(-4Y)) * 16/15 but the code uses the log form). dot as llvmpipe
// evaluates it, x*wx + (y*wy + z*wz) (aa-facts §1.9).
inline float LogLuma(glm::vec3 linear) {
  const float y = linear.x * 0.212671f + (linear.y * 0.715160f + linear.z * 0.072169f);
  return std::log2(1.0f + y * 15.0f) / 4.0f;
}

// The 3x3 luma neighbourhood pass 1 reads from its LDS cache.
struct Neighbourhood {
  float n, w, m, e, s, nw, ne, sw, se;
};

struct Classification {
  bool horizontal = false;       // edgeHorz >= edgeVert: the item goes to the front (pass 2H)
  std::uint32_t gradientDir = 0;  // 1: the stronger gradient is towards +y (+x)
  std::uint32_t subpix = 0;       // uint(subpixelShift * 254) & 0xFE
};

// The contrast test (range < ContrastThreshold returns early) on the five ordinal lumas.
inline bool PassesContrast(float n, float w, float m, float e, float s, float contrastThreshold) {
  const float rangeMax = std::max(std::max(n, w), std::max(e, std::max(s, m)));
  const float rangeMin = std::min(std::min(n, w), std::min(e, std::min(s, m)));
  return !(rangeMax - rangeMin < contrastThreshold);
}

inline float Saturate(float v) { return std::min(std::max(v, 0.0f), 1.0f); }

// Pass 1 after the contrast test: edge orientation, gradient side, sub-pixel shift.
inline Classification Classify(const Neighbourhood& l, float subpixelRemoval) {
  const float rangeMax = std::max(std::max(l.n, l.w), std::max(l.e, std::max(l.s, l.m)));
  const float rangeMin = std::min(std::min(l.n, l.w), std::min(l.e, std::min(l.s, l.m)));
  const float range = rangeMax - rangeMin;
  const float ns = l.n + l.s, we = l.w + l.e;
  const float nwsw = l.nw + l.sw, nese = l.ne + l.se, swse = l.sw + l.se, nwne = l.nw + l.ne;
  const float edgeHorz =
      std::abs(nwsw - 2.0f * l.w) + std::abs(ns - 2.0f * l.m) * 2.0f + std::abs(nese - 2.0f * l.e);
  const float edgeVert =
      std::abs(swse - 2.0f * l.s) + std::abs(we - 2.0f * l.m) * 2.0f + std::abs(nwne - 2.0f * l.n);
  const float avgNeighbour = ((ns + we) * 2.0f + nwsw + nese) / 12.0f;
  // smoothstep(0, 1, v) = t * t * (3 - 2t) with t = saturate(v); pow(x, 2) = x * x.
  const float t = Saturate(std::abs(avgNeighbour - l.m) / range);
  const float smooth = t * t * (3.0f - 2.0f * t);
  const float subpixelShift = Saturate(smooth * smooth * subpixelRemoval * 2.0f);
  const bool horizontal = edgeHorz >= edgeVert;
  const float negGrad = (horizontal ? l.n : l.w) - l.m;
  const float posGrad = (horizontal ? l.s : l.e) - l.m;
  return {.horizontal = horizontal,
          .gradientDir = std::abs(posGrad) >= std::abs(negGrad) ? 1u : 0u,
          .subpix = static_cast<std::uint32_t>(subpixelShift * 254.0f) & 0xFEu};
}

// Pass 2's step distances along the edge (FXAAPass2CS.hlsli s_SampleDistances): the first
// NUM_SAMPLES are sampled on each side, the last is the distance used when no end is found.
// Default: FXAA quality preset 25; FXAA_EXTREME_QUALITY: preset 39.
inline constexpr std::array<float, 8> kDefaultDistances{1.0f, 2.5f, 4.5f, 6.5f, 8.5f, 10.5f, 14.5f, 22.5f};
inline constexpr std::array<float, 12> kExtremeDistances{1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.5f,
                                                         8.5f, 10.5f, 12.5f, 14.5f, 18.5f, 36.5f};
inline std::span<const float> SampleDistances(bool extreme) {
  return extreme ? std::span<const float>(kExtremeDistances) : std::span<const float>(kDefaultDistances);
}

inline float Sign(float v) { return v > 0.0f ? 1.0f : (v < 0.0f ? -1.0f : 0.0f); }

// The end search and blend amount of one item. `sample(distance, side)` returns the luma
// SampleLevel gives `distance` texels along the edge on side -1 or +1 of the start.
struct EdgeEnds {
  float negDist = 0.0f, posDist = 0.0f;
  bool negGood = false, posGood = false;
};
template <typename Sample>
EdgeEnds SearchEnds(std::span<const float> distances, float centerLuma, float gradientSgn, float gradientMag,
                    Sample&& sample) {
  const std::size_t samples = distances.size() - 1;
  EdgeEnds ends{.negDist = distances[samples], .posDist = distances[samples]};
  for (std::size_t i = 0; i < samples; ++i) {
    const float distance = distances[i];
    const float negGrad = sample(distance, -1) - centerLuma;
    if (std::abs(negGrad) >= gradientMag && distance < ends.negDist) {
      ends.negDist = distance;
      ends.negGood = Sign(negGrad) == gradientSgn;
    }
    const float posGrad = sample(distance, 1) - centerLuma;
    if (std::abs(posGrad) >= gradientMag && distance < ends.posDist) {
      ends.posDist = distance;
      ends.posGood = Sign(posGrad) == gradientSgn;
    }
  }
  return ends;
}

// 0.5 - min / (pos + neg) where the nearer end is "good", raised to the sub-pixel shift.
inline float PixelShift(const EdgeEnds& ends, float subpix) {
  const float shift = 0.5f - std::min(ends.negDist, ends.posDist) / (ends.posDist + ends.negDist);
  const bool goodSpan = ends.negDist < ends.posDist ? ends.negGood : ends.posGood;
  return std::max(subpix, goodSpan ? shift : 0.0f);
}

// HLSL lerp(a, b, t) = a + t * (b - a).
inline glm::vec3 Lerp(glm::vec3 a, glm::vec3 b, float t) { return a + t * (b - a); }

// The colour queue's element: DXGI R11G11B10_FLOAT (R in bits 0-10, G 11-21, B 22-31), the
// format of the colour it copies, so packing a fetched colour is lossless.
inline std::uint32_t PackR11G11B10(glm::vec3 c) {
  return std::uint32_t{sim::FloatToFloat11(c.x)} | std::uint32_t{sim::FloatToFloat11(c.y)} << 11 |
         std::uint32_t{sim::FloatToFloat10(c.z)} << 22;
}
inline glm::vec3 UnpackR11G11B10(std::uint32_t bits) {
  return {sim::Float11ToFloat(static_cast<std::uint16_t>(bits & 0x7FFu)),
          sim::Float11ToFloat(static_cast<std::uint16_t>((bits >> 11) & 0x7FFu)),
          sim::Float10ToFloat(static_cast<std::uint16_t>(bits >> 22))};
}

}  // namespace passes::fxaa_miniengine
