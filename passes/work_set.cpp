// The work set's resources and its shared queue-arguments kernel (see work_set.h).

#include "passes/work_set.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

namespace passes {
namespace {

constexpr sim::KernelInfo kQueueArgumentsKernel{
    .vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 8,
    .source = "hand count: one load, an add and a shift for ceil(n / 64), three stores (the MiniEngine FXAA "
              "argument shader has the same shape, aa-facts §3)"};

}  // namespace

WorkSet::WorkSet(std::string_view pass) : pass_(pass) {}

void WorkSet::Prepare(Strategy strategy, const WorkSetKernels& kernels, int width, int height,
                      const WorkRegion& region) {
  const int consumes = kernels.Consumes();
  if (width != width_ || height != height_ || (!queues_.empty() && queues_.size() != static_cast<std::size_t>(consumes))) {
    stencil_.reset();
    queues_.clear();
    arguments_.reset();
    slots_.reset();
    packedItems_.reset();
    packedPayloads_.reset();
    width_ = width;
    height_ = height;
  }
  AASIM_CHECK(region.x >= 0 && region.y >= 0 && region.width >= 1 && region.height >= 1 &&
              region.x + region.width <= width && region.y + region.height <= height);
  region_ = region;
  padding_ = 0;
  overflowed_ = false;
  if (strategy == Strategy::StencilCulled) {
    if (!stencil_ || stencil_->Width() != region.width || stencil_->Height() != region.height) {
      stencil_.emplace(Name("stencil"), region.width, region.height);
    }
    stencil_->Clear(0);
    if (kernels.packed != nullptr && (!itemRecords_ || itemRecords_->Width() != region.width ||
                                      itemRecords_->Height() != region.height)) {
      itemRecords_.emplace(Name("item-records"), region.width, region.height);
      payloadRecords_.emplace(Name("payload-records"), region.width, region.height);
    }
    return;
  }
  if (kernels.packed != nullptr) {
    AASIM_CHECK_EQ(consumes, 2);
    unpack_ = kernels.packed->unpack;
    if (!slots_) {
      // Created once, its counters cleared once: the resolve kernel resets them after each use.
      const std::size_t capacity = kernels.packed->capacity(width, height);
      slots_.emplace(Name("queue-counters"), capacity);
      packedItems_.emplace(Name("queue"), capacity);
      packedPayloads_.emplace(Name("payload-queue"), capacity);
      arguments_.emplace(Name("dispatch-args"), 6);
      // MiniEngine's initial arguments {0, 1, 1, 0, 1, 1}: the resolve writes the group counts only.
      for (const std::size_t i : {1, 2, 4, 5}) arguments_->At(i) = 1;
    }
    return;
  }
  // Every pixel may join the work set: a full-size queue cannot overflow.
  const auto capacity = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  while (queues_.size() < static_cast<std::size_t>(consumes)) {
    queues_.emplace_back(Name(queues_.empty() ? "queue" : "queue-" + std::to_string(queues_.size() + 1)), capacity);
  }
  if (!arguments_) arguments_.emplace(Name("dispatch-args"), 3 * queues_.size());
  for (sim::AppendBuffer<std::uint32_t>& queue : queues_) queue.ResetCounter();
}

std::uint64_t WorkSet::StencilPixels() const {
  std::uint64_t marked = 0;
  for (int y = 0; y < stencil_->Height(); ++y) {
    for (int x = 0; x < stencil_->Width(); ++x) marked += stencil_->Surface().Stencil(x, y) != 0;
  }
  return marked;
}

std::vector<std::uint8_t> WorkSet::Membership(Strategy strategy) const {
  const WorkRegion r = region_;
  std::vector<std::uint8_t> joined(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height), 0);
  const auto join = [&](glm::ivec2 pixel, std::size_t consume) {
    const glm::ivec2 at = pixel - glm::ivec2(r.x, r.y);
    if (at.x < 0 || at.y < 0 || at.x >= r.width || at.y >= r.height) return;
    joined[static_cast<std::size_t>(at.y) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(at.x)] =
        static_cast<std::uint8_t>(consume);
  };
  if (strategy == Strategy::StencilCulled) {
    for (int y = 0; y < r.height; ++y) {
      for (int x = 0; x < r.width; ++x) join({x + r.x, y + r.y}, stencil_->Surface().Stencil(x, y));
    }
  } else if (packedItems_) {
    const std::span<const std::uint32_t> items = packedItems_->Elements();
    glm::ivec2 (*unpack)(std::uint32_t) = unpack_;
    for (std::uint32_t k = 0; k < frontCount_; ++k) join(unpack(items[k]), 1);
    for (std::uint32_t k = 0; k < backCount_; ++k) join(unpack(items[LastSlot() - k]), 2);
  } else {
    for (std::size_t q = 0; q < queues_.size(); ++q) {
      for (const std::uint32_t item : queues_[q].Storage().Elements().first(queues_[q].Count())) {
        join(sim::UnpackPixelItem(item), q + 1);
      }
    }
  }
  return joined;
}

WorkSetShape WorkSet::Shape(Strategy strategy) const {
  return ShapeOf(Membership(strategy), region_.width, region_.height);
}

WorkSetShape ShapeOf(std::span<const std::uint8_t> marked, int width, int height) {
  // One pass over the pixels marks the quads and tiles they touch (unsigned divisions by the
  // constant sides: shifts).
  constexpr std::size_t kQuad = 2, kTile = kWorkSetTileSide;
  const auto w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  const std::size_t quadColumns = (w + kQuad - 1) / kQuad, tileColumns = (w + kTile - 1) / kTile;
  std::vector<std::uint8_t> quads(quadColumns * ((h + kQuad - 1) / kQuad), 0);
  std::vector<std::uint8_t> tiles(tileColumns * ((h + kTile - 1) / kTile), 0);
  std::uint64_t pixels = 0;
  for (std::size_t y = 0; y < h; ++y) {
    const std::uint8_t* row = marked.data() + y * w;
    for (std::size_t x = 0; x < w; ++x) {
      if (row[x] == 0) continue;
      ++pixels;
      quads[y / kQuad * quadColumns + x / kQuad] = 1;
      tiles[y / kTile * tileColumns + x / kTile] = 1;
    }
  }
  const auto touched = [](const std::vector<std::uint8_t>& cells) {
    return static_cast<std::uint64_t>(std::count(cells.begin(), cells.end(), 1));
  };
  return {.pixels = pixels, .quads = touched(quads), .tiles = touched(tiles)};
}

void WorkSet::WriteQueueArguments(sim::Machine& machine) {
  sim::Dispatch d(Name("queue-args"), kQueueArgumentsKernel);
  std::vector<sim::BufferView<std::uint32_t>> counts;
  for (const sim::AppendBuffer<std::uint32_t>& queue : queues_) counts.push_back(d.Read(queue.Counter()));
  const sim::RwBufferView<std::uint32_t> args = d.ReadWrite(*arguments_);
  machine.Compute(d, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}}, [&](sim::ComputeLane& lane) {
    for (std::size_t q = 0; q < counts.size(); ++q) {
      const std::uint32_t n = counts[q].Load(lane, 0);
      args.Store(lane, 3 * q, (n + sim::kWaveLanes - 1) / sim::kWaveLanes);
      args.Store(lane, 3 * q + 1, 1);
      args.Store(lane, 3 * q + 2, 1);
    }
  });
}

void WorkSet::ResolvePackedQueue(sim::Machine& machine, const PackedQueueLayout& layout) {
  sim::Dispatch d(std::string(layout.resolveDispatch), layout.resolve);
  const sim::RwBufferView<std::uint32_t> counts = d.ReadWrite(slots_->Counters());
  const sim::RwBufferView<std::uint32_t> queue = d.ReadWrite(*packedItems_);
  const sim::RwBufferView<std::uint32_t> args = d.ReadWrite(*arguments_);
  const auto last = static_cast<std::uint32_t>(LastSlot());
  constexpr std::uint32_t kWave = sim::kWaveLanes;
  // Each thread pads one slot of each end (MiniEngine's resolve shader, aa-facts §3); after the
  // group barrier thread 0 writes the group counts and resets the counters.
  auto pad = [&](sim::ComputeLane& lane) {
    const auto thread = static_cast<std::uint32_t>(lane.localIndex);
    const std::uint32_t front = counts.Load(lane, 0), back = counts.Load(lane, 1);
    if (thread + front < (front + kWave - 1) / kWave * kWave) queue.Store(lane, front + thread, layout.dummyItem);
    if (thread + back < (back + kWave - 1) / kWave * kWave) queue.Store(lane, last - back - thread, layout.dummyItem);
    lane.Private<glm::uvec2>() = {front, back};
  };
  auto writeArguments = [&](sim::ComputeLane& lane) {
    if (lane.localIndex != 0) return;
    const glm::uvec2 n = lane.Private<glm::uvec2>();
    args.Store(lane, 0, (n.x + kWave - 1) / kWave);
    args.Store(lane, 3, (n.y + kWave - 1) / kWave);
    counts.Store(lane, 0, 0);
    counts.Store(lane, 1, 0);
  };
  machine.Compute(d, {.threads = {sim::kWaveLanes, 1, 1}, .groupSize = {sim::kWaveLanes, 1, 1}}, pad, writeArguments);
  const std::uint64_t padded = (std::uint64_t{arguments_->At(0)} + arguments_->At(3)) * kWave;
  padding_ = padded - frontCount_ - backCount_;
  // Padding past the other end's items overwrote them (or was dropped past the buffer).
  overflowed_ = overflowed_ || padded > packedItems_->Size();
}

}  // namespace passes
