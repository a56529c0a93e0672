#pragma once
// History sampling shared by the temporal passes, kernel side: where a pixel's history lies in the
// previous frame, and the 5-tap bicubic filters that read it there.
//
// Both 5-tap filters start from a separable 4x4 cubic (16 taps), fold the middle two texels of
// each axis into one bilinear tap at offset w2 / (w1 + w2) (9 bilinear taps) and then drop the four
// corner taps, leaving a '+' of five bilinear fetches:
//
//          A            A = (m.x, t0.y)   B = (t0.x, m.y)   C = (m.x, m.y)
//       B  C  D         D = (t3.x, m.y)   E = (m.x, t3.y)
//          E            t0 = t1 - 1, t3 = t1 + 2, m = t1 + w2 / (w1 + w2), t1 the texel left of/above p
//
// They differ in what replaces the corners (aa-facts §2 vs §5.3):
//   Filmic SMAA  drops them and divides by the five taps' summed weight (sharpness c settable);
//   Intel TAA    Catmull-Rom (c = 0.5) with each corner's contribution approximated by an average
//                of side taps, no renormalisation. The top-right corner takes (A + B) / 2, as the
//                published shader does (TAAResolve.hlsl BicubicSampling5), not (A + D) / 2.
// Where one fraction is 0 the corner weights vanish and both equal the full bicubic exactly; with
// both fractions non-zero neither reproduces a linear ramp exactly (the dropped corners carry
// ramp values), which is the published approximation.

#include <cmath>

#include <glm/vec2.hpp>

#include "sim/views.h"

namespace passes::temporal {

// The previous-frame position of pixel (x, y) as a normalised coordinate: the pixel centre minus
// its velocity (FrameInputs::velocity: pixels, current - previous, so the previous position of p
// is p - v).
inline glm::vec2 HistoryUv(int x, int y, glm::vec2 velocity, int width, int height) {
  return (glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f) - velocity) /
         glm::vec2(static_cast<float>(width), static_cast<float>(height));
}

// The cubic's four weights for fraction f in [0, 1) of the way from texel 1 to texel 2, per axis
// (aa-facts §2): c = 0.5 is Catmull-Rom; every c gives weights summing to 1.
struct CubicWeights {
  glm::vec2 w0, w1, w2, w3;
};
inline CubicWeights CubicWeightsAt(glm::vec2 f, float c) {
  const glm::vec2 f2 = f * f, f3 = f2 * f;
  return {.w0 = -c * f3 + 2.0f * c * f2 - c * f,
          .w1 = (2.0f - c) * f3 - (3.0f - c) * f2 + 1.0f,
          .w2 = -(2.0f - c) * f3 + (3.0f - 2.0f * c) * f2 + c * f,
          .w3 = c * f3 - c * f2};
}

// Catmull-Rom's sharpness: the Intel form's fixed s (aa-facts §5.3) and Filmic SMAA's default c.
inline constexpr float kCatmullRom = 0.5f;

namespace detail {
// The five taps' texel-space positions (texel centres at i + 0.5) and the weights at `texel`.
struct FiveTaps {
  CubicWeights w;
  glm::vec2 w12;      // w1 + w2, the middle tap's weight per axis
  glm::vec2 t0, m, t3;  // texel-space coordinates of the outer, middle and far taps per axis
};
inline FiveTaps FiveTapsAt(glm::vec2 texel, float c) {
  const glm::vec2 t1 = glm::floor(texel - 0.5f) + 0.5f;
  FiveTaps taps{.w = CubicWeightsAt(texel - t1, c), .w12 = {}, .t0 = t1 - 1.0f, .m = {}, .t3 = t1 + 2.0f};
  taps.w12 = taps.w.w1 + taps.w.w2;
  taps.m = t1 + taps.w.w2 / taps.w12;
  return taps;
}
// The five bilinear fetches A..E of the diagram, in texel space divided back to uv.
template <typename T>
struct FiveFetches {
  T a, b, c, d, e;
};
template <typename T>
FiveFetches<T> Fetch(const sim::TextureView<T>& view, const sim::LaneBase& lane, const FiveTaps& taps) {
  const glm::vec2 size(static_cast<float>(view.Width()), static_cast<float>(view.Height()));
  const auto at = [&](float x, float y) { return view.SampleBilinear(lane, glm::vec2(x, y) / size); };
  return {at(taps.m.x, taps.t0.y), at(taps.t0.x, taps.m.y), at(taps.m.x, taps.m.y), at(taps.t3.x, taps.m.y),
          at(taps.m.x, taps.t3.y)};
}
}  // namespace detail

// Filmic SMAA's history filter (aa-facts §2): the five taps weighted by the cubic of sharpness c
// and divided by their summed weight, so a constant image stays constant for any c.
template <typename T>
T SampleHistoryFilmic(const sim::TextureView<T>& view, const sim::LaneBase& lane, glm::vec2 uv, float c) {
  const detail::FiveTaps taps =
      detail::FiveTapsAt(uv * glm::vec2(static_cast<float>(view.Width()), static_cast<float>(view.Height())), c);
  const detail::FiveFetches<T> f = detail::Fetch(view, lane, taps);
  const float wa = taps.w12.x * taps.w.w0.y, wb = taps.w.w0.x * taps.w12.y, wc = taps.w12.x * taps.w12.y;
  const float wd = taps.w.w3.x * taps.w12.y, we = taps.w12.x * taps.w.w3.y;
  return (f.a * wa + f.b * wb + f.c * wc + f.d * wd + f.e * we) / (wa + wb + wc + wd + we);
}

// Intel TAA's history filter (aa-facts §5.3): Catmull-Rom, corners as averages of side taps, row
// by row (top, middle, bottom) as the published shader sums them.
template <typename T>
T SampleHistoryIntel(const sim::TextureView<T>& view, const sim::LaneBase& lane, glm::vec2 uv) {
  const detail::FiveTaps taps = detail::FiveTapsAt(
      uv * glm::vec2(static_cast<float>(view.Width()), static_cast<float>(view.Height())), kCatmullRom);
  const detail::FiveFetches<T> f = detail::Fetch(view, lane, taps);
  const CubicWeights& w = taps.w;
  const T top = (f.a + f.b) * 0.5f * w.w0.x + f.a * taps.w12.x + (f.a + f.b) * 0.5f * w.w3.x;
  const T middle = f.b * w.w0.x + f.c * taps.w12.x + f.d * w.w3.x;
  const T bottom = (f.b + f.e) * 0.5f * w.w0.x + f.e * taps.w12.x + (f.d + f.e) * 0.5f * w.w3.x;
  return top * w.w0.y + middle * taps.w12.y + bottom * w.w3.y;
}

}  // namespace passes::temporal
