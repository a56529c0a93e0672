// Low-footprint velocity buffers (see velocity_buffer.h).

#include "study/velocity_buffer.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "sim/dispatch_inl.h"
#include "sim/formats.h"

namespace study {
namespace {

// The two pieces: |v| <= kFinePixels in kFineSteps steps, then up to the range in the rest.
constexpr float kFinePixels = 2.0f;
constexpr int kFineSteps = 64;
constexpr int kSteps = 127;  // codes 128 +- 127
constexpr float kFineStep = kFinePixels / kFineSteps;
constexpr float kCoarseStep = (kVelocityRangePixels - kFinePixels) / (kSteps - kFineSteps);

constexpr std::array<std::string_view, 3> kNames = {"float", "rg8", "rg8-half"};

int Steps(float magnitude) {
  if (magnitude <= kFinePixels) return static_cast<int>(std::lround(magnitude / kFineStep));
  return kFineSteps + static_cast<int>(std::lround((magnitude - kFinePixels) / kCoarseStep));
}

}  // namespace

std::string_view VelocityBufferName(VelocityBuffer buffer) { return kNames[static_cast<std::size_t>(buffer)]; }

std::vector<std::string> VelocityBufferNames() { return {kNames.begin(), kNames.end()}; }

std::optional<VelocityBuffer> VelocityBufferByName(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    if (kNames[i] == name) return static_cast<VelocityBuffer>(i);
  }
  return std::nullopt;
}

std::uint8_t EncodeVelocityComponent(float pixels) {
  const int steps = Steps(std::min(std::abs(pixels), kVelocityRangePixels));
  return static_cast<std::uint8_t>(pixels < 0.0f ? 128 - steps : 128 + steps);
}

float DecodeVelocityComponent(std::uint8_t code) {
  const int signedSteps = static_cast<int>(code) - 128;
  const int steps = std::min(std::abs(signedSteps), kSteps);
  const float magnitude = steps <= kFineSteps ? static_cast<float>(steps) * kFineStep
                                              : kFinePixels + static_cast<float>(steps - kFineSteps) * kCoarseStep;
  return signedSteps < 0 ? -magnitude : magnitude;
}

sim::Texture2D<glm::vec2> PackVelocity(sim::Machine& machine, VelocityBuffer buffer,
                                       const sim::Texture2D<glm::vec2>& velocity, const sim::Texture2D<float>& depth) {
  if (buffer == VelocityBuffer::Float) return velocity;
  const int width = velocity.Width(), height = velocity.Height();
  const int factor = buffer == VelocityBuffer::Rg8Half ? 2 : 1;
  const int packedWidth = (width + factor - 1) / factor, packedHeight = (height + factor - 1) / factor;
  sim::Texture2D<glm::vec2> packed("velocity " + std::string(VelocityBufferName(buffer)), packedWidth, packedHeight,
                                   sim::Format::RG8Unorm);
  sim::Dispatch dispatch("frame/velocity-pack", kVelocityPackKernel);
  const sim::TextureView<glm::vec2> in = dispatch.Read(velocity);
  const sim::TextureView<float> z = dispatch.Read(depth);
  const sim::RwTextureView<glm::vec2> out = dispatch.ReadWrite(packed);
  const sim::CounterView clamped = dispatch.Counter("velocity/clamped");
  machine.Compute(dispatch, {.threads = {packedWidth, packedHeight, 1}, .groupSize = {8, 8, 1}},
                  [&](sim::ComputeLane& lane) {
                    const int x0 = lane.threadId.x * factor, y0 = lane.threadId.y * factor;
                    // Half resolution keeps the block's front-most pixel (seed 000), the first on ties.
                    glm::ivec2 nearest{x0, y0};
                    float nearestDepth = z.Load(lane, x0, y0);
                    for (int dy = 0; dy < factor; ++dy) {
                      for (int dx = 0; dx < factor; ++dx) {
                        const int x = std::min(x0 + dx, width - 1), y = std::min(y0 + dy, height - 1);
                        if (dx + dy == 0) continue;
                        const float d = z.Load(lane, x, y);
                        if (d < nearestDepth) {
                          nearestDepth = d;
                          nearest = {x, y};
                        }
                      }
                    }
                    const glm::vec2 v = in.Load(lane, nearest.x, nearest.y);
                    if (std::abs(v.x) > kVelocityRangePixels || std::abs(v.y) > kVelocityRangePixels) clamped.Add(lane);
                    out.Store(lane, lane.threadId.x, lane.threadId.y,
                              glm::vec2(sim::Unorm8ToFloat(EncodeVelocityComponent(v.x)),
                                        sim::Unorm8ToFloat(EncodeVelocityComponent(v.y))));
                  });
  // What a pass's fetch decodes: counted at the packed buffer's 2 bytes a texel.
  sim::Texture2D<glm::vec2> decoded("velocity", width, height, 2);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec2 codes = packed.Get(x / factor, y / factor);
      decoded.At(x, y) = {DecodeVelocityComponent(sim::FloatToUnorm8(codes.x)),
                          DecodeVelocityComponent(sim::FloatToUnorm8(codes.y))};
    }
  }
  return decoded;
}

}  // namespace study
