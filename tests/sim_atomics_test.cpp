// Slot atomics (sim/atomics.h): reservations from both ends of one range, granted in chunk order
// so slot indices and buffer contents do not depend on the host thread count, and refused whole
// when the two fills meet. Atomics returning a value (linked lists): only where chunks run
// serially, and then identical for any thread count.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/dispatch.h"
#include "sim_test_util.h"

namespace sim {
namespace {

using sim::testing::TestMachine;

using sim::testing::SmallKernel;

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
FillRun FillFromBothEnds(int threads, int items, std::size_t capacity, bool serial = false) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  Machine machine = TestMachine();
  SlotCounter counter("queue/counters", capacity);
  Buffer<std::uint32_t> queue("queue/items", capacity, 4, kEmpty);
  Buffer<std::uint32_t> colour("queue/colours", capacity, 4, kEmpty);
  Dispatch d("test/fill", SmallKernel());
  if (serial) d.SerialChunks();
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

  // Serial chunks grant at once instead of at commit: the same slots.
  const FillRun serial = FillFromBothEnds(2, items, capacity, true);
  testing::ExpectSameReports(one.reports, serial.reports);
  EXPECT_EQ(serial.items, expected);
  EXPECT_EQ(serial.colours, two.colours);
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
    EXPECT_EQ(r.resources[1].bytesWritten, 40u);  // refused stores are dropped, and counted so
    EXPECT_EQ(r.resources[1].storesDroppedOob, static_cast<std::uint64_t>(threads - 10));
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
  EXPECT_EQ(r.resources[1].storesDroppedOob, 3u);

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
  EXPECT_EQ(r.resources[1].storesDroppedOob, 2u);
  EXPECT_EQ(r.lanes.slotOverflow, 0u);
}

// CMAA2's deferred blend lists (aa-facts §4.1): an item takes a slot, swaps its index into its
// quad's head and links to the previous head.
struct Node {
  std::uint32_t next, value;
  friend bool operator==(const Node&, const Node&) = default;
};
constexpr int kListThreads = 4096;
constexpr std::size_t kListCapacity = 3000;  // fewer than the reservations: some are refused
constexpr std::uint32_t kBuckets = 37;

bool Reserves(std::uint32_t i) { return i % 5 != 4; }
std::uint32_t BucketOf(std::uint32_t i) { return (i * 2654435761u >> 12) % kBuckets; }

struct ListRun {
  std::vector<DispatchReport> reports;
  std::vector<std::uint32_t> heads;
  std::vector<Node> nodes;
};

ListRun BuildLists(int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  Machine machine = TestMachine();
  SlotCounter counter("lists/counter", kListCapacity);
  Buffer<std::uint32_t> heads("lists/heads", kBuckets, 4, kEmpty);
  Buffer<Node> nodes("lists/nodes", kListCapacity, 8, Node{kEmpty, kEmpty});
  Dispatch d("test/lists", SmallKernel());
  d.SerialChunks();
  const SlotCounterView slots = d.Slots(counter);
  const SlotView<Node> nodesOut = d.SlotWrite(nodes);
  const RwBufferView<std::uint32_t> headsRw = d.ReadWrite(heads);
  machine.Compute(d, {.threads = {kListThreads, 1, 1}, .groupSize = {64, 1, 1}}, [&](ComputeLane& lane) {
    const auto i = static_cast<std::uint32_t>(lane.threadId.x);
    if (!Reserves(i)) return;
    const QueueSlot slot = slots.Reserve(lane, End::Front);
    const std::optional<std::size_t> index = slots.Index(lane, slot);
    if (!index) return;
    const std::uint32_t previous = headsRw.InterlockedExchange(lane, BucketOf(i), static_cast<std::uint32_t>(*index));
    nodesOut.Store(lane, slot, Node{previous, i});
  });
  return {machine.Reports(), {heads.Elements().begin(), heads.Elements().end()},
          {nodes.Elements().begin(), nodes.Elements().end()}};
}

TEST(SimAtomics, LinkedListsBuiltWithExchangeDoNotDependOnTheThreadCount) {
  const ListRun one = BuildLists(1);
  const ListRun two = BuildLists(2);
  testing::ExpectSameReports(one.reports, two.reports);
  EXPECT_EQ(one.heads, two.heads);
  EXPECT_EQ(one.nodes, two.nodes);

  // Brute force: threads in launch order, until the slots run out.
  std::vector<std::uint32_t> heads(kBuckets, kEmpty);
  std::vector<Node> nodes(kListCapacity, Node{kEmpty, kEmpty});
  std::uint64_t used = 0, refused = 0;
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(kListThreads); ++i) {
    if (!Reserves(i)) continue;
    if (used == kListCapacity) {
      ++refused;
      continue;
    }
    nodes[used] = {heads[BucketOf(i)], i};
    heads[BucketOf(i)] = static_cast<std::uint32_t>(used++);
  }
  ASSERT_GT(refused, 0u);
  EXPECT_EQ(two.heads, heads);
  EXPECT_EQ(two.nodes, nodes);
  const DispatchReport& r = two.reports[0];
  EXPECT_EQ(r.lanes.slotOverflow, refused);
  EXPECT_EQ(r.resources[2].atomics, kListCapacity);           // one exchange per granted item
  EXPECT_EQ(r.resources[1].bytesWritten, 8u * kListCapacity);  // the nodes
}

TEST(SimAtomics, ReturningAtomicsReturnThePreviousValueInLaneOrder) {
  Machine machine = TestMachine();
  Buffer<std::uint32_t> cells("cells", 4, 4, 50);
  Buffer<std::uint32_t> returned("returned", 5 * 100, 4, 0);
  Dispatch d("test/returning", SmallKernel());
  d.SerialChunks();
  const RwBufferView<std::uint32_t> rw = d.ReadWrite(cells);
  const RwBufferView<std::uint32_t> out = d.ReadWrite(returned);
  auto value = [](std::uint32_t i) { return (i * 37u) % 101u; };
  machine.Compute(d, {.threads = {100, 1, 1}}, [&](ComputeLane& lane) {
    const auto i = static_cast<std::uint32_t>(lane.threadId.x);
    out.Store(lane, 5 * i + 0, rw.InterlockedAdd(lane, 0, value(i)));
    out.Store(lane, 5 * i + 1, rw.InterlockedMin(lane, 1, value(i)));
    out.Store(lane, 5 * i + 2, rw.InterlockedMax(lane, 2, value(i)));
    out.Store(lane, 5 * i + 3, rw.InterlockedCompareExchange(lane, 3, value(i) % 2 == 0 ? 50u : 0u, value(i)));
    out.Store(lane, 5 * i + 4, rw.InterlockedAdd(lane, 99, 1));  // out of range: 0, nothing changes
  });
  std::vector<std::uint32_t> cell(4, 50), expected(5 * 100, 0);
  for (std::uint32_t i = 0; i < 100; ++i) {
    const std::uint32_t v = value(i);
    expected[5 * i + 0] = std::exchange(cell[0], cell[0] + v);
    expected[5 * i + 1] = std::exchange(cell[1], std::min(cell[1], v));
    expected[5 * i + 2] = std::exchange(cell[2], std::max(cell[2], v));
    expected[5 * i + 3] = cell[3];
    if (cell[3] == (v % 2 == 0 ? 50u : 0u)) cell[3] = v;
  }
  EXPECT_EQ(std::vector<std::uint32_t>(returned.Elements().begin(), returned.Elements().end()), expected);
  EXPECT_EQ(std::vector<std::uint32_t>(cells.Elements().begin(), cells.Elements().end()), cell);
}

TEST(SimAtomics, OrderIndependentAtomicsRunInParallelAndOrderDependentOnesAreRefused) {
  Machine machine = TestMachine();
  Buffer<std::uint32_t> cells("cells", 3, 4, 500);
  Dispatch d("test/commuting", SmallKernel());
  const RwBufferView<std::uint32_t> rw = d.ReadWrite(cells);
  machine.Compute(d, {.threads = {2048, 1, 1}}, [&](ComputeLane& lane) {
    const auto i = static_cast<std::uint32_t>(lane.threadId.x);
    rw.AtomicAdd(lane, 0, i);
    rw.AtomicMin(lane, 1, (i * 37u) % 1001u + 3);
    rw.AtomicMax(lane, 2, (i * 37u) % 1001u + 3);
  });
  EXPECT_EQ(cells.At(0), 500u + 2047u * 2048u / 2);
  EXPECT_EQ(cells.At(1), 3u);
  EXPECT_EQ(cells.At(2), 1003u);

  SlotCounter counter("refused/counter", 16);
  auto expectRefused = [&](const char* name, auto&& kernel) {
    Dispatch parallel(name, SmallKernel());
    const RwBufferView<std::uint32_t> cellsRw = parallel.ReadWrite(cells);
    const SlotCounterView slots = parallel.Slots(counter);
    try {
      machine.Compute(parallel, {.threads = {64, 1, 1}}, [&](ComputeLane& lane) { kernel(lane, cellsRw, slots); });
      ADD_FAILURE() << name << ": expected a KernelError";
    } catch (const KernelError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(name), std::string::npos) << message;
      EXPECT_NE(message.find("SerialChunks"), std::string::npos) << message;
    }
  };
  expectRefused("test/exchange", [](ComputeLane& lane, const RwBufferView<std::uint32_t>& target, const SlotCounterView&) {
    target.InterlockedExchange(lane, 0, 1);
  });
  expectRefused("test/add", [](ComputeLane& lane, const RwBufferView<std::uint32_t>& target, const SlotCounterView&) {
    target.InterlockedAdd(lane, 0, 1);
  });
  expectRefused("test/slot-index", [](ComputeLane& lane, const RwBufferView<std::uint32_t>&, const SlotCounterView& slots) {
    slots.Index(lane, slots.Reserve(lane, End::Front));
  });
}

}  // namespace
}  // namespace sim
