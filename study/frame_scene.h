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
#include "sim/resources.h"

// Declared only (sim/frame.h defines them), so raster-only users skip the machine's headers.
namespace sim {
struct FrameGeometry;
struct FrameSettings;
}  // namespace sim

namespace study {

struct ClipSpaceScene {
  std::vector<glm::vec4> positions;
  std::vector<std::uint32_t> indices;

  std::size_t TriangleCount() const { return indices.size() / 3; }
  // A view for raster::Rasterize; valid while this object lives.
  raster::DrawInput DrawInput() const { return {positions, indices, 0}; }
};

ClipSpaceScene ToClipSpace(const scenes::Scene& scene, float aspect);

// Everything sim::FramePipeline::Render reads, in ToClipSpace's vertex and triangle order.
// Textured meshes carry the material's factor in baseColours and the texture as a machine
// resource, so the material kernel shades what scenes::BaseColour (and the ground truth) does.
struct FrameScene {
  ClipSpaceScene clip;
  std::vector<glm::vec3> normals;        // world space, per vertex
  std::vector<std::uint32_t> objectIds;  // per triangle: the index of its mesh
  std::vector<glm::vec3> baseColours;    // per mesh: the factor (palette colour without material)
  std::vector<glm::vec2> texcoords;      // per vertex; empty when no mesh is textured
  std::vector<int> baseColourTextures;   // per mesh: index into textures, or -1
  std::vector<sim::Texture2D<glm::vec4>> textures;  // the scene's textures, linear RGBA

  // A still frame: no previous positions, so every velocity is zero. Valid while this lives.
  sim::FrameGeometry Geometry() const;
  // A frame of a sequence: `previousClip` holds the same vertices' clip positions one frame
  // earlier (ToClipSpace of the previous frame's scene), so the pipeline writes velocities.
  sim::FrameGeometry Geometry(std::span<const glm::vec4> previousClip) const;
};

// The scene's light and ambient term, so the material kernel shades what the ground truth does.
void ApplyLighting(const scenes::Lighting& lighting, sim::FrameSettings& settings);

// Normals from scenes::VertexNormals: the mesh's own, else smooth ones from its triangles.
FrameScene ToFrameScene(const scenes::Scene& scene, float aspect);
// The same scene at another frame of its motion (scenes::SceneAt: same meshes, moved, another
// camera): replaces the clip positions and normals, keeps ids, colours and textures.
void MoveFrameScene(const scenes::Scene& moved, float aspect, FrameScene& frame);

}  // namespace study
