#pragma once
// History resampling for HRAA's TAA (seed 001 "Higher Order Resampling", "2nd Order Resampling:
// Mac Cormack", "BFCCE", "GPU BFCEE"): reprojecting an exponential history through velocity is
// an advection step; bilinear resampling is first-order semi-Lagrangian and diffuses a little
// more every frame, the three second-order forms undo most of that.
//
// Notation: A(phi)(p) = phi bilinearly sampled at p - v(p) (project N -> N+1, the current frame's
// velocity: the previous position of pixel p is p - v); A^R(phi)(q) = phi sampled at q + v(q)
// (reproject N+1 -> N). The backward step needs each previous-frame pixel's motion to N+1, which
// the renderer does not give: v(q) of the current frame stands in for it (exact for uniform
// motion, the usual assumption of semi-Lagrangian back-tracing). Clamp addressing throughout.
//
//   bilinear     h(p) = A(H)(p)                                      (in the TAA kernel)
//   maccormack   hraa/forward   F = A(H)          "1 - project value into future N+1"
//                hraa/backward  B = A^R(F)        "2 - reproject back into N"
//                hraa/correct   C = H + (H - B)/2 "3 - correct value by half accumulated error"
//                h(p) = A(C)(p)                   "4 - project corrected value into N+1" (TAA kernel)
//   bfecc        hraa/forward, hraa/backward as above; h(p) = F(p) + (H(p) - B(p))/2
//                ("3 - correct projected value by half accumulated error": reads phi_n, phi^_n,
//                phi^_n+1 as the seed says)
//   gpu-bfecc    hraa/forward F = A(H); the TAA kernel evaluates FF = A(A^R(F))(p) itself, four
//                bilinear taps of F at the outer footprint's texels j, each at j + v(p) (the
//                pixel's own UV offset: "projections ... quick to evaluate at shader execution
//                time by UV offsets"), and h(p) = F(p) + (F(p) - FF(p))/2 ("4 - correct projected
//                value by half accumulated error between projected and double projected value").
//
// The seed's names are swapped against the fluid-simulation literature (Selle et al. 2008 call
// the seed's "BFECC" MacCormack and vice versa); we follow the seed. For a linear projection
// (bilinear is linear in phi) gpu-bfecc = A(H + (H - A^R A H)/2) = maccormack exactly, up to
// float16 storage rounding and the v(p)-for-v(j) substitution; bfecc differs from both by
// (I - A)(H - B)/2 (its error term is not transported), which is why the seed notes the forms
// agree only for linear projections. No limiter: the seed gives none; the TAA's soft bounds and
// a clamp at zero treat the overshoot the correction can make at sharp edges.
//
// Intermediates F, B, C: RGBA16F (8 bytes per pixel each), kept across frames.

#include <optional>
#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "sim/dispatch.h"

namespace passes::hraa {

enum class Resampling : int { Bilinear = 0, MacCormack = 1, Bfecc = 2, GpuBfecc = 3 };
std::string_view ResamplingName(Resampling mode);

// The TAA kernel's history read, bound on its dispatch.
struct HistoryFetch {
  Resampling mode;
  std::optional<sim::TextureView<glm::vec4>> history, forward, backward, corrected;
  int width, height;

  // The history at pixel (x, y) of the current frame, whose velocity is v.
  glm::vec4 operator()(const sim::LaneBase& lane, int x, int y, glm::vec2 v) const;
};

class HistoryResampler {
 public:
  // Runs the dispatches `mode` needs before the TAA kernel (none for bilinear).
  void Prepare(sim::Machine& machine, Resampling mode, const sim::Texture2D<glm::vec4>& history,
               const sim::Texture2D<glm::vec2>& velocity);
  // Binds the TAA kernel's history reads on `d`.
  HistoryFetch Bind(sim::Dispatch& d, Resampling mode, const sim::Texture2D<glm::vec4>& history) const;

 private:
  std::optional<sim::Texture2D<glm::vec4>> forward_, backward_, corrected_;
};

// The uv of a position in pixels (texel centres at +0.5).
inline glm::vec2 UvOf(glm::vec2 pixel, int width, int height) {
  return {(pixel.x + 0.5f) / static_cast<float>(width), (pixel.y + 0.5f) / static_cast<float>(height)};
}

}  // namespace passes::hraa
