// SMAA 1x on the pass framework (see smaa.h).

#include "passes/smaa/smaa.h"

#include <cstdint>
#include <optional>
#include <string>

#include "passes/smaa/smaa_pipeline.h"
#include "sim/formats.h"

namespace passes::smaa {
namespace {

const DispatchNames kDispatchNames{"smaa/edge-detection", "smaa/blending-weights", "smaa/neighbourhood-blending"};

}  // namespace

Config ConfigOf(Variant variant, const PassSettings& settings) {
  Config config;
  config.edges = variant == Variant::Colour ? EdgeMode::Colour
                 : variant == Variant::Depth ? EdgeMode::Depth
                                             : EdgeMode::Luma;
  config.predication = variant == Variant::LumaPredicated;
  const auto get = [&](std::string_view key) { return static_cast<float>(settings.Get(key)); };
  config.threshold = get("threshold");
  config.maxSearchSteps = static_cast<int>(settings.Get("max_search_steps"));
  config.maxSearchStepsDiag = static_cast<int>(settings.Get("max_search_steps_diag"));
  config.cornerRounding = get("corner_rounding");
  if (variant != Variant::Depth) config.localContrastFactor = get("local_contrast_adaptation_factor");
  if (config.predication) {
    config.predicationThreshold = get("predication_threshold");
    config.predicationScale = get("predication_scale");
    config.predicationStrength = get("predication_strength");
  }
  return config;
}

std::unique_ptr<Pass> MakeS2x(const PassInfo& info, const Config& config);

namespace {

class SmaaPass final : public Pass {
 public:
  SmaaPass(const PassInfo& info, const Config& config) : info_(info), smaa_(info.name, config, kDispatchNames) {}

  const PassInfo& Info() const override { return info_; }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const sim::Texture2D<glm::vec4>& colour = frame.ColourSrgb8();
    // The output target, kept across frames as a renderer keeps it.
    sim::Texture2D<glm::vec4>& blended =
        FrameTexture(blended_, "smaa/output", frame.Width(), frame.Height(), sim::Format::RGBA8Srgb);
    PassOutput output;
    const Smaa1x::Frame result = smaa_.Run(machine, strategy, colour, frame.depth, blended, Blend::Replace);
    output.SetWorkSet(result.workSet);
    output.colour = DecodedSrgb8("smaa/output", blended);
    output.layers.push_back(LayerOf("edges", result.targets.edges, {"R", "G"}));
    output.layers.push_back(LayerOf("weights", result.targets.weights, {"R", "G", "B", "A"}));
    return output;
  }

 private:
  const PassInfo& info_;
  Smaa1x smaa_;
  std::optional<sim::Texture2D<glm::vec4>> blended_;
};

}  // namespace

std::vector<SettingInfo> SettingsOf(Variant variant) {
  std::vector<SettingInfo> settings =
      SearchSettings(variant == Variant::Depth ? "SMAA_THRESHOLD; depth edges use 0.1 x this (SMAA_DEPTH_THRESHOLD)"
                                               : "SMAA_THRESHOLD: edge contrast in gamma space");
  if (variant != Variant::Depth) {
    settings.push_back({.name = "local_contrast_adaptation_factor", .defaultValue = 2.0, .min = 1.0, .max = 16.0,
                        .doc = "SMAA_LOCAL_CONTRAST_ADAPTATION_FACTOR: an edge survives if no neighbour delta "
                               "exceeds it times the edge's own"});
  }
  if (variant == Variant::LumaPredicated) {
    settings.push_back({.name = "predication_threshold", .defaultValue = 0.01, .min = 0.0, .max = 1.0,
                        .doc = "SMAA_PREDICATION_THRESHOLD: depth difference that marks a predication edge"});
    settings.push_back({.name = "predication_scale", .defaultValue = 2.0, .min = 1.0, .max = 5.0,
                        .doc = "SMAA_PREDICATION_SCALE: the threshold's scale away from depth edges"});
    settings.push_back({.name = "predication_strength", .defaultValue = 0.4, .min = 0.0, .max = 1.0,
                        .doc = "SMAA_PREDICATION_STRENGTH: how much a depth edge lowers the scaled threshold"});
  }
  return settings;
}

namespace {

struct VariantNames {
  std::string_view name, description;
};
constexpr VariantNames NamesOf(Variant variant) {
  switch (variant) {
    case Variant::Luma: return {"smaa", "SMAA 1x: luma edges, orthogonal and diagonal searches, neighbourhood blend"};
    case Variant::Colour: return {"smaa-colour", "SMAA 1x with colour edges (max RGB difference)"};
    case Variant::Depth: return {"smaa-depth", "SMAA 1x with depth edges (no local contrast adaptation)"};
    case Variant::S2x:
      return {"smaa-s2x", "SMAA S2x: SMAA 1x on each sample of a 2-sample surface, blended (needs a 2S frame)"};
    case Variant::LumaPredicated:
      return {"smaa-predicated", "SMAA 1x: luma edges with thresholds predicated by the frame's depth"};
  }
  return {};
}

PassInfo MakeInfo(Variant variant) {
  std::vector<FrameInput> inputs{FrameInput::Colour};
  if (variant == Variant::Depth || variant == Variant::LumaPredicated) inputs.push_back(FrameInput::Depth);
  if (variant == Variant::S2x) inputs = {FrameInput::Eqaa};
  return {
      .name = NamesOf(variant).name,
      .description = NamesOf(variant).description,
      .source = "passes/smaa/smaa.h",
      .settings = SettingsOf(variant),
      .presets = SearchPresets(),
      .inputs = inputs,
      .studiedDispatches = variant == Variant::S2x
                               ? std::vector<std::string_view>{"smaa-s2x/s0/blending-weights", "smaa-s2x/s1/blending-weights"}
                               : std::vector<std::string_view>{kDispatchNames.weights},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // S2x holds both samples' runs and the two separated sample textures at once.
      .bytesPerPixel = variant == Variant::S2x ? 2 * kBytesPerPixel + 2 * sizeof(glm::vec4) : kBytesPerPixel,
      // Edges (R, G) and weights (R, G, B, A), per sample run for S2x.
      .layerBytesPerPixel = (variant == Variant::S2x ? 2u : 1u) * (2u + 4u),  // RG8 and RGBA8 codes
      .temporal = false,
      .eqaaSamples = variant == Variant::S2x ? 2 : 0,
      .variantOf = variant == Variant::Luma ? "" : "smaa",
  };
}

}  // namespace

std::vector<SettingInfo> SearchSettings(std::string_view thresholdDoc) {
  // Defaults and ranges: SMAA.hlsl's configuration macros (aa-facts §1.2).
  return {
      {.name = "threshold", .defaultValue = 0.1, .min = 0.0, .max = 0.5, .minExclusive = true, .doc = thresholdDoc},
      {.name = "max_search_steps", .defaultValue = 16, .min = 0, .max = 98, .integer = true,
       .doc = "SMAA_MAX_SEARCH_STEPS: orthogonal search steps per side, 2 px each"},
      {.name = "max_search_steps_diag", .defaultValue = 8, .min = 0, .max = 20, .integer = true,
       .doc = "SMAA_MAX_SEARCH_STEPS_DIAG: diagonal search steps per side, 1 px each; 0 disables diagonals"},
      {.name = "corner_rounding", .defaultValue = 25, .min = 0, .max = 100,
       .doc = "SMAA_CORNER_ROUNDING in percent; 100 disables corner detection"},
  };
}

// SMAA_PRESET_LOW .. _ULTRA (aa-facts §1.2): LOW and MEDIUM disable diagonals and corners.
std::vector<Preset> SearchPresets() {
  return {
      {"low", {{"threshold", 0.15}, {"max_search_steps", 4}, {"max_search_steps_diag", 0}, {"corner_rounding", 100}}},
      {"medium",
       {{"threshold", 0.1}, {"max_search_steps", 8}, {"max_search_steps_diag", 0}, {"corner_rounding", 100}}},
      {"high", {{"threshold", 0.1}, {"max_search_steps", 16}, {"max_search_steps_diag", 8}, {"corner_rounding", 25}}},
      {"ultra",
       {{"threshold", 0.05}, {"max_search_steps", 32}, {"max_search_steps_diag", 16}, {"corner_rounding", 25}}},
  };
}

template <Variant V>
const PassInfo& Info() {
  static const PassInfo info = MakeInfo(V);
  return info;
}

template <Variant V>
std::unique_ptr<Pass> Make(const PassSettings& settings) {
  if constexpr (V == Variant::S2x) return MakeS2x(Info<V>(), ConfigOf(V, settings));
  return std::make_unique<SmaaPass>(Info<V>(), ConfigOf(V, settings));
}

template const PassInfo& Info<Variant::Luma>();
template const PassInfo& Info<Variant::Colour>();
template const PassInfo& Info<Variant::Depth>();
template const PassInfo& Info<Variant::LumaPredicated>();
template const PassInfo& Info<Variant::S2x>();
template std::unique_ptr<Pass> Make<Variant::Luma>(const PassSettings&);
template std::unique_ptr<Pass> Make<Variant::Colour>(const PassSettings&);
template std::unique_ptr<Pass> Make<Variant::Depth>(const PassSettings&);
template std::unique_ptr<Pass> Make<Variant::LumaPredicated>(const PassSettings&);
template std::unique_ptr<Pass> Make<Variant::S2x>(const PassSettings&);

}  // namespace passes::smaa
