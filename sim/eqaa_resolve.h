#pragma once
// The resolves of an EQAA surface every renderer has, as pixel-shader kernels on the machine, so
// what they read of FMASK and colour fragments is counted where it is read (issue 14):
//   box    the colour block's resolve (hw-facts §1.6): the mean of the known samples' fragment
//          colours, UNKNOWN samples dropped; no known sample -> transparent black. It reads the
//          FMASK element once and each fragment the element names once.
//   fetch  the shader resolve through the texture unit's fetch path (hw-facts §1.4): the mean of
//          every sample's fetch, an UNKNOWN sample reading fragment 0. One FMASK read and one
//          fragment fetch per sample, as a resolve shader looping over samples issues them.
// The frame pipeline runs `box` to produce its colour; passes/resolves registers both for the
// EQAA study. Both agree bit for bit with the host definitions fmask::EqaaSurface::BoxResolve and
// FetchSample (tests/sim_eqaa_resolve_test.cpp).

#include <string>

#include <glm/vec4.hpp>

#include "sim/dispatch.h"
#include "sim/eqaa_resources.h"

namespace sim {

// Hand counts of the kernels below, for the timing model: per sample an FMASK code extract
// (shift, mask, compare: 3) and an accumulate of 4 channels (4).
inline constexpr KernelInfo kBoxResolveKernel{
    .vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 80,
    .source = "hand count of the box resolve at 8 samples: FMASK code extract (3) and a 4-channel accumulate "
              "(4) per sample (56), fragment-mask build (8), the reciprocal and scale (6), export (10)"};
inline constexpr KernelInfo kFetchResolveKernel{
    .vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 90,
    .source = "hand count of a fetch-path resolve at 8 samples: the shader-visible code per sample (4), a "
              "fetch address (3) and a 4-channel accumulate (4) (88 at 8 samples), the scale and export"};

inline glm::vec4 ToVec4(const fmask::Colour& c) { return {c.r, c.g, c.b, c.a}; }

// The box resolve of pixel (x, y): each fragment the FMASK names is fetched once, then summed per
// sample in sample order (the host's order, so the result is bit-identical to BoxResolve).
template <typename Lane>
glm::vec4 BoxResolvePixel(const EqaaView& eqaa, const Lane& lane, int x, int y) {
  const fmask::EqaaSurface& surface = eqaa.Surface();
  const fmask::FmaskLayout& layout = surface.Layout();
  const fmask::FmaskElement element = eqaa.Fmask(lane, x, y);
  const int samples = surface.Config().coverageSamples;
  std::array<glm::vec4, 8> fragments{};
  std::uint32_t fetched = 0;
  glm::vec4 sum(0.0f);
  int known = 0;
  for (int s = 0; s < samples; ++s) {
    const int code = layout.Code(element, s);
    if (layout.IsEqaa() && code == layout.UnknownCode()) continue;
    if ((fetched >> code & 1u) == 0) {
      fragments[static_cast<std::size_t>(code)] = ToVec4(eqaa.Fragment(lane, x, y, code));
      fetched |= 1u << code;
    }
    sum += fragments[static_cast<std::size_t>(code)];
    ++known;
  }
  if (known == 0) return glm::vec4(0.0f);
  return sum * (1.0f / static_cast<float>(known));
}

template <typename Lane>
glm::vec4 FetchResolvePixel(const EqaaView& eqaa, const Lane& lane, int x, int y) {
  const fmask::EqaaSurface& surface = eqaa.Surface();
  const std::uint64_t visible = fmask::ShaderVisibleMask(surface.Layout(), eqaa.Fmask(lane, x, y));
  const int samples = surface.Config().coverageSamples;
  glm::vec4 sum(0.0f);
  for (int s = 0; s < samples; ++s) sum += ToVec4(eqaa.Fragment(lane, x, y, fmask::FetchFragmentIndex(visible, s)));
  return sum / static_cast<float>(samples);
}

// One full-screen pixel-shader dispatch named `name` writing every pixel's box (or fetch) resolve
// of `surface` into `target` (the surface's size). Returns the dispatch's report.
DispatchReport RunBoxResolve(Machine& machine, const fmask::EqaaSurface& surface, Texture2D<glm::vec4>& target,
                             std::string name);
DispatchReport RunFetchResolve(Machine& machine, const fmask::EqaaSurface& surface, Texture2D<glm::vec4>& target,
                               std::string name);

}  // namespace sim
