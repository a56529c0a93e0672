#pragma once
// The two dispatch strategies, written once (DESIGN.md "Dispatch strategies"). A pass supplies
// a detect kernel (does the pixel's per-pixel work and says whether the pixel joins the work set)
// and a consume kernel (the expensive work on work-set pixels); RunWorkSet runs them as
//
//   stencil-culled   <pass>/<detect>   full-screen PS: detect, stencil = 1 on work-set pixels
//                    <pass>/<consume>  full-screen PS, stencil == 1, hi-stencil pretest on
//   deferred queue   <pass>/<detect>   compute, 8x8 groups: [prologue, barrier,] detect, append
//                                      the pixel to the queue
//                    <pass>/queue-args one thread: queue count -> indirect group counts
//                    <pass>/<consume>  indirect compute, 64 threads per group, one queued pixel
//                                      per thread (the pixel comes with the indirect call)
//
// A pass may name a second consume (Filmic SMAA's horizontal edges after its vertical ones):
// the detect then returns which consume a pixel joins (1 or 2, 0 for none) and each consume runs
// on its own pixels, in order: stencil values 1 and 2 tested by two full-screen passes, or two
// queues, one queue-args thread writing both argument triples, two indirect dispatches.
//
// A pass may instead give the queue a packed layout (PackedQueueLayout, MiniEngine FXAA's,
// aa-facts §3): the detect returns a PackedItem (which consume, a pass-encoded 32-bit item, a
// 32-bit payload); the queue strategy keeps ONE double-ended queue whose first consume's items
// fill from the front and the second's from the back, with a payload queue written at the same
// slots; a one-group resolve kernel pads each count to a multiple of 64 with the layout's dummy
// item, writes both argument triples and resets the counters; each consume thread gets its item
// (from the back for the second consume) and loads the payload when it asks for it. Dummy lanes
// run the consume, which must make their stores out-of-bounds (dropped and counted). The stencil
// strategy records item and payload per pixel in two R32 targets next to the stencil (the
// detect's extra render targets) and its consumes load them, so both strategies run the same
// consume on the same items. The consume is (lane, x, y, item, loadPayload).
//
// Run may be given a region (WorkRegion) instead of the screen size: the detect and consumes run
// over that rectangle only (MiniEngine FXAA runs its whole pipeline per screen quadrant): compute
// threads and full-screen lanes are offset by the region's origin, the stencil and record
// targets have the region's size, the queue and arguments keep the screen's.
//
// Kernels are bound per dispatch: the pass gives factories that take the sim::Dispatch, bind the
// resources they read and write on it and return the kernel, a generic callable
// (lane, x, y) templated on the lane type (sim::PixelLane under the stencil strategy,
// sim::ComputeLane under the queue). A compute detect may come with a prologue stage (e.g. an
// LDS tile fill) by returning StagedDetect. Identical arithmetic under both strategies is the
// pass's promise; passes/compare.h checks it.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "passes/pass.h"
#include "sim/atomics.h"
#include "sim/check.h"
#include "sim/dispatch.h"

namespace passes {

// A queue of pass-encoded items (MiniEngine FXAA, aa-facts §3).
struct PackedQueueLayout {
  glm::ivec2 (*unpack)(std::uint32_t item);  // the item's screen pixel
  std::uint32_t dummyItem;                     // the padding item; its pixel must be off the screen
  // Slots of the double-ended queue for a screen (both consumes' items and their padding).
  std::size_t (*capacity)(int screenWidth, int screenHeight);
  std::string_view resolveDispatch;            // "fxaa-miniengine/resolve-work-queue"
  sim::KernelInfo resolve;
  // The pixel form of side effects the compute detect's prologue has beyond its own pixels
  // (MiniEngine stores the luma of its whole LDS tile, apron included): under the stencil
  // strategy a full-screen pass over the region grown by `pixelPrologueApron` pixels (clipped to
  // the screen) runs the kernel the detect factory gives for PixelPrologueForm before the detect.
  // Empty dispatch name: none.
  std::string_view pixelPrologueDispatch = {};
  sim::KernelInfo pixelPrologue = {};
  int pixelPrologueApron = 0;
};

// What a detect returns under a packed layout: joins 0 (none), 1 (front) or 2 (back).
struct PackedItem {
  int joins = 0;
  std::uint32_t item = 0;
  std::uint32_t payload = 0;
};

// The rectangle of the screen a work set runs over.
struct WorkRegion {
  int x = 0, y = 0, width = 0, height = 0;
};

struct WorkSetKernels {
  std::string_view detectDispatch;   // "demo/edge-detect"
  std::string_view consumeDispatch;  // "demo/blend"
  sim::KernelInfo detectPixel;       // the stencil strategy's full-screen detect
  sim::KernelInfo detectCompute;     // the queue strategy's compute detect (its LDS included)
  sim::KernelInfo consume;           // both strategies' consume
  // Optional second consume, run after the first on the pixels the detect gave 2; its factory is
  // then make_consume(sim::Dispatch&, int consume) with consume 0 or 1.
  std::string_view secondConsumeDispatch = {};
  sim::KernelInfo secondConsume = {};
  // Optional packed queue layout (see above); requires a second consume.
  const PackedQueueLayout* packed = nullptr;

  int Consumes() const { return secondConsumeDispatch.empty() ? 1 : 2; }
};

// A compute detect with a prologue every thread of the group runs before a barrier.
template <typename Prologue, typename Detect>
struct StagedDetect {
  Prologue prologue;  // (sim::ComputeLane&) -> void
  Detect detect;      // (sim::ComputeLane&, int x, int y) -> bool, or int with two consumes
};

// Which kernel a detect factory binds: its full-screen pixel form or its compute form, as a
// type so the factory can return a different kernel type for each (if constexpr on the tag).
enum class DetectForm : std::uint8_t { Pixel, Compute, PixelPrologue };
using PixelForm = std::integral_constant<DetectForm, DetectForm::Pixel>;
using ComputeForm = std::integral_constant<DetectForm, DetectForm::Compute>;
// Asked for only under a packed layout with a pixel prologue (PackedQueueLayout).
using PixelPrologueForm = std::integral_constant<DetectForm, DetectForm::PixelPrologue>;

// 8x8: a hi-stencil tile and a compute group (one 64-lane wave), the MiniEngine FXAA and CMAA2
// group shape (aa-facts §3, §4).
inline constexpr int kWorkSetTileSide = 8;

// The shape of a work set given as one byte per pixel (non-zero = in the set).
WorkSetShape ShapeOf(std::span<const std::uint8_t> marked, int width, int height);

// The work set's machine resources, kept across frames so a sequence does not reallocate them:
// the stencil target and the pixel queue with its indirect arguments, named after the pass.
class WorkSet {
 public:
  explicit WorkSet(std::string_view pass);

  // make_detect(sim::Dispatch&, PixelForm or ComputeForm) -> detect kernel (or a StagedDetect in
  // the compute form);
  // make_consume(sim::Dispatch&) -> consume kernel, or make_consume(sim::Dispatch&, int consume)
  // with a second consume. Returns the work set's shape (both consumes' pixels).
  template <typename MakeDetect, typename MakeConsume>
  WorkSetShape Run(sim::Machine& machine, Strategy strategy, const WorkSetKernels& kernels, int width,
                   int height, MakeDetect&& makeDetect, MakeConsume&& makeConsume) {
    return Run(machine, strategy, kernels, width, height, {0, 0, width, height}, makeDetect, makeConsume);
  }
  // The same over `region` of a screen of width x height; the shape is the region's (its
  // coordinates relative to the region's origin).
  template <typename MakeDetect, typename MakeConsume>
  WorkSetShape Run(sim::Machine& machine, Strategy strategy, const WorkSetKernels& kernels, int width, int height,
                   const WorkRegion& region, MakeDetect&& makeDetect, MakeConsume&& makeConsume);

  // After Run, read back on the host (not a machine operation): per pixel of the region,
  // row-major, the consume it joined (1 or 2) or 0.
  std::vector<std::uint8_t> Membership(Strategy strategy) const;
  // After Run: the dummy items the packed queue's consumes ran (0 otherwise).
  std::uint64_t Padding() const { return padding_; }
  // After Run: whether the packed queue overflowed (reservations refused, counted as
  // slots/overflow, or one end's padding overwriting the other end's items, as on a GPU).
  bool Overflowed() const { return overflowed_; }
  // After a packed queue run, host readbacks: the queue's slots, the payload slots, the two
  // argument triples and the two counters (reset by the resolve).
  std::span<const std::uint32_t> PackedQueue() const { return packedItems_->Elements(); }
  std::span<const std::uint32_t> PackedPayloads() const { return packedPayloads_->Elements(); }
  std::span<const std::uint32_t> QueueArguments() const { return arguments_->Elements(); }
  std::span<const std::uint32_t> PackedCounters() const { return slots_->Counters().Elements(); }

 private:
  static constexpr int kGroupSide = kWorkSetTileSide;

  void Prepare(Strategy strategy, const WorkSetKernels& kernels, int width, int height, const WorkRegion& region);
  std::uint64_t StencilPixels() const;
  // Read back on the host after the consume dispatch, for the report (not a machine operation).
  WorkSetShape Shape(Strategy strategy) const;
  void WriteQueueArguments(sim::Machine& machine);
  void ResolvePackedQueue(sim::Machine& machine, const PackedQueueLayout& layout);
  std::string Name(std::string_view suffix) const { return pass_ + "/" + std::string(suffix); }
  std::size_t LastSlot() const { return packedItems_->Size() - 1; }

  template <typename MakeDetect, typename MakeConsume>
  std::uint64_t RunStencilCulled(sim::Machine& machine, const WorkSetKernels& kernels, MakeDetect& makeDetect,
                                 MakeConsume& makeConsume);
  template <typename MakeDetect, typename MakeConsume>
  std::uint64_t RunDeferredQueue(sim::Machine& machine, const WorkSetKernels& kernels, MakeDetect& makeDetect,
                                 MakeConsume& makeConsume);
  template <typename MakeDetect>
  void RunPixelPrologue(sim::Machine& machine, const PackedQueueLayout& layout, MakeDetect& makeDetect) const;
  // The compute detect over the region: `join(lane, x, y, result)` takes each thread's result.
  // Returns the dispatch's refused slot reservations.
  template <typename Detect, typename Join>
  std::uint64_t RunComputeDetect(sim::Machine& machine, sim::Dispatch& d, Detect& detect, Join&& join) const;

  std::string pass_;
  int width_ = 0, height_ = 0;  // the screen
  WorkRegion region_;
  std::optional<sim::StencilBuffer> stencil_;  // the region's
  // One queue per consume; the arguments hold one {groups, 1, 1} triple per queue.
  std::vector<sim::AppendBuffer<std::uint32_t>> queues_;
  std::optional<sim::Buffer<std::uint32_t>> arguments_;
  // The packed layout's double-ended queue, its payloads and counters; under the stencil
  // strategy the per-pixel item and payload records of the region.
  std::optional<sim::SlotCounter> slots_;
  std::optional<sim::Buffer<std::uint32_t>> packedItems_, packedPayloads_;
  std::optional<sim::Texture2D<std::uint32_t>> itemRecords_, payloadRecords_;
  glm::ivec2 (*unpack_)(std::uint32_t item) = nullptr;
  std::uint32_t frontCount_ = 0, backCount_ = 0;  // read back before the resolve resets them
  std::uint64_t padding_ = 0;
  bool overflowed_ = false;
};

// Whether a detect factory's kernels return PackedItem (the packed queue layout).
template <typename MakeDetect>
constexpr bool kDetectsPackedItems = [] {
  using Pixel = decltype(std::declval<MakeDetect&>()(std::declval<sim::Dispatch&>(), PixelForm{}));
  return std::is_same_v<std::invoke_result_t<Pixel&, sim::PixelLane&, int, int>, PackedItem>;
}();

// The consume factory's call for consume `index`: with one consume it takes the dispatch only.
template <typename MakeConsume>
auto MakeConsumeKernel(MakeConsume& makeConsume, sim::Dispatch& d, int index) {
  if constexpr (std::is_invocable_v<MakeConsume&, sim::Dispatch&, int>) {
    return makeConsume(d, index);
  } else {
    return makeConsume(d);
  }
}

inline const sim::KernelInfo& ConsumeKernel(const WorkSetKernels& kernels, int index) {
  return index == 0 ? kernels.consume : kernels.secondConsume;
}
inline std::string_view ConsumeDispatch(const WorkSetKernels& kernels, int index) {
  return index == 0 ? kernels.consumeDispatch : kernels.secondConsumeDispatch;
}

template <typename MakeDetect, typename MakeConsume>
WorkSetShape WorkSet::Run(sim::Machine& machine, Strategy strategy, const WorkSetKernels& kernels, int width,
                          int height, const WorkRegion& region, MakeDetect&& makeDetect, MakeConsume&& makeConsume) {
  Prepare(strategy, kernels, width, height, region);
  const std::uint64_t pixels = strategy == Strategy::StencilCulled
                                   ? RunStencilCulled(machine, kernels, makeDetect, makeConsume)
                                   : RunDeferredQueue(machine, kernels, makeDetect, makeConsume);
  const WorkSetShape shape = Shape(strategy);
  // An overflowed packed queue lost items (refused, or overwritten by the other end's padding):
  // its shape is what the queue still holds.
  AASIM_CHECK(overflowed_ || shape.pixels == pixels);
  return shape;
}

template <typename MakeDetect, typename MakeConsume>
std::uint64_t WorkSet::RunStencilCulled(sim::Machine& machine, const WorkSetKernels& kernels,
                                        MakeDetect& makeDetect, MakeConsume& makeConsume) {
  const WorkRegion r = region_;
  if constexpr (kDetectsPackedItems<MakeDetect>) {
    if (!kernels.packed->pixelPrologueDispatch.empty()) RunPixelPrologue(machine, *kernels.packed, makeDetect);
  }
  {
    sim::Dispatch d(std::string(kernels.detectDispatch), kernels.detectPixel);
    auto detect = makeDetect(d, PixelForm{});
    const sim::StencilView mark = d.Stencil(*stencil_);
    if constexpr (kDetectsPackedItems<MakeDetect>) {
      AASIM_CHECK(kernels.packed != nullptr);
      // The detect's two extra render targets: the item and its payload.
      const sim::RwTextureView<std::uint32_t> items = d.ReadWrite(*itemRecords_), payloads = d.ReadWrite(*payloadRecords_);
      machine.FullScreen(d, {.width = r.width, .height = r.height}, [&](sim::PixelLane& lane) {
        const PackedItem joined = detect(lane, lane.x + r.x, lane.y + r.y);
        if (joined.joins == 0) return;
        mark.Store(lane, static_cast<std::uint8_t>(joined.joins));
        items.Store(lane, lane.x, lane.y, joined.item);
        payloads.Store(lane, lane.x, lane.y, joined.payload);
      });
    } else {
      machine.FullScreen(d, {.width = r.width, .height = r.height}, [&](sim::PixelLane& lane) {
        if (const int joins = static_cast<int>(detect(lane, lane.x + r.x, lane.y + r.y))) {
          mark.Store(lane, static_cast<std::uint8_t>(joins));
        }
      });
    }
  }
  for (int index = 0; index < kernels.Consumes(); ++index) {
    sim::Dispatch d(std::string(ConsumeDispatch(kernels, index)), ConsumeKernel(kernels, index));
    auto consume = MakeConsumeKernel(makeConsume, d, index);
    const sim::FullScreenCall call{.width = r.width, .height = r.height, .stencil = &*stencil_,
                                   .stencilRef = static_cast<std::uint8_t>(index + 1)};
    if constexpr (kDetectsPackedItems<MakeDetect>) {
      const sim::TextureView<std::uint32_t> items = d.Read(*itemRecords_), payloads = d.Read(*payloadRecords_);
      machine.FullScreen(d, call, [&](sim::PixelLane& lane) {
        consume(lane, lane.x + r.x, lane.y + r.y, items.Load(lane, lane.x, lane.y),
                [&] { return payloads.Load(lane, lane.x, lane.y); });
      });
    } else {
      machine.FullScreen(d, call, [&](sim::PixelLane& lane) { consume(lane, lane.x + r.x, lane.y + r.y); });
    }
  }
  return StencilPixels();
}

template <typename MakeDetect>
void WorkSet::RunPixelPrologue(sim::Machine& machine, const PackedQueueLayout& layout, MakeDetect& makeDetect) const {
  const int apron = layout.pixelPrologueApron;
  const int x0 = std::max(0, region_.x - apron), y0 = std::max(0, region_.y - apron);
  const int x1 = std::min(width_, region_.x + region_.width + apron);
  const int y1 = std::min(height_, region_.y + region_.height + apron);
  sim::Dispatch d(std::string(layout.pixelPrologueDispatch), layout.pixelPrologue);
  auto prologue = makeDetect(d, PixelPrologueForm{});
  machine.FullScreen(d, {.width = x1 - x0, .height = y1 - y0},
                     [&](sim::PixelLane& lane) { prologue(lane, lane.x + x0, lane.y + y0); });
}

template <typename Detect, typename Join>
std::uint64_t WorkSet::RunComputeDetect(sim::Machine& machine, sim::Dispatch& d, Detect& detect, Join&& join) const {
  const WorkRegion r = region_;
  d.SetPixelGrid(width_, height_, {r.x, r.y});
  auto detectAndJoin = [&](auto& kernel) {
    return [&](sim::ComputeLane& lane) {
      if (lane.threadId.x >= r.width || lane.threadId.y >= r.height) return;
      const int x = lane.threadId.x + r.x, y = lane.threadId.y + r.y;
      join(lane, x, y, kernel(lane, x, y));
    };
  };
  constexpr glm::ivec3 group{kGroupSide, kGroupSide, 1};
  if constexpr (requires { detect.prologue; }) {
    // Whole groups over the region, so every thread of an edge group helps its prologue; threads
    // past the region skip the detect stage.
    const glm::ivec3 threads{(r.width + kGroupSide - 1) / kGroupSide * kGroupSide,
                             (r.height + kGroupSide - 1) / kGroupSide * kGroupSide, 1};
    return machine.Compute(d, {.threads = threads, .groupSize = group}, detect.prologue, detectAndJoin(detect.detect))
        .lanes.slotOverflow;
  } else {
    return machine.Compute(d, {.threads = {r.width, r.height, 1}, .groupSize = group}, detectAndJoin(detect))
        .lanes.slotOverflow;
  }
}

template <typename MakeDetect, typename MakeConsume>
std::uint64_t WorkSet::RunDeferredQueue(sim::Machine& machine, const WorkSetKernels& kernels,
                                        MakeDetect& makeDetect, MakeConsume& makeConsume) {
  const PackedQueueLayout* packed = kernels.packed;
  {
    sim::Dispatch d(std::string(kernels.detectDispatch), kernels.detectCompute);
    auto detect = makeDetect(d, ComputeForm{});
    if constexpr (kDetectsPackedItems<MakeDetect>) {
      AASIM_CHECK(packed != nullptr);
      const sim::SlotCounterView slots = d.Slots(*slots_);
      const sim::SlotView<std::uint32_t> items = d.SlotWrite(*packedItems_), payloads = d.SlotWrite(*packedPayloads_);
      overflowed_ = RunComputeDetect(machine, d, detect, [&](sim::ComputeLane& lane, int, int, const PackedItem& joined) {
        if (joined.joins == 0) return;
        const sim::QueueSlot slot = slots.Reserve(lane, joined.joins == 1 ? sim::End::Front : sim::End::Back);
        items.Store(lane, slot, joined.item);
        payloads.Store(lane, slot, joined.payload);
      }) != 0;
    } else {
      std::vector<sim::AppendView<std::uint32_t>> appends;
      for (sim::AppendBuffer<std::uint32_t>& queue : queues_) appends.push_back(d.Append(queue));
      RunComputeDetect(machine, d, detect, [&](sim::ComputeLane& lane, int x, int y, auto joined) {
        if (const int joins = static_cast<int>(joined)) {
          appends[static_cast<std::size_t>(joins - 1)].Append(lane, sim::PackPixelItem(x, y));
        }
      });
    }
  }
  if (packed != nullptr) {
    frontCount_ = slots_->Count(sim::End::Front);
    backCount_ = slots_->Count(sim::End::Back);
    ResolvePackedQueue(machine, *packed);
  } else {
    WriteQueueArguments(machine);
  }
  std::uint64_t pixels = 0;
  for (int index = 0; index < kernels.Consumes(); ++index) {
    sim::Dispatch d(std::string(ConsumeDispatch(kernels, index)), ConsumeKernel(kernels, index));
    d.SetPixelGrid(width_, height_);
    if constexpr (kDetectsPackedItems<MakeDetect>) {
      const sim::BufferView<std::uint32_t> items = d.Read(*packedItems_), payloads = d.Read(*packedPayloads_);
      auto consume = MakeConsumeKernel(makeConsume, d, index);
      const bool fromBack = index == 1;
      const sim::IndirectCall call{.arguments = &*arguments_, .offset = 3 * static_cast<std::size_t>(index),
                                   .groupSize = {sim::kWaveLanes, 1, 1}, .pixelItems = items,
                                   .unpackItem = packed->unpack, .itemsFromBack = fromBack};
      const std::size_t last = LastSlot();
      machine.ComputeIndirect(d, call, [&](sim::ComputeLane& lane) {
        const auto thread = static_cast<std::size_t>(lane.threadId.x);
        const std::size_t slot = fromBack ? last - thread : thread;
        consume(lane, lane.pixel.x, lane.pixel.y, lane.item, [&] { return payloads.Load(lane, slot); });
      });
      pixels += fromBack ? backCount_ : frontCount_;
    } else {
    sim::AppendBuffer<std::uint32_t>& queue = queues_[static_cast<std::size_t>(index)];
    const sim::BufferView<std::uint32_t> items = d.Read(queue.Storage());
    auto consume = MakeConsumeKernel(makeConsume, d, index);
    const sim::IndirectCall call{.arguments = &*arguments_, .offset = 3 * static_cast<std::size_t>(index),
                                 .groupSize = {sim::kWaveLanes, 1, 1}, .itemCount = &queue.Counter(),
                                 .itemCountIndex = 0, .pixelItems = items};
    machine.ComputeIndirect(d, call, [&](sim::ComputeLane& lane) { consume(lane, lane.pixel.x, lane.pixel.y); });
    pixels += queue.Count();
    }
  }
  return pixels;
}

}  // namespace passes
