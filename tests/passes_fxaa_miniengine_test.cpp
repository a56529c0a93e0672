// MiniEngine's compute FXAA (aa-facts §3; passes/fxaa_miniengine/) and the work set's packed
// queue layout it runs on: the item encoding, the double-ended queue with its padding and
// arguments, dropped dummy stores, the worst-case queue size, the step tables and end search,
// hand-derived blends on step edges, symmetry, and the quadrant seam.

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <oneapi/tbb/global_control.h>

#include "passes/compare.h"
#include "passes/fxaa_miniengine/fxaa_miniengine_math.h"
#include "passes/registry.h"
#include "passes/work_set.h"
#include "passes_test_util.h"
#include "sim/formats.h"
#include "sim/gpu_config.h"

namespace passes {
namespace {

using namespace fxaa_miniengine;

// ---- The work item ----

TEST(FxaaMiniEngineItem, PackedItemsRoundTripOverEveryFieldValue) {
  for (int x = 0; x <= kMaxSide; ++x) {
    for (std::uint32_t subpix = 0; subpix <= 0xFE; subpix += 2) {
      for (const std::uint32_t dir : {0u, 1u}) {
        const int y = (x * 7 + static_cast<int>(subpix)) % (kMaxSide + 1);
        const std::uint32_t item = PackWorkItem(x, y, subpix, dir);
        ASSERT_EQ(WorkItemPixel(item), glm::ivec2(x, y));
        ASSERT_EQ(WorkItemGradientDir(item), dir);
        ASSERT_EQ(item & 0xFEu, subpix);
      }
    }
  }
  for (int y = 0; y <= kMaxSide; ++y) ASSERT_EQ(WorkItemPixel(PackWorkItem(kMaxSide - y, y, 0, 0)), glm::ivec2(kMaxSide - y, y));
}

TEST(FxaaMiniEngineItem, SubpixSpansZeroToOneHalfAndTheDummyDecodesOffEveryScreen) {
  EXPECT_EQ(WorkItemSubpix(PackWorkItem(3, 4, 0, 1)), 0.0f);
  EXPECT_EQ(WorkItemSubpix(PackWorkItem(3, 4, 0xFE, 0)), 0.5f);
  EXPECT_EQ(WorkItemPixel(kDummyItem), glm::ivec2(4095, 4095));
  EXPECT_EQ(WorkItemSubpix(kDummyItem), 0.5f);  // a dummy lane blends, so it stores: dropped off screen
}

TEST(FxaaMiniEngineItem, TheColourQueueWordKeepsAnR11G11B10Colour) {
  for (const glm::vec3 c : {glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.25f, 0.5f, 0.75f), glm::vec3(0.031f, 0.6f, 2.0f)}) {
    const glm::vec3 stored = sim::Quantize(sim::Format::R11G11B10Float, c);
    EXPECT_EQ(UnpackR11G11B10(PackR11G11B10(stored)), stored);
  }
}

// ---- Step tables and the end search ----

TEST(FxaaMiniEngineSearch, StepDistancesArePresets25And39) {
  EXPECT_EQ(std::vector<float>(kDefaultDistances.begin(), kDefaultDistances.end()),
            (std::vector<float>{1, 2.5f, 4.5f, 6.5f, 8.5f, 10.5f, 14.5f, 22.5f}));
  EXPECT_EQ(std::vector<float>(kExtremeDistances.begin(), kExtremeDistances.end()),
            (std::vector<float>{1, 2, 3, 4, 5, 6.5f, 8.5f, 10.5f, 12.5f, 14.5f, 18.5f, 36.5f}));
}

// A line whose end lies `end` texels from the start on the negative side and none on the
// positive: the search stops at the first table distance >= end; none found -> the last entry.
TEST(FxaaMiniEngineSearch, EndsOfLinesOfKnownLengthLandOnTheTablesNextDistance) {
  for (const bool extreme : {false, true}) {
    const std::span<const float> table = SampleDistances(extreme);
    for (float end = 0.5f; end <= 40.0f; end += 0.5f) {
      const EdgeEnds ends = SearchEnds(table, 0.5f, -1.0f, 0.25f,
                                       [&](float d, int side) { return side < 0 && d >= end ? 0.0f : 0.5f; });
      float expected = table.back();
      for (std::size_t i = 0; i + 1 < table.size(); ++i) {
        if (table[i] >= end) {
          expected = table[i];
          break;
        }
      }
      EXPECT_EQ(ends.negDist, expected) << end;
      EXPECT_EQ(ends.negGood, expected != table.back()) << end;  // 0 - 0.5 has the gradient's sign
      EXPECT_EQ(ends.posDist, table.back());
      EXPECT_FALSE(ends.posGood);
    }
  }
}

TEST(FxaaMiniEngineSearch, TheShiftIsOneHalfLessTheNearerEndsShareOnlyWhenThatEndIsGood) {
  EXPECT_FLOAT_EQ(PixelShift({.negDist = 2.5f, .posDist = 22.5f, .negGood = true, .posGood = false}, 0.0f), 0.4f);
  EXPECT_EQ(PixelShift({.negDist = 2.5f, .posDist = 22.5f, .negGood = false, .posGood = true}, 0.03f), 0.03f);
  EXPECT_EQ(PixelShift({.negDist = 4.5f, .posDist = 4.5f, .negGood = true, .posGood = true}, 0.0f), 0.0f);
}

// ---- Running the pass ----

struct MiniEngineRun {
  PassOutput output;
  std::vector<sim::DispatchReport> reports;
};

MiniEngineRun RunMiniEngine(const sim::Texture2D<glm::vec4>& image, Strategy strategy, const std::string& spec = "fxaa-miniengine",
            int threads = 2) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const PassConfig config = ResolvePass(spec);
  FrameInputs frame;
  frame.colour = &image;
  MiniEngineRun run{config.pass->make(config.settings)->Run(machine, frame, strategy), {}};
  run.reports = machine.Reports();
  return run;
}

float Red(const PassOutput& output, int x, int y) { return output.colour.At(x, y).x; }

std::uint64_t Sum(const MiniEngineRun& run, std::string_view dispatch, std::uint64_t sim::LaneCounters::*counter) {
  std::uint64_t total = 0;
  for (const sim::DispatchReport& report : run.reports) {
    if (report.name == dispatch) total += report.lanes.*counter;
  }
  return total;
}

std::uint64_t DroppedStores(const MiniEngineRun& run, std::string_view dispatch, std::string_view resource) {
  std::uint64_t total = 0;
  for (const sim::DispatchReport& report : run.reports) {
    if (report.name != dispatch) continue;
    for (const sim::ResourceTraffic& traffic : report.resources) {
      if (traffic.name == resource) total += traffic.storesDroppedOob;
    }
  }
  return total;
}

// White (x >= 20) beside black, on rows [8, 40) of a 128x128 black image: a vertical edge of 32
// rows inside the first quadrant (64x64), away from its borders.
sim::Texture2D<glm::vec4> VerticalSegment(bool transposed = false) {
  return testing::GreyImage(128, 128, [transposed](int x, int y) {
    if (transposed) std::swap(x, y);
    return x >= 20 && y >= 8 && y < 40 ? 255 : 0;
  });
}

float StoredR11G11B10(float value) { return sim::QuantizeChannel(sim::Format::R11G11B10Float, 0, value); }

// Hand derivation (docs/fxaa-miniengine.md "A worked step edge"): a white pixel beside the edge
// has N, S, E white and W black: edgeVert 4 > edgeHorz 0, a vertical item, gradient towards -x
// (dir 0); its 3x3 average 8/12 differs from M by 1/3 of the range 1: smoothstep(1/3)^2 * 0.5 * 2
// = 0.0672 -> subpix bits 16 -> 0.0315. Pass 2 samples the luma on the column boundary: 128/255
// on rows of the segment, 64/255 where one of the two rows is outside (|0.251 - 0.5| < 0.25, not
// an end), 0 where both are outside (an end with the gradient's sign: good). Row 9: ends at 2.5
// (rows 6, 7) and none within 14.5 below -> 0.5 - 2.5 / 25 = 0.4. Row 16: the first end above is
// at 10.5 (rows 5, 6; 8.5 straddles rows 7, 8) -> 0.5 - 10.5 / 33. The black pixel beside it sees
// ends of the other sign (not good): only its sub-pixel shift, 16 / 254 * 0.5.
TEST(FxaaMiniEngineGolden, AStepEdgeBlendsByTheDistanceToItsNearerEnd) {
  for (const Strategy strategy : kAllStrategies) {
    const PassOutput out = RunMiniEngine(VerticalSegment(), strategy).output;
    const float subpix = 16.0f / 254.0f * 0.5f;
    EXPECT_EQ(Red(out, 20, 9), StoredR11G11B10(1.0f + 0.4f * (0.0f - 1.0f))) << StrategyName(strategy);
    EXPECT_EQ(Red(out, 20, 16), StoredR11G11B10(1.0f + (0.5f - 10.5f / 33.0f) * (0.0f - 1.0f))) << StrategyName(strategy);
    EXPECT_EQ(Red(out, 19, 16), StoredR11G11B10(0.0f + subpix * 1.0f)) << StrategyName(strategy);
    EXPECT_EQ(Red(out, 40, 60), 0.0f);  // far from the edge: untouched
    EXPECT_EQ(Red(out, 21, 24), 1.0f);
  }
}

// FXAA_EXTREME_QUALITY's table samples 2 px (row 7, outside: an end) where the default's first
// step past 1 is 2.5, and gives up at 36.5: row 9 blends by 0.5 - 2 / 38.5.
TEST(FxaaMiniEngineGolden, TheExtremeTableFindsTheEndAtTwoPixels) {
  for (const Strategy strategy : kAllStrategies) {
    const PassOutput out = RunMiniEngine(VerticalSegment(), strategy, "fxaa-miniengine:extreme_quality=1").output;
    EXPECT_EQ(Red(out, 20, 9), StoredR11G11B10(1.0f + (0.5f - 2.0f / 38.5f) * (0.0f - 1.0f))) << StrategyName(strategy);
    EXPECT_EQ(Red(out, 20, 16), StoredR11G11B10(1.0f + (0.5f - 10.5f / 47.0f) * (0.0f - 1.0f))) << StrategyName(strategy);
  }
}

TEST(FxaaMiniEngineGolden, TheTransposedEdgeGivesTheTransposedImage) {
  for (const Strategy strategy : kAllStrategies) {
    const PassOutput out = RunMiniEngine(VerticalSegment(), strategy).output;
    const PassOutput transposed = RunMiniEngine(VerticalSegment(true), strategy).output;
    for (int y = 0; y < 128; ++y) {
      for (int x = 0; x < 128; ++x) ASSERT_EQ(out.colour.At(x, y), transposed.colour.At(y, x)) << x << ", " << y;
    }
  }
}

// ---- The queue ----

// 128x128 black with the white segment: the queue strategy's reports follow MiniEngine's
// resolve: every pass-2 dispatch runs whole waves, the dummies it adds are fewer than 64 per end
// and quadrant, and each dummy's store is dropped and counted on the colour target.
TEST(FxaaMiniEngineQueue, DummyItemsPadEachEndToWholeWavesAndTheirStoresAreDropped) {
  const MiniEngineRun run = RunMiniEngine(VerticalSegment(), Strategy::DeferredQueue);
  const std::uint64_t active = Sum(run, "fxaa-miniengine/pass2-h", &sim::LaneCounters::lanesActive) +
                               Sum(run, "fxaa-miniengine/pass2-v", &sim::LaneCounters::lanesActive);
  EXPECT_EQ(active % sim::kWaveLanes, 0u);
  EXPECT_EQ(active, run.output.workItems + run.output.paddingItems);
  EXPECT_GT(run.output.paddingItems, 0u);
  EXPECT_LT(run.output.paddingItems, 4u * 2u * sim::kWaveLanes);
  const std::uint64_t dropped = DroppedStores(run, "fxaa-miniengine/pass2-h", "fxaa-miniengine/colour") +
                                DroppedStores(run, "fxaa-miniengine/pass2-v", "fxaa-miniengine/colour");
  EXPECT_EQ(dropped, run.output.paddingItems);
  EXPECT_EQ(Sum(run, "fxaa-miniengine/pass1", &sim::LaneCounters::slotOverflow), 0u);
}

// A work set with the packed layout, on a 16x16 screen: column 0 joins the front (16 items),
// columns 14 and 15 the back (32): slots 0..15 hold the front items, 16..63 dummies; from the
// back 32 items then 32 dummies; one group per end; the counters end at 0.
std::size_t SmallCapacity(int width, int height) { return static_cast<std::size_t>(width * height / 4 + 128); }
glm::ivec2 UnpackSmall(std::uint32_t item) { return WorkItemPixel(item); }
constexpr PackedQueueLayout kSmallLayout{
    .unpack = UnpackSmall, .dummyItem = kDummyItem, .capacity = SmallCapacity, .resolveDispatch = "t/resolve",
    .resolve = {.source = "test"}};
constexpr WorkSetKernels kSmallKernels{
    .detectDispatch = "t/detect", .consumeDispatch = "t/front", .detectPixel = {.source = "test"},
    .detectCompute = {.source = "test"}, .consume = {.source = "test"}, .secondConsumeDispatch = "t/back",
    .secondConsume = {.source = "test"}, .packed = &kSmallLayout};

TEST(FxaaMiniEngineQueue, FrontItemsFromTheStartBackItemsFromTheEndPaddedToSixtyFour) {
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  WorkSet workSet("t");
  sim::Texture2D<float> written("t/written", 16, 16);
  auto makeDetect = [](sim::Dispatch&, auto) {
    return [](const auto&, int x, int y) {
      const int joins = x == 0 ? 1 : x >= 14 ? 2 : 0;
      return PackedItem{.joins = joins, .item = PackWorkItem(x, y, 0, 0), .payload = static_cast<std::uint32_t>(y)};
    };
  };
  auto makeConsume = [&](sim::Dispatch& d, int) {
    const sim::RwTextureView<float> out = d.ReadWrite(written);
    return [=](const auto& lane, int x, int y, std::uint32_t, auto&& payload) {
      out.Store(lane, x, y, static_cast<float>(payload()) + 1.0f);
    };
  };
  const WorkSetShape shape = workSet.Run(machine, Strategy::DeferredQueue, kSmallKernels, 16, 16, makeDetect, makeConsume);
  EXPECT_EQ(shape.pixels, 48u);
  const std::span<const std::uint32_t> queue = workSet.PackedQueue();
  ASSERT_EQ(queue.size(), 16u * 16u / 4u + 128u);
  for (std::size_t i = 0; i < 64; ++i) {
    if (i < 16) {
      EXPECT_EQ(WorkItemPixel(queue[i]).x, 0) << i;
    } else {
      EXPECT_EQ(queue[i], kDummyItem) << i;
    }
    const std::uint32_t back = queue[queue.size() - 1 - i];
    if (i < 32) {
      EXPECT_GE(WorkItemPixel(back).x, 14) << i;
    } else {
      EXPECT_EQ(back, kDummyItem) << i;
    }
  }
  EXPECT_EQ(std::vector<std::uint32_t>(workSet.QueueArguments().begin(), workSet.QueueArguments().end()),
            (std::vector<std::uint32_t>{1, 1, 1, 1, 1, 1}));
  EXPECT_EQ(workSet.PackedCounters()[0], 0u);
  EXPECT_EQ(workSet.PackedCounters()[1], 0u);
  EXPECT_EQ(workSet.Padding(), 48u + 32u);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) EXPECT_EQ(written.At(x, y), x == 0 || x >= 14 ? static_cast<float>(y) + 1.0f : 0.0f);
  }
  std::uint64_t dropped = 0;
  for (const sim::DispatchReport& report : machine.Reports()) {
    for (const sim::ResourceTraffic& traffic : report.resources) {
      if (traffic.name == "t/written") dropped += traffic.storesDroppedOob;
    }
  }
  EXPECT_EQ(dropped, 80u);
}

// The worst case: a checkerboard makes every pixel an item. With quadrants of whole 8x8 groups
// (128x128: 64x64 each) the W*H/4 + 128 queue holds every quadrant's items and padding, nothing
// overflows and every pixel is processed under both strategies alike.
TEST(FxaaMiniEngineQueue, ACheckerboardFillsTheQueueWithoutOverflowOrLoss) {
  const sim::Texture2D<glm::vec4> board = testing::GreyImage(128, 128, [](int x, int y) { return (x + y) % 2 ? 255 : 0; });
  const MiniEngineRun queue = RunMiniEngine(board, Strategy::DeferredQueue);
  const MiniEngineRun stencil = RunMiniEngine(board, Strategy::StencilCulled);
  EXPECT_EQ(queue.output.workItems, 128u * 128u);
  EXPECT_EQ(queue.output.paddingItems, 0u);
  EXPECT_EQ(Sum(queue, "fxaa-miniengine/pass1", &sim::LaneCounters::slotOverflow), 0u);
  EXPECT_TRUE(CompareOutputs(queue.output, stencil.output).Identical()) << CompareOutputs(queue.output, stencil.output).Describe();
}

// FXAA.cpp dispatches W/2 x H/2 threads per quadrant: a screen one pixel wide or high launches no
// group, and the frame comes back as its R11G11B10 target holds it (it used to fail a region check).
TEST(FxaaMiniEngineQueue, AScreenOnePixelWideOrHighLaunchesNothing) {
  for (const glm::ivec2 size : {glm::ivec2(1, 1), glm::ivec2(2, 1), glm::ivec2(1, 9), glm::ivec2(64, 1)}) {
    const sim::Texture2D<glm::vec4> image =
        testing::GreyImage(size.x, size.y, [](int x, int y) { return (x * 7 + y * 13) % 2 ? 200 : 10; });
    for (const Strategy strategy : kAllStrategies) {
      const MiniEngineRun run = RunMiniEngine(image, strategy);
      EXPECT_TRUE(run.reports.empty()) << size.x << "x" << size.y;
      EXPECT_EQ(run.output.workItems, 0u);
      for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) EXPECT_EQ(Red(run.output, x, y), StoredR11G11B10(image.At(x, y).x)) << x << "," << y;
      }
    }
  }
}

// Where a quadrant side is not a multiple of 8, MiniEngine's Dispatch2D launches whole groups
// past it and pass 1 has no bounds check: on a 100x100 screen the quadrants classify 56x56,
// 56x50, 50x56 and 50x50 pixels (clipped to the screen), the first three more than the 2628
// slots: the refused reservations are counted (slots/overflow).
TEST(FxaaMiniEngineQueue, QuadrantsOfPartialGroupsOverflowTheReferenceQueueSizeOnACheckerboard) {
  const sim::Texture2D<glm::vec4> board = testing::GreyImage(100, 100, [](int x, int y) { return (x + y) % 2 ? 255 : 0; });
  const MiniEngineRun queue = RunMiniEngine(board, Strategy::DeferredQueue);
  EXPECT_EQ(Sum(queue, "fxaa-miniengine/pass1", &sim::LaneCounters::slotOverflow), 56u * 56u + 2u * 56u * 50u - 3u * (100u * 100u / 4u + 128u));
}

// ---- Quadrant seams ----

// A full-height edge crosses the border between the first two quadrants (0,0) and (0,1). The
// first quadrant's pass 2 runs before pass 1 of the second wrote its lumas (still 0 this frame),
// so a white pixel a few rows above the border finds a false, "good" end just past it; the same
// pixel far from the border, and every pixel of the second quadrant (whose luma above is
// written), sees an endless edge: only its sub-pixel shift.
TEST(FxaaMiniEngineSeam, TheFirstQuadrantsSearchSeesTheUnwrittenLumaPastItsBorder) {
  const sim::Texture2D<glm::vec4> edge = testing::GreyImage(64, 64, [](int x, int) { return x >= 20 ? 255 : 0; });
  for (const Strategy strategy : kAllStrategies) {
    const PassOutput out = RunMiniEngine(edge, strategy).output;
    const float subpixOnly = StoredR11G11B10(1.0f + 16.0f / 254.0f * 0.5f * (0.0f - 1.0f));
    // Row 24: the luma rows 32 (the first quadrant's apron) and 33.. (unwritten): the sample at
    // 10.5 (rows 34, 35) is the first with both rows 0.
    EXPECT_EQ(Red(out, 20, 24), StoredR11G11B10(1.0f + (0.5f - 10.5f / 33.0f) * (0.0f - 1.0f))) << StrategyName(strategy);
    EXPECT_EQ(Red(out, 20, 4), subpixOnly) << StrategyName(strategy);
    EXPECT_EQ(Red(out, 20, 40), subpixOnly) << StrategyName(strategy);
  }
}

}  // namespace
}  // namespace passes
