// SMAA 1TX (see smaa_1tx.h).

#include "passes/smaa/smaa_1tx.h"

#include <algorithm>
#include <array>
#include <optional>
#include <string>

#include "passes/smaa/smaa.h"
#include "passes/smaa/smaa_pipeline.h"
#include "passes/smaa/smaa_targets.h"
#include "passes/smaa/temporal_resolve.h"
#include "sim/formats.h"

namespace passes::smaa {

glm::vec3 SpatialContrastBlend(const glm::vec3& centre, const glm::vec3 (&diagonals)[4], const glm::vec3& history,
                               float lowFrequencyFrames, float highFrequencyFrames) {
  const glm::vec3 low = glm::min(glm::min(diagonals[0], diagonals[1]), glm::min(diagonals[2], diagonals[3]));
  const glm::vec3 high = glm::max(glm::max(diagonals[0], diagonals[1]), glm::max(diagonals[2], diagonals[3]));
  const glm::vec3 accumulated = glm::clamp(history, low, high);
  const glm::vec3 contrast = glm::abs((diagonals[0] + diagonals[1] + diagonals[2] + diagonals[3]) * 0.25f - centre);
  glm::vec3 result;
  for (int c = 0; c < 3; ++c) {
    const float frames = lowFrequencyFrames * (1.0f - contrast[c]) + highFrequencyFrames * contrast[c];
    const float weight = Saturate(1.0f / frames);
    result[c] = accumulated[c] * (1.0f - weight) + centre[c] * weight;
  }
  return result;
}

namespace {

constexpr sim::KernelInfo kTemporal{
    .vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 60,
    .source = "hand count of the spatial-contrast history (seed 000 SMAA 1TX): 6 fetches' addresses (8), the "
              "velocity negation and history address (3), 4-tap min, max and mean (18), the clamp (6), contrast, "
              "frames, rcp and saturate per channel (15), the blend (6), export (4)"};

class OneTxPass final : public Pass {
 public:
  explicit OneTxPass(const PassSettings& settings)
      : smaa_(OneTxInfo().name, ConfigOf(Variant::Luma, settings),
              {"smaa-1tx/edge-detection", "smaa-1tx/blending-weights", "smaa-1tx/neighbourhood-blending"}),
        lowFrames_(static_cast<float>(settings.Get("k_lowfreq"))),
        highFrames_(static_cast<float>(settings.Get("k_hifreq"))) {}

  const PassInfo& Info() const override { return OneTxInfo(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.Width(), height = frame.Height();
    const sim::Texture2D<glm::vec4>& colour = frame.ColourSrgb8();
    sim::Texture2D<glm::vec4>& smaaOutput = FrameTexture(smaaOutput_, "smaa-1tx/smaa", width, height, sim::Format::RGBA8Srgb);
    const Smaa1x::Frame result = smaa_.Run(machine, strategy, colour, nullptr, smaaOutput, Blend::Replace);
    const sim::Texture2D<glm::vec2>& velocity = StoreUvVelocity(frame, velocity_, "smaa-1tx/velocity", width, height);
    PassOutput output;
    output.SetWorkSet(result.workSet);
    output.layers.push_back(LayerOf("edges", result.targets.edges, {"R", "G"}));
    output.layers.push_back(LayerOf("weights", result.targets.weights, {"R", "G", "B", "A"}));
    output.colour = Temporal(machine, frame, smaaOutput, velocity);
    return output;
  }

 private:
  sim::Texture2D<glm::vec4> Temporal(sim::Machine& machine, const FrameInputs& frame,
                                     const sim::Texture2D<glm::vec4>& current, const sim::Texture2D<glm::vec2>& velocity) {
    const int width = current.Width(), height = current.Height();
    const bool resized = !history_[0] || history_[0]->Width() != width || history_[0]->Height() != height;
    if (resized || frame.frameIndex == 0) valid_ = false;
    for (std::size_t i = 0; i < 2; ++i) {
      FrameTexture(history_[i], "smaa-1tx/history" + std::to_string(i), width, height, sim::Format::RGBA8Srgb);
    }
    sim::Texture2D<glm::vec4>& target = *history_[current_];
    const sim::Texture2D<glm::vec4>& previous = valid_ ? *history_[1 - current_] : current;
    const Metrics metrics = Metrics::Of(width, height);
    const float low = lowFrames_, high = highFrames_;
    {
      sim::Dispatch d("smaa-1tx/temporal", kTemporal);
      const sim::TextureView<glm::vec4> now = d.Read(current), before = d.Read(previous);
      const sim::TextureView<glm::vec2> motion = d.Read(velocity);
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(target);
      machine.FullScreen(d, {.width = width, .height = height}, [&](sim::PixelLane& lane) {
        const glm::vec2 uv = metrics.Texcoord(lane.x, lane.y);
        const glm::vec2 half(0.5f * metrics.invWidth, 0.5f * metrics.invHeight);
        const glm::vec4 centre = now.Load(lane, lane.x, lane.y);
        const glm::vec3 diagonals[4] = {glm::vec3(now.SampleBilinear(lane, uv + glm::vec2(-half.x, -half.y))),
                                        glm::vec3(now.SampleBilinear(lane, uv + glm::vec2(half.x, -half.y))),
                                        glm::vec3(now.SampleBilinear(lane, uv + glm::vec2(-half.x, half.y))),
                                        glm::vec3(now.SampleBilinear(lane, uv + glm::vec2(half.x, half.y)))};
        const glm::vec2 v = motion.SamplePoint(lane, uv);
        const glm::vec3 history(before.SampleBilinear(lane, uv - v));
        out.Store(lane, lane.x, lane.y,
                  glm::vec4(SpatialContrastBlend(glm::vec3(centre), diagonals, history, low, high), centre.a));
      });
    }
    current_ = 1 - current_;
    valid_ = true;
    return DecodedSrgb8("smaa-1tx/output", target);
  }

  Smaa1x smaa_;
  float lowFrames_, highFrames_;
  std::optional<sim::Texture2D<glm::vec4>> smaaOutput_;
  std::optional<sim::Texture2D<glm::vec2>> velocity_;
  std::array<std::optional<sim::Texture2D<glm::vec4>>, 2> history_;
  std::size_t current_ = 0;
  bool valid_ = false;
};

std::vector<SettingInfo> OneTxSettings() {
  std::vector<SettingInfo> settings = SettingsOf(Variant::Luma);
  settings.push_back({.name = "k_lowfreq", .defaultValue = static_cast<double>(kOneTxLowFrequencyFrames), .min = 1, .max = 64,
                      .doc = "K_lowfreq: frames kept in history where the local contrast is low (seed 000 gives no "
                             "value; CryEngine's r_AntialiasingTAAFalloffLowFreq 2.0)"});
  settings.push_back({.name = "k_hifreq", .defaultValue = static_cast<double>(kOneTxHighFrequencyFrames), .min = 1, .max = 64,
                      .doc = "K_hifreq: frames kept in history where the local contrast is high (CryEngine's "
                             "r_AntialiasingTAAFalloffHiFreq 6.0)"});
  return settings;
}

}  // namespace

const PassInfo& OneTxInfo() {
  static const PassInfo info{
      .name = "smaa-1tx",
      .description = "SMAA 1TX: SMAA 1x, then a spatial-contrast exponential history clamped to the diagonal "
                     "neighbours (no jitter)",
      .source = "passes/smaa/smaa_1tx.h",
      .settings = OneTxSettings(),
      .presets = SearchPresets(),
      .inputs = {FrameInput::Colour, FrameInput::Velocity},
      .studiedDispatches = {"smaa-1tx/blending-weights"},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // SMAA 1x's, plus the two history targets, the velocity and the decoded output.
      .bytesPerPixel = kBytesPerPixel + 3 * sizeof(glm::vec4) + sizeof(glm::vec2),
      .layerBytesPerPixel = 2 + 4,  // edges RG8, weights RGBA8 codes
      .temporal = true,
      .jitter = "none",
      .variantOf = "smaa",
  };
  return info;
}

std::unique_ptr<Pass> MakeOneTx(const PassSettings& settings) { return std::make_unique<OneTxPass>(settings); }

}  // namespace passes::smaa
