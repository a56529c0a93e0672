// Demonstration post pass under both dispatch strategies (see demo_edge_blend.h).

#include "passes/demo_edge_blend.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace passes {

namespace {

using sim::ComputeLane;
using sim::PixelLane;

// Estimates for the timing model (VALU instructions per wave), not compiled shaders.
constexpr sim::KernelInfo kEdgePixelKernel{.vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0,
                                           .valuInstructionsPerWave = 40};
constexpr int kGroupSide = 8;
constexpr int kTileSide = kGroupSide + 2;  // one-pixel apron, as the MiniEngine FXAA luma cache (aa-facts §3)
constexpr sim::KernelInfo kEdgeComputeKernel{.vgprs = 16, .sgprs = 24,
                                             .ldsBytesPerGroup = kTileSide * kTileSide * 4,
                                             .valuInstructionsPerWave = 48};
constexpr sim::KernelInfo kQueueArgumentsKernel{.vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0,
                                                .valuInstructionsPerWave = 8};
constexpr sim::KernelInfo kBlendKernel{.vgprs = 20, .sgprs = 16, .ldsBytesPerGroup = 0,
                                       .valuInstructionsPerWave = 48};

float EncodeSrgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// aa-facts §1.3: SMAA's luma edge detection weights gamma-encoded colour by Rec. 709.
float Luma(const glm::vec4& linear) {
  return 0.2126f * EncodeSrgb(linear.r) + 0.7152f * EncodeSrgb(linear.g) + 0.0722f * EncodeSrgb(linear.b);
}

// Left, top, right, bottom: the same order in both strategies keeps the results bit-identical.
bool IsEdge(float centre, float left, float top, float right, float bottom, float threshold) {
  const float delta = std::max(std::max(std::fabs(centre - left), std::fabs(centre - top)),
                               std::max(std::fabs(centre - right), std::fabs(centre - bottom)));
  return delta >= threshold;
}

template <typename Load>
glm::vec4 BoxBlend3x3(Load&& load, int x, int y, int width, int height) {
  glm::vec4 sum(0.0f);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) sum += load(std::clamp(x + dx, 0, width - 1), std::clamp(y + dy, 0, height - 1));
  }
  return sum / 9.0f;
}

std::uint32_t PackPixel(int x, int y) { return static_cast<std::uint32_t>(y) << 16 | static_cast<std::uint32_t>(x); }

class DemoPass {
 public:
  DemoPass(sim::Machine& machine, const sim::Texture2D<glm::vec4>& colour, float threshold, DemoEdgeBlendResult& result)
      : machine_(machine), colour_(colour), threshold_(threshold), result_(result),
        width_(colour.Width()), height_(colour.Height()) {}

  void RunStencilCulled() {
    sim::StencilBuffer stencil("demo/stencil", width_, height_);
    {
      sim::Dispatch d("demo/edge-detect", kEdgePixelKernel);
      const sim::TextureView<glm::vec4> in = d.Read(colour_);
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(result_.output);
      const sim::RwTextureView<float> edges = d.ReadWrite(result_.edges);
      const sim::StencilView stencilOut = d.Stencil(stencil);
      Record(machine_.FullScreen(d, {.width = width_, .height = height_}, [&](PixelLane& lane) {
        auto luma = [&](int x, int y) { return Luma(in.Load(lane, ClampX(x), ClampY(y))); };
        const int x = lane.x, y = lane.y;
        const glm::vec4 centre = in.Load(lane, x, y);
        const bool edge = IsEdge(Luma(centre), luma(x - 1, y), luma(x, y - 1), luma(x + 1, y), luma(x, y + 1), threshold_);
        out.Store(lane, x, y, centre);
        edges.Store(lane, x, y, edge ? 1.0f : 0.0f);
        if (edge) stencilOut.Store(lane, 1);
      }));
    }
    sim::Dispatch d("demo/blend", kBlendKernel);
    const sim::TextureView<glm::vec4> in = d.Read(colour_);
    const sim::RwTextureView<glm::vec4> out = d.ReadWrite(result_.output);
    Record(machine_.FullScreen(d, {.width = width_, .height = height_, .stencil = &stencil}, [&](PixelLane& lane) {
      auto load = [&](int x, int y) { return in.Load(lane, x, y); };
      out.Store(lane, lane.x, lane.y, BoxBlend3x3(load, lane.x, lane.y, width_, height_));
    }));
  }

  void RunDeferredQueue() {
    // Every pixel may be an edge: a full-size queue cannot overflow.
    sim::AppendBuffer<std::uint32_t> queue("demo/queue", static_cast<std::size_t>(width_) * height_);
    sim::Buffer<std::uint32_t> arguments("demo/dispatch-args", 3);
    DetectIntoQueue(queue);
    {
      sim::Dispatch d("demo/queue-args", kQueueArgumentsKernel);
      const sim::BufferView<std::uint32_t> count = d.Read(queue.Counter());
      const sim::RwBufferView<std::uint32_t> args = d.ReadWrite(arguments);
      Record(machine_.Compute(d, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}}, [&](ComputeLane& lane) {
        const std::uint32_t n = count.Load(lane, 0);
        args.Store(lane, 0, (n + sim::kWaveLanes - 1) / sim::kWaveLanes);
        args.Store(lane, 1, 1);
        args.Store(lane, 2, 1);
      }));
    }
    sim::Dispatch d("demo/blend", kBlendKernel);
    const sim::BufferView<std::uint32_t> items = d.Read(queue.Storage());
    const sim::TextureView<glm::vec4> in = d.Read(colour_);
    const sim::RwTextureView<glm::vec4> out = d.ReadWrite(result_.output);
    sim::IndirectCall call{.arguments = &arguments, .offset = 0, .groupSize = {sim::kWaveLanes, 1, 1},
                           .itemCount = &queue.Counter(), .itemCountIndex = 0};
    d.SetPixelGrid(width_, height_);
    Record(machine_.ComputeIndirect(d, call, [&](ComputeLane& lane) {
      const std::uint32_t item = items.Load(lane, static_cast<std::size_t>(lane.threadId.x));
      const int x = static_cast<int>(item & 0xFFFFu), y = static_cast<int>(item >> 16);
      lane.AttributeTo(x, y);
      auto load = [&](int px, int py) { return in.Load(lane, px, py); };
      out.Store(lane, x, y, BoxBlend3x3(load, x, y, width_, height_));
    }));
  }

 private:
  int ClampX(int x) const { return std::clamp(x, 0, width_ - 1); }
  int ClampY(int y) const { return std::clamp(y, 0, height_ - 1); }

  // 8x8 groups cover the image in whole groups so every thread helps fill the LDS tile; threads
  // past the image edge skip the second stage's work.
  void DetectIntoQueue(sim::AppendBuffer<std::uint32_t>& queue) {
    sim::Dispatch d("demo/edge-detect", kEdgeComputeKernel);
    const sim::TextureView<glm::vec4> in = d.Read(colour_);
    const sim::RwTextureView<glm::vec4> out = d.ReadWrite(result_.output);
    const sim::RwTextureView<float> edges = d.ReadWrite(result_.edges);
    const sim::AppendView<std::uint32_t> append = d.Append(queue);
    d.SetPixelGrid(width_, height_);
    const glm::ivec3 threads{RoundUp(width_), RoundUp(height_), 1};
    auto fillTile = [&](ComputeLane& lane) {
      for (int entry = lane.localIndex; entry < kTileSide * kTileSide; entry += kGroupSide * kGroupSide) {
        const int x = lane.groupId.x * kGroupSide + entry % kTileSide - 1;
        const int y = lane.groupId.y * kGroupSide + entry / kTileSide - 1;
        lane.LdsStore<float>(static_cast<std::size_t>(entry), Luma(in.Load(lane, ClampX(x), ClampY(y))));
      }
    };
    auto detect = [&](ComputeLane& lane) {
      const int x = lane.threadId.x, y = lane.threadId.y;
      if (x >= width_ || y >= height_) return;
      auto luma = [&](int dx, int dy) {
        return lane.LdsLoad<float>(static_cast<std::size_t>((lane.localId.y + 1 + dy) * kTileSide + lane.localId.x + 1 + dx));
      };
      const bool edge = IsEdge(luma(0, 0), luma(-1, 0), luma(0, -1), luma(1, 0), luma(0, 1), threshold_);
      out.Store(lane, x, y, in.Load(lane, x, y));
      edges.Store(lane, x, y, edge ? 1.0f : 0.0f);
      if (edge) append.Append(lane, PackPixel(x, y));
    };
    Record(machine_.Compute(d, {.threads = threads, .groupSize = {kGroupSide, kGroupSide, 1}}, fillTile, detect));
  }

  static int RoundUp(int n) { return (n + kGroupSide - 1) / kGroupSide * kGroupSide; }

  void Record(const sim::DispatchReport& report) { result_.dispatches.push_back(report); }

  sim::Machine& machine_;
  const sim::Texture2D<glm::vec4>& colour_;
  float threshold_;
  DemoEdgeBlendResult& result_;
  int width_, height_;
};

}  // namespace

std::string_view StrategyName(Strategy strategy) {
  return strategy == Strategy::StencilCulled ? "stencil" : "queue";
}

DemoEdgeBlendResult RunDemoEdgeBlend(sim::Machine& machine, const sim::Texture2D<glm::vec4>& colour,
                                     Strategy strategy, const DemoEdgeBlendSettings& settings) {
  if (!(settings.threshold > 0.0f && settings.threshold <= 1.0f)) {
    throw std::invalid_argument("demo edge blend: threshold " + std::to_string(settings.threshold) +
                                " outside (0, 1]");
  }
  DemoEdgeBlendResult result{sim::Texture2D<glm::vec4>("demo/output", colour.Width(), colour.Height(), 4),
                             sim::Texture2D<float>("demo/edges", colour.Width(), colour.Height(), 1), 0, {}};
  DemoPass pass(machine, colour, settings.threshold, result);
  if (strategy == Strategy::StencilCulled) {
    pass.RunStencilCulled();
  } else {
    pass.RunDeferredQueue();
  }
  for (const float e : result.edges.Texels()) result.edgePixels += e != 0.0f;
  return result;
}

}  // namespace passes
