#pragma once
// The frame pipeline: geometry -> draw -> the material pixel kernel (Lambert + base colour) ->
// EQAA surface, plus pixel-rate targets for the post passes (depth, normal, object id,
// velocity), then the box resolve (the dispatch "frame/resolve", sim/eqaa_resolve.h) into a
// single-sample colour texture. Post passes (passes/) take the targets from here; every dispatch
// lands in the Machine's report list.
//
// Pixel-rate targets keep the fragment that last passed coverage sample 0 of the pixel, the
// sample an MSAA G-buffer read at sample 0 returns, so they are defined for every S.
//
// Seed 001's CRAA setup notes (draw order, a depth pre-pass then an EQUAL test, compressed depth)
// are FrameSettings; docs/eqaa.md "CRAA setup" says what each does to the EQAA surface.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fmask/eqaa_surface.h"
#include "raster/depth_stencil.h"
#include "raster/sample_pattern.h"
#include "sim/dispatch.h"
#include "sim/draw_order.h"

namespace sim {

// Everything in the draw's vertex order; primitive id = triangle index into `indices`.
struct FrameGeometry {
  std::span<const glm::vec4> clipPositions;
  std::span<const glm::vec4> previousClipPositions;  // same size, or empty for a still frame
  std::span<const glm::vec3> normals;                // world space per vertex, or empty (face normals)
  std::span<const std::uint32_t> indices;
  std::span<const std::uint32_t> objectIds;          // per triangle
  std::span<const glm::vec3> baseColours;            // linear base colour factor, per object id
  // Optional base colour textures (scenes/shading.h: factor times a bilinear, repeat-wrapped
  // sample at TEXCOORD_0): per object an index into `textures` or -1; empty = untextured.
  std::span<const glm::vec2> texcoords{};            // per vertex; required if any object is textured
  std::span<const int> baseColourTextures{};         // per object id, or empty
  std::span<const Texture2D<glm::vec4>> textures{};  // linear RGBA
};

struct FrameSettings {
  int width = 1920;
  int height = 1080;
  fmask::EqaaConfig eqaa{8, 4, 2};
  raster::SamplePattern pattern = raster::MakeBuiltinPattern("eqaa", 8);
  fmask::ArbitrationPolicy policy = fmask::PolicyByName("hraa");
  // Z planes per 8x8 depth tile (hw-facts §5.2 default 4); 0 turns depth compression off: a tile
  // is decompressed at its first write, and from then on its unanchored samples are tested
  // against their nearest anchor (the seed's "Compressed Depth Buffer" off). (The colour block's side of the Z-plane rescue
  // is the policy's zPlaneRescue, policy `no-zplane-rescue`.)
  int maxZPlanes = 4;
  // Triangles are drawn in this order; primitive ids are positions in the drawn order.
  DrawOrder drawOrder = DrawOrder::Submission;
  // A depth-only draw of the same triangles (dispatch "frame/depth-prepass": depth test LESS and
  // writes on, no pixel shader, no colour block) before the material draw, which then tests
  // EQUAL with depth writes off, so only the visible surface reaches the colour block.
  bool depthPrepass = false;
  // One-sample surfaces only: the material kernel interpolates every attribute at the sample's
  // position instead of the centroid (which is the pixel centre for a covered 1S pixel), as a
  // jittered projection matrix or HLSL's `sample` modifier does (seed 001 "Temporal FLIPQUAD: In
  // Practice": "UVs need to be interpolated at SAMPLE positions"). Jitter schedules turn it on so
  // that textures, not only edges, are sampled at the jittered positions.
  bool sampleRateShading = false;
  WaveFlush flush = WaveFlush::MixPrimitives;
  raster::CullMode cull = raster::CullMode::Back;
  glm::vec3 towardsLight{0.4f, 0.8f, 0.45f};  // world space; normalised on use
  float ambient = 0.15f;
  fmask::Colour clearColour{0.05f, 0.05f, 0.08f, 1.0f};
};

// The material kernel (scenes/shading.h's model): base colour factor times an optional
// bilinear, repeat-wrapped texture sample at the centroid, Lambert plus ambient.
// Its declared resources and instruction estimate (an estimate for the timing
// model, not a compiled shader): interpolation, normalise, one N.L and the G-buffer exports.
inline constexpr KernelInfo kMaterialKernel{
    .vgprs = 24, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 64,
    .source = "hand count of sim/frame.cpp's material kernel: 3 barycentric interpolations of normal, colour "
              "and texcoord (~18), normalise (~8), N.L and the Lambert mix (~10), a bilinear sample's "
              "address and weights (~16), exports (~12)"};

// The depth-only draw of the pre-pass: no pixel shader runs, so it declares no VALU work; the
// registers are the smallest legal declaration (occupancy is reported but no wave launches).
inline constexpr KernelInfo kDepthPrepassKernel{
    .vgprs = 1, .sgprs = 0, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 0,
    .source = "no pixel shader: a depth-only draw launches no pixel waves (vertex work is not modelled for any draw)"};

// Triangle t of the drawn order is triangle order[t] of the geometry. Submission is the
// identity; the front-to-back orders sort by nearest depth (the smallest z/w of the triangle's
// vertices, 0 for a vertex at or behind the eye, where clipping puts the triangle on the near
// plane), ties keeping submission order (a stable sort: the same input gives the same order).
// ObjectsFrontToBack keys every triangle by the nearest depth of its object.
std::vector<std::uint32_t> DrawOrderPermutation(const FrameGeometry& geometry, DrawOrder order);

// What may change from one frame to the next without reallocating the pipeline's surfaces: the
// sample pattern (a jitter or pattern schedule: halton:K offsets, alternating T2x patterns) and
// the frame's index in its sequence.
struct FrameParams {
  const raster::SamplePattern* pattern = nullptr;  // nullptr keeps the current one; S must not change
  int frameIndex = 0;
};

class FramePipeline {
 public:
  // Throws std::invalid_argument for an impossible EQAA mode, a pattern whose sample count is
  // not S, or a size outside 1..kMaxDimension.
  FramePipeline(Machine& machine, FrameSettings settings);

  // Clears the surfaces, draws the geometry with the material kernel and resolves colour.
  // Returns the draw's report. Throws std::invalid_argument naming the bad input (geometry, or a
  // pattern whose sample count is not the surface's S); the surfaces are reused across frames.
  DispatchReport Render(const FrameGeometry& geometry, const FrameParams& params = {});

  const FrameSettings& Settings() const { return settings_; }
  // Dispatches Render issues before the material draw (the depth pre-pass, when on), so a caller
  // that records the machine's reports can find the draw among them.
  std::size_t DispatchesBeforeDraw() const { return settings_.depthPrepass ? 1 : 0; }
  int FrameIndex() const { return frameIndex_; }
  fmask::EqaaSurface& Eqaa() { return eqaa_; }
  const fmask::EqaaSurface& Eqaa() const { return eqaa_; }
  raster::DepthStencilSurface& DepthSurface() { return depth_; }
  // Box-resolved colour (hw-facts §1.6), linear RGBA, modelled as RGBA8.
  const Texture2D<glm::vec4>& Colour() const { return colour_; }
  // The same frame as the renderer's RGBA8 sRGB render target holds it (StoreSrgb8 after the
  // resolve): the input of every pass with an 8-bit colour target, stored once per frame.
  const Texture2D<glm::vec4>& ColourSrgb8() const { return colourSrgb8_; }
  const Texture2D<float>& Depth() const { return depthTarget_; }
  const Texture2D<glm::vec4>& Normal() const { return normal_; }  // xyz world normal, w = 1 if written
  const Texture2D<std::uint32_t>& ObjectId() const { return objectId_; }
  const Texture2D<glm::vec2>& Velocity() const { return velocity_; }  // pixels, current - previous
  const fmask::FragmentCounters& Fragments() const { return fragments_; }

 private:
  void Validate(const FrameGeometry& geometry) const;
  void ValidateTextures(const FrameGeometry& geometry) const;
  void ClearTargets();
  // The geometry in the settings' draw order (the caller's own for Submission).
  FrameGeometry Ordered(const FrameGeometry& geometry);
  void DepthPrepass(const FrameGeometry& geometry);
  void Resolve();

  Machine& machine_;
  FrameSettings settings_;
  raster::DepthStencilSurface depth_;
  fmask::EqaaSurface eqaa_;
  Texture2D<glm::vec4> colour_;
  Texture2D<glm::vec4> colourSrgb8_;
  Texture2D<float> depthTarget_;
  Texture2D<glm::vec4> normal_;
  Texture2D<std::uint32_t> objectId_;
  Texture2D<glm::vec2> velocity_;
  fmask::FragmentCounters fragments_;
  std::vector<std::uint32_t> orderedIndices_;    // Ordered's copies, reused across frames
  std::vector<std::uint32_t> orderedObjectIds_;
  int frameIndex_ = 0;
};

inline constexpr std::uint32_t kNoObject = 0xFFFFFFFFu;

}  // namespace sim
