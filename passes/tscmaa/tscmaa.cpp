// TSCMAA on the pass framework (see tscmaa.h).

#include "passes/tscmaa/tscmaa.h"

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "passes/cmaa2/cmaa2.h"
#include "passes/cmaa2/cmaa2_kernels.h"
#include "passes/temporal/colour_box.h"
#include "passes/temporal/history_filter.h"
#include "passes/work_set.h"
#include "sim/colour.h"
#include "sim/formats.h"

namespace passes::tscmaa {
namespace {

constexpr std::string_view kDetectDispatch = "tscmaa/taa-candidates";
constexpr std::string_view kTaaDispatch = "tscmaa/taa";

constexpr WorkSetKernels kKernels{
    .detectDispatch = kDetectDispatch,
    .consumeDispatch = kTaaDispatch,
    .detectPixel = {.vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 34,
                    .source = "hand count: the colour copy's load and store (~4), the edges load and nibble, the "
                              "four corner tests (~8), the position hash (6 ALU) and threshold compare, the stencil "
                              "export"},
    .detectCompute = {.vgprs = 12, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 38,
                      .source = "hand count: as the pixel form, plus bounds compare, pack x | y << 16 and the append "
                                "address"},
    .consume = {.vgprs = 48, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 190,
                .source = "hand count of the TAA per candidate: velocity load and history address (~10), 5-tap "
                          "Catmull-Rom weights and tap positions (~45), the corner-averaged sum (~25), 9 loads with "
                          "clamped addresses (~20), 9 YCoCg conversions and moments (~45), sigma (3 sqrt) and the "
                          "clip (~30), blend and store (~15)"},
};

struct Config {
  double threshold = 1.0 / 22.0;
  double localContrastAdaptation = 0.5;
  double taaFraction = 0.5;
  float blend = 0.8f;
  float gamma = 1.0f;
};

Config ConfigOf(const PassSettings& settings) {
  return {.threshold = settings.Get("threshold"),
          .localContrastAdaptation = settings.Get("local_contrast_adaptation"),
          .taaFraction = settings.Get("taa_fraction"),
          .blend = static_cast<float>(settings.Get("blend")),
          .gamma = static_cast<float>(settings.Get("variance_gamma"))};
}

std::unique_ptr<cmaa2::Stage> MakeCmaa2(const Config& config) {
  PassSettings settings(cmaa2::Info().name, cmaa2::Info().settings);
  settings.Set("threshold", config.threshold);
  settings.Set("local_contrast_adaptation", config.localContrastAdaptation);
  return cmaa2::MakeStage(settings);
}

// The TAA on one candidate (the diagram's tscmaa/taa).
struct TaaKernel {
  sim::TextureView<glm::vec4> current, history;  // CMAA2's colour, the previous output (sRGB views)
  std::optional<sim::TextureView<glm::vec2>> velocity;
  sim::RwTextureView<glm::vec4> out;
  sim::CounterView clipped, offscreen;
  float blend, gamma;
  int width, height;
  bool useHistory;

  template <typename Lane>
  void operator()(const Lane& lane, int x, int y) const {
    // No history yet: the CMAA pixel, already copied.
    if (!useHistory) return;
    const glm::vec2 v = velocity ? velocity->Load(lane, x, y) : glm::vec2(0.0f);
    const glm::vec2 uv = temporal::HistoryUv(x, y, v, width, height);
    if (uv.x < 0.0f || uv.x > 1.0f || uv.y < 0.0f || uv.y > 1.0f) {
      offscreen.Add(lane);
      return;
    }
    const glm::vec3 c(current.Load(lane, x, y));
    const glm::vec3 h = Clipped(lane, x, y, c, glm::vec3(temporal::SampleHistoryIntel(history, lane, uv)));
    out.Store(lane, x, y, glm::vec4(c + (h - c) * blend, 1.0f));
  }

  // The history clipped to the variance box of CMAA2's 3x3 in YCoCg, along the segment towards the
  // current colour (Intel's ray towards the current colour, aa-facts §5.3), the current colour
  // brought into the box first so the clip lands inside it.
  template <typename Lane>
  glm::vec3 Clipped(const Lane& lane, int x, int y, const glm::vec3& c, const glm::vec3& h) const {
    const temporal::Moments moments = temporal::MomentsOf(temporal::Neighbourhood::Box3x3, [&](glm::ivec2 o) {
      const int nx = std::clamp(x + o.x, 0, width - 1), ny = std::clamp(y + o.y, 0, height - 1);
      return sim::RgbToYCoCg(glm::vec3(current.Load(lane, nx, ny)));
    });
    const temporal::ColourBox box = temporal::VarianceBox(moments, gamma);
    const glm::vec3 hy = sim::RgbToYCoCg(h);
    const glm::vec3 clippedY = temporal::ClipTowards(hy, box, temporal::ClampToBox(sim::RgbToYCoCg(c), box));
    if (clippedY == hy) return h;
    clipped.Add(lane);
    return sim::YCoCgToRgb(clippedY);
  }
};

class TscmaaPass final : public Pass {
 public:
  explicit TscmaaPass(const Config& config) : config_(config), cmaa2_(MakeCmaa2(config)), workSet_(tscmaa::Info().name) {}

  const PassInfo& Info() const override { return tscmaa::Info(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override;

 private:
  Config config_;
  std::unique_ptr<cmaa2::Stage> cmaa2_;
  WorkSet workSet_;
  std::array<std::optional<sim::Texture2D<glm::vec4>>, 2> history_;
  int current_ = 0;          // the history target this frame writes
  bool hasHistory_ = false;  // the other target holds the previous frame's output
};

PassOutput TscmaaPass::Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) {
  const int width = frame.Width(), height = frame.Height();
  const cmaa2::Stage::Targets cmaa = cmaa2_->Process(machine, frame, strategy);
  const sim::Texture2D<glm::vec4>& colour = cmaa.colour;
  const sim::Texture2D<std::uint32_t>& edges = cmaa.edges;

  const int previous = 1 - current_;
  const bool resized = !history_[previous] || history_[previous]->Width() != width || history_[previous]->Height() != height;
  const bool useHistory = hasHistory_ && !resized && frame.frameIndex != 0;
  sim::Texture2D<glm::vec4>& read =
      FrameTexture(history_[previous], "tscmaa/history-" + std::to_string(previous), width, height, sim::Format::RGBA8Srgb);
  sim::Texture2D<glm::vec4>& write =
      FrameTexture(history_[current_], "tscmaa/history-" + std::to_string(current_), width, height, sim::Format::RGBA8Srgb);
  const double fraction = config_.taaFraction;
  // Every pixel copies CMAA2's codes into the new history (UNORM views, bit for bit), so the
  // pixels the TAA does not run on keep CMAA2's; then the candidate test.
  auto makeDetect = [&](sim::Dispatch& d, auto) {
    const sim::TextureView<glm::vec4> cmaaCodes = d.Read(colour).As(sim::Format::RGBA8Unorm);
    const sim::RwTextureView<glm::vec4> historyCodes = d.ReadWrite(write).As(sim::Format::RGBA8Unorm);
    const sim::TextureView<std::uint32_t> edgeView = d.Read(edges);
    return [=](const auto& lane, int x, int y) {
      historyCodes.Store(lane, x, y, cmaaCodes.Load(lane, x, y));
      return cmaa2::IsCandidate(cmaa2::LoadEdge(lane, edgeView, x, y)) && ChosenForTaa(x, y, fraction);
    };
  };
  auto makeTaa = [&](sim::Dispatch& d) {
    return TaaKernel{.current = d.Read(colour),
                     .history = d.Read(read),
                     .velocity = frame.velocity ? std::optional(d.Read(*frame.velocity)) : std::nullopt,
                     .out = d.ReadWrite(write),
                     .clipped = d.Counter("tscmaa/history_clipped"),
                     .offscreen = d.Counter("tscmaa/history_offscreen"),
                     .blend = config_.blend,
                     .gamma = config_.gamma,
                     .width = width,
                     .height = height,
                     .useHistory = useHistory};
  };
  PassOutput output;
  output.SetWorkSet(workSet_.Run(machine, strategy, kKernels, width, height, makeDetect, makeTaa));
  hasHistory_ = true;
  current_ = previous;

  output.colour = DecodedSrgb8("tscmaa/output", write);
  output.layers.push_back(cmaa2_->EdgesLayer());
  output.layers.push_back(cmaa2_->CandidatesLayer(strategy));
  output.layers.push_back(MembershipLayer("taa-candidates", workSet_.Membership(strategy), width, height));
  return output;
}

std::vector<SettingInfo> Settings() {
  return {
      {.name = "threshold", .defaultValue = 1.0 / 22.0, .min = 1.0 / 32.0, .max = 1.0,
       .doc = "CMAA2's edge threshold; TSCMAA's default 1/22 and recommended range [1/32, 1] (seed 003 "
              "SetEdgeThresholds)"},
      {.name = "local_contrast_adaptation", .defaultValue = 0.5, .min = 0.0, .max = 3.0,
       .doc = "CMAA2's local contrast adaptation, read from TSCMAA's nonDominantEdgeRemovalAmount (default 0.5, "
              "range [0, 3], seed 003; docs/cmaa2.md \"the tscmaa reading\")"},
      {.name = "taa_fraction", .defaultValue = 0.5, .min = 0.0, .max = 1.0,
       .doc = "share of CMAA's edge candidates the TAA runs on, chosen by a fixed hash of the pixel position "
              "(seed 003: 50 percent)"},
      {.name = "blend", .defaultValue = 0.8, .min = 0.0, .max = 1.0,
       .doc = "history weight on TAA candidates, lerp(current, history, blend) (seed 003: 0.8)"},
      {.name = "variance_gamma", .defaultValue = 1.0, .min = 0.0, .max = 4.0, .minExclusive = true,
       .doc = "variance clipping box mean ± gamma sigma over the 3x3 (seed 003 names variance clipping, no gamma; "
              "1 is Salvi's usual value, aa-facts §5.4 [unverified])"},
  };
}

}  // namespace

const PassInfo& Info() {
  static const PassInfo info{
      .name = "tscmaa",
      .description = "TSCMAA: CMAA2 at threshold 1/22, then TAA on half of its edge candidates (5-tap Catmull-Rom "
                     "history, YCoCg variance clipping, blend 0.8); the history is the TSCMAA output",
      .source = "passes/tscmaa/tscmaa.h",
      .settings = Settings(),
      .presets = {},
      .inputs = {FrameInput::Colour, FrameInput::Velocity},
      .studiedDispatches = {kTaaDispatch},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // CMAA2's own (its decoded output included, which this pass does not make), two histories
      // and the output (vec4 each), the stencil byte, the queue entry and the membership byte.
      .bytesPerPixel = cmaa2::Info().bytesPerPixel + 3 * sizeof(glm::vec4) + 1 + sizeof(std::uint32_t) + 1,
      .layerBytesPerPixel = 3 * sizeof(float),  // edges, candidates, taa-candidates
      .temporal = true,
      .jitter = "none",
  };
  return info;
}

std::unique_ptr<Pass> Make(const PassSettings& settings) { return std::make_unique<TscmaaPass>(ConfigOf(settings)); }

}  // namespace passes::tscmaa
