#pragma once
// UE4 temporal AA's per-pixel arithmetic (seed 002, aa-facts §5.1), kept apart from the dispatch
// so tests can check each rule on its own. Colours are linear RGB; boxes are in YCoCg.

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "passes/temporal/colour_box.h"
#include "sim/colour.h"

namespace passes::taa_ue4 {

// Seed 002 "Reconstruction filter": a Gaussian fit to Blackman-Harris 3.3, W(x) = e^(-2.29 x²),
// x in pixels (support ~2 px wide).
inline constexpr float kGaussianFalloff = 2.29f;
inline float ReconstructionWeight(glm::vec2 offset) {
  return std::exp(-kGaussianFalloff * (offset.x * offset.x + offset.y * offset.y));
}

// Seed 002 "Better tone map solution": weight = 1 / (1 + luma). Luma here is luminance: the
// BT.709 weights on the linear colour (the renderer's HDR values; Karis weights before tone mapping).
inline float LumaWeight(const glm::vec3& linear) { return 1.0f / (1.0f + sim::Rec709Luma(linear)); }

// Seed 002 "Our current anti-flickering solution": reduce the blend factor (the current frame's
// weight) when the history is near clamping. The talk gives no formula; ours: with d the history
// luma's distance to the nearer face of the box's luma range [yMin, yMax],
//   alpha' = alpha * lerp(1, 3 d / (d + (yMax - yMin)), strength),
// which is alpha at the box centre (d = range / 2 gives 1/3) and alpha * (1 - strength) on a face,
// so a history just clamped to a face recovers slowly (the sawtooth's amplitude shrinks). A flat
// box (zero range) has nothing to flicker between and keeps alpha.
inline float AntiFlickerAlpha(float alpha, float yHistory, float yMin, float yMax, float strength) {
  const float range = yMax - yMin;
  if (!(range > 0.0f)) return alpha;
  const float d = std::max(0.0f, std::min(yHistory - yMin, yMax - yHistory));
  const float nearCentre = std::min(1.0f, 3.0f * d / (d + range));
  return alpha * (1.0f + strength * (nearCentre - 1.0f));
}

// The exponential history blend with luma weights (seed 002 "Exponential smoothing", "Luma
// weight"): (alpha w_c c + (1 - alpha) w_h h) / (alpha w_c + (1 - alpha) w_h), written as a step
// from the history so that equal colours give the history back bit for bit. Returns the current
// colour's share beta.
inline float CurrentShare(float alpha, float currentWeight, float historyWeight) {
  const float current = alpha * currentWeight;
  return current / (current + (1.0f - alpha) * historyWeight);
}

// How the history is kept near the current neighbourhood (seed 002 "Neighborhood clamping" to
// "Clip instead of clamp"), the setting `constraint`.
enum class Constraint { None = 0, ClampRgb3x3 = 1, ClipShapedYCoCg = 2 };

}  // namespace passes::taa_ue4
