#pragma once
// Colour maths shared by the machine's formats, the passes, the metrics and image output: one
// copy of each transfer function and luma form, so a pass and the metric that scores it can never
// disagree about what "sRGB" or "luma" means.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

namespace sim {

// IEC 61966-2-1 (sRGB) transfer functions on [0, 1], the one copy of the curve: float for shading
// and metrics, double where the machine's formats need the exact value to quantise
// (sim/formats.cpp). aa-facts §1.9: an exact curve stays within 1/255 of llvmpipe's approximation.
template <typename T>
T SrgbEncodeCurve(T linear) {
  return linear <= T(0.0031308) ? T(12.92) * linear : T(1.055) * std::pow(linear, T(1) / T(2.4)) - T(0.055);
}
template <typename T>
T SrgbDecodeCurve(T encoded) {
  return encoded <= T(0.04045) ? encoded / T(12.92) : std::pow((encoded + T(0.055)) / T(1.055), T(2.4));
}

// The curves after clamping to [0, 1].
inline float EncodeSrgb(float linear) { return SrgbEncodeCurve(std::clamp(linear, 0.0f, 1.0f)); }
inline float DecodeSrgb(float encoded) { return SrgbDecodeCurve(std::clamp(encoded, 0.0f, 1.0f)); }

inline glm::vec3 EncodeSrgb(const glm::vec3& linear) {
  return {EncodeSrgb(linear.r), EncodeSrgb(linear.g), EncodeSrgb(linear.b)};
}

// 8-bit sRGB for image files (PNG previews): rounded to nearest.
inline std::uint8_t EncodeSrgb8(float linear) {
  return static_cast<std::uint8_t>(std::lround(EncodeSrgb(linear) * 255.0f));
}

// ITU-R BT.709 luma weights applied to gamma-encoded channels (Y', not luminance): SMAA's luma
// edge detection (aa-facts §1.3) and the metrics' luma. Summed left to right.
inline float Rec709Luma(const glm::vec3& encoded) {
  return 0.2126f * encoded.r + 0.7152f * encoded.g + 0.0722f * encoded.b;
}

// Rec. 601 weights on the stored (gamma) colour: FXAA 3.11's integration example computes this in
// a pre-pass into alpha (aa-facts §1.9).
inline float Rec601Luma(const glm::vec3& encoded) {
  return 0.299f * encoded.r + 0.587f * encoded.g + 0.114f * encoded.b;
}

// CMAA2's default luma path: Rec. 601 weights on sqrt(linear), sqrt as a cheap gamma (aa-facts §4,
// CMAA2_EDGE_DETECTION_LUMA_PATH 1).
inline float Cmaa2Luma(const glm::vec3& linear) {
  return Rec601Luma({std::sqrt(linear.r), std::sqrt(linear.g), std::sqrt(linear.b)});
}

// MiniEngine's FXAA luma: log2(1 + 15 Y) / 4 of linear luminance, mapping 0 -> 0 and 1 -> 1
// (aa-facts §3).
inline float MiniEngineFxaaLuma(const glm::vec3& linear) {
  const float y = 0.212671f * linear.r + 0.715160f * linear.g + 0.072169f * linear.b;
  return std::log2(1.0f + 15.0f * y) / 4.0f;
}

// YCoCg, the space temporal passes clamp and clip history in (aa-facts §5.2, Lottes in §5.4):
// Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4, and its exact inverse.
inline glm::vec3 RgbToYCoCg(const glm::vec3& rgb) {
  return {0.25f * rgb.r + 0.5f * rgb.g + 0.25f * rgb.b, 0.5f * rgb.r - 0.5f * rgb.b,
          -0.25f * rgb.r + 0.5f * rgb.g - 0.25f * rgb.b};
}
inline glm::vec3 YCoCgToRgb(const glm::vec3& ycocg) {
  const float y = ycocg.x, co = ycocg.y, cg = ycocg.z;
  return {y + co - cg, y + cg, y - co - cg};
}

}  // namespace sim
