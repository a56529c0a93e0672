#pragma once
// CMAA2's LDR blend-item colour packing (aa-facts §4.1; CMAA2.hlsl Pack_R11G11B10_E4_FLOAT and
// Unpack_R11G11B10_E4_FLOAT, which credit MiniEngine's PixelPacking_R11G11B10.hlsli): R11G11B10
// with one exponent bit moved into each mantissa (4-bit exponents, 7/7/6-bit mantissas), for
// values clamped to [0, 2). Written from the formula: clamp, f32tof16, add half of the dropped
// mantissa bits' range, shift into place, mask. f32tof16 follows D3D's float conversion rules
// (its sm5 asm reference page): sim::FloatToHalf, round toward zero (D3D11 §3.2.2).

#include <cstdint>

#include <glm/vec3.hpp>

#include "sim/formats.h"

namespace passes::cmaa2 {

// asfloat(0x3FFFFFFF): the largest float below 2 ("1.FFFFF x 2^0").
inline constexpr float kE4Max = 0x1.fffffep0f;

inline std::uint32_t PackR11G11B10E4(const glm::vec3& rgb) {
  // HLSL clamp(x, lo, hi) = min(max(x, lo), hi).
  const auto half = [](float value) {
    return static_cast<std::uint32_t>(sim::FloatToHalf(std::min(std::max(value, 0.0f), kE4Max)));
  };
  const std::uint32_t r = ((half(rgb.r) + 4u) >> 3) & 0x000007FFu;
  const std::uint32_t g = ((half(rgb.g) + 4u) << 8) & 0x003FF800u;
  const std::uint32_t b = ((half(rgb.b) + 8u) << 18) & 0xFFC00000u;
  return r | g | b;
}

inline glm::vec3 UnpackR11G11B10E4(std::uint32_t packed) {
  const auto half = [](std::uint32_t bits) { return sim::HalfToFloat(static_cast<std::uint16_t>(bits)); };
  return {half((packed << 3) & 0x3FF8u), half((packed >> 8) & 0x3FF8u), half((packed >> 18) & 0x3FF0u)};
}

}  // namespace passes::cmaa2
