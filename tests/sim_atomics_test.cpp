// Slot atomics (sim/atomics.h): reservations from both ends of one range, granted in chunk order
// so slot indices and buffer contents do not depend on the host thread count, and refused whole
// when the two fills meet.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstdint>
#include <vector>

#include "sim/dispatch.h"
#include "sim_test_util.h"

namespace sim {
namespace {

Machine TestMachine() { return Machine(GpuConfigByName("ps4-class")); }

KernelInfo SmallKernel() { return {.vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 10}; }

constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;

// Which end thread i reserves from (none for a third of them), scattered so that every chunk
// mixes both ends.
enum class Pick { Front, Back, None };
Pick PickFor(std::uint32_t i) {
  const std::uint32_t h = i * 2654435761u;
  return static_cast<Pick>((h >> 16) % 3);
}

struct FillRun {
  std::vector<DispatchReport> reports;
  std::vector<std::uint32_t> items, colours;
  std::uint32_t front = 0, back = 0;
};

// The FXAA queue's shape (aa-facts §3): one counter pair, two buffers written through one slot.
FillRun FillFromBothEnds(int threads, int items, std::size_t capacity) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  Machine machine = TestMachine();
  SlotCounter counter("queue/counters", capacity);
  Buffer<std::uint32_t> queue("queue/items", capacity, 4, kEmpty);
  Buffer<std::uint32_t> colour("queue/colours", capacity, 4, kEmpty);
  Dispatch d("test/fill", SmallKernel());
  const SlotCounterView slots = d.Slots(counter);
  const SlotView<std::uint32_t> queueOut = d.SlotWrite(queue);
  const SlotView<std::uint32_t> colourOut = d.SlotWrite(colour);
  machine.Compute(d, {.threads = {items, 1, 1}, .groupSize = {64, 1, 1}}, [&](ComputeLane& lane) {
    const auto i = static_cast<std::uint32_t>(lane.threadId.x);
    const Pick pick = PickFor(i);
    if (pick == Pick::None) return;
    const QueueSlot slot = slots.Reserve(lane, pick == Pick::Front ? End::Front : End::Back);
    queueOut.Store(lane, slot, i);
    colourOut.Store(lane, slot, i * 7);
  });
  return {machine.Reports(), {queue.Elements().begin(), queue.Elements().end()},
          {colour.Elements().begin(), colour.Elements().end()}, counter.Count(End::Front), counter.Count(End::Back)};
}

TEST(SimAtomics, SlotsAndBufferContentsDoNotDependOnTheThreadCount) {
  // 128 groups of 64: eight chunks of 16 groups, so two host threads interleave them.
  const int items = 128 * 64;
  const std::size_t capacity = static_cast<std::size_t>(items);
  const FillRun one = FillFromBothEnds(1, items, capacity);
  const FillRun two = FillFromBothEnds(2, items, capacity);
  testing::ExpectSameReports(one.reports, two.reports);
  EXPECT_EQ(one.items, two.items);
  EXPECT_EQ(one.colours, two.colours);

  // Brute force: front slots in thread order from index 0, back slots in thread order from the
  // last index down; the middle stays untouched.
  std::vector<std::uint32_t> expected(capacity, kEmpty);
  std::uint32_t front = 0, back = 0;
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(items); ++i) {
    if (PickFor(i) == Pick::Front) expected[front++] = i;
    if (PickFor(i) == Pick::Back) expected[capacity - 1 - back++] = i;
  }
  ASSERT_GT(front, 1000u);
  ASSERT_GT(back, 1000u);
  EXPECT_EQ(two.items, expected);
  for (std::size_t k = 0; k < capacity; ++k) {
    ASSERT_EQ(two.colours[k], expected[k] == kEmpty ? kEmpty : expected[k] * 7) << k;
  }
  EXPECT_EQ(two.front, front);
  EXPECT_EQ(two.back, back);
  const DispatchReport& r = two.reports[0];
  ASSERT_EQ(r.resources.size(), 3u);
  EXPECT_EQ(r.resources[0].name, "queue/counters");
  EXPECT_EQ(r.resources[0].atomics, front + back);
  EXPECT_EQ(r.resources[0].linesWritten, 1u);
  EXPECT_EQ(r.resources[1].bytesWritten, 4u * (front + back));
  EXPECT_EQ(r.resources[2].bytesWritten, 4u * (front + back));
  EXPECT_EQ(r.lanes.slotOverflow, 0u);
}

TEST(SimAtomics, FrontAndBackFillsMeetInTheMiddle) {
  // Even threads take the front, odd threads the back; ten slots for twelve threads: the first
  // ten in lane order are granted and the last two refused.
  for (const int threads : {10, 12}) {
    Machine machine = TestMachine();
    SlotCounter counter("meet/counters", 10);
    Buffer<std::uint32_t> queue("meet/items", 10, 4, kEmpty);
    Dispatch d("test/meet", SmallKernel());
    const SlotCounterView slots = d.Slots(counter);
    const SlotView<std::uint32_t> out = d.SlotWrite(queue);
    const DispatchReport r = machine.Compute(d, {.threads = {threads, 1, 1}}, [&](ComputeLane& lane) {
      const auto i = static_cast<std::uint32_t>(lane.threadId.x);
      out.Store(lane, slots.Reserve(lane, i % 2 == 0 ? End::Front : End::Back), i);
    });
    const std::vector<std::uint32_t> items(queue.Elements().begin(), queue.Elements().end());
    EXPECT_EQ(items, (std::vector<std::uint32_t>{0, 2, 4, 6, 8, 9, 7, 5, 3, 1})) << threads;
    EXPECT_EQ(counter.Count(End::Front), 5u);
    EXPECT_EQ(counter.Count(End::Back), 5u);
    EXPECT_EQ(r.lanes.slotOverflow, static_cast<std::uint64_t>(threads - 10));
    EXPECT_EQ(r.resources[0].atomics, static_cast<std::uint64_t>(threads));  // refused reservations are atomics too
    EXPECT_EQ(r.resources[1].bytesWritten, 40u);                             // refused stores are dropped
  }
}

TEST(SimAtomics, ARefusedReservationIsRefusedWholeAndLaterOnesStillFit) {
  Machine machine = TestMachine();
  SlotCounter counter("multi/counters", 10);
  Buffer<std::uint32_t> queue("multi/items", 10, 4, kEmpty);
  Dispatch d("test/multi", SmallKernel());
  const SlotCounterView slots = d.Slots(counter);
  const SlotView<std::uint32_t> out = d.SlotWrite(queue);
  struct Ask {
    End end;
    std::uint32_t count;
  };
  // 4 front + 4 back leave two slots: 3 front is refused, 2 back then fits.
  const Ask asks[] = {{End::Front, 4}, {End::Back, 4}, {End::Front, 3}, {End::Back, 2}};
  const DispatchReport r = machine.Compute(d, {.threads = {4, 1, 1}}, [&](ComputeLane& lane) {
    const Ask ask = asks[lane.threadId.x];
    const QueueSlot slot = slots.Reserve(lane, ask.end, ask.count);
    EXPECT_EQ(slot.Count(), ask.count);
    for (std::uint32_t e = 0; e < ask.count; ++e) {
      out.Store(lane, slot, static_cast<std::uint32_t>(lane.threadId.x) * 100 + e, e);
    }
  });
  const std::vector<std::uint32_t> items(queue.Elements().begin(), queue.Elements().end());
  EXPECT_EQ(items, (std::vector<std::uint32_t>{0, 1, 2, 3, 301, 300, 103, 102, 101, 100}));
  EXPECT_EQ(counter.Count(End::Front), 4u);
  EXPECT_EQ(counter.Count(End::Back), 6u);
  EXPECT_EQ(r.lanes.slotOverflow, 3u);

  Dispatch bad("test/past-the-slot", SmallKernel());
  const SlotCounterView badSlots = bad.Slots(counter);
  const SlotView<std::uint32_t> badOut = bad.SlotWrite(queue);
  counter.Reset();
  try {
    machine.Compute(bad, {.threads = {1, 1, 1}}, [&](ComputeLane& lane) {
      badOut.Store(lane, badSlots.Reserve(lane, End::Front, 2), 0u, 2);
    });
    FAIL() << "expected a KernelError";
  } catch (const KernelError& error) {
    EXPECT_NE(std::string(error.what()).find("test/past-the-slot"), std::string::npos) << error.what();
  }
}

TEST(SimAtomics, SlotStoresPastTheBufferAreDropped) {
  // A buffer shorter than the counter's range: back slots land past its end.
  Machine machine = TestMachine();
  SlotCounter counter("short/counters", 8);
  Buffer<std::uint32_t> queue("short/items", 6, 4, kEmpty);
  Dispatch d("test/short", SmallKernel());
  const SlotCounterView slots = d.Slots(counter);
  const SlotView<std::uint32_t> out = d.SlotWrite(queue);
  const DispatchReport r = machine.Compute(d, {.threads = {4, 1, 1}}, [&](ComputeLane& lane) {
    const auto i = static_cast<std::uint32_t>(lane.threadId.x);
    out.Store(lane, slots.Reserve(lane, i < 2 ? End::Front : End::Back), i);
  });
  const std::vector<std::uint32_t> items(queue.Elements().begin(), queue.Elements().end());
  EXPECT_EQ(items, (std::vector<std::uint32_t>{0, 1, kEmpty, kEmpty, kEmpty, kEmpty}));
  EXPECT_EQ(r.resources[1].bytesWritten, 8u);
  EXPECT_EQ(r.lanes.slotOverflow, 0u);
}

}  // namespace
}  // namespace sim
