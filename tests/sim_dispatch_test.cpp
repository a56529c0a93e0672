// The machine's closed-form cases (issue "The machine"): indirect dispatch utilization, full-screen
// passes with and without stencil, hi-stencil tiles, helper lanes against a brute-force count,
// wave packing rules, compute groups with LDS and barriers, traffic accounting and determinism.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "raster_test_util.h"
#include "sim/dispatch.h"
#include "sim_test_util.h"

namespace sim {
namespace {

using raster::testing::ScreenToClip;

using sim::testing::TestMachine;

using sim::testing::SmallKernel;

std::uint64_t Ceil64(std::uint64_t n) { return (n + 63) / 64; }

// Appends N items with a compute pass, turns the counter into dispatch arguments with a
// one-thread kernel, then consumes the queue indirectly: the deferred-queue shape of seed 000.
struct QueueRun {
  DispatchReport append, arguments, consume;
  std::vector<std::uint32_t> consumed;
};

QueueRun RunQueue(Machine& machine, int items) {
  AppendBuffer<std::uint32_t> queue("queue", 4096);
  Buffer<std::uint32_t> args("args", 3);
  Buffer<std::uint32_t> seen("seen", 4096, 4, 0xFFFFFFFFu);
  QueueRun run;
  {
    Dispatch d("test/append", SmallKernel());
    const AppendView<std::uint32_t> out = d.Append(queue);
    run.append = machine.Compute(d, {.threads = {items, 1, 1}, .groupSize = {64, 1, 1}},
                                 [&](ComputeLane& lane) { out.Append(lane, static_cast<std::uint32_t>(lane.threadId.x)); });
  }
  {
    Dispatch d("test/arguments", SmallKernel());
    const BufferView<std::uint32_t> count = d.Read(queue.Counter());
    const RwBufferView<std::uint32_t> argsOut = d.ReadWrite(args);
    run.arguments = machine.Compute(d, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}}, [&](ComputeLane& lane) {
      const std::uint32_t n = count.Load(lane, 0);
      argsOut.Store(lane, 0, (n + 63) / 64);
      argsOut.Store(lane, 1, 1);
      argsOut.Store(lane, 2, 1);
    });
  }
  {
    Dispatch d("test/consume", SmallKernel());
    const BufferView<std::uint32_t> in = d.Read(queue.Storage());
    const RwBufferView<std::uint32_t> out = d.ReadWrite(seen);
    run.consume = machine.ComputeIndirect(
        d, {.arguments = &args, .offset = 0, .groupSize = {64, 1, 1}, .itemCount = &queue.Counter()},
        [&](ComputeLane& lane) {
          const auto i = static_cast<std::size_t>(lane.threadId.x);
          out.Store(lane, i, in.Load(lane, i));
        });
  }
  run.consumed.assign(seen.Elements().begin(), seen.Elements().begin() + items);
  return run;
}

TEST(SimDispatch, IndirectDispatchLaunchesCeilNOver64Waves) {
  Machine machine = TestMachine();
  for (const int n : {0, 1, 2, 63, 64, 65, 127, 1000, 4096}) {
    const QueueRun run = RunQueue(machine, n);
    const LaneCounters& c = run.consume.lanes;
    const std::uint64_t waves = Ceil64(static_cast<std::uint64_t>(n));
    EXPECT_EQ(c.waves, waves) << n;
    EXPECT_EQ(c.lanesLaunched, 64 * waves) << n;
    EXPECT_EQ(c.lanesActive, static_cast<std::uint64_t>(n)) << n;
    EXPECT_EQ(c.lanesDeadEmpty, 64 * waves - static_cast<std::uint64_t>(n)) << n;
    EXPECT_EQ(c.lanesHelper + c.lanesDeadStencil, 0u);
    // Every item consumed exactly once, in the (deterministic) append order.
    for (int i = 0; i < n; ++i) ASSERT_EQ(run.consumed[static_cast<std::size_t>(i)], static_cast<std::uint32_t>(i));
    // The argument kernel is one thread: one wave with a single active lane.
    EXPECT_EQ(run.arguments.lanes.waves, 1u);
    EXPECT_EQ(run.arguments.lanes.wavesByActiveLanes[1], 1u);
    EXPECT_EQ(run.append.resources[1].atomics, static_cast<std::uint64_t>(n));  // the hidden counter
    // The command processor's argument read and the per-wave count loads touch one line each.
    for (const ResourceTraffic& traffic : run.consume.resources) {
      if (traffic.name == "args" || traffic.name == "queue/counter") {
        EXPECT_EQ(traffic.linesRead, 1u) << traffic.name;
      }
    }
    EXPECT_EQ(run.consume.resources.size(), 4u);
  }
}

TEST(SimDispatch, FullScreenWithoutStencilUsesEveryLaneAtMultipleOfEight) {
  Machine machine = TestMachine();
  for (const auto& [w, h] : {std::pair{64, 48}, std::pair{1920, 1080}, std::pair{8, 8}}) {
    Dispatch d("test/fullscreen", SmallKernel());
    const DispatchReport& r = machine.FullScreen(d, {.width = w, .height = h}, [](PixelLane&) {});
    const auto pixels = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
    EXPECT_EQ(r.lanes.lanesActive, pixels);
    EXPECT_EQ(r.lanes.lanesLaunched, pixels);
    EXPECT_EQ(r.lanes.waves, pixels / 64);
    EXPECT_EQ(r.lanes.wavesByActiveLanes[64], pixels / 64);
    EXPECT_EQ(r.lanes.quadsByLivePixels[4], pixels / 4);
  }
}

TEST(SimDispatch, FullScreenAtOddSizeRunsHelpersOutsideTheTarget) {
  Machine machine = TestMachine();
  Dispatch d("test/odd", SmallKernel());
  int kernelRuns = 0, helperRuns = 0;
  const DispatchReport& r = machine.FullScreen(d, {.width = 13, .height = 7}, [&](PixelLane& lane) {
    ++kernelRuns;
    helperRuns += lane.helper;
  });
  EXPECT_EQ(r.lanes.lanesActive, 91u);
  EXPECT_EQ(r.lanes.quadsLaunched, 7u * 4u);
  EXPECT_EQ(r.lanes.lanesHelper, 7u * 4u * 4u - 91u);
  EXPECT_EQ(static_cast<std::uint64_t>(kernelRuns), r.lanes.lanesActive + r.lanes.lanesHelper);
  EXPECT_EQ(static_cast<std::uint64_t>(helperRuns), r.lanes.lanesHelper);
}

TEST(SimDispatch, CheckerboardStencilHalvesActiveLanesWithEveryQuadLive) {
  Machine machine = TestMachine();
  const int w = 64, h = 32;
  StencilBuffer stencil("stencil", w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) stencil.Surface().SetStencil(x, y, static_cast<std::uint8_t>((x + y) % 2 == 0));
  }
  Dispatch d("test/checker", SmallKernel());
  const DispatchReport& r = machine.FullScreen(d, {.width = w, .height = h, .stencil = &stencil}, [](PixelLane&) {});
  const std::uint64_t pixels = w * h;
  EXPECT_EQ(r.lanes.lanesActive, pixels / 2);
  EXPECT_EQ(r.lanes.lanesDeadStencil, pixels / 2);
  EXPECT_EQ(r.lanes.lanesLaunched, pixels);
  EXPECT_EQ(r.lanes.quadsByLivePixels[2], pixels / 4);
  EXPECT_EQ(r.lanes.quadsCulled, 0u);
  EXPECT_EQ(r.lanes.tilesHiStencilCulled, 0u);
  for (int ty = 0; ty < r.heat.TilesY(); ++ty) {
    for (int tx = 0; tx < r.heat.TilesX(); ++tx) EXPECT_FLOAT_EQ(r.heat.Utilization(tx, ty), 0.5f);
  }
  // The DB read one stencil byte per pixel.
  ASSERT_EQ(r.resources.size(), 1u);
  EXPECT_EQ(r.resources[0].bytesRead, pixels);
}

TEST(SimDispatch, WholeTileStencilHasNoDeadLanesAndHiStencilCullsTheRest) {
  Machine machine = TestMachine();
  const int w = 64, h = 48;
  StencilBuffer stencil("stencil", w, h);
  int passingTiles = 0;
  for (int ty = 0; ty < h / 8; ++ty) {
    for (int tx = 0; tx < w / 8; ++tx) {
      const bool pass = (tx + 2 * ty) % 3 == 0;
      passingTiles += pass;
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) stencil.Surface().SetStencil(tx * 8 + x, ty * 8 + y, pass ? 1 : 0);
      }
    }
  }
  Dispatch d("test/tiles", SmallKernel());
  const DispatchReport& r = machine.FullScreen(d, {.width = w, .height = h, .stencil = &stencil}, [](PixelLane&) {});
  const int tiles = (w / 8) * (h / 8);
  EXPECT_EQ(r.lanes.lanesDeadStencil, 0u);
  EXPECT_EQ(r.lanes.lanesDeadEmpty, 0u);
  EXPECT_EQ(r.lanes.lanesActive, static_cast<std::uint64_t>(passingTiles) * 64);
  EXPECT_EQ(r.lanes.tilesHiStencilCulled, static_cast<std::uint64_t>(tiles - passingTiles));
  EXPECT_EQ(r.lanes.quadsCulled, 0u);
  // Without the pretest the same pass forms and culls the quads one by one.
  Dispatch noHi("test/tiles-no-histencil", SmallKernel());
  const DispatchReport& r2 =
      machine.FullScreen(noHi, {.width = w, .height = h, .stencil = &stencil, .hiStencil = false}, [](PixelLane&) {});
  EXPECT_EQ(r2.lanes.tilesHiStencilCulled, 0u);
  EXPECT_EQ(r2.lanes.quadsCulled, static_cast<std::uint64_t>(tiles - passingTiles) * 16);
  EXPECT_EQ(r2.lanes.lanesActive, r.lanes.lanesActive);
}

TEST(SimDispatch, HelperLanesOfASingleTriangleMatchABruteForceCount) {
  const int w = 40, h = 30;
  const std::vector<glm::vec4> clip = {ScreenToClip(3.3, 2.1, 0.5, w, h), ScreenToClip(37.6, 9.8, 0.5, w, h),
                                       ScreenToClip(11.2, 27.9, 0.5, w, h)};
  const std::vector<std::uint32_t> indices = {0, 1, 2};
  raster::DrawState state;
  state.cull = raster::CullMode::None;
  raster::DepthStencilSurface depth = testing::FourSampleDepth(w, h);
  const raster::SamplePattern& pattern = depth.Pattern();
  const raster::testing::ReferenceResult ref =
      raster::testing::ReferenceRasterize({clip, indices, 0}, state, pattern, w, h);
  std::uint64_t covered = 0, helpers = 0;
  for (int qy = 0; qy < h; qy += 2) {
    for (int qx = 0; qx < w; qx += 2) {
      int live = 0;
      for (int p = 0; p < 4; ++p) {
        const int x = qx + (p & 1), y = qy + (p >> 1);
        bool any = false;
        for (int s = 0; s < 4; ++s) any |= ref.passed[(static_cast<std::size_t>(y) * w + x) * 4 + s] > 0;
        live += any;
      }
      covered += static_cast<std::uint64_t>(live);
      if (live > 0) helpers += static_cast<std::uint64_t>(4 - live);
    }
  }
  Machine machine = TestMachine();
  Dispatch d("test/triangle", SmallKernel());
  const DispatchReport& r = machine.Draw(d, {.input = {clip, indices, 0}, .state = state, .depth = &depth},
                                         [](PixelLane&) { return fmask::Colour{}; });
  EXPECT_GT(helpers, 0u);
  EXPECT_EQ(r.lanes.lanesActive, covered);
  EXPECT_EQ(r.lanes.lanesHelper, helpers);
  // Waves never span 32x32 bins, so each bin's last wave may be partial.
  EXPECT_GE(r.lanes.waves, Ceil64(4 * r.lanes.quadsLaunched));
  EXPECT_EQ(r.lanes.lanesDeadEmpty, 64 * r.lanes.waves - 4 * r.lanes.quadsLaunched);
  EXPECT_EQ(r.lanes.wavesByPrimitives[1], r.lanes.waves);
}

raster::QuadFragment LiveQuad(std::uint32_t primitive, int livePixels) {
  raster::QuadFragment quad;
  quad.primitiveId = primitive;
  for (int p = 0; p < livePixels; ++p) quad.passed.SetPixel(p, 1);
  quad.covered = quad.passed;
  return quad;
}

TEST(SimDispatch, WavePackingMixesPrimitivesUnlessTheFlushRuleSaysOtherwise) {
  std::vector<raster::QuadFragment> quads;
  for (int i = 0; i < 20; ++i) quads.push_back(LiveQuad(0, 4));
  quads.push_back(LiveQuad(0, 0));  // culled
  for (int i = 0; i < 3; ++i) quads.push_back(LiveQuad(1, 1));
  PackedWaves packed;
  LaneCounters mixed;
  PackPixelWaves(quads, WaveFlush::MixPrimitives, packed, mixed);
  EXPECT_EQ(packed.WaveCount(), 2u);
  EXPECT_EQ(mixed.waves, 2u);
  EXPECT_EQ(mixed.quadsCulled, 1u);
  EXPECT_EQ(mixed.quadsLaunched, 23u);
  EXPECT_EQ(mixed.wavesByPrimitives[1], 1u);  // 16 quads of primitive 0
  EXPECT_EQ(mixed.wavesByPrimitives[2], 1u);  // 4 of primitive 0, 3 of primitive 1
  LaneCounters split;
  PackPixelWaves(quads, WaveFlush::OnePrimitivePerWave, packed, split);
  EXPECT_EQ(packed.WaveCount(), 3u);
  EXPECT_EQ(split.wavesByPrimitives[1], 3u);
  EXPECT_EQ(packed.waveStarts, (std::vector<std::uint32_t>{0, 16, 20, 23}));

  std::vector<raster::QuadFragment> many;
  for (std::uint32_t i = 0; i < 17; ++i) many.push_back(LiveQuad(i, 1));
  LaneCounters sixteen;
  PackPixelWaves(many, WaveFlush::MixPrimitives, packed, sixteen);
  EXPECT_EQ(sixteen.wavesByPrimitives[16], 1u);  // hw-facts §6.1: up to 16 primitives per wave
  EXPECT_EQ(sixteen.wavesByPrimitives[1], 1u);
}

TEST(SimDispatch, ComputeGroupsSplitIntoConsecutiveWavesAndBarriersOrderLds) {
  Machine machine = TestMachine();
  const int groupThreads = 100;
  Buffer<std::uint32_t> out("out", 3 * groupThreads);
  KernelInfo kernel = SmallKernel();
  kernel.ldsBytesPerGroup = groupThreads * 4;
  Dispatch d("test/lds", kernel);
  const RwBufferView<std::uint32_t> result = d.ReadWrite(out);
  const DispatchReport& r = machine.Compute(
      d, {.threads = {3 * groupThreads, 1, 1}, .groupSize = {groupThreads, 1, 1}},
      [](ComputeLane& lane) {
        lane.LdsStore<std::uint32_t>(static_cast<std::size_t>(lane.localIndex),
                                     static_cast<std::uint32_t>(lane.threadId.x * 10));
      },
      [&](ComputeLane& lane) {
        // After the barrier every thread sees its right neighbour's store.
        const std::size_t next = static_cast<std::size_t>((lane.localIndex + 1) % groupThreads);
        result.Store(lane, static_cast<std::size_t>(lane.threadId.x), lane.LdsLoad<std::uint32_t>(next));
      });
  for (int g = 0; g < 3; ++g) {
    for (int i = 0; i < groupThreads; ++i) {
      ASSERT_EQ(out.At(static_cast<std::size_t>(g * groupThreads + i)),
                static_cast<std::uint32_t>((g * groupThreads + (i + 1) % groupThreads) * 10));
    }
  }
  EXPECT_EQ(r.lanes.groups, 3u);
  EXPECT_EQ(r.lanes.waves, 6u);  // ceil(100 / 64) = 2 per group
  EXPECT_EQ(r.lanes.wavesByActiveLanes[64], 3u);
  EXPECT_EQ(r.lanes.wavesByActiveLanes[36], 3u);
  EXPECT_EQ(r.lanes.barriers, 3u);
  EXPECT_EQ(r.lanes.ldsBytesWritten, 300u * 4);
  EXPECT_EQ(r.lanes.ldsBytesRead, 300u * 4);

  Dispatch bad("test/lds-overrun", kernel);
  EXPECT_THROW(machine.Compute(bad, {.threads = {64, 1, 1}, .groupSize = {64, 1, 1}},
                               [](ComputeLane& lane) { lane.LdsStore<std::uint32_t>(1000, 1u); }),
               KernelError);
}

TEST(SimDispatch, TrafficCountsRequestsAndDistinctLines) {
  Machine machine = TestMachine();
  Texture2D<glm::vec4> texture("colour", 64, 64, 4);  // RGBA8 in the model
  Texture2D<float> target("target", 64, 64, 4);
  Dispatch d("test/traffic", SmallKernel());
  const TextureView<glm::vec4> in = d.Read(texture);
  const RwTextureView<float> out = d.ReadWrite(target);
  d.SetPixelGrid(64, 64);
  const DispatchReport& r = machine.Compute(d, {.threads = {64, 64, 1}, .groupSize = {8, 8, 1}}, [&](ComputeLane& lane) {
    const glm::vec4 a = in.Load(lane, lane.threadId.x, lane.threadId.y);
    const glm::vec4 b = in.SampleBilinear(lane, (glm::vec2(lane.threadId) + 0.5f) / 64.0f);
    out.Store(lane, lane.threadId.x, lane.threadId.y, a.x + b.x);
    out.Store(lane, -1, 0, 1.0f);  // out of range: dropped
  });
  ASSERT_EQ(r.resources.size(), 2u);
  EXPECT_EQ(r.resources[0].fetches, 2u * 4096);
  EXPECT_EQ(r.resources[0].bytesRead, 4096u * 4 + 4096u * 16);
  EXPECT_EQ(r.resources[0].linesRead, 4096u * 4 / 64);
  EXPECT_EQ(r.resources[1].bytesWritten, 4096u * 4);
  EXPECT_EQ(r.resources[1].linesWritten, 4096u * 4 / 64);
  EXPECT_EQ(r.DramBytes(), 2u * 4096 * 4);
  EXPECT_EQ(r.lanes.lanesActive, 4096u);
  EXPECT_FLOAT_EQ(r.heat.Utilization(3, 5), 1.0f);
}

// A compute group whose pixels lie in one tile adds its active lanes to the heat map at once;
// any other group adds lane by lane. Either way each tile holds the live lanes whose pixel it
// contains, counted here directly: groups aligned to tiles and not, pixel origins off the tile
// grid, grids ending mid-group and pixels past the map.
TEST(SimDispatch, ComputeHeatMapsCountEveryLiveLaneInItsPixelsTile) {
  Machine machine = TestMachine();
  const glm::ivec3 threads{37, 29, 2};
  const glm::ivec2 map{40, 30};
  for (const glm::ivec3 groupSize : {glm::ivec3{8, 8, 1}, glm::ivec3{4, 4, 2}, glm::ivec3{16, 16, 1},
                                     glm::ivec3{5, 3, 1}, glm::ivec3{64, 1, 1}, glm::ivec3{8, 4, 2}}) {
    for (const glm::ivec2 origin : {glm::ivec2{0, 0}, glm::ivec2{8, 8}, glm::ivec2{3, 5}, glm::ivec2{6, 0}}) {
      Dispatch d("test/heat", SmallKernel());
      d.SetPixelGrid(map.x, map.y, origin);
      const DispatchReport& r = machine.Compute(d, {.threads = threads, .groupSize = groupSize}, [](ComputeLane&) {});
      std::vector<std::uint32_t> expected(static_cast<std::size_t>(r.heat.TilesX() * r.heat.TilesY()), 0);
      for (int z = 0; z < threads.z; ++z) {
        for (int y = 0; y < threads.y; ++y) {
          for (int x = 0; x < threads.x; ++x) {
            const glm::ivec2 pixel = glm::ivec2(x, y) + origin;
            if (pixel.x >= map.x || pixel.y >= map.y) continue;
            ++expected[static_cast<std::size_t>(pixel.y / sim::kTileSize * r.heat.TilesX() + pixel.x / sim::kTileSize)];
          }
        }
      }
      for (int ty = 0; ty < r.heat.TilesY(); ++ty) {
        for (int tx = 0; tx < r.heat.TilesX(); ++tx) {
          EXPECT_EQ(r.heat.Active(tx, ty), expected[static_cast<std::size_t>(ty * r.heat.TilesX() + tx)])
              << "group " << groupSize.x << "x" << groupSize.y << "x" << groupSize.z << ", origin " << origin.x << ","
              << origin.y << ", tile " << tx << "," << ty;
        }
      }
      EXPECT_EQ(r.lanes.lanesActive, static_cast<std::uint64_t>(threads.x) * threads.y * threads.z);
    }
  }
}

TEST(SimDispatch, OutOfRangeUavStoresAreDroppedAndCountedPerResource) {
  Machine machine = TestMachine();
  Texture2D<float> target("target", 6, 5, 4, 0.0f);
  Buffer<std::uint32_t> cells("cells", 10, 4, 0);
  Dispatch d("test/oob", SmallKernel());
  const RwTextureView<float> texture = d.ReadWrite(target);
  const RwBufferView<std::uint32_t> buffer = d.ReadWrite(cells);
  const DispatchReport r = machine.Compute(d, {.threads = {3, 1, 1}}, [&](ComputeLane& lane) {
    for (const glm::ivec2 at : {glm::ivec2(-1, 0), glm::ivec2(0, -1), glm::ivec2(6, 0), glm::ivec2(0, 5)}) {
      texture.Store(lane, at.x, at.y, 9.0f);
    }
    texture.Store(lane, lane.threadId.x, 0, 1.0f);
    buffer.Store(lane, 10, 9u);
    buffer.AtomicAdd(lane, 10, 1u);
    buffer.Store(lane, static_cast<std::size_t>(lane.threadId.x), 1u);
  });
  EXPECT_EQ(r.resources[0].storesDroppedOob, 3u * 4);
  EXPECT_EQ(r.resources[0].bytesWritten, 3u * 4);
  EXPECT_EQ(r.resources[1].storesDroppedOob, 3u * 2);
  EXPECT_EQ(r.resources[1].bytesWritten, 3u * 4);
  EXPECT_EQ(r.resources[1].atomics, 0u);
  float sum = 0.0f;
  for (const float t : target.Texels()) sum += t;
  EXPECT_EQ(sum, 3.0f);
  EXPECT_EQ(cells.At(0) + cells.At(1) + cells.At(2), 3u);

  // Helper lanes' stores are dropped by the helper rule, not counted as out of range: a 7x5
  // target runs helper lanes at x = 7 and y = 5.
  Texture2D<float> odd("odd", 7, 5, 4, 0.0f);
  Dispatch pixels("test/oob-helpers", SmallKernel());
  const RwTextureView<float> oddOut = pixels.ReadWrite(odd);
  const DispatchReport p = machine.FullScreen(pixels, {.width = 7, .height = 5}, [&](PixelLane& lane) {
    oddOut.Store(lane, lane.x, lane.y, 1.0f);
  });
  EXPECT_GT(p.lanes.lanesHelper, 0u);
  EXPECT_EQ(p.resources[0].storesDroppedOob, 0u);
}

TEST(SimDispatch, AViewFromAnEarlierDispatchIsAKernelErrorNamingBoth) {
  // Kernel rule violations are sim::KernelError (as an LDS overrun): catchable by the CLI, which
  // reports the message and exits, and by tests. Aborting is for aasim's own invariants.
  Machine machine = TestMachine();
  Buffer<std::uint32_t> cells("cells", 4, 4, 0);
  std::optional<RwBufferView<std::uint32_t>> stale;
  {
    Dispatch first("test/first", SmallKernel());
    stale.emplace(first.ReadWrite(cells));
    machine.Compute(first, {.threads = {1, 1, 1}}, [&](ComputeLane& lane) { stale->Store(lane, 0, 1u); });
  }
  Dispatch second("test/second", SmallKernel());
  const RwBufferView<std::uint32_t> mine = second.ReadWrite(cells);
  try {
    machine.Compute(second, {.threads = {1, 1, 1}}, [&](ComputeLane& lane) {
      mine.Store(lane, 1, 1u);
      stale->Store(lane, 0, 2u);
    });
    FAIL() << "expected a KernelError";
  } catch (const KernelError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'test/first'"), std::string::npos) << message;
    EXPECT_NE(message.find("'test/second'"), std::string::npos) << message;
  }
  EXPECT_EQ(cells.At(0), 1u);  // the stale store never landed

  // Reading through a stale texture view in a pixel kernel is caught too.
  Texture2D<float> texture("texture", 8, 8, 4, 0.0f);
  std::optional<TextureView<float>> staleTexture;
  {
    Dispatch first("test/first-pixels", SmallKernel());
    staleTexture.emplace(first.Read(texture));
  }
  Dispatch third("test/third", SmallKernel());
  EXPECT_THROW(machine.FullScreen(third, {.width = 8, .height = 8},
                                  [&](PixelLane& lane) { staleTexture->Load(lane, lane.x, lane.y); }),
               KernelError);
}

// Reports print a binding's access modes under the names they always had.
TEST(SimDispatch, AccessModesKeepTheirReportedNames) {
  Machine machine = TestMachine();
  auto names = [](const DispatchReport& r) {
    std::vector<std::pair<std::string, std::string_view>> out;
    for (const ResourceTraffic& t : r.resources) out.emplace_back(t.name, AccessName(t.access));
    return out;
  };
  using Names = std::vector<std::pair<std::string, std::string_view>>;
  Texture2D<float> in("in", 8, 8), out("out", 8, 8);
  Buffer<std::uint32_t> both("both", 4), slotItems("slot-items", 4), args("args", 3, 4, 1);
  AppendBuffer<std::uint32_t> queue("queue", 4);
  SlotCounter counter("slots", 4);
  Dispatch d("test/access", SmallKernel());
  d.Read(in);
  d.ReadWrite(out);
  d.Append(queue);
  d.Read(both);
  d.ReadWrite(both);
  d.Slots(counter);
  d.SlotWrite(slotItems);
  EXPECT_EQ(names(machine.Compute(d, {.threads = {1, 1, 1}}, [](ComputeLane&) {})),
            (Names{{"in", "read"},
                   {"out", "read-write"},
                   {"queue", "append"},
                   {"queue/counter", "append-counter"},
                   {"both", "read-write"},
                   {"slots", "slot-counter"},
                   {"slot-items", "slot-write"}}));
  Dispatch indirect("test/access-indirect", SmallKernel());
  EXPECT_EQ(names(machine.ComputeIndirect(indirect, {.arguments = &args, .itemCount = &queue.Counter()},
                                          [](ComputeLane&) {})),
            (Names{{"args", "indirect-args"}, {"queue/counter", "read"}}));
  StencilBuffer exported("exported", 8, 8), tested("tested", 8, 8);
  Dispatch pixels("test/access-stencil", SmallKernel());
  pixels.Stencil(exported);
  EXPECT_EQ(names(machine.FullScreen(pixels, {.width = 8, .height = 8, .stencil = &tested}, [](PixelLane&) {})),
            (Names{{"exported", "stencil"}, {"tested", "stencil-test"}}));
}

std::vector<DispatchReport> CountPassEvents(int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  Machine machine = TestMachine();
  Dispatch d("test/pass-counters", SmallKernel());
  const CounterView odd = d.Counter("test/odd_threads");
  const CounterView steps = d.Counter("test/steps");
  const CounterView again = d.Counter("test/odd_threads");  // the same counter
  machine.Compute(d, {.threads = {8192, 1, 1}}, [&](ComputeLane& lane) {
    const auto i = static_cast<std::uint64_t>(lane.threadId.x);
    if (i % 2 == 1) odd.Add(lane);
    if (i % 6 == 1) again.Add(lane);
    steps.Add(lane, i % 7);
  });
  return machine.Reports();
}

TEST(SimDispatch, PassCountersAreCountedPerChunkAndMergedLikeTraffic) {
  const std::vector<DispatchReport> one = CountPassEvents(1);
  const std::vector<DispatchReport> two = CountPassEvents(2);
  testing::ExpectSameReports(one, two);
  std::uint64_t odd = 0, steps = 0;
  for (std::uint64_t i = 0; i < 8192; ++i) {
    odd += (i % 2 == 1) + (i % 6 == 1);
    steps += i % 7;
  }
  EXPECT_EQ(two[0].passCounters, (std::vector<PassCounter>{{"test/odd_threads", odd}, {"test/steps", steps}}));
  DispatchReport changed = two[0];
  ++changed.passCounters[1].value;
  EXPECT_FALSE(changed.SameSimulation(two[0]));

  // Helper lanes run the kernel but do not count, as their stores do not land.
  Machine machine = TestMachine();
  Dispatch pixels("test/pass-counters-pixels", SmallKernel());
  const CounterView lanes = pixels.Counter("test/lanes");
  const DispatchReport r = machine.FullScreen(pixels, {.width = 7, .height = 5}, [&](PixelLane& lane) { lanes.Add(lane); });
  EXPECT_GT(r.lanes.lanesHelper, 0u);
  ASSERT_EQ(r.passCounters.size(), 1u);
  EXPECT_EQ(r.passCounters[0].value, r.lanes.lanesActive);
  Dispatch unnamed("test/unnamed", SmallKernel());
  EXPECT_THROW(unnamed.Counter(""), std::invalid_argument);
}

TEST(SimDispatch, AppendOverflowIsCountedNotLost) {
  Machine machine = TestMachine();
  AppendBuffer<std::uint32_t> queue("small", 10);
  Dispatch d("test/overflow", SmallKernel());
  const AppendView<std::uint32_t> out = d.Append(queue);
  const DispatchReport& r =
      machine.Compute(d, {.threads = {25, 1, 1}}, [&](ComputeLane& lane) { out.Append(lane, 7u); });
  EXPECT_EQ(queue.Count(), 10u);
  EXPECT_EQ(r.lanes.appendOverflow, 15u);
}

TEST(SimDispatch, InvalidDispatchesAreRefusedWithTheirName) {
  Machine machine = TestMachine();
  KernelInfo tooMany = SmallKernel();
  tooMany.vgprs = 300;
  Dispatch d("test/too-many-vgprs", tooMany);
  try {
    machine.FullScreen(d, {.width = 8, .height = 8}, [](PixelLane&) {});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("test/too-many-vgprs"), std::string::npos) << error.what();
  }
  Dispatch big("test/group", SmallKernel());
  EXPECT_THROW(machine.Compute(big, {.threads = {64, 1, 1}, .groupSize = {2048, 1, 1}}, [](ComputeLane&) {}),
               std::invalid_argument);
  Buffer<std::uint32_t> shortArgs("args", 2);
  Dispatch ind("test/indirect", SmallKernel());
  EXPECT_THROW(machine.ComputeIndirect(ind, {.arguments = &shortArgs}, [](ComputeLane&) {}), std::invalid_argument);
  EXPECT_TRUE(machine.Reports().empty());
}

}  // namespace
}  // namespace sim
