// SMAA 1x's three passes (see smaa_pipeline.h).

#include "passes/smaa/smaa_pipeline.h"

#include <optional>

#include "passes/smaa/blending_weights.h"
#include "sim/formats.h"

namespace passes::smaa {
namespace {

// Estimates for the timing model. The reference publishes no instruction counts; these are hand
// counts of SMAA.hlsl's shaders as GCN VALU instructions (a dot3 is 3, a fetch's address 1-2).
constexpr sim::KernelInfo kDetectPixel{
    .vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 48,
    .source = "hand count of SMAALumaEdgeDetectionPS: 7 point fetches' addresses (7), 7 luma dot products (21), "
              "6 abs differences (6), 2 steps, the discard test, the max tree and the local-contrast step (~14)"};
constexpr sim::KernelInfo kDetectCompute{
    .vgprs = 16, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 56,
    .source = "the pixel form's 48 plus the thread-to-pixel mapping, bounds test and the append's mbcnt and "
              "address (~8)"};
constexpr sim::KernelInfo kWeights{
    .vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 220,
    .source = "hand count of SMAABlendingWeightCalculationPS on a typical edge pixel (HIGH): two diagonal searches "
              "of 2-3 steps (~60), one orthogonal search pair of ~4 steps each at ~8 per step (~70), search-length "
              "and area addressing (~30), corner rounding (~25), branches and weight stores (~35); longer lines "
              "cost ~8 per extra step"};
constexpr sim::KernelInfo kBlend{
    .vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 36,
    .source = "hand count of SMAANeighborhoodBlendingPS: 3 weight fetches' addresses (4), the sum and branch (5), "
              "the axis choice and offsets (10), the normalise (4), 2 fetches and the weighted sum (13)"};
constexpr sim::KernelInfo kBlendReprojection{
    .vgprs = 20, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 46,
    .source = "kBlend's 36 plus SMAA_REPROJECTION's velocity: 2 fetches' weighted sum (4), length (4), the "
              "sqrt(5 |v|) (2)"};

}  // namespace

Smaa1x::Smaa1x(std::string_view pass, const Config& config, DispatchNames names)
    : config_(config), names_(std::move(names)), tables_(LookupTables::Make()), workSet_(pass) {}

Smaa1x::Frame Smaa1x::Run(sim::Machine& machine, Strategy strategy, const sim::Texture2D<glm::vec4>& colour,
                          const sim::Texture2D<float>* depth, sim::Texture2D<glm::vec4>& target, Blend blend,
                          const sim::Texture2D<glm::vec2>* velocity) {
  if (!targets_ || targets_->edges.Width() != colour.Width() || targets_->edges.Height() != colour.Height()) {
    targets_.emplace(colour.Width(), colour.Height());
  } else {
    targets_->edges.Fill(glm::vec2(0.0f));
    targets_->weights.Fill(glm::vec4(0.0f));
  }
  const WorkSetShape workSet = EdgesAndWeights(machine, strategy, colour, depth, *targets_);
  NeighbourhoodBlend(machine, colour, *targets_, target, blend, velocity);
  return {*targets_, workSet};
}

WorkSetShape Smaa1x::EdgesAndWeights(sim::Machine& machine, Strategy strategy,
                                     const sim::Texture2D<glm::vec4>& colour, const sim::Texture2D<float>* depth,
                                     Intermediates& targets) {
  const Metrics metrics = Metrics::Of(colour.Width(), colour.Height());
  auto makeDetect = [&](sim::Dispatch& d, auto) {
    std::optional<sim::TextureView<glm::vec4>> gamma;
    if (config_.edges != EdgeMode::Depth) gamma = d.Read(colour).As(sim::Format::RGBA8Unorm);
    std::optional<sim::TextureView<float>> depthView;
    if (config_.edges == EdgeMode::Depth || config_.predication) depthView = d.Read(*depth);
    const EdgeDetection detect(config_, metrics, gamma, depthView);
    const sim::RwTextureView<glm::vec2> edges = d.ReadWrite(targets.edges);
    return [=](const sim::LaneBase& lane, int x, int y) {
      const glm::vec2 e = detect(lane, x, y);
      if (e.x + e.y == 0.0f) return false;  // the reference's discard: nothing written
      edges.Store(lane, x, y, e);
      return true;
    };
  };
  auto makeWeights = [&](sim::Dispatch& d) {
    const BlendingWeights weights(config_, metrics,
                                  {.edges = d.Read(targets.edges), .area = d.Read(tables_.area),
                                   .search = d.Read(tables_.search), .searchSteps = d.Counter("search_steps")});
    const sim::RwTextureView<glm::vec4> out = d.ReadWrite(targets.weights);
    return [=](const sim::LaneBase& lane, int x, int y) { out.Store(lane, x, y, weights(lane, x, y)); };
  };
  const WorkSetKernels kernels{.detectDispatch = names_.edges, .consumeDispatch = names_.weights,
                               .detectPixel = kDetectPixel, .detectCompute = kDetectCompute, .consume = kWeights};
  return workSet_.Run(machine, strategy, kernels, colour.Width(), colour.Height(), makeDetect, makeWeights);
}

void Smaa1x::NeighbourhoodBlend(sim::Machine& machine, const sim::Texture2D<glm::vec4>& colour,
                                const Intermediates& targets, sim::Texture2D<glm::vec4>& target, Blend blend,
                                const sim::Texture2D<glm::vec2>* velocity) {
  const Metrics metrics = Metrics::Of(colour.Width(), colour.Height());
  sim::Dispatch d(names_.blending, velocity != nullptr ? kBlendReprojection : kBlend);
  std::optional<sim::TextureView<glm::vec2>> velocityView;
  if (velocity != nullptr) velocityView = d.Read(*velocity);
  const NeighbourhoodBlending kernel{metrics, d.Read(colour), d.Read(targets.weights), velocityView};
  const sim::RwTextureView<glm::vec4> out = d.ReadWrite(target);
  const sim::FullScreenCall call{.width = colour.Width(), .height = colour.Height()};
  if (blend == Blend::Replace) {
    machine.FullScreen(d, call, [&](sim::PixelLane& lane) { out.Store(lane, lane.x, lane.y, kernel(lane, lane.x, lane.y)); });
    return;
  }
  // The blend unit reads the destination through the target's sRGB view (linear), blends,
  // and the store encodes once.
  machine.FullScreen(d, call, [&](sim::PixelLane& lane) {
    const glm::vec4 source = kernel(lane, lane.x, lane.y);
    out.Store(lane, lane.x, lane.y, 0.5f * source + 0.5f * out.Load(lane, lane.x, lane.y));
  });
}

}  // namespace passes::smaa
