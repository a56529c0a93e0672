#pragma once
// SMAA's textures: the per-frame intermediates at the reference's formats (aa-facts §1.1) and
// the two lookup tables as textures of this pass instance (a texture records the cache lines
// its dispatches touch, so instances never share one).

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "sim/formats.h"
#include "sim/resources.h"

namespace passes::smaa {

struct Intermediates {
  Intermediates(int width, int height)
      : edges("smaa/edges", width, height, sim::Format::RG8Unorm),
        weights("smaa/weights", width, height, sim::Format::RGBA8Unorm) {}
  // Cleared every frame: the edge pass writes only edge pixels and the weight pass only reads them.
  sim::Texture2D<glm::vec2> edges;
  sim::Texture2D<glm::vec4> weights;
};

struct LookupTables {
  static LookupTables Make();
  sim::Texture2D<glm::vec2> area;  // RG8 160x560
  sim::Texture2D<float> search;    // R8 64x16
};

// Host bytes per pixel one frame holds: the sRGB colour copy and the output (RGBA8 as vec4
// floats), the decoded output, edges and weights, their two layer copies, the stencil byte and a
// queue entry.
inline constexpr std::uint64_t kBytesPerPixel =
    3 * sizeof(glm::vec4) + sizeof(glm::vec2) + sizeof(glm::vec4) + 6 * sizeof(float) + 1 + sizeof(std::uint32_t);

}  // namespace passes::smaa
