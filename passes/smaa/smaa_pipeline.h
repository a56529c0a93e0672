#pragma once
// SMAA 1x's three passes on one 8-bit sRGB colour texture (smaa.h's diagram), shared by SMAA 1x
// and S2x (which runs it once per MSAA sample).

#include <optional>
#include <string>

#include "passes/pass.h"
#include "passes/smaa/smaa_kernels.h"
#include "passes/smaa/smaa_targets.h"
#include "passes/work_set.h"

namespace passes::smaa {

struct DispatchNames {
  std::string edges, weights, blending;
};

// How neighbourhood blending writes its target: replace, or the S2x demo's second run blended
// onto the first with factor 0.5 (aa-facts §1.8) by the output merger, in linear space as an
// sRGB target blends.
enum class Blend : std::uint8_t { Replace, HalfOver };

class Smaa1x {
 public:
  Smaa1x(std::string_view pass, const Config& config, DispatchNames names);

  struct Frame {
    const Intermediates& targets;  // kept by this object until its next Run
    WorkSetShape workSet;
  };
  // colour: RGBA8 sRGB; depth: the depth edges' or predication's buffer (may be null when the
  // configuration reads neither); target: RGBA8 sRGB, written by neighbourhood blending.
  // velocity (T2x/4x with SMAA_REPROJECTION, else null): RG16F in UV units, motion-blur
  // convention (current - previous, v down); neighbourhood blending packs its length in alpha.
  Frame Run(sim::Machine& machine, Strategy strategy, const sim::Texture2D<glm::vec4>& colour,
            const sim::Texture2D<float>* depth, sim::Texture2D<glm::vec4>& target, Blend blend,
            const sim::Texture2D<glm::vec2>* velocity = nullptr);
  // T2x and 4x change the AreaTex subsample indices every frame (aa-facts §1.8).
  void SetSubsampleIndices(glm::vec4 indices) { config_.subsampleIndices = indices; }

 private:
  WorkSetShape EdgesAndWeights(sim::Machine& machine, Strategy strategy, const sim::Texture2D<glm::vec4>& colour,
                               const sim::Texture2D<float>* depth, Intermediates& targets);
  void NeighbourhoodBlend(sim::Machine& machine, const sim::Texture2D<glm::vec4>& colour,
                          const Intermediates& targets, sim::Texture2D<glm::vec4>& target, Blend blend,
                          const sim::Texture2D<glm::vec2>* velocity);

  Config config_;
  DispatchNames names_;
  LookupTables tables_;
  WorkSet workSet_;
  std::optional<Intermediates> targets_;  // kept across frames, cleared every frame
};

}  // namespace passes::smaa
