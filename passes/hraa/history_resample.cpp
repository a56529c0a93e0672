// History resampling (see history_resample.h).

#include "passes/hraa/history_resample.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "passes/pass.h"
#include "sim/formats.h"

namespace passes::hraa {
namespace {

constexpr std::string_view kForwardDispatch = "hraa/forward";
constexpr std::string_view kBackwardDispatch = "hraa/backward";
constexpr std::string_view kCorrectDispatch = "hraa/correct";

constexpr sim::KernelInfo kProjectKernel{.vgprs = 12, .sgprs = 16, .ldsBytesPerGroup = 0,
                                         .valuInstructionsPerWave = 14,
                                         .source = "hand count: velocity load, uv = (p + 0.5 -+ v) / size, one "
                                                   "bilinear sample, store"};
constexpr sim::KernelInfo kCorrectKernel{.vgprs = 12, .sgprs = 16, .ldsBytesPerGroup = 0,
                                         .valuInstructionsPerWave = 10,
                                         .source = "hand count: two loads, H + (H - B) / 2 on four channels, store"};

// One projection pass: out(p) = in sampled at p + sign * v(p).
void Project(sim::Machine& machine, std::string_view name, const sim::Texture2D<glm::vec4>& in,
             const sim::Texture2D<glm::vec2>& velocity, float sign, sim::Texture2D<glm::vec4>& out) {
  const int width = in.Width(), height = in.Height();
  sim::Dispatch d(std::string(name), kProjectKernel);
  const sim::TextureView<glm::vec4> source = d.Read(in);
  const sim::TextureView<glm::vec2> motion = d.Read(velocity);
  const sim::RwTextureView<glm::vec4> target = d.ReadWrite(out);
  machine.FullScreen(d, {.width = width, .height = height}, [&](sim::PixelLane& lane) {
    const glm::vec2 at = glm::vec2(lane.x, lane.y) + sign * motion.Load(lane, lane.x, lane.y);
    target.Store(lane, lane.x, lane.y, source.SampleBilinear(lane, UvOf(at, width, height)));
  });
}

void Correct(sim::Machine& machine, const sim::Texture2D<glm::vec4>& history, const sim::Texture2D<glm::vec4>& back,
             sim::Texture2D<glm::vec4>& out) {
  sim::Dispatch d(std::string(kCorrectDispatch), kCorrectKernel);
  const sim::TextureView<glm::vec4> h = d.Read(history);
  const sim::TextureView<glm::vec4> b = d.Read(back);
  const sim::RwTextureView<glm::vec4> target = d.ReadWrite(out);
  machine.FullScreen(d, {.width = history.Width(), .height = history.Height()}, [&](sim::PixelLane& lane) {
    const glm::vec4 value = h.Load(lane, lane.x, lane.y);
    target.Store(lane, lane.x, lane.y, value + 0.5f * (value - b.Load(lane, lane.x, lane.y)));
  });
}

}  // namespace

std::string_view ResamplingName(Resampling mode) {
  switch (mode) {
    case Resampling::Bilinear: return "bilinear";
    case Resampling::MacCormack: return "maccormack";
    case Resampling::Bfecc: return "bfecc";
    case Resampling::GpuBfecc: return "gpu-bfecc";
  }
  return "?";
}

void HistoryResampler::Prepare(sim::Machine& machine, Resampling mode, const sim::Texture2D<glm::vec4>& history,
                               const sim::Texture2D<glm::vec2>& velocity) {
  if (mode == Resampling::Bilinear) return;
  const int width = history.Width(), height = history.Height();
  sim::Texture2D<glm::vec4>& forward = FrameTexture(forward_, "hraa/forward", width, height, sim::Format::RGBA16Float);
  Project(machine, kForwardDispatch, history, velocity, -1.0f, forward);
  if (mode == Resampling::GpuBfecc) return;
  sim::Texture2D<glm::vec4>& backward = FrameTexture(backward_, "hraa/backward", width, height, sim::Format::RGBA16Float);
  Project(machine, kBackwardDispatch, forward, velocity, 1.0f, backward);
  if (mode == Resampling::Bfecc) return;
  Correct(machine, history, backward, FrameTexture(corrected_, "hraa/corrected", width, height, sim::Format::RGBA16Float));
}

HistoryFetch HistoryResampler::Bind(sim::Dispatch& d, Resampling mode, const sim::Texture2D<glm::vec4>& history) const {
  HistoryFetch fetch{.mode = mode, .history = std::nullopt, .forward = std::nullopt, .backward = std::nullopt,
                     .corrected = std::nullopt, .width = history.Width(), .height = history.Height()};
  // Each form binds only what its last step reads.
  if (mode == Resampling::Bilinear || mode == Resampling::Bfecc) fetch.history = d.Read(history);
  if (mode == Resampling::Bfecc || mode == Resampling::GpuBfecc) fetch.forward = d.Read(*forward_);
  if (mode == Resampling::Bfecc) fetch.backward = d.Read(*backward_);
  if (mode == Resampling::MacCormack) fetch.corrected = d.Read(*corrected_);
  return fetch;
}

glm::vec4 HistoryFetch::operator()(const sim::LaneBase& lane, int x, int y, glm::vec2 v) const {
  const glm::vec2 previous = glm::vec2(x, y) - v;
  switch (mode) {
    case Resampling::Bilinear: return history->SampleBilinear(lane, UvOf(previous, width, height));
    case Resampling::MacCormack: return corrected->SampleBilinear(lane, UvOf(previous, width, height));
    case Resampling::Bfecc: {
      const glm::vec4 f = forward->Load(lane, x, y);
      return f + 0.5f * (history->Load(lane, x, y) - backward->Load(lane, x, y));
    }
    case Resampling::GpuBfecc: {
      // A(A^R(F))(p): the bilinear footprint of p - v (the weights of the view's float filter),
      // each of its texels j reprojected back by the pixel's own offset, F sampled at j + v.
      const glm::vec2 base = glm::floor(previous);
      const glm::vec2 f = previous - base;
      // Forced inline: called, GCC returned each vec4 through the stack.
      const auto back = [&](int dx, int dy) __attribute__((always_inline)) {
        const glm::vec2 j(std::clamp(static_cast<int>(base.x) + dx, 0, width - 1),
                          std::clamp(static_cast<int>(base.y) + dy, 0, height - 1));
        return forward->SampleBilinear(lane, UvOf(j + v, width, height));
      };
      const glm::vec4 top = back(0, 0) * (1.0f - f.x) + back(1, 0) * f.x;
      const glm::vec4 bottom = back(0, 1) * (1.0f - f.x) + back(1, 1) * f.x;
      const glm::vec4 twice = top * (1.0f - f.y) + bottom * f.y;
      const glm::vec4 once = forward->Load(lane, x, y);
      return once + 0.5f * (once - twice);
    }
  }
  return glm::vec4(0.0f);
}

}  // namespace passes::hraa
