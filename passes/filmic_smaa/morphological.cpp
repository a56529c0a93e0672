// Filmic SMAA's morphological stage (see morphological.h).

#include "passes/filmic_smaa/morphological.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include "passes/filmic_smaa/edge_suppression.h"
#include "passes/smaa/blending_weights.h"
#include "sim/formats.h"

namespace passes::filmic_smaa {
namespace {

using smaa::BlendingWeights;
using smaa::Config;
using smaa::Metrics;

// The compute form's LDS tile: the 8x8 group plus the window's apron (3 px left/up, 2 px
// right/down), rounded up to whole 2x2 gather footprints.
constexpr int kGroupSide = kWorkSetTileSide;
constexpr int kApron = -kWindowMin;
constexpr int kTileSide = (kGroupSide + kWindowSide - 1 + 1) / 2 * 2;
constexpr int kTileBlocks = (kTileSide / 2) * (kTileSide / 2);
static_assert(kTileBlocks <= kGroupSide * kGroupSide, "one 2x2 block per thread at most");
constexpr int kTileBytes = kTileSide * kTileSide * static_cast<int>(sizeof(float));

// Hand counts of this file's kernels as GCN VALU instructions (no reference shader exists: the
// seed's deck shows none). The detect branches: every wave runs the early exit, a wave holding a
// candidate pixel also runs the window and the scores (~490 in the pixel form: 33 fetch addresses
// and lumas ~130, 10 edge scores of 6+6 two-edge patterns on ~40 shared deltas ~330, the choices
// ~30; ~360 in the compute form, whose tile holds lumas). The share of such waves is the scene's:
// counted as 1 in 10 (SMAA's work set touches 5% of the 8x8 tiles on the default scene and 21% on
// 2CylinderEngine at 640x360, `aasim run --quick`; edges grow with the side, tiles with the area,
// so about a third of that at 1080p; a candidate is any pixel past the early exit, a superset).
WorkSetKernels KernelsFor(std::string_view detect, std::string_view vertical, std::string_view horizontal) {
  return {
    .detectDispatch = detect,
    .consumeDispatch = vertical,
    .detectPixel = {.vgprs = 48, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 70,
                    .source = "hand count of passes/filmic_smaa: early exit for every wave (3 fetch addresses, 3 "
                              "lumas, 2 deltas and compares, the stencil export, ~20) plus the candidate path "
                              "(~490) on 1 wave in 10"},
    .detectCompute = {.vgprs = 48, .sgprs = 24, .ldsBytesPerGroup = kTileBytes, .valuInstructionsPerWave = 74,
                      .source = "hand count of passes/filmic_smaa: the tile fill (3 gathers' addresses, 4 lumas, LDS "
                                "addressing, ~20), the early exit from LDS (~10), the thread mapping and append (~8), "
                                "plus the candidate path without fetches or lumas (~360) on 1 wave in 10"},
    .consume = {.vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 150,
                .source = "hand count of SMAABlendingWeightCalculationPS's vertical half (search pair ~70, "
                          "search-length and area addressing ~25, corner rounding ~25) plus the two-pixel blend "
                          "(2 loads, 2 lerps, 2 stores, ~30)"},
    .secondConsumeDispatch = horizontal,
    .secondConsume = {.vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 210,
                      .source = "hand count of SMAABlendingWeightCalculationPS's top-edge half (two diagonal searches "
                                "~60, search pair ~70, addressing ~25, corner rounding ~25) plus the two-pixel blend "
                                "(~30)"},
  };
}

// The detect's shared tail: the window's decision, the edges store, the item.
template <typename Lane>
int Finish(const Lane& lane, int x, int y, const LumaWindow& window, float threshold,
           const sim::RwTextureView<glm::vec2>& edges, const sim::CounterView& lost) {
  const PixelEdges decided = Decide(window, threshold);
  if (decided.edges.x + decided.edges.y > 0.0f) edges.Store(lane, x, y, decided.edges);
  if (decided.lostAgreement) lost.Add(lane);
  return static_cast<int>(decided.item);
}

// Fills the window from `luma(dx, dy)`: the centre, left and top first, then (if P may have an
// edge) the rest; returns false at the early exit.
template <typename Fetch>
bool FillWindow(LumaWindow& window, float threshold, Fetch&& luma) {
  window.At(0, 0) = luma(0, 0);
  window.At(-1, 0) = luma(-1, 0);
  window.At(0, -1) = luma(0, -1);
  if (!MayHaveEdge(window.At(0, 0), window.At(-1, 0), window.At(0, -1), threshold)) return false;
  for (int dy = kWindowMin; dy <= kWindowMax; ++dy) {
    for (int dx = kWindowMin; dx <= kWindowMax; ++dx) {
      if ((dx == 0 && dy == 0) || (dx == -1 && dy == 0) || (dx == 0 && dy == -1)) continue;
      window.At(dx, dy) = luma(dx, dy);
    }
  }
  return true;
}

}  // namespace

Config ConfigOf(const PassSettings& settings) {
  Config config;
  config.threshold = static_cast<float>(settings.Get("threshold"));
  config.maxSearchSteps = static_cast<int>(settings.Get("max_search_steps"));
  config.maxSearchStepsDiag = static_cast<int>(settings.Get("max_search_steps_diag"));
  config.cornerRounding = static_cast<float>(settings.Get("corner_rounding"));
  return config;
}

Morphological::Morphological(std::string_view pass, const smaa::Config& config)
    : detect_(std::string(pass) + "/edge-detection"),
      vertical_(std::string(pass) + "/vertical-edges"),
      horizontal_(std::string(pass) + "/horizontal-edges"),
      kernels_(KernelsFor(detect_, vertical_, horizontal_)),
      config_(config),
      tables_(smaa::LookupTables::Make()),
      workSet_(pass) {}

template <typename Form>
auto Morphological::MakeDetect(sim::Dispatch& d, Form, const sim::Texture2D<glm::vec4>& colour,
                               sim::Texture2D<glm::vec2>& edges) const {
  const sim::TextureView<glm::vec4> gamma = d.Read(colour).As(sim::Format::RGBA8Unorm);
  const sim::RwTextureView<glm::vec2> edgesOut = d.ReadWrite(edges);
  const sim::CounterView lost = d.Counter("lost_agreement");
  const float threshold = config_.threshold;
  const int width = colour.Width(), height = colour.Height();
  if constexpr (Form::value == DetectForm::Pixel) {
    // The reference's point samples with clamp addressing: the clamped neighbour's texel.
    return [=](sim::PixelLane& lane, int x, int y) {
      LumaWindow window;
      const bool candidate = FillWindow(window, threshold, [&](int dx, int dy) {
        return Luma(glm::vec3(
            gamma.Load(lane, std::clamp(x + dx, 0, width - 1), std::clamp(y + dy, 0, height - 1))));
      });
      return candidate ? Finish(lane, x, y, window, threshold, edgesOut, lost) : 0;
    };
  } else {
    // "LDS preloading via Gather4" (seed 000): one gather per channel fetches a 2x2 block's
    // red, green or blue; the tile holds the blocks' lumas.
    auto fillTile = [=](sim::ComputeLane& lane) {
      if (lane.localIndex >= kTileBlocks) return;
      const int bx = 2 * (lane.localIndex % (kTileSide / 2)), by = 2 * (lane.localIndex / (kTileSide / 2));
      const int x0 = lane.groupId.x * kGroupSide - kApron + bx, y0 = lane.groupId.y * kGroupSide - kApron + by;
      // The footprint's top-left texel is x0, y0 when uv sits on the corner between the four.
      const glm::vec2 uv(static_cast<float>(x0 + 1) / static_cast<float>(width),
                         static_cast<float>(y0 + 1) / static_cast<float>(height));
      const glm::vec4 r = gamma.Gather(lane, uv, 0), g = gamma.Gather(lane, uv, 1), b = gamma.Gather(lane, uv, 2);
      // Gather order (x, y, z, w) = (x0, y0+1), (x0+1, y0+1), (x0+1, y0), (x0, y0).
      const auto store = [&](int component, int tx, int ty) {
        lane.LdsStore<float>(static_cast<std::size_t>(ty * kTileSide + tx),
                             Luma({r[component], g[component], b[component]}));
      };
      store(3, bx, by);
      store(2, bx + 1, by);
      store(0, bx, by + 1);
      store(1, bx + 1, by + 1);
    };
    auto detect = [=](sim::ComputeLane& lane, int x, int y) {
      LumaWindow window;
      const bool candidate = FillWindow(window, threshold, [&](int dx, int dy) {
        return lane.LdsLoad<float>(
            static_cast<std::size_t>((lane.localId.y + kApron + dy) * kTileSide + lane.localId.x + kApron + dx));
      });
      return candidate ? Finish(lane, x, y, window, threshold, edgesOut, lost) : 0;
    };
    return StagedDetect<decltype(fillTile), decltype(detect)>{fillTile, detect};
  }
}

WorkSetShape Morphological::Run(sim::Machine& machine, Strategy strategy, const sim::Texture2D<glm::vec4>& colour,
                                sim::Texture2D<glm::vec4>& blended, sim::Texture2D<glm::vec2>& edges) {
  const int width = colour.Width(), height = colour.Height();
  const Metrics metrics = Metrics::Of(width, height);
  auto makeDetect = [&](sim::Dispatch& d, auto form) { return MakeDetect(d, form, colour, edges); };
  auto makeBlend = [&](sim::Dispatch& d, int consume) {
    const BlendingWeights weights(config_, metrics,
                                  {.edges = d.Read(edges), .area = d.Read(tables_.area),
                                   .search = d.Read(tables_.search), .searchSteps = d.Counter("search_steps")});
    const sim::RwTextureView<glm::vec4> out = d.ReadWrite(blended);
    const bool vertical = consume == 0;
    return [=](const auto& lane, int x, int y) {
      // (this pixel's weight towards the other, the other's towards this one): B, A for the left
      // edge, R, G for the top edge (aa-facts §1.5).
      const glm::vec2 w = vertical ? weights.LeftEdgeWeights(lane, x, y)
                                   : weights.TopEdgeWeights(lane, x, y, weights.EdgesAt(lane, x, y)).weights;
      const int ox = vertical ? x - 1 : x, oy = vertical ? y : y - 1;
      if (w.x + w.y == 0.0f) return;
      const glm::vec4 here = out.Load(lane, x, y), other = out.Load(lane, ox, oy);
      // SMAA's neighbourhood blend along one axis: a bilinear fetch w px towards the neighbour.
      if (w.x > 0.0f) out.Store(lane, x, y, here * (1.0f - w.x) + other * w.x);
      if (w.y > 0.0f) out.Store(lane, ox, oy, other * (1.0f - w.y) + here * w.y);
    };
  };
  return workSet_.Run(machine, strategy, kernels_, width, height, makeDetect, makeBlend);
}

}  // namespace passes::filmic_smaa
