// SMAA S2x (see smaa.h): SMAA 1x per MSAA sample of a 2-sample surface, the second run blended
// onto the first (aa-facts §1.8, the reference demo's S2x path).

#include <array>
#include <string>

#include "passes/smaa/s2x.h"
#include "passes/smaa/smaa.h"
#include "passes/smaa/smaa_pipeline.h"
#include "sim/eqaa_resources.h"
#include "sim/formats.h"

namespace passes::smaa {
namespace {

// SMAASeparatePS: two loads of the multisampled colour per pixel, two render-target stores.
constexpr sim::KernelInfo kSeparateKernel{
    .vgprs = 12, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 12,
    .source = "hand count of SMAASeparatePS: the integer position (2), two sample loads' addresses (4), two "
              "exports (6)"};

// aa-facts §1.8: D3D's standard 2x pattern puts sample 0 at (+0.25, +0.25) px (y down; the table's
// S0 at (+0.25, -0.25) with y up) and sample 1 at (-0.25, -0.25): their subsample indices
// (vertical ortho, horizontal ortho, diagonal 1, diagonal 2).
constexpr std::array<glm::vec4, 2> kSubsampleIndices = {glm::vec4(1, 1, 1, 0), glm::vec4(2, 2, 2, 0)};

DispatchNames NamesFor(std::string_view pass, int sample) {
  const std::string prefix = std::string(pass) + "/s" + std::to_string(sample) + "/";
  return {prefix + "edge-detection", prefix + "blending-weights", prefix + "neighbourhood-blending"};
}

class SmaaS2xPass final : public Pass {
 public:
  SmaaS2xPass(const PassInfo& info, const Config& config) : info_(info), runs_(info.name, config) {}

  const PassInfo& Info() const override { return info_; }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    sim::Texture2D<glm::vec4> target("smaa-s2x/output", frame.Width(), frame.Height(), sim::Format::RGBA8Srgb);
    S2xRuns::Frame result = runs_.Run(machine, strategy, *frame.eqaa, kSubsampleIndices, target);
    PassOutput output;
    output.SetWorkSet(result.workSet);
    output.layers = std::move(result.layers);
    output.colour = DecodedSrgb8("smaa-s2x/output", target);
    return output;
  }

 private:
  const PassInfo& info_;
  S2xRuns runs_;
};

}  // namespace

S2xRuns::S2xRuns(std::string_view pass, const Config& config)
    : pass_(pass),
      samples_{Smaa1x(pass_ + "/s0", config, NamesFor(pass, 0)),
               Smaa1x(pass_ + "/s1", config, NamesFor(pass, 1))} {}

S2xRuns::Frame S2xRuns::Run(sim::Machine& machine, Strategy strategy, const fmask::EqaaSurface& surface,
                            const std::array<glm::vec4, 2>& indices, sim::Texture2D<glm::vec4>& target,
                            const sim::Texture2D<glm::vec2>* velocity) {
  const int width = surface.Width(), height = surface.Height();
  std::array<sim::Texture2D<glm::vec4>, 2> separated{
      sim::Texture2D<glm::vec4>(pass_ + "/sample0", width, height, sim::Format::RGBA8Srgb),
      sim::Texture2D<glm::vec4>(pass_ + "/sample1", width, height, sim::Format::RGBA8Srgb)};
  Separate(machine, surface, separated);
  Frame frame;
  for (std::size_t s = 0; s < 2; ++s) {
    samples_[s].SetSubsampleIndices(indices[s]);
    const Smaa1x::Frame result = samples_[s].Run(machine, strategy, separated[s], nullptr, target,
                                                 s == 0 ? Blend::Replace : Blend::HalfOver, velocity);
    frame.workSet.pixels += result.workSet.pixels;
    frame.workSet.quads += result.workSet.quads;
    frame.workSet.tiles += result.workSet.tiles;
    const std::string suffix = ".s" + std::to_string(s);
    frame.layers.push_back(LayerOf("edges" + suffix, result.targets.edges, {"R", "G"}));
    frame.layers.push_back(LayerOf("weights" + suffix, result.targets.weights, {"R", "G", "B", "A"}));
  }
  return frame;
}

void S2xRuns::Separate(sim::Machine& machine, const fmask::EqaaSurface& surface,
                       std::array<sim::Texture2D<glm::vec4>, 2>& separated) const {
  if (surface.Config().coverageSamples != 2) {
    throw std::invalid_argument(pass_ + " needs a 2-sample EQAA surface; the frame has " +
                                std::to_string(surface.Config().coverageSamples) + " samples");
  }
  const sim::EqaaResources resources(surface);
  sim::Dispatch d(pass_ + "/separate", kSeparateKernel);
  const sim::EqaaView msaa = d.Read(resources);
  const sim::RwTextureView<glm::vec4> first = d.ReadWrite(separated[0]), second = d.ReadWrite(separated[1]);
  const auto linear = [](const fmask::Colour& c) { return glm::vec4(c.r, c.g, c.b, c.a); };
  machine.FullScreen(d, {.width = surface.Width(), .height = surface.Height()}, [&](sim::PixelLane& lane) {
    first.Store(lane, lane.x, lane.y, linear(msaa.FetchSample(lane, lane.x, lane.y, 0)));
    second.Store(lane, lane.x, lane.y, linear(msaa.FetchSample(lane, lane.x, lane.y, 1)));
  });
}

std::unique_ptr<Pass> MakeS2x(const PassInfo& info, const Config& config) {
  return std::make_unique<SmaaS2xPass>(info, config);
}

}  // namespace passes::smaa
