#pragma once
// SMAAResolvePS (aa-facts §1.8) as a kernel, and the velocity target the reference reads.

#include <cmath>
#include <optional>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "passes/pass.h"
#include "passes/smaa/smaa_kernels.h"
#include "sim/views.h"

namespace passes::smaa {

// The reference's velocity target (smaa_temporal.h "Velocity"): FrameInputs::velocity (pixels,
// current - previous, +y down) divided by the frame size, stored RG16F by the renderer (host side,
// like the colour target) into `kept`. Throws std::invalid_argument when the frame has none.
const sim::Texture2D<glm::vec2>& StoreUvVelocity(const FrameInputs& frame, std::optional<sim::Texture2D<glm::vec2>>& kept,
                                                 const std::string& name, int width, int height);

// SMAA_REPROJECTION_WEIGHT_SCALE's default (SMAA.hlsl; aa-facts §1.8).
inline constexpr float kReprojectionWeightScale = 30.0f;

// The previous frame's weight from the packed velocity lengths a = sqrt(5 |v|):
// delta = |a_cur^2 - a_prev^2| / 5 (= ||v_cur| - |v_prev||), 0.5 * saturate(1 - sqrt(delta) * scale).
inline float ResolveWeight(float currentAlpha, float previousAlpha, float scale) {
  const float delta = std::fabs(currentAlpha * currentAlpha - previousAlpha * previousAlpha) / 5.0f;
  return 0.5f * Saturate(1.0f - std::sqrt(delta) * scale);
}

// HLSL lerp(x, y, s) = x + s (y - x) (the HLSL reference's definition).
inline glm::vec4 Lerp(const glm::vec4& x, const glm::vec4& y, float s) { return x + s * (y - x); }

class TemporalResolve {
 public:
  // current, previous: the two frames' SMAA outputs through sRGB views; velocity: UV units,
  // motion-blur convention, or none (no reprojection).
  TemporalResolve(const Metrics& metrics, sim::TextureView<glm::vec4> current, sim::TextureView<glm::vec4> previous,
                  std::optional<sim::TextureView<glm::vec2>> velocity, float weightScale)
      : metrics_(metrics), current_(std::move(current)), previous_(std::move(previous)),
        velocity_(std::move(velocity)), weightScale_(weightScale) {}

  [[gnu::always_inline]] glm::vec4 operator()(const sim::LaneBase& lane, int x, int y) const {
    const glm::vec2 uv = metrics_.Texcoord(x, y);
    if (!velocity_) return Lerp(current_.SamplePoint(lane, uv), previous_.SamplePoint(lane, uv), 0.5f);
    // "Velocity is assumed to be calculated for motion blur, so we need to inverse it."
    const glm::vec2 velocity = -velocity_->SamplePoint(lane, uv);
    const glm::vec4 current = current_.SamplePoint(lane, uv);
    const glm::vec4 previous = previous_.SamplePoint(lane, uv + velocity);
    return Lerp(current, previous, ResolveWeight(current.a, previous.a, weightScale_));
  }

 private:
  Metrics metrics_;
  sim::TextureView<glm::vec4> current_, previous_;
  std::optional<sim::TextureView<glm::vec2>> velocity_;
  float weightScale_;
};

}  // namespace passes::smaa
