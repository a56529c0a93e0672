// The work set's resources and its shared queue-arguments kernel (see work_set.h).

#include "passes/work_set.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace passes {
namespace {

constexpr sim::KernelInfo kQueueArgumentsKernel{
    .vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 8,
    .source = "hand count: one load, an add and a shift for ceil(n / 64), three stores (the MiniEngine FXAA "
              "argument shader has the same shape, aa-facts §3)"};

}  // namespace

WorkSet::WorkSet(std::string_view pass) : pass_(pass) {}

void WorkSet::Prepare(Strategy strategy, int consumes, int width, int height) {
  if (width != width_ || height != height_ || (!queues_.empty() && queues_.size() != static_cast<std::size_t>(consumes))) {
    stencil_.reset();
    queues_.clear();
    arguments_.reset();
    width_ = width;
    height_ = height;
  }
  if (strategy == Strategy::StencilCulled) {
    if (!stencil_) stencil_.emplace(Name("stencil"), width, height);
    stencil_->Clear(0);
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
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) marked += stencil_->Surface().Stencil(x, y) != 0;
  }
  return marked;
}

std::vector<std::uint8_t> WorkSet::Membership(Strategy strategy) const {
  std::vector<std::uint8_t> joined(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0);
  const auto at = [&](int x, int y) -> std::uint8_t& {
    return joined[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)];
  };
  if (strategy == Strategy::StencilCulled) {
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) at(x, y) = stencil_->Surface().Stencil(x, y);
    }
  } else {
    for (std::size_t q = 0; q < queues_.size(); ++q) {
      for (const std::uint32_t item : queues_[q].Storage().Elements().first(queues_[q].Count())) {
        const glm::ivec2 pixel = sim::UnpackPixelItem(item);
        at(pixel.x, pixel.y) = static_cast<std::uint8_t>(q + 1);
      }
    }
  }
  return joined;
}

WorkSetShape WorkSet::Shape(Strategy strategy) const { return ShapeOf(Membership(strategy), width_, height_); }

WorkSetShape ShapeOf(std::span<const std::uint8_t> marked, int width, int height) {
  const auto count = [&](int side) {
    const int columns = (width + side - 1) / side, rows = (height + side - 1) / side;
    std::vector<std::uint8_t> touched(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows), 0);
    std::uint64_t pixels = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        if (!marked[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]) continue;
        ++pixels;
        touched[static_cast<std::size_t>(y / side) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(x / side)] = 1;
      }
    }
    return std::pair{pixels, static_cast<std::uint64_t>(std::count(touched.begin(), touched.end(), 1))};
  };
  return {.pixels = count(1).first, .quads = count(2).second, .tiles = count(kWorkSetTileSide).second};
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

}  // namespace passes
