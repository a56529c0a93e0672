#pragma once
// Temporal FLIPQUAD (seed 001 "Temporal FLIPQUAD", "Temporal Super Sampling"; aa-facts §6, §8):
// the 2x FLIPQUAD pattern split over two frames, resolved per pixel from the current frame and
// the reprojected previous one.
//
//   tfq/resolve   full-screen PS   colour N, N-1, N-2 (RGBA8 sRGB, the renderer's targets),
//                                  velocity N, N-1 (RG16F) -> tfq (RGBA16F)
//   [tfq/unsharp] full-screen PS   tfq -> tfq-sharp (RGBA16F); only with unsharp > 0
//
// History: the renderer's last three colour targets and last two velocity targets, kept as a
// ring (3 x 4 + 2 x 4 bytes per pixel on the machine); the pass stores each frame's colour and
// velocity into the ring on the host, as the renderer's own writes (not a pass dispatch), so only
// the resolve's reads are counted. No history resource is written by a dispatch.
//
// The per-pixel combination. Schedule "flipquad-split" (raster/jitter_schedule.h) draws frame A
// with FLIPQUAD sample 0 (the pixel's LEFT-edge point) and frame B with sample 1 (its TOP-edge
// point), one sample per pixel (raster/sample_pattern.cpp kFlipQuadEven/Odd). FLIPQUAD's four
// points of pixel (x, y) are its left and top points and the left point of (x+1, y) (its right
// point) and the top point of (x, y+1) (its bottom point) (docs/sample-patterns.md "flipquad:
// derivation"). So
//
//   PixelO(x, y) = 1/4 [A(x, y) + A(x+1, y) + B(x, y) + B(x, y+1)]
//               = avg( avg(A(x,y), A(x+1,y)),  avg(B(x,y), B(x,y+1)) )
//
// which is the seed's PixelO = avg(BLUE(0,1), RED(0,2)) written for quad pixel 0, with quad
// pixels numbered X0Y0 = 0, X1Y0 = 1, X0Y1 = 2 (BLUE = frame A's points, paired along X with the
// right neighbour; RED = frame B's, paired along Y with the lower neighbour): the "convenient
// blend on X or Y axis depending on frame". Every other pixel pairs with its own right and lower
// neighbours (which may lie in the next quad); at the right and bottom screen edges the missing
// neighbour is the pixel itself (clamp). When the current frame is A its half is the X pair of
// frame N and the Y pair comes from frame N-1 at the reprojected pixel; when it is B the roles
// swap.
//
// Reprojection and the validity tests (seed "Temporal Super Sampling", after Killzone SF):
//   q = p - round(v_N(p)): the previous frame's pixel (nearest: the N-1 values are point samples
//       at staggered edge positions, a bilinear fetch would average samples of different
//       positions; the residual is under 0.5 px and fails the colour test where it matters).
//   motion flow: mean over the 3x3 window of |v_N(p+d) - v_N-1(q+d)| (L1, px) <= motion_threshold,
//       and q inside the screen (its pair clamps
//       at the right and bottom edges like the current one). Failing it (a disocclusion, a new object): the N-1
//       half is interpolated from N: the missing axis's pair is the tent 1/4, 1/2, 1/4 of frame
//       N's pairs at p - a, p, p + a (a the missing pairing axis), so PixelO = 1/8 pair(p - a) +
//       3/4 pair(p) + 1/8 pair(p + a).
//   colour flow: N-2 has N's jitter (seed: "N-2 and N have same sub-pixel jitter"), so with r =
//       q - round(v_N-1(q)): mean over 3x3 of |L(N(p+d)) - L(N-2(r+d))| <= colour_threshold, L the
//       Rec. 709 luma of the sRGB-encoded (8-bit) value, the seed's SAD on packed 8-bit data
//       (msad4). Failing it, or with no N-2 yet: the N-1 half is limited (per channel) by the
//       min/max box of frame N's 3x3 samples.
// The seed publishes no thresholds: defaults and ranges are ours (docs/temporal.md).
//
// Frame 0 (no N-1, or a previous frame of the same phase, e.g. under schedule "none"): the N-1
// half is interpolated from N everywhere. The phase comes from the frame's pattern (sample 0 of
// quad pixel 0 at FLIPQUAD's left point -> A, top point -> B), else from frameIndex parity.
//
// Hi-frequency recovery (seed "HRAA: Hi Frequency Recovery"): the FLIPQUAD box resolve is a
// 0.5-px-radius blur (its four points lie 0.5 px from the centre along X or Y); the option
// unsharp = s subtracts s times the same blur expressed on the pixel grid (a point at +-0.5 px is
// the average of two adjacent pixels): K = 1/2 centre + 1/8 each 4-neighbour, out = max(0,
// c + s (c - K c)): one negative lobe, off by default.
//
// Sample-rate UVs and analytic gradients (seed "Temporal FLIPQUAD: In Practice") are a renderer
// property: sim/frame.cpp's material kernel interpolates UV and normal at the CENTROID, and with
// one sample per pixel a covered pixel's centroid is its centre (raster::CentroidPosition), so
// textures are shaded at the pixel centre in both frames and only geometric edges are super-
// sampled. There are no mip levels on the machine (docs/machine.md "Sampling": every sample reads
// level 0), so the seed's wrong-derivative / oversharpened-mip issue cannot occur. See
// docs/temporal.md "Sample-rate shading".
//
// Strategies: full-screen per-pixel work with no work set (every pixel is resolved every frame),
// so one strategy, stencil (a full-screen PS without a stencil test); the queue form would append
// every pixel and only add the copy pass's floor (passes/copy/copy.h).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "passes/pass.h"

namespace passes::hraa {

struct TfqParams {
  float motionThreshold = 0.5f;   // px, mean L1 velocity difference over 3x3
  float colourThreshold = 0.04f;  // mean |luma difference| over 3x3, luma of 8-bit sRGB in [0, 1]
  float unsharp = 0.0f;           // 0: off
};

// What the resolve did with the N-1 half of a pixel (the "validity" layer's values).
enum class TfqValidity : std::uint8_t { NoHistory = 0, Accepted = 1, ColourLimited = 2, MotionRejected = 3 };

// The renderer's colour and velocity targets of the last frames, as the temporal passes read them.
class FrameRing {
 public:
  // Stores the frame (host side, the renderer's writes); a frame with index 0 or a new size
  // starts a new sequence.
  void Store(const FrameInputs& frame);
  int Frames() const { return frames_; }  // frames stored in this sequence, the current included
  const sim::Texture2D<glm::vec4>& Colour(int age) const;  // age 0 = N, 1 = N-1, 2 = N-2
  const sim::Texture2D<glm::vec2>& Velocity(int age) const;  // age 0 or 1
  bool PhaseB(int age) const;

 private:
  std::array<std::optional<sim::Texture2D<glm::vec4>>, 3> colour_;
  std::array<std::optional<sim::Texture2D<glm::vec2>>, 2> velocity_;
  std::array<bool, 3> phaseB_{};
  int frames_ = 0;
};

// The TFQ resolve on the machine; its instance keeps the frame ring.
class TfqStage {
 public:
  explicit TfqStage(const TfqParams& params) : params_(params) {}
  // Stores the frame and resolves it: the RGBA16F result (sharpened when unsharp > 0).
  const sim::Texture2D<glm::vec4>& Run(sim::Machine& machine, const FrameInputs& frame);
  const FrameRing& Ring() const { return ring_; }
  FrameRing& Ring() { return ring_; }
  PassLayer ValidityLayer() const;

 private:
  void Resolve(sim::Machine& machine, sim::Texture2D<glm::vec4>& out);
  void Unsharp(sim::Machine& machine, const sim::Texture2D<glm::vec4>& in, sim::Texture2D<glm::vec4>& out) const;

  TfqParams params_;
  FrameRing ring_;
  std::optional<sim::Texture2D<glm::vec4>> resolved_, sharpened_;
  std::vector<std::uint8_t> validity_;
};

inline constexpr std::string_view kTfqResolveDispatch = "tfq/resolve";
TfqParams TfqParamsOf(const PassSettings& settings);
std::vector<SettingInfo> TfqSettings();
// Every pixel of the screen as a work set (the full-screen passes' shape).
WorkSetShape FullScreenShape(int width, int height);

const PassInfo& TfqInfo();
std::unique_ptr<Pass> MakeTfq(const PassSettings& settings);

}  // namespace passes::hraa
