// State a compute group keeps across its stages: LDS atomics returning the old value (lanes run
// in order, so deterministic) with their LDS bytes counted, and per-thread private values that
// survive barriers and start zeroed in every group.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sim/dispatch.h"
#include "sim_test_util.h"

namespace sim {
namespace {

using sim::testing::TestMachine;

constexpr int kGroupThreads = 100;  // two waves, the second partial
constexpr int kGroups = 40;         // three chunks of up to 16 groups

bool Stages(std::uint32_t i) { return (i * 2654435761u >> 13) % 3 == 0; }
std::uint32_t ValueOf(std::uint32_t i) { return (i * 7919u) % 1000u; }

struct LdsRun {
  std::vector<DispatchReport> reports;
  std::vector<std::uint32_t> out;
};

// CMAA2's LDS staging (aa-facts §4.3): threads with an item take an LDS slot with an atomic add,
// then after the barrier every thread picks up one staged item. The running min/max/exchange
// values each thread got back are kept too.
LdsRun StageThroughLds(int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  Machine machine = TestMachine();
  constexpr std::size_t kCount = 0, kMin = 1, kMax = 2, kLast = 3, kItems = 4;
  const KernelInfo kernel{.vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = (kItems + kGroupThreads) * 4,
                          .valuInstructionsPerWave = 10};
  Buffer<std::uint32_t> out("out", 5 * kGroupThreads * kGroups, 4, 0xFFFFFFFFu);
  Dispatch d("test/lds-atomics", kernel);
  const RwBufferView<std::uint32_t> outRw = d.ReadWrite(out);
  machine.Compute(
      d, {.threads = {kGroupThreads * kGroups, 1, 1}, .groupSize = {kGroupThreads, 1, 1}},
      [](ComputeLane& lane) {
        if (lane.localIndex == 0) lane.LdsStore<std::uint32_t>(kMin, 0xFFFFFFFFu);
      },
      [&](ComputeLane& lane) {
        const auto i = static_cast<std::uint32_t>(lane.threadId.x);
        const std::size_t at = 5 * i;
        outRw.Store(lane, at + 1, lane.LdsAtomicMin<std::uint32_t>(kMin, ValueOf(i)));
        outRw.Store(lane, at + 2, lane.LdsAtomicMax<std::uint32_t>(kMax, ValueOf(i)));
        outRw.Store(lane, at + 3, lane.LdsAtomicExchange<std::uint32_t>(kLast, i));
        if (!Stages(i)) return;
        const std::uint32_t slot = lane.LdsAtomicAdd<std::uint32_t>(kCount, 1);
        lane.LdsStore<std::uint32_t>(kItems + slot, i);
      },
      [&](ComputeLane& lane) {
        const auto local = static_cast<std::uint32_t>(lane.localIndex);
        if (local >= lane.LdsLoad<std::uint32_t>(kCount)) return;
        outRw.Store(lane, 5 * static_cast<std::size_t>(lane.threadId.x), lane.LdsLoad<std::uint32_t>(kItems + local));
      });
  return {machine.Reports(), {out.Elements().begin(), out.Elements().end()}};
}

TEST(SimGroupState, LdsAtomicsReturnTheOldValueInLaneOrderForAnyThreadCount) {
  const LdsRun one = StageThroughLds(1);
  const LdsRun two = StageThroughLds(2);
  testing::ExpectSameReports(one.reports, two.reports);
  EXPECT_EQ(one.out, two.out);

  // Brute force: each group's lanes in order.
  std::vector<std::uint32_t> expected(two.out.size(), 0xFFFFFFFFu);
  std::uint64_t staged = 0;
  for (std::uint32_t g = 0; g < kGroups; ++g) {
    std::uint32_t low = 0xFFFFFFFFu, high = 0, last = 0;
    std::vector<std::uint32_t> items;
    for (std::uint32_t local = 0; local < kGroupThreads; ++local) {
      const std::uint32_t i = g * kGroupThreads + local;
      expected[5 * i + 1] = std::exchange(low, std::min(low, ValueOf(i)));
      expected[5 * i + 2] = std::exchange(high, std::max(high, ValueOf(i)));
      expected[5 * i + 3] = std::exchange(last, i);
      if (Stages(i)) items.push_back(i);
    }
    for (std::uint32_t k = 0; k < items.size(); ++k) expected[5 * (g * kGroupThreads + k)] = items[k];
    staged += items.size();
  }
  ASSERT_GT(staged, 0u);
  EXPECT_EQ(two.out, expected);
  // Per thread: min, max, exchange (4 bytes read and written each); per staged item an add
  // (4 + 4) and a store; stage 3 loads the count, and the item where there is one; stage 1 one
  // store per group.
  const std::uint64_t threads = static_cast<std::uint64_t>(kGroupThreads) * kGroups;
  const LaneCounters& c = two.reports[0].lanes;
  EXPECT_EQ(c.ldsBytesRead, 3 * 4 * threads + 4 * staged + 4 * threads + 4 * staged);
  EXPECT_EQ(c.ldsBytesWritten, 3 * 4 * threads + 4 * staged + 4 * staged + 4u * kGroups);
}

struct Carried {
  std::uint32_t a, b;
  float c;
};

TEST(SimGroupState, PrivateValuesPersistAcrossStagesAndStartZeroedInEveryGroup) {
  Machine machine = TestMachine();
  const KernelInfo kernel{.vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = kGroupThreads * 4,
                          .valuInstructionsPerWave = 10};
  const int threads = kGroupThreads * kGroups;
  Buffer<std::uint32_t> out("out", static_cast<std::size_t>(threads), 4, 0);
  Buffer<std::uint32_t> notZero("not-zero", 1, 4, 0);
  Dispatch d("test/private", kernel);
  const RwBufferView<std::uint32_t> outRw = d.ReadWrite(out);
  const RwBufferView<std::uint32_t> notZeroRw = d.ReadWrite(notZero);
  const DispatchReport r = machine.Compute(
      d, {.threads = {threads, 1, 1}, .groupSize = {kGroupThreads, 1, 1}},
      [&](ComputeLane& lane) {
        Carried& mine = lane.Private<Carried>();
        if (mine.a != 0 || mine.b != 0 || mine.c != 0.0f) notZeroRw.AtomicAdd(lane, 0, 1);
        mine.a = static_cast<std::uint32_t>(lane.threadId.x) * 3;
        lane.LdsStore<std::uint32_t>(static_cast<std::size_t>(lane.localIndex), mine.a);
      },
      [&](ComputeLane& lane) {
        const std::size_t next = static_cast<std::size_t>((lane.localIndex + 1) % kGroupThreads);
        lane.Private<Carried>().b = lane.LdsLoad<std::uint32_t>(next);
      },
      [&](ComputeLane& lane) {
        const Carried& mine = lane.Private<Carried>();
        outRw.Store(lane, static_cast<std::size_t>(lane.threadId.x), mine.a + mine.b);
      });
  EXPECT_EQ(notZero.At(0), 0u);
  for (int i = 0; i < threads; ++i) {
    const int group = i / kGroupThreads, next = group * kGroupThreads + (i % kGroupThreads + 1) % kGroupThreads;
    ASSERT_EQ(out.At(static_cast<std::size_t>(i)), static_cast<std::uint32_t>(3 * i + 3 * next)) << i;
  }
  // Private values are registers: no LDS or memory traffic beyond the LDS exchange itself.
  EXPECT_EQ(r.lanes.ldsBytesWritten, 4u * static_cast<std::uint64_t>(threads));
  EXPECT_EQ(r.lanes.ldsBytesRead, 4u * static_cast<std::uint64_t>(threads));

  Dispatch twoTypes("test/private-types", kernel);
  try {
    machine.Compute(
        twoTypes, {.threads = {64, 1, 1}}, [](ComputeLane& lane) { lane.Private<Carried>().a = 1; },
        [](ComputeLane& lane) { lane.Private<std::uint64_t>() = 2; });
    FAIL() << "expected a KernelError";
  } catch (const KernelError& error) {
    EXPECT_NE(std::string(error.what()).find("test/private-types"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace sim
