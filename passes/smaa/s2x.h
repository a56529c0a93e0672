#pragma once
// SMAA S2x's per-frame work (smaa.h's diagram), shared by the S2x pass and SMAA 4x (S2x every
// frame with per-frame subsample indices, aa-facts §1.8): the separate pass, then SMAA 1x on each
// sample, the second blended onto the first with factor 0.5.

#include <array>
#include <string>
#include <vector>

#include "passes/pass.h"
#include "passes/smaa/smaa_pipeline.h"

namespace passes::smaa {

class S2xRuns {
 public:
  // Dispatches <pass>/separate and <pass>/s<k>/{edge-detection, blending-weights,
  // neighbourhood-blending}.
  S2xRuns(std::string_view pass, const Config& config);

  struct Frame {
    WorkSetShape workSet;            // both samples' work sets, summed
    std::vector<PassLayer> layers;   // edges.s<k>, weights.s<k>
  };
  // indices: each sample run's subsample indices; target: RGBA8 sRGB; velocity as Smaa1x::Run.
  Frame Run(sim::Machine& machine, Strategy strategy, const fmask::EqaaSurface& surface,
            const std::array<glm::vec4, 2>& indices, sim::Texture2D<glm::vec4>& target,
            const sim::Texture2D<glm::vec2>* velocity = nullptr);

 private:
  void Separate(sim::Machine& machine, const fmask::EqaaSurface& surface,
                std::array<sim::Texture2D<glm::vec4>, 2>& separated) const;

  std::string pass_;
  std::array<Smaa1x, 2> samples_;
};

}  // namespace passes::smaa
