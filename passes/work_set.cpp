// The work set's resources and its shared queue-arguments kernel (see work_set.h).

#include "passes/work_set.h"

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
