// Demonstration post pass (see demo.h).

#include "passes/demo/demo.h"

#include <algorithm>
#include <cmath>

#include "passes/work_set.h"
#include "sim/colour.h"

namespace passes::demo {
namespace {

constexpr std::string_view kDetectDispatch = "demo/edge-detect";
constexpr std::string_view kBlendDispatch = "demo/blend";
constexpr int kGroupSide = 8;
constexpr int kTileSide = kGroupSide + 2;  // one-pixel apron, as the MiniEngine FXAA luma cache (aa-facts §3)

// The demo has no reference shader to count: the estimates are hand counts of this file's kernels.
constexpr WorkSetKernels kKernels{
    .detectDispatch = kDetectDispatch,
    .consumeDispatch = kBlendDispatch,
    .detectPixel = {.vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 40,
                    .source = "hand count of passes/demo: 5 luma dot products (15), 4 abs differences and a "
                              "max tree (11), the compare, 2 stores and the stencil export (~14)"},
    .detectCompute = {.vgprs = 16, .sgprs = 24, .ldsBytesPerGroup = kTileSide * kTileSide * 4,
                      .valuInstructionsPerWave = 48,
                      .source = "hand count of passes/demo: the pixel form's 40 minus 4 lumas read from LDS, "
                                "plus the 10x10 tile fill (2 lumas per thread, addressing) and the append"},
    .consume = {.vgprs = 20, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 48,
                .source = "hand count of passes/demo: 9 clamped addresses (~12), 8 vec4 adds (32), the divide "
                          "as 4 multiplies"},
};

// aa-facts §1.3: SMAA's luma edge detection weights gamma-encoded colour by Rec. 709.
float Luma(const glm::vec4& linear) { return sim::Rec709Luma(sim::EncodeSrgb(glm::vec3(linear))); }

// Left, top, right, bottom: the same order in both strategies keeps the results bit-identical.
bool IsEdge(float centre, float left, float top, float right, float bottom, float threshold) {
  const float delta = std::max(std::max(std::fabs(centre - left), std::fabs(centre - top)),
                               std::max(std::fabs(centre - right), std::fabs(centre - bottom)));
  return delta >= threshold;
}

class DemoPass final : public Pass {
 public:
  explicit DemoPass(const PassSettings& settings)
      : threshold_(static_cast<float>(settings.Get("threshold"))), workSet_(Info().name) {}

  const PassInfo& Info() const override { return demo::Info(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.Width(), height = frame.Height();
    PassOutput output{.colour = {"demo/output", width, height, 4}, .layers = {}, .workItems = 0, .workSet = {}};
    sim::Texture2D<float> edges("demo/edges", width, height, 1);
    const sim::Texture2D<glm::vec4>& colour = *frame.colour;
    auto clampX = [=](int x) { return std::clamp(x, 0, width - 1); };
    auto clampY = [=](int y) { return std::clamp(y, 0, height - 1); };
    auto makeDetect = [&](sim::Dispatch& d, auto form) {
      const sim::TextureView<glm::vec4> in = d.Read(colour);
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(output.colour);
      const sim::RwTextureView<float> edgesOut = d.ReadWrite(edges);
      // The pixel's own work under both forms: copy the colour, mark the edge.
      auto mark = [=, threshold = threshold_](const auto& lane, int x, int y, const glm::vec4& centre,
                                              float centreLuma, auto&& luma) {
        const bool edge = IsEdge(centreLuma, luma(-1, 0), luma(0, -1), luma(1, 0), luma(0, 1), threshold);
        out.Store(lane, x, y, centre);
        edgesOut.Store(lane, x, y, edge ? 1.0f : 0.0f);
        return edge;
      };
      if constexpr (decltype(form)::value == DetectForm::Pixel) {
        return [=](sim::PixelLane& lane, int x, int y) {
          const glm::vec4 centre = in.Load(lane, x, y);
          return mark(lane, x, y, centre, Luma(centre),
                      [&](int dx, int dy) { return Luma(in.Load(lane, clampX(x + dx), clampY(y + dy))); });
        };
      } else {
        auto fillTile = [=](sim::ComputeLane& lane) {
          for (int entry = lane.localIndex; entry < kTileSide * kTileSide; entry += kGroupSide * kGroupSide) {
            const int x = lane.groupId.x * kGroupSide + entry % kTileSide - 1;
            const int y = lane.groupId.y * kGroupSide + entry / kTileSide - 1;
            lane.LdsStore<float>(static_cast<std::size_t>(entry), Luma(in.Load(lane, clampX(x), clampY(y))));
          }
        };
        auto detect = [=](sim::ComputeLane& lane, int x, int y) {
          auto luma = [&](int dx, int dy) {
            return lane.LdsLoad<float>(
                static_cast<std::size_t>((lane.localId.y + 1 + dy) * kTileSide + lane.localId.x + 1 + dx));
          };
          return mark(lane, x, y, in.Load(lane, x, y), luma(0, 0), luma);
        };
        return StagedDetect<decltype(fillTile), decltype(detect)>{fillTile, detect};
      }
    };
    auto makeBlend = [&](sim::Dispatch& d) {
      const sim::TextureView<glm::vec4> in = d.Read(colour);
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(output.colour);
      return [=](const auto& lane, int x, int y) {
        glm::vec4 sum(0.0f);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) sum += in.Load(lane, clampX(x + dx), clampY(y + dy));
        }
        out.Store(lane, x, y, sum / 9.0f);
      };
    };
    output.SetWorkSet(workSet_.Run(machine, strategy, kKernels, width, height, makeDetect, makeBlend));
    output.layers.push_back(LayerOf("edges", edges));
    return output;
  }

 private:
  float threshold_;
  WorkSet workSet_;
};

}  // namespace

const PassInfo& Info() {
  static const PassInfo info{
      .name = "demo",
      .description = "luma edge detection, then a 3x3 box blend on edge pixels",
      .source = "passes/demo/demo.h",
      .settings = {{.name = "threshold", .defaultValue = 0.1, .min = 0.0, .max = 1.0, .minExclusive = true,
                    .doc = "luma difference that makes an edge (SMAA's default, aa-facts §1.2)"}},
      .presets = {},
      .inputs = {FrameInput::Colour},
      .studiedDispatches = {kBlendDispatch},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // Blended colour, edge texture and its layer copy, stencil byte, queue entry.
      .bytesPerPixel = sizeof(glm::vec4) + 2 * sizeof(float) + 1 + sizeof(std::uint32_t),
      .layerBytesPerPixel = sizeof(float),  // edges
      .temporal = false,
  };
  return info;
}

std::unique_ptr<Pass> Make(const PassSettings& settings) { return std::make_unique<DemoPass>(settings); }

}  // namespace passes::demo
