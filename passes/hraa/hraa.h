#pragma once
// HRAA's temporal part (seed 001 "HRAA: Final Implementation": "Temporal FLIPQUAD Reconstruction
// combined with Temporal Anti-aliasing (TAA)"; aa-facts §6): temporal FLIPQUAD (tfq.h) feeding an
// exponential history with the seed's frequency-based acceptance metric, the history resampled
// by bilinear, MacCormack, BFECC or GPU BFECC (history_resample.h).
//
//   [tfq/resolve, tfq/unsharp]        tfq = 1 (tfq.h): frame ring -> current (RGBA16F)
//                                     tfq = 0: current = the frame's own colour (RGBA8 sRGB)
//   [hraa/forward, hraa/backward,     by resample (history_resample.h): RGBA16F intermediates
//    hraa/correct]
//   hraa/taa      full-screen PS      current 3x3, velocity N (RG16F), history (resampled) ->
//                                     history' (RGBA16F) = the output
//
// History: two RGBA16F textures (8 bytes per pixel each), read and written alternately, plus the
// frame ring of tfq.h (colour N, N-1, N-2 RGBA8 sRGB, velocity N, N-1 RG16F) and up to three
// RGBA16F resampling intermediates: 3 x 4 + 2 x 4 + 2 x 8 + 3 x 8 = 60 machine bytes per pixel
// at most (gpu-bfecc: 44; each dispatch counts what it reads and writes).
//
// The acceptance metric (seed 001 "Temporal Anti Aliasing", "Frequency based acceptance metric":
// "operate on fresh data neighborhood (3x3 window); history sample close to mean doesn't bring
// new information; further away brings more information; too far might be a fluctuation; local
// minima / maxima provide soft bounds for exponential weight function"). The seed gives the idea,
// not the formula; ours, in YCoCg (sim/colour.h) over the current image's 3x3 window with mean m,
// minimum lo and maximum hi per channel, history h:
//
//   t = max over channels of |h - m| / (d + eps),  d = hi - m if h >= m else m - lo,  eps = 1/256
//       (t = 0 at the mean, 1 on the local min/max box, > 1 outside it)
//   beta(t) = feedback_mean + (feedback_bound - feedback_mean) t     for t <= 1
//           = feedback_bound exp(-falloff (t - 1))                   for t > 1
//   out = current + beta (h - current)
//
// beta is the history's weight: near the mean the history adds little the current window lacks,
// so fresh data is taken in faster (feedback_mean); towards the bounds the history carries detail
// the current frame lacks (sub-pixel samples of earlier frames) and is trusted most
// (feedback_bound); beyond the local min/max it may be a fluctuation or stale, and its weight falls
// exponentially with the distance (the soft bound; a hard clamp would be falloff = infinity). eps
// keeps a flat window (d = 0) from dividing by zero: one 8-bit step, so a history off a flat
// window by more than a few steps is rejected at once. Defaults 0.85 / 0.95 / 4 are ours (Salvi's
// typical alpha 0.1 sits between them, aa-facts §5.4). With feedback_mean = feedback_bound and
// falloff = 0 the pass is a plain exponential history (the BFECC experiment's setting, preset
// "exponential").
//
// Frame 0 of a sequence (or a new size): the current image is the history (beta = 0). A pixel
// whose previous position p - v lies off the screen takes beta = 0 too.
//
// Strategies: full-screen per-pixel work, no work set; one strategy, stencil (see tfq.h).

#include <memory>

#include "passes/pass.h"

namespace passes::hraa {

inline constexpr std::string_view kTaaDispatch = "hraa/taa";

const PassInfo& HraaInfo();
std::unique_ptr<Pass> MakeHraa(const PassSettings& settings);

}  // namespace passes::hraa
