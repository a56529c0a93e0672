#pragma once
// What every post pass is to the rest of aasim (DESIGN.md "Passes and studies"): a Pass object
// built once per run and strategy from its registered description (PassInfo) and validated
// settings, called once per frame. Kernels inside a pass are templates inlined into the
// machine's wave loops; the only virtual call is Run, once per frame.
//
// A temporal pass keeps its history in its instance, which is why the study makes one instance
// per strategy and never shares one between them.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/vec4.hpp>

#include "passes/settings.h"
#include "raster/sample_pattern.h"
#include "sim/dispatch.h"
#include "sim/frame.h"
#include "sim/parallel.h"

namespace passes {

// The study's central axis (DESIGN.md "Dispatch strategies"): the same detect/consume work run as
// a stencil-culled full-screen pixel shader pair, or as a compute pass that appends the work set to
// a queue consumed by an indirect dispatch.
enum class Strategy : std::uint8_t { StencilCulled, DeferredQueue };
inline constexpr Strategy kAllStrategies[] = {Strategy::StencilCulled, Strategy::DeferredQueue};
std::string_view StrategyName(Strategy strategy);  // "stencil", "queue"
std::optional<Strategy> StrategyByName(std::string_view name);

// The frame a pass reads. Targets a frame does not have are null; a pass that needs one lists it
// in PassInfo::inputs and the study supplies it.
struct FrameInputs {
  const sim::Texture2D<glm::vec4>* colour = nullptr;  // resolved, linear RGBA
  // The same frame as the renderer's RGBA8 sRGB render target holds it (sim::StoreSrgb8), stored
  // once per frame: passes with an 8-bit colour input bind it, or copy it where they write their
  // colour in place, so their views read the codes (UNORM, gamma values) or decode them (sRGB,
  // linear) as the reference shaders do (aa-facts §1.9). ColourSrgb8() checks it is there.
  const sim::Texture2D<glm::vec4>* colourSrgb8 = nullptr;
  const sim::Texture2D<float>* depth = nullptr;
  const sim::Texture2D<glm::vec4>* normal = nullptr;
  const sim::Texture2D<std::uint32_t>* objectId = nullptr;
  const sim::Texture2D<glm::vec2>* velocity = nullptr;
  const fmask::EqaaSurface* eqaa = nullptr;
  // The sample pattern the frame was drawn with (a jitter schedule's pattern for this frame).
  const raster::SamplePattern* pattern = nullptr;
  int frameIndex = 0;
  // This frame's projection jitter in pixels, +y down: the offset of sample 0 of quad pixel 0
  // (a 1-sample schedule's whole jitter when the pattern is the same in all quad pixels).
  glm::vec2 jitter{0.0f};
  // Time since the previous frame, for frame-rate-aware blends (alpha = exp(-dt / tau), aa-facts
  // §5.4): the run's fixed frame rate.
  double frameSeconds = 1.0 / 60.0;

  int Width() const { return colour->Width(); }
  int Height() const { return colour->Height(); }
  const sim::Texture2D<glm::vec4>& ColourSrgb8() const;
};

// Whether a resource is history a temporal pass carries from frame to frame: the last component of
// its name starts with "history" ("taa-ue4/history-0", "filmic-smaa-t2x/history-depth1"). The
// sequence study's history bytes are the traffic on these (docs/temporal.md).
inline bool IsHistoryResource(std::string_view name) {
  const std::size_t slash = name.rfind('/');
  return name.substr(slash == std::string_view::npos ? 0 : slash + 1).starts_with("history");
}

// Sample 0 of quad pixel 0, in pixels (+y down): FrameInputs::jitter.
glm::vec2 PatternJitter(const raster::SamplePattern& pattern);
// Every target of a rendered frame, its pattern and its index in its sequence.
FrameInputs FrameInputsOf(const sim::FramePipeline& frame);

enum class FrameInput : std::uint8_t { Colour, Depth, Normal, ObjectId, Velocity, Eqaa };

// An intermediate a pass exposes for inspection (SMAA's edges and blend weights, CMAA2's
// candidates): named channels, written as image layers and compared between strategies.
struct PassLayer {
  std::string name;                   // "edges"
  std::vector<std::string> channels;  // {"Y"}, {"R", "G"}
  int width = 0, height = 0;
  std::vector<float> values;          // row-major, channels interleaved
  // A layer of an 8-bit texture keeps the texture's codes instead of `values` (a copy of what its
  // render target held, a quarter of the floats' bytes, decoded only when read): `codeChannels`
  // bytes per pixel, read as its UNORM view does (code / 255; channels past them 0, alpha 1).
  std::vector<std::uint8_t> codes;
  int codeChannels = 0;

  std::size_t Size() const {  // pixels x channels
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels.size();
  }
  // Element i of the row-major, channel-interleaved values.
  float Value(std::size_t i) const {
    if (codeChannels == 0) return values[i];
    const std::size_t n = channels.size(), c = i % n, stride = static_cast<std::size_t>(codeChannels);
    if (c < stride) return sim::Unorm8ToFloat(codes[i / n * stride + c]);
    return c == 3 ? 1.0f : 0.0f;
  }
  // Every value, decoded.
  std::vector<float> Floats() const;
};

// A one-channel layer ("Y") of a work set's membership bytes (WorkSet::Membership: 0, or the
// consume a pixel joined), row-major, converted by rows on the worker threads.
PassLayer MembershipLayer(std::string name, std::span<const std::uint8_t> joined, int width, int height);
// A one-channel layer ("Y") holding the texture's values.
PassLayer LayerOf(std::string name, const sim::Texture2D<float>& texture);
// A layer of `components` channels from an 8-bit texture's codes, read as k / 255 as its UNORM
// view does (channels past the format's 0, alpha 1).
PassLayer CodesLayer(std::string name, std::vector<std::string> channels, int width, int height,
                     std::span<const std::uint8_t> codes, int codeChannels, int components);
// A layer of a vector texture, one named channel per component.
template <glm::length_t N>
PassLayer LayerOf(std::string name, const sim::Texture2D<glm::vec<N, float>>& texture,
                  std::vector<std::string> channels) {
  if (texture.KeepsCodes()) {
    return CodesLayer(std::move(name), std::move(channels), texture.Width(), texture.Height(), texture.Codes(),
                      texture.CodeChannels(), N);
  }
  // A glm vector array is its channels interleaved (glm::value_ptr's contract): one copy, with no
  // zero-fill of the layer before it.
  static_assert(sizeof(glm::vec<N, float>) == N * sizeof(float));
  const std::span<const glm::vec<N, float>> texels = texture.Texels();
  const float* const first = glm::value_ptr(texels.front());
  return {std::move(name), std::move(channels), texture.Width(), texture.Height(),
          std::vector<float>(first, first + texels.size() * N), {}, 0};
}

// A linear colour stored into a new RGBA8 sRGB texture (sim::StoreSrgb8): FrameInputs::colourSrgb8
// for a frame that did not come from a sim::FramePipeline.
sim::Texture2D<glm::vec4> Srgb8ColourTarget(std::string name, const sim::Texture2D<glm::vec4>& linear);
// The frame's 8-bit codes into a target of the pass's own that it then writes in place (CMAA2's
// deferred apply, Filmic SMAA's output, TFQ's frame ring), as a renderer's CopyResource would.
void CopySrgb8Frame(const FrameInputs& frame, sim::Texture2D<glm::vec4>& target);
// Per-texel host work on a whole frame (conversions, copies), by rows on the worker threads:
// convert(texel index) does one texel and touches no other, so the result does not depend on the
// thread count.
template <typename Convert>
void ByRows(int width, int height, Convert convert) {
  const auto row = static_cast<std::size_t>(width);
  sim::ParallelFor(static_cast<std::size_t>(height), [&](std::size_t y) {
    for (std::size_t i = y * row; i < (y + 1) * row; ++i) convert(i);
  });
}
// A texture a pass keeps across frames, (re)made when the frame size changes.
template <typename T, typename... Args>
sim::Texture2D<T>& FrameTexture(std::optional<sim::Texture2D<T>>& kept, const std::string& name, int width, int height,
                                Args... args) {
  if (!kept || kept->Width() != width || kept->Height() != height) kept.emplace(name, width, height, args...);
  return *kept;
}
// What an RGBA8 sRGB target holds, decoded to linear floats for metrics and image output.
sim::Texture2D<glm::vec4> DecodedSrgb8(std::string name, const sim::Texture2D<glm::vec4>& target);

// How the work set lies on the screen (seed 000's argument for queues: scattered edges leave a
// stencil-culled shader's quads and waves mostly idle): its pixels, and the 2x2 quads and 8x8
// tiles (hi-stencil tiles, compute groups) holding at least one of them.
struct WorkSetShape {
  std::uint64_t pixels = 0, quads = 0, tiles = 0;
  friend bool operator==(const WorkSetShape&, const WorkSetShape&) = default;
};

struct PassOutput {
  sim::Texture2D<glm::vec4> colour{"pass output", 1, 1};
  std::vector<PassLayer> layers;
  // Pixels the strategies' work set held (edge pixels for the demo): under the queue strategy the
  // consume dispatch's active lanes, under the stencil strategy its stencil-passing pixels.
  std::uint64_t workItems = 0;
  WorkSetShape workSet;  // workSet.pixels == workItems
  // Dummy items the queue strategy's consumes ran besides the work items, padding each queue to
  // whole waves (MiniEngine FXAA, aa-facts §3): active lanes that store nothing. 0 otherwise.
  std::uint64_t paddingItems = 0;

  void SetWorkSet(const WorkSetShape& shape) {
    workSet = shape;
    workItems = shape.pixels;
  }
};

struct PassInfo {
  std::string_view name;         // registry key: "demo"
  std::string_view description;  // one line for --help and the report
  std::string_view source;       // header with the pass diagram: "passes/demo/demo.h"
  std::vector<SettingInfo> settings;
  std::vector<Preset> presets;
  std::vector<FrameInput> inputs;
  // The dispatches the strategies exist for, compared side by side in the report.
  std::vector<std::string_view> studiedDispatches;
  std::vector<Strategy> strategies;
  // Host bytes per pixel one run of the pass holds at once (outputs, intermediates, queues), for
  // the memory guard.
  std::uint64_t bytesPerPixel = 0;
  // Bytes per pixel of the layers one run returns (PassLayer floats): the study keeps them for
  // every strategy it runs, after the pass's instance is gone, so the memory guard adds them up.
  std::uint64_t layerBytesPerPixel = 0;
  bool temporal = false;  // keeps history across frames
  // The per-frame sample-pattern schedule the pass is built for (raster/jitter_schedule.h:
  // "none", "halton8", "t2x", ...): the study renders its sequence with it. Spatial passes: "none".
  std::string_view jitter = "none";
  // The coverage samples of the EQAA surface the pass reads (S2x: 2); 0 when it reads none. The
  // study runs such a pass on the first of its frames with that many samples.
  int eqaaSamples = 0;
  // The registered pass this one varies (the same technique with other maths, inputs or
  // thresholds): when both run on the same frame, the report measures how far their images differ.
  std::string_view variantOf = {};
};

class Pass {
 public:
  virtual ~Pass() = default;
  virtual const PassInfo& Info() const = 0;
  // Runs one frame; dispatches go to the machine's report list.
  virtual PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) = 0;
};

}  // namespace passes
