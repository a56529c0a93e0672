#pragma once
// Slot atomics: a counter pair a kernel reserves slots from, and stores into reserved slots.
//
// MiniEngine's FXAA fills one queue from both ends (aa-facts §3): horizontal items take
// idx = atomicAdd(counter[0], 1) from the front, vertical items idx = last - atomicAdd(counter[1], 1)
// from the back. On a GPU the indices depend on which wave reaches the atomic first; here they
// must not depend on the host thread count. Chunks (sim/lanes.h) run in parallel, so a lane
// cannot know how many slots earlier chunks will take: a reservation is logged in its chunk and
// granted when the chunk is committed after the dispatch, chunks in order and lanes in order
// within a chunk (a prefix sum in chunk order). Until then a slot has no index, so stores into
// it are staged too and land at commit (SlotView): nothing can read a slot value before it is
// final. Where the index itself is data (CMAA2 links list items by it, aa-facts §4.1) the
// dispatch runs its chunks serially (Dispatch::SerialChunks): a reservation is granted at once,
// SlotCounterView::Index returns it and slot stores land at once.
//
// Overflow: a reservation is granted only when all its slots fit between the front and the back
// fill; otherwise it is refused whole, its slots are counted in slots/overflow and its stores
// are dropped like out-of-range stores (stores_dropped_oob), as a GPU's would be. The counters
// hold granted slots only (as the append counter does), so a later resolve kernel never sees
// more than the capacity. A GPU keeps counting past the capacity and lets the two fills
// overwrite each other; MiniEngine sizes its queue so that cannot happen.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "sim/lanes.h"
#include "sim/resources.h"
#include "sim/views.h"

namespace sim {

// Two counters over `capacity` slots: element 0 counts slots granted from the front (indices 0,
// 1, ...), element 1 slots granted from the back (capacity - 1, capacity - 2, ...). Later
// dispatches read the counters through Counters() (MiniEngine's resolve kernel turns them into
// indirect arguments and resets them).
class SlotCounter {
 public:
  SlotCounter(std::string name, std::size_t capacity) : counters_(CheckedName(std::move(name), capacity), 2, 4),
                                                        capacity_(capacity) {}

  const std::string& Name() const { return counters_.Name(); }
  std::size_t Capacity() const { return capacity_; }
  std::uint32_t Count(End end) const { return counters_.At(Element(end)); }
  void Reset() { counters_.At(0) = counters_.At(1) = 0; }
  Buffer<std::uint32_t>& Counters() { return counters_; }
  const Buffer<std::uint32_t>& Counters() const { return counters_; }

  // Grants `count` slots from `end` when they fit between the two fills, returning the end's
  // count before them (what the GPU's atomicAdd returns); std::nullopt when refused.
  std::optional<std::uint32_t> Grant(End end, std::uint32_t count) {
    const std::uint64_t taken = std::uint64_t{counters_.At(0)} + counters_.At(1);
    if (taken + count > capacity_) return std::nullopt;
    std::uint32_t& counter = counters_.At(Element(end));
    const std::uint32_t before = counter;
    counter += count;
    return before;
  }
  // The buffer index of the k-th slot from `end`.
  std::size_t Index(End end, std::uint32_t k) const { return end == End::Front ? k : capacity_ - 1 - k; }
  static std::size_t Element(End end) { return end == End::Front ? 0 : 1; }

 private:
  static std::string CheckedName(std::string name, std::size_t capacity) {
    // The counters are 32-bit, as the UAV counters they model.
    if (capacity > std::numeric_limits<std::uint32_t>::max()) {
      throw std::invalid_argument("slot counter '" + name + "': capacity " + std::to_string(capacity) +
                                  " exceeds 2^32 - 1");
    }
    return name;
  }

  Buffer<std::uint32_t> counters_;
  std::size_t capacity_;
};

// `count` consecutive slots reserved from one end by one lane; element i is the i-th slot
// counted from that end. Opaque: a kernel passes it to SlotView::Store.
class QueueSlot {
 public:
  std::uint32_t Count() const { return count_; }

 private:
  friend class SlotCounterView;
  template <typename T>
  friend class SlotView;

  const SlotCounter* counter_ = nullptr;
  int counterIndex_ = -1;      // the dispatch's slot counter binding
  End end_ = End::Front;
  std::uint32_t count_ = 0;
  // Position in the chunk's reservation log; once granted (serial chunks), the first slot's k
  // from its end, or kSlotRefused.
  std::uint32_t ordinal_ = 0;
  bool granted_ = false;
  bool dropped_ = false;  // reserved by a helper lane: nothing was reserved
};

namespace detail {
inline constexpr std::uint32_t kSlotRefused = std::numeric_limits<std::uint32_t>::max();

// A staged store into a slot, followed in the staging bytes by the value.
struct StagedSlotStore {
  const SlotCounter* counter;
  std::uint32_t counterIndex;
  std::uint32_t ordinal;
  std::uint32_t element;
  End end;
};

inline void CheckSlotElement(const LaneBase& lane, const std::string& counter, std::uint32_t count,
                             std::uint32_t element) {
  if (element >= count) {
    throw KernelError(lane.chunk->dispatch->name + ": element " + std::to_string(element) + " of a slot of " +
                      std::to_string(count) + " from '" + counter + "'");
  }
}

// Grants one chunk's reservations of one counter in lane order: the first granted k per
// reservation, or kSlotRefused (whose slots are added to `overflow`).
inline std::vector<std::uint32_t> GrantReservations(SlotCounter& counter, std::span<const SlotReservation> log,
                                                    std::uint64_t& overflow) {
  std::vector<std::uint32_t> granted;
  granted.reserve(log.size());
  for (const SlotReservation& reservation : log) {
    const std::optional<std::uint32_t> first = counter.Grant(reservation.end, reservation.count);
    if (!first) overflow += reservation.count;
    granted.push_back(first.value_or(kSlotRefused));
  }
  return granted;
}

// Writes one chunk's staged stores into `buffer` once its reservations are granted (`granted`
// per counter binding, as GrantReservations returned them).
template <typename T>
void CommitSlotStores(Buffer<T>& buffer, std::span<const std::byte> staged,
                      std::span<const std::vector<std::uint32_t>> granted, ResourceTraffic& traffic) {
  const auto bytes = static_cast<std::size_t>(buffer.ElementBytes());
  for (std::size_t at = 0; at < staged.size(); at += sizeof(StagedSlotStore) + sizeof(T)) {
    StagedSlotStore store;
    std::memcpy(&store, staged.data() + at, sizeof(store));
    const std::uint32_t first = granted[store.counterIndex][store.ordinal];
    const std::size_t index =
        first == kSlotRefused ? buffer.Size() : store.counter->Index(store.end, first + store.element);
    if (index >= buffer.Size()) {
      ++traffic.storesDroppedOob;
      continue;
    }
    std::memcpy(&buffer.At(index), staged.data() + at + sizeof(store), sizeof(T));
    buffer.TouchWrite(index * bytes, bytes);
    traffic.bytesWritten += bytes;
  }
}
}  // namespace detail

// Reserves slots from a SlotCounter bound to a dispatch (Dispatch::Slots).
class SlotCounterView {
 public:
  SlotCounterView(SlotCounter& counter, int counterIndex, ViewBinding binding)
      : counter_(&counter), counterIndex_(counterIndex), binding_(std::move(binding)) {}

  // idx = atomicAdd(counter[end], count): one atomic on the counter. Helper lanes reserve
  // nothing (their atomics are dropped, hw-facts §6.1).
  QueueSlot Reserve(const LaneBase& lane, End end, std::uint32_t count = 1) const {
    QueueSlot slot;
    slot.counter_ = counter_;
    slot.counterIndex_ = counterIndex_;
    slot.end_ = end;
    slot.count_ = count;
    if (lane.helper) {
      slot.dropped_ = true;
      return slot;
    }
    ++detail::Traffic(lane, binding_).atomics;
    counter_->Counters().TouchWrite(SlotCounter::Element(end) * 4, 4);
    if (lane.chunk->serial) {
      const std::optional<std::uint32_t> first = counter_->Grant(end, count);
      if (!first) lane.chunk->lanes.slotOverflow += count;
      slot.ordinal_ = first.value_or(detail::kSlotRefused);
      slot.granted_ = true;
      return slot;
    }
    std::vector<detail::SlotReservation>& log = lane.chunk->reservations[static_cast<std::size_t>(counterIndex_)];
    slot.ordinal_ = static_cast<std::uint32_t>(log.size());
    log.push_back({end, count});
    return slot;
  }
  // The buffer index of `element` of a slot (the value atomicAdd gave the GPU kernel), for kernels
  // that store it as data, as CMAA2's linked lists do (aa-facts §4.1); std::nullopt when the
  // reservation was refused or made by a helper lane. Known only where chunks run serially: a
  // KernelError elsewhere.
  std::optional<std::size_t> Index(const LaneBase& lane, const QueueSlot& slot, std::uint32_t element = 0) const {
    detail::CheckOrigin(lane, binding_);
    detail::RequireSerialChunks(lane, "a slot's index");
    detail::CheckSlotElement(lane, slot.counter_->Name(), slot.count_, element);
    if (slot.dropped_ || slot.ordinal_ == detail::kSlotRefused) return std::nullopt;
    return slot.counter_->Index(slot.end_, slot.ordinal_ + element);
  }

 private:
  SlotCounter* counter_;
  int counterIndex_;
  ViewBinding binding_;
};

// Stores into slots reserved in the same dispatch (Dispatch::SlotWrite). Stores are staged and
// written when the dispatch commits, so the buffer shows them only to later dispatches; a store
// to a refused slot or past the buffer is dropped.
template <typename T>
class SlotView {
 public:
  SlotView(Buffer<T>& buffer, ViewBinding binding, int stagingIndex)
      : buffer_(&buffer), binding_(std::move(binding)), stagingIndex_(stagingIndex) {}

  std::size_t Size() const { return buffer_->Size(); }
  // buffer[idx + element] for a front slot, buffer[idx - element] for a back slot.
  void Store(const LaneBase& lane, const QueueSlot& slot, const T& value, std::uint32_t element = 0) const {
    static_assert(std::is_trivially_copyable_v<T>);
    detail::CheckOrigin(lane, binding_);
    detail::CheckSlotElement(lane, slot.counter_->Name(), slot.count_, element);
    if (lane.helper || slot.dropped_) return;
    if (slot.granted_) {
      StoreGranted(lane, slot, value, element);
      return;
    }
    const detail::StagedSlotStore store{slot.counter_, static_cast<std::uint32_t>(slot.counterIndex_), slot.ordinal_,
                                        element, slot.end_};
    std::vector<std::byte>& staging = lane.chunk->slotStores[static_cast<std::size_t>(stagingIndex_)];
    const std::size_t at = staging.size();
    staging.resize(at + sizeof(store) + sizeof(T));
    std::memcpy(staging.data() + at, &store, sizeof(store));
    std::memcpy(staging.data() + at + sizeof(store), &value, sizeof(T));
  }

 private:
  void StoreGranted(const LaneBase& lane, const QueueSlot& slot, const T& value, std::uint32_t element) const {
    const std::size_t index = slot.ordinal_ == detail::kSlotRefused
                                  ? buffer_->Size()
                                  : slot.counter_->Index(slot.end_, slot.ordinal_ + element);
    ResourceTraffic& traffic = detail::Traffic(lane, binding_);
    if (index >= buffer_->Size()) {
      ++traffic.storesDroppedOob;
      return;
    }
    const auto bytes = static_cast<std::size_t>(buffer_->ElementBytes());
    std::memcpy(&buffer_->At(index), &value, sizeof(T));
    buffer_->TouchWrite(index * bytes, bytes);
    traffic.bytesWritten += bytes;
  }

  Buffer<T>* buffer_;
  ViewBinding binding_;
  int stagingIndex_;
};

}  // namespace sim
