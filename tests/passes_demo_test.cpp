// The demonstration post pass: both dispatch strategies against a slow host reference of the
// same arithmetic, and the lane accounting that distinguishes them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "passes/demo/demo.h"
#include "passes/registry.h"
#include "raster_test_util.h"

namespace passes {
namespace {

sim::Texture2D<glm::vec4> Rectangles(int w, int h, std::uint64_t seed) {
  sim::Texture2D<glm::vec4> image("input", w, h, 4, glm::vec4(0.1f, 0.1f, 0.1f, 1.0f));
  raster::testing::Random rng(seed);
  for (int i = 0; i < 12; ++i) {
    const int x0 = rng.Int(0, w - 1), y0 = rng.Int(0, h - 1);
    const int x1 = std::min(w, x0 + rng.Int(1, w / 2)), y1 = std::min(h, y0 + rng.Int(1, h / 2));
    const glm::vec4 c(static_cast<float>(rng.Uniform(0, 1)), static_cast<float>(rng.Uniform(0, 1)),
                      static_cast<float>(rng.Uniform(0, 1)), 1.0f);
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) image.At(x, y) = c;
    }
  }
  return image;
}

PassOutput RunDemo(sim::Machine& machine, const sim::Texture2D<glm::vec4>& input, Strategy strategy) {
  const std::unique_ptr<Pass> pass = demo::Make(PassSettings("demo", demo::Info().settings));
  return pass->Run(machine, FrameInputs{.colour = &input}, strategy);
}

float EdgeAt(const PassOutput& output, int x, int y) {
  const PassLayer& edges = output.layers.at(0);
  return edges.Floats().at(static_cast<std::size_t>(y) * static_cast<std::size_t>(edges.width) + static_cast<std::size_t>(x));
}

// Slow host reference of the same rule, written without the machine.
float RefLuma(const glm::vec4& c) {
  auto srgb = [](float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  };
  return 0.2126f * srgb(c.r) + 0.7152f * srgb(c.g) + 0.0722f * srgb(c.b);
}

TEST(PassesDemo, BothStrategiesMatchTheHostReference) {
  const int w = 67, h = 45;  // not multiples of 8: partial groups and partial quads
  const sim::Texture2D<glm::vec4> input = Rectangles(w, h, 11);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const PassOutput stencil = RunDemo(machine, input, Strategy::StencilCulled);
  const PassOutput queue = RunDemo(machine, input, Strategy::DeferredQueue);
  auto at = [&](int x, int y) { return input.At(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1)); };
  std::uint64_t edges = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float l = RefLuma(at(x, y));
      float delta = 0.0f;
      for (const auto& [dx, dy] : {std::pair{-1, 0}, std::pair{0, -1}, std::pair{1, 0}, std::pair{0, 1}}) {
        delta = std::max(delta, std::fabs(l - RefLuma(at(x + dx, y + dy))));
      }
      const bool edge = delta >= 0.1f;
      edges += edge;
      glm::vec4 expected = at(x, y);
      if (edge) {
        glm::vec4 sum(0.0f);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) sum += at(x + dx, y + dy);
        }
        expected = sum / 9.0f;
      }
      ASSERT_EQ(EdgeAt(stencil, x, y), edge ? 1.0f : 0.0f) << x << "," << y;
      ASSERT_EQ(EdgeAt(queue, x, y), edge ? 1.0f : 0.0f) << x << "," << y;
      for (int c = 0; c < 4; ++c) {
        ASSERT_NEAR(stencil.colour.At(x, y)[c], expected[c], 1e-6f) << x << "," << y;
        ASSERT_EQ(stencil.colour.At(x, y)[c], queue.colour.At(x, y)[c]) << x << "," << y;
      }
    }
  }
  EXPECT_GT(edges, 100u);
  EXPECT_EQ(stencil.workItems, edges);
  EXPECT_EQ(queue.workItems, edges);
}

TEST(PassesDemo, QueueBlendUsesALanePerEdgeWhileTheStencilPassWastesQuadLanes) {
  const int w = 128, h = 96;
  const sim::Texture2D<glm::vec4> input = Rectangles(w, h, 5);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const PassOutput stencil = RunDemo(machine, input, Strategy::StencilCulled);
  const PassOutput queue = RunDemo(machine, input, Strategy::DeferredQueue);
  const std::vector<sim::DispatchReport>& reports = machine.Reports();
  ASSERT_EQ(reports.size(), 2u + 3u);
  const sim::LaneCounters& ps = reports[1].lanes;
  const sim::LaneCounters& cs = reports[4].lanes;
  EXPECT_EQ(reports[1].name, "demo/blend");
  EXPECT_EQ(reports[4].kind, sim::DispatchKind::IndirectCompute);
  EXPECT_EQ(ps.lanesActive, stencil.workItems);
  EXPECT_EQ(cs.lanesActive, queue.workItems);
  EXPECT_EQ(cs.waves, (queue.workItems + 63) / 64);
  EXPECT_GT(ps.lanesDeadStencil, 0u);
  EXPECT_GT(ps.lanesLaunched, cs.lanesLaunched);
  EXPECT_GT(ps.tilesHiStencilCulled, 0u);
  // The first pass of the stencil strategy is a full-screen pass with every lane active.
  EXPECT_EQ(reports[0].lanes.lanesActive, static_cast<std::uint64_t>(w) * h);
  // The queue's edge detection reads a 10x10 luma tile per 8x8 group through LDS.
  EXPECT_EQ(reports[2].lanes.ldsBytesWritten, (w / 8) * (h / 8) * 100u * 4u);
}

TEST(PassesDemo, RefusesAThresholdOutsideItsRange) {
  EXPECT_THROW(ResolvePass("demo:threshold=0"), SettingsError);
  EXPECT_THROW(ResolvePass("demo:threshold=nan"), SettingsError);
  EXPECT_THROW(ResolvePass("demo:threshold=1.5"), SettingsError);
  EXPECT_EQ(ResolvePass("demo:threshold=1").settings.Get("threshold"), 1.0);
}

TEST(PassesDemo, AHigherThresholdFindsFewerEdges) {
  const sim::Texture2D<glm::vec4> input = Rectangles(64, 48, 3);
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  auto edges = [&](const char* spec) {
    return ResolvePass(spec).Make()->Run(machine, FrameInputs{.colour = &input}, Strategy::DeferredQueue).workItems;
  };
  EXPECT_GT(edges("demo:threshold=0.05"), edges("demo:threshold=0.5"));
}

}  // namespace
}  // namespace passes
