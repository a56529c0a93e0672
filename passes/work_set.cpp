// The work set's resources and its shared queue-arguments kernel (see work_set.h).

#include "passes/work_set.h"

#include <algorithm>
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

void WorkSet::Prepare(Strategy strategy, int width, int height) {
  if (width != width_ || height != height_) {
    stencil_.reset();
    queue_.reset();
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
  if (!queue_) queue_.emplace(Name("queue"), static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  if (!arguments_) arguments_.emplace(Name("dispatch-args"), 3);
  queue_->ResetCounter();
}

std::uint64_t WorkSet::StencilPixels() const {
  std::uint64_t marked = 0;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) marked += stencil_->Surface().Stencil(x, y) == 1;
  }
  return marked;
}

WorkSetShape WorkSet::Shape(Strategy strategy) const {
  std::vector<std::uint8_t> marked(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0);
  const auto mark = [&](int x, int y) { marked[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] = 1; };
  if (strategy == Strategy::StencilCulled) {
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) {
        if (stencil_->Surface().Stencil(x, y) == 1) mark(x, y);
      }
    }
  } else {
    const std::span<const std::uint32_t> items = queue_->Storage().Elements().first(queue_->Count());
    for (const std::uint32_t item : items) {
      const glm::ivec2 pixel = sim::UnpackPixelItem(item);
      mark(pixel.x, pixel.y);
    }
  }
  return ShapeOf(marked, width_, height_);
}

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
  const sim::BufferView<std::uint32_t> count = d.Read(queue_->Counter());
  const sim::RwBufferView<std::uint32_t> args = d.ReadWrite(*arguments_);
  machine.Compute(d, {.threads = {1, 1, 1}, .groupSize = {1, 1, 1}}, [&](sim::ComputeLane& lane) {
    const std::uint32_t n = count.Load(lane, 0);
    args.Store(lane, 0, (n + sim::kWaveLanes - 1) / sim::kWaveLanes);
    args.Store(lane, 1, 1);
    args.Store(lane, 2, 1);
  });
}

}  // namespace passes
