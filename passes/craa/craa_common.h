#pragma once
// What the CRAA resolves share: which surfaces they read, the checks of their inputs, and the
// neighbourhood fetch (seed 001: the UNKNOWN samples take the colour of the up, bottom, left or
// right neighbour's stored fragment).

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <glm/vec4.hpp>

#include "passes/craa/craa_simple.h"
#include "passes/resolve.h"
#include "sim/eqaa_resolve.h"

namespace passes::craa {

// The FMASK bits of S samples of a 1F surface (one bit each, hw-facts §1.1).
constexpr std::uint32_t SampleBits(int samples) {
  return samples >= 32 ? 0xFFFFFFFFu : (1u << samples) - 1u;
}

// Seed 001 "CRAA Setup": colour and depth 1F xS; 1S has no FMASK to reconstruct from.
inline bool ReadsCraaModes(const fmask::EqaaConfig& mode) { return mode.fragments == 1 && mode.coverageSamples > 1; }

inline const raster::SamplePattern& RequirePattern(const ResolveInfo& info, const ResolveContext& context) {
  if (context.pattern == nullptr) {
    throw std::invalid_argument(std::string(info.name) + " needs the frame's sample pattern");
  }
  return *context.pattern;
}

inline void CheckSurface(const ResolveInfo& info, const fmask::EqaaSurface& surface,
                         const raster::SamplePattern& pattern) {
  if (!info.reads(surface.Config())) {
    throw std::invalid_argument(std::string(info.name) + " reads " + std::string(info.surfaces) + ", not " +
                                fmask::EqaaName(surface.Config()));
  }
  if (pattern.Count() != surface.Config().coverageSamples) {
    throw std::invalid_argument(std::string(info.name) + ": pattern " + pattern.Name() + " has " +
                                std::to_string(pattern.Count()) + " samples, the surface " +
                                std::to_string(surface.Config().coverageSamples));
  }
}

// One full-screen dispatch `name` resolving `surface` into a new linear RGBA texture.
// `bindPixel(dispatch, eqaa)` binds whatever else the kernel reads and returns the per-lane
// function (const sim::PixelLane&) -> glm::vec4.
template <typename BindPixel>
sim::Texture2D<glm::vec4> RunResolveDispatch(sim::Machine& machine, const fmask::EqaaSurface& surface,
                                             const std::string& name, const sim::KernelInfo& kernel,
                                             BindPixel&& bindPixel) {
  sim::Texture2D<glm::vec4> colour(name, surface.Width(), surface.Height(), 4);
  const sim::EqaaResources resources(surface);
  sim::Dispatch dispatch(name, kernel);
  const sim::EqaaView eqaa = dispatch.Read(resources);
  const auto pixel = bindPixel(dispatch, eqaa);
  const sim::RwTextureView<glm::vec4> out = dispatch.ReadWrite(colour);
  machine.FullScreen(dispatch, {.width = surface.Width(), .height = surface.Height()},
                     [&](sim::PixelLane& lane) { out.Store(lane, lane.x, lane.y, pixel(lane)); });
  return colour;
}

// The stored fragment of the neighbour on `side`; clamp addressing at the screen's border.
template <typename Lane>
glm::vec4 Neighbour(const sim::EqaaView& eqaa, const Lane& lane, Side side) {
  int x = lane.x, y = lane.y;
  switch (side) {
    case Side::Up: --y; break;
    case Side::Bottom: ++y; break;
    case Side::Left: --x; break;
    case Side::Right: ++x; break;
    default: break;
  }
  x = std::clamp(x, 0, eqaa.Surface().Width() - 1);
  y = std::clamp(y, 0, eqaa.Surface().Height() - 1);
  return sim::ToVec4(eqaa.Fragment(lane, x, y, 0));
}

template <typename Lane>
glm::vec4 NeighbourMean(const sim::EqaaView& eqaa, const Lane& lane) {
  return (Neighbour(eqaa, lane, Side::Up) + Neighbour(eqaa, lane, Side::Bottom) +
          Neighbour(eqaa, lane, Side::Left) + Neighbour(eqaa, lane, Side::Right)) *
         0.25f;
}

}  // namespace passes::craa
