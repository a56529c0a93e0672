#pragma once
// Scene -> raster input: every mesh transformed to D3D clip space with the scene's camera and
// concatenated into one triangle list, so primitive ids are triangle indices in mesh order.
// Shared by `aasim raster` and the raster benchmark; `aasim frame` adds the per-vertex normals,
// per-triangle object ids and per-object colours the frame pipeline shades with.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "raster/rasterizer.h"
#include "scenes/scene.h"

// Declared only (sim/frame.h defines it), so raster-only users skip the machine's headers.
namespace sim {
struct FrameGeometry;
}  // namespace sim

namespace cli {

struct ClipSpaceScene {
  std::vector<glm::vec4> positions;
  std::vector<std::uint32_t> indices;

  std::size_t TriangleCount() const { return indices.size() / 3; }
  // A view for raster::Rasterize; valid while this object lives.
  raster::DrawInput DrawInput() const { return {positions, indices, 0}; }
};

ClipSpaceScene ToClipSpace(const scenes::Scene& scene, float aspect);

// Scenes carry no materials yet, so object k (mesh k) gets kMeshPalette[k % size]: linear
// colours far enough apart that neighbouring meshes, and their AA edges, stand out.
inline constexpr std::array<glm::vec3, 8> kMeshPalette{{
    {0.80f, 0.80f, 0.80f},  // light grey
    {0.80f, 0.25f, 0.20f},  // red
    {0.25f, 0.60f, 0.25f},  // green
    {0.20f, 0.35f, 0.80f},  // blue
    {0.85f, 0.65f, 0.20f},  // amber
    {0.55f, 0.30f, 0.70f},  // purple
    {0.20f, 0.65f, 0.70f},  // teal
    {0.75f, 0.45f, 0.55f},  // pink
}};

// Everything sim::FramePipeline::Render reads, in ToClipSpace's vertex and triangle order.
struct FrameScene {
  ClipSpaceScene clip;
  std::vector<glm::vec3> normals;        // world space, per vertex
  std::vector<std::uint32_t> objectIds;  // per triangle: the index of its mesh
  std::vector<glm::vec3> baseColours;    // per mesh, from kMeshPalette

  // A still frame: no previous positions, so every velocity is zero. Valid while this lives.
  sim::FrameGeometry Geometry() const;
};

// Mesh normals where the mesh has them, else SmoothNormals of its positions.
FrameScene ToFrameScene(const scenes::Scene& scene, float aspect);

// Area-weighted vertex normals: each triangle adds its unnormalised face normal (counter-
// clockwise = front, as glTF) to its three corners. A vertex whose sum is zero (unused, only in
// degenerate triangles, or between exactly opposite faces) gets +z so the kernel never
// normalises a zero vector.
std::vector<glm::vec3> SmoothNormals(std::span<const glm::vec3> positions,
                                     std::span<const std::uint32_t> indices);

}  // namespace cli
