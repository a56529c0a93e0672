// Filmic SMAA's morphological part on the pass framework (see filmic_smaa.h).

#include "passes/filmic_smaa/filmic_smaa.h"

#include "passes/filmic_smaa/morphological.h"
#include "passes/smaa/smaa.h"
#include "sim/formats.h"

namespace passes::filmic_smaa {
namespace {

constexpr std::string_view kVerticalDispatch = "filmic-smaa/vertical-edges";
constexpr std::string_view kHorizontalDispatch = "filmic-smaa/horizontal-edges";

class FilmicSmaaPass final : public Pass {
 public:
  explicit FilmicSmaaPass(const smaa::Config& config) : morphological_(filmic_smaa::Info().name, config) {}

  const PassInfo& Info() const override { return filmic_smaa::Info(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.Width(), height = frame.Height();
    const sim::Texture2D<glm::vec4>& colour = frame.ColourSrgb8();
    // The output target starts as the frame (a copy, as CopyResource would make).
    sim::Texture2D<glm::vec4> blended("filmic-smaa/output", width, height, sim::Format::RGBA8Srgb);
    CopySrgb8Frame(frame, blended);
    sim::Texture2D<glm::vec2> edges("filmic-smaa/edges", width, height, sim::Format::RG8Unorm);
    PassOutput output;
    output.SetWorkSet(morphological_.Run(machine, strategy, colour, blended, edges));
    output.colour = DecodedSrgb8("filmic-smaa/output", blended);
    output.layers.push_back(LayerOf("edges", edges, {"R", "G"}));
    output.layers.push_back(MembershipLayer("items", morphological_.Membership(strategy), width, height));
    return output;
  }

 private:
  Morphological morphological_;
};

}  // namespace

const PassInfo& Info() {
  static const PassInfo info{
      .name = "filmic-smaa",
      .description = "Filmic SMAA's morphological part: pattern-score edge suppression, LDS luma tile, dual edge "
                     "blending (vertical then horizontal items, scattered writes)",
      .source = "passes/filmic_smaa/filmic_smaa.h",
      // SMAA.hlsl's configuration macros and presets (aa-facts §1.2); local contrast adaptation is
      // replaced by the pattern scores.
      .settings = smaa::SearchSettings("SMAA_THRESHOLD: edge contrast in gamma space; patterns through an edge "
                                       "must score 2x it"),
      .presets = smaa::SearchPresets(),
      .inputs = {FrameInput::Colour},
      .studiedDispatches = {kVerticalDispatch, kHorizontalDispatch},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // The colour copy, the output target and its decoded copy (vec4 each), edges and their layer,
      // the items layer, membership and shape bytes, the stencil byte and two full-size queues.
      .bytesPerPixel = 3 * sizeof(glm::vec4) + sizeof(glm::vec2) + 3 * sizeof(float) + 3 + 2 * sizeof(std::uint32_t),
      .layerBytesPerPixel = 2 + sizeof(float),  // edges (RG8 codes), items
      .temporal = false,
      .variantOf = "smaa",
  };
  return info;
}

std::unique_ptr<Pass> Make(const PassSettings& settings) { return std::make_unique<FilmicSmaaPass>(ConfigOf(settings)); }

}  // namespace passes::filmic_smaa
