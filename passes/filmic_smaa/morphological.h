#pragma once
// Filmic SMAA's morphological part (filmic_smaa.h's diagram) as a reusable stage: the Filmic SMAA
// 1x pass runs it once per frame, Filmic SMAA T2x once per frame with the frame's subsample
// indices (aa-facts §1.8) before its temporal stages.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "passes/pass.h"
#include "passes/smaa/smaa_kernels.h"
#include "passes/smaa/smaa_targets.h"
#include "passes/work_set.h"

namespace passes::filmic_smaa {

// SMAA's threshold and search settings (smaa::SearchSettings) as the kernels' configuration.
smaa::Config ConfigOf(const PassSettings& settings);

class Morphological {
 public:
  // Dispatches <pass>/edge-detection, <pass>/queue-args, <pass>/vertical-edges and
  // <pass>/horizontal-edges.
  Morphological(std::string_view pass, const smaa::Config& config);
  Morphological(const Morphological&) = delete;
  Morphological& operator=(const Morphological&) = delete;

  void SetSubsampleIndices(glm::vec4 indices) { config_.subsampleIndices = indices; }
  // colour: the frame's RGBA8 sRGB target; blended: RGBA8 sRGB, holding a copy of colour on entry,
  // blended in place; edges: RG8, cleared to 0 on entry. Returns the work set's shape.
  WorkSetShape Run(sim::Machine& machine, Strategy strategy, const sim::Texture2D<glm::vec4>& colour,
                   sim::Texture2D<glm::vec4>& blended, sim::Texture2D<glm::vec2>& edges);
  // After Run: per pixel, 1 = a vertical item, 2 = a horizontal item, 0 = none.
  std::vector<std::uint8_t> Membership(Strategy strategy) const { return workSet_.Membership(strategy); }
  // The dispatch names, for PassInfo::studiedDispatches.
  std::string_view VerticalDispatch() const { return vertical_; }
  std::string_view HorizontalDispatch() const { return horizontal_; }

 private:
  template <typename Form>
  auto MakeDetect(sim::Dispatch& d, Form, const sim::Texture2D<glm::vec4>& colour,
                  sim::Texture2D<glm::vec2>& edges) const;

  std::string detect_, vertical_, horizontal_;
  WorkSetKernels kernels_;
  smaa::Config config_;
  smaa::LookupTables tables_;
  WorkSet workSet_;
};

}  // namespace passes::filmic_smaa
