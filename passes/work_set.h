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
#include <vector>

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
  // Optional second consume, run after the first on the pixels the detect gave 2; its factory is
  // then make_consume(sim::Dispatch&, int consume) with consume 0 or 1.
  std::string_view secondConsumeDispatch = {};
  sim::KernelInfo secondConsume = {};

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
  // make_consume(sim::Dispatch&) -> consume kernel, or make_consume(sim::Dispatch&, int consume)
  // with a second consume. Returns the work set's shape (both consumes' pixels).
  template <typename MakeDetect, typename MakeConsume>
  WorkSetShape Run(sim::Machine& machine, Strategy strategy, const WorkSetKernels& kernels, int width,
                    int height, MakeDetect&& makeDetect, MakeConsume&& makeConsume);

  // After Run, read back on the host (not a machine operation): per pixel, row-major, the consume
  // it joined (1 or 2) or 0.
  std::vector<std::uint8_t> Membership(Strategy strategy) const;

 private:
  static constexpr int kGroupSide = kWorkSetTileSide;

  void Prepare(Strategy strategy, int consumes, int width, int height);
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
  // One queue per consume; the arguments hold one {groups, 1, 1} triple per queue.
  std::vector<sim::AppendBuffer<std::uint32_t>> queues_;
  std::optional<sim::Buffer<std::uint32_t>> arguments_;
};

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
                          int height, MakeDetect&& makeDetect, MakeConsume&& makeConsume) {
  Prepare(strategy, kernels.Consumes(), width, height);
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
      if (const int joins = static_cast<int>(detect(lane, lane.x, lane.y))) mark.Store(lane, static_cast<std::uint8_t>(joins));
    });
  }
  for (int index = 0; index < kernels.Consumes(); ++index) {
    sim::Dispatch d(std::string(ConsumeDispatch(kernels, index)), ConsumeKernel(kernels, index));
    auto consume = MakeConsumeKernel(makeConsume, d, index);
    machine.FullScreen(d, {.width = width_, .height = height_, .stencil = &*stencil_,
                           .stencilRef = static_cast<std::uint8_t>(index + 1)},
                       [&](sim::PixelLane& lane) { consume(lane, lane.x, lane.y); });
  }
  return StencilPixels();
}

template <typename MakeDetect, typename MakeConsume>
std::uint64_t WorkSet::RunDeferredQueue(sim::Machine& machine, const WorkSetKernels& kernels,
                                        MakeDetect& makeDetect, MakeConsume& makeConsume) {
  {
    sim::Dispatch d(std::string(kernels.detectDispatch), kernels.detectCompute);
    auto detect = makeDetect(d, ComputeForm{});
    std::vector<sim::AppendView<std::uint32_t>> appends;
    for (sim::AppendBuffer<std::uint32_t>& queue : queues_) appends.push_back(d.Append(queue));
    d.SetPixelGrid(width_, height_);
    auto detectAndAppend = [&](auto& kernel) {
      return [&](sim::ComputeLane& lane) {
        const int x = lane.threadId.x, y = lane.threadId.y;
        if (x >= width_ || y >= height_) return;
        if (const int joins = static_cast<int>(kernel(lane, x, y))) {
          appends[static_cast<std::size_t>(joins - 1)].Append(lane, sim::PackPixelItem(x, y));
        }
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
  std::uint64_t pixels = 0;
  for (int index = 0; index < kernels.Consumes(); ++index) {
    sim::AppendBuffer<std::uint32_t>& queue = queues_[static_cast<std::size_t>(index)];
    sim::Dispatch d(std::string(ConsumeDispatch(kernels, index)), ConsumeKernel(kernels, index));
    const sim::BufferView<std::uint32_t> items = d.Read(queue.Storage());
    auto consume = MakeConsumeKernel(makeConsume, d, index);
    d.SetPixelGrid(width_, height_);
    const sim::IndirectCall call{.arguments = &*arguments_, .offset = 3 * static_cast<std::size_t>(index),
                                 .groupSize = {sim::kWaveLanes, 1, 1}, .itemCount = &queue.Counter(),
                                 .itemCountIndex = 0, .pixelItems = items};
    machine.ComputeIndirect(d, call, [&](sim::ComputeLane& lane) { consume(lane, lane.pixel.x, lane.pixel.y); });
    pixels += queue.Count();
  }
  return pixels;
}

}  // namespace passes
