#pragma once
// Scene -> raster input: every mesh transformed to D3D clip space with the scene's camera and
// concatenated into one triangle list, so primitive ids are triangle indices in mesh order.
// Shared by `aasim raster` and the raster benchmark.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "raster/rasterizer.h"
#include "scenes/scene.h"

namespace cli {

struct ClipSpaceScene {
  std::vector<glm::vec4> positions;
  std::vector<std::uint32_t> indices;

  std::size_t TriangleCount() const { return indices.size() / 3; }
  // A view for raster::Rasterize; valid while this object lives.
  raster::DrawInput DrawInput() const { return {positions, indices, 0}; }
};

ClipSpaceScene ToClipSpace(const scenes::Scene& scene, float aspect);

}  // namespace cli
