// SMAA T2x and 4x (see smaa_temporal.h).

#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include "passes/smaa/s2x.h"
#include "passes/smaa/smaa.h"
#include "passes/smaa/smaa_pipeline.h"
#include "passes/smaa/smaa_temporal.h"
#include "passes/smaa/smaa_targets.h"
#include "passes/smaa/temporal_resolve.h"
#include "sim/formats.h"

namespace passes::smaa {

glm::vec4 T2xSubsampleIndices(int frameIndex) {
  // aa-facts §1.8: frame 0 draws S0 (1,1,1,0), frame 1 S1 (2,2,2,0).
  return frameIndex % 2 == 0 ? glm::vec4(1, 1, 1, 0) : glm::vec4(2, 2, 2, 0);
}

std::array<glm::vec4, 2> FourXSubsampleIndices(int frameIndex) {
  // aa-facts §1.8's table, index 2 * frame + sample (msaaReorder is the identity for D3D's
  // standard 2x pattern, whose sample 0 is the table's S0: passes/smaa/s2x.cpp).
  static constexpr std::array<glm::vec4, 4> kTable = {glm::vec4(5, 3, 1, 3), glm::vec4(4, 6, 2, 3),
                                                      glm::vec4(3, 5, 1, 4), glm::vec4(6, 4, 2, 4)};
  const std::size_t frame = static_cast<std::size_t>(frameIndex % 2);
  return {kTable[2 * frame], kTable[2 * frame + 1]};
}

const sim::Texture2D<glm::vec2>& StoreUvVelocity(const FrameInputs& frame, std::optional<sim::Texture2D<glm::vec2>>& kept,
                                                 const std::string& name, int width, int height) {
  if (frame.velocity == nullptr) throw std::invalid_argument(name + ": the pass needs the frame's velocity");
  sim::Texture2D<glm::vec2>& velocity = FrameTexture(kept, name, width, height, sim::Format::RG16Float);
  const glm::vec2 toUv(1.0f / static_cast<float>(width), 1.0f / static_cast<float>(height));
  const std::span<const glm::vec2> pixels = frame.velocity->Texels();
  const std::span<glm::vec2> uv = velocity.Texels();
  ByRows(width, height, [&](std::size_t i) { uv[i] = sim::Quantize(sim::Format::RG16Float, pixels[i] * toUv); });
  return velocity;
}

namespace {

constexpr sim::KernelInfo kResolve{
    .vgprs = 12, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 26,
    .source = "hand count of SMAAResolvePS with SMAA_REPROJECTION: 3 point fetches' addresses (4), the negated "
              "velocity and reprojected address (3), two squares, difference, abs and /5 (5), sqrt, mad and "
              "saturate (4), the 4-channel lerp (8), export (2)"};
constexpr sim::KernelInfo kResolveAverage{
    .vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 12,
    .source = "hand count of SMAAResolvePS without reprojection: 2 point fetches' addresses (2), the 4-channel "
              "lerp (8), export (2)"};

struct TemporalConfig {
  bool reprojection = true;
  float weightScale = kReprojectionWeightScale;
};

TemporalConfig TemporalConfigOf(const PassSettings& settings) {
  return {.reprojection = settings.Get("reprojection") != 0.0,
          .weightScale = static_cast<float>(settings.Get("reprojection_weight_scale"))};
}

// The two SMAA output targets T2x and 4x keep (the demo's finalRT[2]), the velocity target and
// the resolve.
class TemporalHistory {
 public:
  TemporalHistory(std::string_view pass, const TemporalConfig& config) : pass_(pass), config_(config) {}

  // This frame's SMAA target. History is lost at a sequence's first frame and at a size change.
  sim::Texture2D<glm::vec4>& Begin(const FrameInputs& frame, int width, int height) {
    const bool resized = !history_[0] || history_[0]->Width() != width || history_[0]->Height() != height;
    if (resized || frame.frameIndex == 0) valid_ = false;
    for (std::size_t i = 0; i < 2; ++i) {
      FrameTexture(history_[i], pass_ + "/history" + std::to_string(i), width, height, sim::Format::RGBA8Srgb);
    }
    return *history_[current_];
  }

  // The reference's velocity target; null without reprojection.
  const sim::Texture2D<glm::vec2>* Velocity(const FrameInputs& frame, int width, int height) {
    if (!config_.reprojection) return nullptr;
    return &StoreUvVelocity(frame, velocity_, pass_ + "/velocity", width, height);
  }

  // Resolves this frame's target with the previous one (this one when there is none) into the
  // output target; returns it decoded.
  sim::Texture2D<glm::vec4> Resolve(sim::Machine& machine) {
    sim::Texture2D<glm::vec4>& current = *history_[current_];
    const sim::Texture2D<glm::vec4>& previous = valid_ ? *history_[1 - current_] : current;
    const int width = current.Width(), height = current.Height();
    sim::Texture2D<glm::vec4>& output = FrameTexture(output_, pass_ + "/output", width, height, sim::Format::RGBA8Srgb);
    {
      sim::Dispatch d(pass_ + "/resolve", config_.reprojection ? kResolve : kResolveAverage);
      std::optional<sim::TextureView<glm::vec2>> velocity;
      if (config_.reprojection) velocity = d.Read(*velocity_);
      const TemporalResolve resolve{Metrics::Of(width, height), d.Read(current), d.Read(previous), velocity,
                                    config_.weightScale};
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(output);
      machine.FullScreen(d, {.width = width, .height = height},
                         [&](sim::PixelLane& lane) { out.Store(lane, lane.x, lane.y, resolve(lane, lane.x, lane.y)); });
    }
    current_ = 1 - current_;
    valid_ = true;
    return DecodedSrgb8(pass_ + "/output", output);
  }

 private:
  std::string pass_;
  TemporalConfig config_;
  std::array<std::optional<sim::Texture2D<glm::vec4>>, 2> history_;
  std::optional<sim::Texture2D<glm::vec2>> velocity_;
  std::optional<sim::Texture2D<glm::vec4>> output_;
  std::size_t current_ = 0;
  bool valid_ = false;
};

class T2xPass final : public Pass {
 public:
  explicit T2xPass(const PassSettings& settings)
      : smaa_(T2xInfo().name, ConfigOf(Variant::Luma, settings),
              {"smaa-t2x/edge-detection", "smaa-t2x/blending-weights", "smaa-t2x/neighbourhood-blending"}),
        history_(T2xInfo().name, TemporalConfigOf(settings)) {}

  const PassInfo& Info() const override { return T2xInfo(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.Width(), height = frame.Height();
    const sim::Texture2D<glm::vec4>& colour = frame.ColourSrgb8();
    sim::Texture2D<glm::vec4>& target = history_.Begin(frame, width, height);
    const sim::Texture2D<glm::vec2>* velocity = history_.Velocity(frame, width, height);
    smaa_.SetSubsampleIndices(T2xSubsampleIndices(frame.frameIndex));
    const Smaa1x::Frame result = smaa_.Run(machine, strategy, colour, nullptr, target, Blend::Replace, velocity);
    PassOutput output;
    output.SetWorkSet(result.workSet);
    output.layers.push_back(LayerOf("edges", result.targets.edges, {"R", "G"}));
    output.layers.push_back(LayerOf("weights", result.targets.weights, {"R", "G", "B", "A"}));
    output.colour = history_.Resolve(machine);
    return output;
  }

 private:
  Smaa1x smaa_;
  TemporalHistory history_;
};

class FourXPass final : public Pass {
 public:
  explicit FourXPass(const PassSettings& settings)
      : runs_(FourXInfo().name, ConfigOf(Variant::Luma, settings)), history_(FourXInfo().name, TemporalConfigOf(settings)) {}

  const PassInfo& Info() const override { return FourXInfo(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.eqaa->Width(), height = frame.eqaa->Height();
    sim::Texture2D<glm::vec4>& target = history_.Begin(frame, width, height);
    const sim::Texture2D<glm::vec2>* velocity = history_.Velocity(frame, width, height);
    S2xRuns::Frame result =
        runs_.Run(machine, strategy, *frame.eqaa, FourXSubsampleIndices(frame.frameIndex), target, velocity);
    PassOutput output;
    output.SetWorkSet(result.workSet);
    output.layers = std::move(result.layers);
    output.colour = history_.Resolve(machine);
    return output;
  }

 private:
  S2xRuns runs_;
  TemporalHistory history_;
};

std::vector<SettingInfo> TemporalSettings() {
  std::vector<SettingInfo> settings = SettingsOf(Variant::Luma);
  settings.push_back({.name = "reprojection", .defaultValue = 1, .min = 0, .max = 1, .integer = true,
                      .doc = "SMAA_REPROJECTION: fetch the previous frame along the velocity and weight it by the "
                             "velocity lengths' difference (on: the demo's Temporal Reprojection default)"});
  settings.push_back({.name = "reprojection_weight_scale", .defaultValue = static_cast<double>(kReprojectionWeightScale), .min = 0,
                      .max = 80,
                      .doc = "SMAA_REPROJECTION_WEIGHT_SCALE: how fast a velocity difference removes the previous "
                             "frame (SMAA.hlsl: 30, range [0, 80])"});
  return settings;
}

// The T2x pass's history: two RGBA8 targets and the RG16F velocity, as vec4 / vec2 floats, plus
// the resolved output and its decoded copy.
constexpr std::uint64_t kTemporalBytesPerPixel = 4 * sizeof(glm::vec4) + sizeof(glm::vec2);

}  // namespace

const PassInfo& T2xInfo() {
  static const PassInfo info{
      .name = "smaa-t2x",
      .description = "SMAA T2x: SMAA 1x with the frame's subsample indices, then the temporal resolve with the "
                     "previous frame (velocity-weighted reprojection)",
      .source = "passes/smaa/smaa_temporal.h",
      .settings = TemporalSettings(),
      .presets = SearchPresets(),
      .inputs = {FrameInput::Colour, FrameInput::Velocity},
      .studiedDispatches = {"smaa-t2x/blending-weights"},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      .bytesPerPixel = kBytesPerPixel + kTemporalBytesPerPixel,
      .layerBytesPerPixel = 2 + 4,  // edges RG8, weights RGBA8 codes
      .temporal = true,
      .jitter = "t2x",
      .variantOf = "smaa",
  };
  return info;
}

const PassInfo& FourXInfo() {
  static const PassInfo info{
      .name = "smaa-4x",
      .description = "SMAA 4x: SMAA S2x with the frame's subsample indices, then the temporal resolve with the "
                     "previous frame (needs a 2S frame)",
      .source = "passes/smaa/smaa_temporal.h",
      .settings = TemporalSettings(),
      .presets = SearchPresets(),
      .inputs = {FrameInput::Eqaa, FrameInput::Velocity},
      .studiedDispatches = {"smaa-4x/s0/blending-weights", "smaa-4x/s1/blending-weights"},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // Both sample runs and the two separated samples, plus the history.
      .bytesPerPixel = 2 * kBytesPerPixel + 2 * sizeof(glm::vec4) + kTemporalBytesPerPixel,
      .layerBytesPerPixel = 2 * (2 + 4),  // per sample run: edges RG8, weights RGBA8 codes
      .temporal = true,
      .jitter = "4x",
      .eqaaSamples = 2,
      .variantOf = "smaa-s2x",
  };
  return info;
}

std::unique_ptr<Pass> MakeT2x(const PassSettings& settings) { return std::make_unique<T2xPass>(settings); }
std::unique_ptr<Pass> MakeFourX(const PassSettings& settings) { return std::make_unique<FourXPass>(settings); }

}  // namespace passes::smaa
