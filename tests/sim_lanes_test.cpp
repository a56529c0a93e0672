// What a kernel sees on its lane: the wave's EXEC mask (pixel, compute and indirect waves),
// quad neighbours that are fully classified before any lane of the quad runs, and quad-neighbour
// derivatives of values computed in an earlier stage against closed-form gradients, helper lanes
// included, without re-running the loads behind them.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "raster_test_util.h"
#include "sim/dispatch.h"
#include "sim_test_util.h"

namespace sim {
namespace {

using raster::testing::ScreenToClip;

using sim::testing::TestMachine;

using sim::testing::SmallKernel;

constexpr std::uint64_t kAllLanes = ~std::uint64_t{0};

constexpr std::uint64_t LowLanes(int n) { return n >= 64 ? kAllLanes : (std::uint64_t{1} << n) - 1; }

// One kernel invocation as the lane saw it.
struct LaneRecord {
  std::uint64_t exec = 0;
  int lane = 0, quadInWave = 0, x = 0, y = 0;
  bool helper = false;
  const raster::QuadFragment* quad = nullptr;
};

// Splits a sequential invocation log into waves: a wave starts at a new quad in slot 0.
std::vector<std::vector<LaneRecord>> SplitIntoWaves(const std::vector<LaneRecord>& log) {
  std::vector<std::vector<LaneRecord>> waves;
  for (std::size_t i = 0; i < log.size(); ++i) {
    const bool starts = i == 0 || (log[i].quadInWave == 0 && log[i].quad != log[i - 1].quad);
    if (starts) waves.emplace_back();
    waves.back().push_back(log[i]);
  }
  return waves;
}

// Runs a full-screen PS with a checkerboard stencil on one host thread (so invocations are logged
// in wave order), checks every wave's EXEC mask against the lanes that actually ran and
// returns the waves.
std::vector<std::vector<LaneRecord>> CheckCheckerboardExec(int w, int h) {
  const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  Machine machine = TestMachine();
  StencilBuffer stencil("stencil", w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) stencil.Surface().SetStencil(x, y, static_cast<std::uint8_t>((x + y) % 2 == 0));
  }
  std::vector<LaneRecord> log;
  Dispatch d("test/checker-exec", SmallKernel());
  const DispatchReport& r = machine.FullScreen(d, {.width = w, .height = h, .stencil = &stencil}, [&](PixelLane& lane) {
    log.push_back({lane.exec, lane.lane, lane.quadInWave, lane.x, lane.y, lane.helper, lane.quad});
  });
  EXPECT_EQ(log.size(), r.lanes.lanesActive + r.lanes.lanesHelper);
  const std::vector<std::vector<LaneRecord>> waves = SplitIntoWaves(log);
  EXPECT_EQ(waves.size(), r.lanes.waves);
  const auto outside = [&](int x, int y) { return x >= w || y >= h; };
  for (const std::vector<LaneRecord>& wave : waves) {
    std::uint64_t ran = 0;
    for (const LaneRecord& record : wave) {
      EXPECT_EQ(record.exec, wave.front().exec) << "one mask per wave";
      ran |= std::uint64_t{1} << record.lane;
      // Helpers are exactly the pixels outside the target; inside it only passing pixels run.
      EXPECT_EQ(record.helper, outside(record.x, record.y)) << record.x << "," << record.y;
      if (!outside(record.x, record.y)) {
        EXPECT_EQ((record.x + record.y) % 2, 0);
      }
      // The quad's nibble: pixel p runs when it passes the checkerboard or lies outside.
      const int qx = record.x & ~1, qy = record.y & ~1;
      for (int p = 0; p < raster::kQuadPixels; ++p) {
        const int px = qx + (p & 1), py = qy + (p >> 1);
        const bool runs = outside(px, py) || (px + py) % 2 == 0;
        EXPECT_EQ((record.exec >> (record.quadInWave * 4 + p)) & 1U, runs ? 1U : 0U) << px << "," << py;
      }
    }
    EXPECT_EQ(wave.front().exec, ran);
    EXPECT_EQ(std::popcount(wave.front().exec), static_cast<int>(wave.size()));
  }
  return waves;
}

// Every coverage a quad can have (covered pixels, and the passed ones among them) under each
// pixel-shader kind: the three masks split the quad's pixels, and each pixel's kind follows the
// rule of hw-facts §6.1 and seed 000 "Stencil Culling Inefficiencies", stated here per pixel.
TEST(SimLanes, QuadLaneKindsSplitEveryCoverageByThePixelRule) {
  for (const DispatchKind kind : {DispatchKind::Draw, DispatchKind::FullScreen}) {
    for (unsigned covered = 0; covered < 16; ++covered) {
      for (unsigned passed = 0; passed < 16; ++passed) {
        if ((passed & ~covered) != 0) continue;
        raster::QuadFragment quad;
        for (int p = 0; p < raster::kQuadPixels; ++p) {
          quad.covered.SetPixel(p, (covered >> p & 1u) != 0 ? 1u : 0u);
          quad.passed.SetPixel(p, (passed >> p & 1u) != 0 ? 1u : 0u);
        }
        const QuadLaneKinds kinds = ClassifyQuad(quad, kind);
        SCOPED_TRACE(::testing::Message() << DispatchKindName(kind) << " covered " << covered << " passed " << passed);
        EXPECT_EQ(kinds.active | kinds.helper | kinds.deadStencil, 0xFu);
        EXPECT_EQ(kinds.active & kinds.helper, 0u);
        EXPECT_EQ(kinds.active & kinds.deadStencil, 0u);
        EXPECT_EQ(kinds.helper & kinds.deadStencil, 0u);
        for (int p = 0; p < raster::kQuadPixels; ++p) {
          const bool isPassed = (passed >> p & 1u) != 0, isCovered = (covered >> p & 1u) != 0;
          const LaneKind expected = isPassed                                          ? LaneKind::Active
                                    : isCovered && kind == DispatchKind::FullScreen ? LaneKind::DeadStencil
                                                                                    : LaneKind::Helper;
          EXPECT_EQ(kinds.Of(p), expected) << "pixel " << p;
        }
      }
    }
  }
}

TEST(SimLanes, PixelWaveExecIsTheCheckerboardOfRunningLanes) {
  // Whole waves: every quad runs pixels 0 and 3, so every wave's mask is 1001 repeated.
  const std::vector<std::vector<LaneRecord>> full = CheckCheckerboardExec(64, 32);
  EXPECT_EQ(full.size(), 64u * 32u / 64u);
  for (const std::vector<LaneRecord>& wave : full) {
    EXPECT_EQ(wave.size(), 32u);
    EXPECT_EQ(wave.front().exec, 0x9999999999999999u);
  }
  // Odd size: border quads add helpers outside the target and bins end in partial waves.
  CheckCheckerboardExec(45, 23);
}

TEST(SimLanes, QuadNeighboursAreClassifiedBeforeAnyLaneRuns) {
  const int w = 40, h = 30;
  const std::vector<glm::vec4> clip = {ScreenToClip(3.3, 2.1, 0.5, w, h), ScreenToClip(37.6, 9.8, 0.5, w, h),
                                       ScreenToClip(11.2, 27.9, 0.5, w, h)};
  const std::vector<std::uint32_t> indices = {0, 1, 2};
  raster::DrawState state;
  state.cull = raster::CullMode::None;
  raster::DepthStencilSurface depth = testing::FourSampleDepth(w, h);
  Machine machine = TestMachine();
  Dispatch d("test/neighbours", SmallKernel());
  // One slot per pixel: a single triangle's quads never overlap, so bins write disjoint slots.
  std::vector<int> helperMismatches(static_cast<std::size_t>(w * h), 0), execMismatches(static_cast<std::size_t>(w * h), 0);
  const DispatchReport& r =
      machine.Draw(d, {.input = {clip, indices, 0}, .state = state, .depth = &depth}, [&](PixelLane& lane) {
        const auto pixel = static_cast<std::size_t>(lane.y * w + lane.x);
        for (int q = 0; q < raster::kQuadPixels; ++q) {
          // A draw runs every pixel of a launched quad; the uncovered ones as helpers.
          helperMismatches[pixel] += lane.QuadLane(q).helper != (lane.quad->passed.Pixel(q) == 0);
          execMismatches[pixel] += ((lane.exec >> (lane.quadInWave * 4 + q)) & 1U) != 1U;
          execMismatches[pixel] += lane.QuadLane(q).exec != lane.exec;
        }
        return fmask::Colour{};
      });
  ASSERT_GT(r.lanes.lanesHelper, 0u);
  for (std::size_t pixel = 0; pixel < helperMismatches.size(); ++pixel) {
    EXPECT_EQ(helperMismatches[pixel], 0) << "pixel " << pixel % w << "," << pixel / w;
    EXPECT_EQ(execMismatches[pixel], 0) << "pixel " << pixel % w << "," << pixel / w;
  }
}

// Per thread: the EXEC mask its wave ran with, or 0 if it did not run.
std::vector<std::uint64_t> ComputeExec(Machine& machine, int threads, int groupSize) {
  std::vector<std::uint64_t> exec(static_cast<std::size_t>(threads), 0);
  Dispatch d("test/compute-exec", SmallKernel());
  machine.Compute(d, {.threads = {threads, 1, 1}, .groupSize = {groupSize, 1, 1}},
                  [&](ComputeLane& lane) { exec[static_cast<std::size_t>(lane.threadId.x)] = lane.exec; });
  return exec;
}

TEST(SimLanes, ComputeWaveExecHoldsTheThreadsInsideTheGrid) {
  Machine machine = TestMachine();
  // 100 threads in groups of 64: the second group's only wave has 36 threads.
  const std::vector<std::uint64_t> groups64 = ComputeExec(machine, 100, 64);
  for (int t = 0; t < 100; ++t) EXPECT_EQ(groups64[static_cast<std::size_t>(t)], t < 64 ? kAllLanes : LowLanes(36)) << t;
  // One group of 100: its second wave has 36 threads (local index = wave * 64 + lane).
  const std::vector<std::uint64_t> group100 = ComputeExec(machine, 100, 100);
  for (int t = 0; t < 100; ++t) EXPECT_EQ(group100[static_cast<std::size_t>(t)], t < 64 ? kAllLanes : LowLanes(36)) << t;
  // 2-D groups: 8x8 threads in a 12x10 grid; a wave of group (1, 1) holds its 4x2 in-grid threads.
  Dispatch d("test/compute-exec-2d", SmallKernel());
  std::vector<std::uint64_t> exec2d(120, 0);
  machine.Compute(d, {.threads = {12, 10, 1}, .groupSize = {8, 8, 1}}, [&](ComputeLane& lane) {
    exec2d[static_cast<std::size_t>(lane.threadId.y * 12 + lane.threadId.x)] = lane.exec;
  });
  std::uint64_t corner = 0;
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) corner |= std::uint64_t{1} << (y * 8 + x);
  }
  EXPECT_EQ(exec2d[0], kAllLanes);
  EXPECT_EQ(exec2d[9 * 12 + 11], corner);
}

TEST(SimLanes, IndirectWaveExecStopsAtTheItemCount) {
  Machine machine = TestMachine();
  for (const auto& [items, groupSize, groups] : {std::tuple{100u, 64, 2u}, std::tuple{130u, 128, 2u}}) {
    Buffer<std::uint32_t> args("args", 3);
    args.At(0) = groups;
    args.At(1) = 1;
    args.At(2) = 1;
    Buffer<std::uint32_t> count("count", 1);
    count.At(0) = items;
    std::vector<std::uint64_t> exec(static_cast<std::size_t>(groups) * static_cast<std::size_t>(groupSize), 0);
    Dispatch d("test/indirect-exec", SmallKernel());
    const DispatchReport& r = machine.ComputeIndirect(
        d, {.arguments = &args, .groupSize = {groupSize, 1, 1}, .itemCount = &count},
        [&](ComputeLane& lane) { exec[static_cast<std::size_t>(lane.threadId.x)] = lane.exec; });
    EXPECT_EQ(r.lanes.lanesActive, items);
    for (std::uint32_t t = 0; t < exec.size(); ++t) {
      std::uint64_t expected = 0;
      if (t < items) {
        const std::uint32_t waveStart = t / 64 * 64;
        expected = LowLanes(static_cast<int>(std::min<std::uint32_t>(64, items - waveStart)));
      }
      EXPECT_EQ(exec[t], expected) << items << " items, thread " << t;
    }
  }
}

TEST(SimLanes, FullScreenDerivativesOfThePixelCentreAreOnePixel) {
  Machine machine = TestMachine();
  for (const std::pair<int, int>& size : {std::pair{64, 32}, std::pair{13, 7}}) {
    const int w = size.first, h = size.second;
    std::vector<int> bad(static_cast<std::size_t>((w + 1) * (h + 1)), 0);
    std::vector<int> helperRuns(bad.size(), 0);
    Dispatch d("test/centre-derivatives", SmallKernel());
    const DispatchReport& r = machine.FullScreen(
        d, {.width = w, .height = h}, [](PixelLane& lane) { lane.Private<glm::vec2>() = lane.Centre(); },
        [&](PixelLane& lane) {
          const auto pixel = static_cast<std::size_t>(lane.y * (w + 1) + lane.x);
          bad[pixel] += lane.Ddx<glm::vec2>() != glm::vec2(1.0f, 0.0f);
          bad[pixel] += lane.Ddy<glm::vec2>() != glm::vec2(0.0f, 1.0f);
          bad[pixel] += lane.Ddx(&glm::vec2::y) != 0.0f;
          bad[pixel] += lane.Ddy(&glm::vec2::y) != 1.0f;
          helperRuns[pixel] += lane.helper;
        });
    int helpers = 0;
    for (std::size_t i = 0; i < bad.size(); ++i) {
      EXPECT_EQ(bad[i], 0) << w << "x" << h << " pixel " << i % (w + 1) << "," << i / (w + 1);
      helpers += helperRuns[i];
    }
    EXPECT_EQ(static_cast<std::uint64_t>(helpers), r.lanes.lanesHelper);
    if (w % 2 != 0) {
      EXPECT_GT(helpers, 0);
    }
  }
}

TEST(SimLanes, DerivativesExchangeValuesInsteadOfRerunningTheirLoads) {
  // A ramp 2x + 3y: the loaded values' derivatives are 2 and 3, and each lane loads once.
  const int w = 16, h = 8;
  Texture2D<float> ramp("ramp", w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) ramp.At(x, y) = static_cast<float>(2 * x + 3 * y);
  }
  Machine machine = TestMachine();
  Dispatch d("test/load-derivatives", SmallKernel());
  const TextureView<float> in = d.Read(ramp);
  int bad = 0;
  const DispatchReport r = machine.FullScreen(
      d, {.width = w, .height = h}, [&](PixelLane& lane) { lane.Private<float>() = in.Load(lane, lane.x, lane.y); },
      [&](PixelLane& lane) { bad += lane.Ddx<float>() != 2.0f || lane.Ddy<float>() != 3.0f; });
  EXPECT_EQ(bad, 0);
  EXPECT_EQ(r.lanes.lanesActive, static_cast<std::uint64_t>(w * h));
  EXPECT_EQ(r.resources[0].fetches, static_cast<std::uint64_t>(w * h));
}

TEST(SimLanes, DrawDerivativesOfAnInterpolatedAttributeMatchItsScreenGradient) {
  // w = 1 everywhere, so the attribute is affine in screen space. Vertices on the 1/256-pixel
  // snapping grid and a power-of-two target keep clip -> screen exact, so the rasterizer's
  // triangle is the one the gradient is computed from.
  const int w = 64, h = 64;
  const std::array<glm::dvec2, 3> p = {glm::dvec2(3.25, 2.5), glm::dvec2(57.75, 13.0), glm::dvec2(17.5, 60.25)};
  const std::array<float, 3> attribute = {1.0f, 7.0f, -3.0f};
  const std::vector<glm::vec4> clip = {ScreenToClip(p[0].x, p[0].y, 0.5, w, h), ScreenToClip(p[1].x, p[1].y, 0.5, w, h),
                                       ScreenToClip(p[2].x, p[2].y, 0.5, w, h)};
  const std::vector<std::uint32_t> indices = {0, 1, 2};
  // Plane through (x_i, y_i, a_i): Cramer's rule on the edge vectors from vertex 0.
  const glm::dvec2 e1 = p[1] - p[0], e2 = p[2] - p[0];
  const double da1 = static_cast<double>(attribute[1] - attribute[0]);
  const double da2 = static_cast<double>(attribute[2] - attribute[0]);
  const double det = e1.x * e2.y - e2.x * e1.y;
  const double gradX = (da1 * e2.y - da2 * e1.y) / det;
  const double gradY = (e1.x * da2 - e2.x * da1) / det;
  // Float barycentrics are good to ~1e-7 relative; times |a| <= 7 and differenced, the error
  // stays below 2e-6. 1e-5 leaves margin and is still far below the gradients (~0.1-0.2).
  constexpr double kTolerance = 1e-5;

  raster::DrawState state;
  state.cull = raster::CullMode::None;
  raster::DepthStencilSurface depth = testing::FourSampleDepth(w, h);
  Machine machine = TestMachine();
  Dispatch d("test/attribute-derivatives", SmallKernel());
  std::vector<float> ddx(static_cast<std::size_t>(w * h), NAN), ddy(ddx.size(), NAN);
  std::vector<std::uint8_t> helper(ddx.size(), 0);
  const DispatchReport& r = machine.Draw(
      d, {.input = {clip, indices, 0}, .state = state, .depth = &depth},
      [&](PixelLane& lane) {
        const std::array<float, 3> b = lane.Barycentrics();
        lane.Private<float>() = b[0] * attribute[0] + b[1] * attribute[1] + b[2] * attribute[2];
      },
      [&](PixelLane& lane) {
        const auto pixel = static_cast<std::size_t>(lane.y * w + lane.x);
        ddx[pixel] = lane.Ddx<float>();
        ddy[pixel] = lane.Ddy<float>();
        helper[pixel] = lane.helper;
        return fmask::Colour{};
      });
  std::uint64_t checked = 0, helpersChecked = 0;
  for (std::size_t pixel = 0; pixel < ddx.size(); ++pixel) {
    if (std::isnan(ddx[pixel])) continue;
    ++checked;
    helpersChecked += helper[pixel];
    EXPECT_NEAR(ddx[pixel], gradX, kTolerance) << "pixel " << pixel % w << "," << pixel / w;
    EXPECT_NEAR(ddy[pixel], gradY, kTolerance) << "pixel " << pixel % w << "," << pixel / w;
  }
  EXPECT_EQ(checked, r.lanes.lanesActive + r.lanes.lanesHelper);
  EXPECT_EQ(helpersChecked, r.lanes.lanesHelper);
  EXPECT_GT(helpersChecked, 0u);
}

}  // namespace
}  // namespace sim
