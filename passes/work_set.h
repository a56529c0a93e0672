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
// Kernels are bound per dispatch: the pass gives factories that take the sim::Dispatch, bind the
// resources they read and write on it and return the kernel, a generic callable
// (lane, x, y) templated on the lane type (sim::PixelLane under the stencil strategy,
// sim::ComputeLane under the queue). A compute detect may come with a prologue stage (e.g. an
// LDS tile fill) by returning StagedDetect. Identical arithmetic under both strategies is the
// pass's promise; passes/compare.h checks it.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "passes/pass.h"
#include "sim/check.h"
#include "sim/dispatch.h"

namespace passes {

struct WorkSetKernels {
  std::string_view detectDispatch;   // "demo/edge-detect"
  std::string_view consumeDispatch;  // "demo/blend"
  sim::KernelInfo detectPixel;       // the stencil strategy's full-screen detect
  sim::KernelInfo detectCompute;     // the queue strategy's compute detect (its LDS included)
  sim::KernelInfo consume;           // both strategies' consume
};

// A compute detect with a prologue every thread of the group runs before a barrier.
template <typename Prologue, typename Detect>
struct StagedDetect {
  Prologue prologue;  // (sim::ComputeLane&) -> void
  Detect detect;      // (sim::ComputeLane&, int x, int y) -> bool
};

// Which kernel a detect factory binds: its full-screen pixel form or its compute form, as a
// type so the factory can return a different kernel type for each (if constexpr on the tag).
enum class DetectForm : std::uint8_t { Pixel, Compute };
using PixelForm = std::integral_constant<DetectForm, DetectForm::Pixel>;
using ComputeForm = std::integral_constant<DetectForm, DetectForm::Compute>;

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
  // make_consume(sim::Dispatch&) -> consume kernel. Returns the work set's shape.
  template <typename MakeDetect, typename MakeConsume>
  WorkSetShape Run(sim::Machine& machine, Strategy strategy, const WorkSetKernels& kernels, int width,
                    int height, MakeDetect&& makeDetect, MakeConsume&& makeConsume);

 private:
  static constexpr int kGroupSide = kWorkSetTileSide;

  void Prepare(Strategy strategy, int width, int height);
  std::uint64_t StencilPixels() const;
  // Read back on the host after the consume dispatch, for the report (not a machine operation).
  WorkSetShape Shape(Strategy strategy) const;
  void WriteQueueArguments(sim::Machine& machine);
  std::string Name(std::string_view suffix) const { return pass_ + "/" + std::string(suffix); }

  template <typename MakeDetect, typename MakeConsume>
  std::uint64_t RunStencilCulled(sim::Machine& machine, const WorkSetKernels& kernels, MakeDetect& makeDetect,
                                 MakeConsume& makeConsume);
  template <typename MakeDetect, typename MakeConsume>
  std::uint64_t RunDeferredQueue(sim::Machine& machine, const WorkSetKernels& kernels, MakeDetect& makeDetect,
                                 MakeConsume& makeConsume);

  std::string pass_;
  int width_ = 0, height_ = 0;
  std::optional<sim::StencilBuffer> stencil_;
  std::optional<sim::AppendBuffer<std::uint32_t>> queue_;
  std::optional<sim::Buffer<std::uint32_t>> arguments_;
};

template <typename MakeDetect, typename MakeConsume>
WorkSetShape WorkSet::Run(sim::Machine& machine, Strategy strategy, const WorkSetKernels& kernels, int width,
                          int height, MakeDetect&& makeDetect, MakeConsume&& makeConsume) {
  Prepare(strategy, width, height);
  const std::uint64_t pixels = strategy == Strategy::StencilCulled
                                   ? RunStencilCulled(machine, kernels, makeDetect, makeConsume)
                                   : RunDeferredQueue(machine, kernels, makeDetect, makeConsume);
  const WorkSetShape shape = Shape(strategy);
  AASIM_CHECK_EQ(shape.pixels, pixels);
  return shape;
}

template <typename MakeDetect, typename MakeConsume>
std::uint64_t WorkSet::RunStencilCulled(sim::Machine& machine, const WorkSetKernels& kernels,
                                        MakeDetect& makeDetect, MakeConsume& makeConsume) {
  {
    sim::Dispatch d(std::string(kernels.detectDispatch), kernels.detectPixel);
    auto detect = makeDetect(d, PixelForm{});
    const sim::StencilView mark = d.Stencil(*stencil_);
    machine.FullScreen(d, {.width = width_, .height = height_}, [&](sim::PixelLane& lane) {
      if (detect(lane, lane.x, lane.y)) mark.Store(lane, 1);
    });
  }
  sim::Dispatch d(std::string(kernels.consumeDispatch), kernels.consume);
  auto consume = makeConsume(d);
  machine.FullScreen(d, {.width = width_, .height = height_, .stencil = &*stencil_},
                     [&](sim::PixelLane& lane) { consume(lane, lane.x, lane.y); });
  return StencilPixels();
}

template <typename MakeDetect, typename MakeConsume>
std::uint64_t WorkSet::RunDeferredQueue(sim::Machine& machine, const WorkSetKernels& kernels,
                                        MakeDetect& makeDetect, MakeConsume& makeConsume) {
  {
    sim::Dispatch d(std::string(kernels.detectDispatch), kernels.detectCompute);
    auto detect = makeDetect(d, ComputeForm{});
    const sim::AppendView<std::uint32_t> append = d.Append(*queue_);
    d.SetPixelGrid(width_, height_);
    auto detectAndAppend = [&](auto& kernel) {
      return [&](sim::ComputeLane& lane) {
        const int x = lane.threadId.x, y = lane.threadId.y;
        if (x < width_ && y < height_ && kernel(lane, x, y)) append.Append(lane, sim::PackPixelItem(x, y));
      };
    };
    constexpr glm::ivec3 group{kGroupSide, kGroupSide, 1};
    if constexpr (requires { detect.prologue; }) {
      // Whole groups over the image, so every thread of an edge group helps its prologue; threads
      // past the image skip the detect stage.
      const glm::ivec3 threads{(width_ + kGroupSide - 1) / kGroupSide * kGroupSide,
                               (height_ + kGroupSide - 1) / kGroupSide * kGroupSide, 1};
      machine.Compute(d, {.threads = threads, .groupSize = group}, detect.prologue, detectAndAppend(detect.detect));
    } else {
      machine.Compute(d, {.threads = {width_, height_, 1}, .groupSize = group}, detectAndAppend(detect));
    }
  }
  WriteQueueArguments(machine);
  sim::Dispatch d(std::string(kernels.consumeDispatch), kernels.consume);
  const sim::BufferView<std::uint32_t> items = d.Read(queue_->Storage());
  auto consume = makeConsume(d);
  d.SetPixelGrid(width_, height_);
  const sim::IndirectCall call{.arguments = &*arguments_, .offset = 0, .groupSize = {sim::kWaveLanes, 1, 1},
                               .itemCount = &queue_->Counter(), .itemCountIndex = 0, .pixelItems = items};
  machine.ComputeIndirect(d, call, [&](sim::ComputeLane& lane) { consume(lane, lane.pixel.x, lane.pixel.y); });
  return queue_->Count();
}

}  // namespace passes
