// Scene -> clip-space triangle list and frame-pipeline inputs (see frame_input.h).

#include "cli/frame_input.h"

#include <string>

#include <glm/mat4x4.hpp>

#include "scenes/normals.h"
#include "scenes/shading.h"
#include "sim/frame.h"

namespace cli {

ClipSpaceScene ToClipSpace(const scenes::Scene& scene, float aspect) {
  const glm::mat4 viewProjection = scene.camera.Projection(aspect) * scene.camera.View();
  ClipSpaceScene clip;
  clip.positions.reserve(scene.VertexCount());
  clip.indices.reserve(scene.TriangleCount() * 3);
  for (const scenes::Mesh& mesh : scene.meshes) {
    const auto baseVertex = static_cast<std::uint32_t>(clip.positions.size());
    for (const glm::vec3& position : mesh.positions) {
      clip.positions.push_back(viewProjection * glm::vec4(position, 1.0f));
    }
    for (const std::uint32_t index : mesh.indices) {
      // Checked here because after concatenation a bad index would silently name a vertex of
      // another mesh instead of failing raster's range check.
      if (index >= mesh.positions.size()) {
        throw scenes::SceneError(scene.name + ": mesh '" + mesh.name + "': index " +
                                 std::to_string(index) + " out of range (" +
                                 std::to_string(mesh.positions.size()) + " vertices)");
      }
      clip.indices.push_back(baseVertex + index);
    }
  }
  return clip;
}

FrameScene ToFrameScene(const scenes::Scene& scene, float aspect) {
  FrameScene frame;
  frame.clip = ToClipSpace(scene, aspect);
  frame.normals.reserve(scene.VertexCount());
  frame.objectIds.reserve(scene.TriangleCount());
  for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
    const scenes::Mesh& source = scene.meshes[mesh];
    const std::vector<glm::vec3> normals = scenes::VertexNormals(source);
    frame.normals.insert(frame.normals.end(), normals.begin(), normals.end());
    frame.objectIds.insert(frame.objectIds.end(), source.indices.size() / 3,
                           static_cast<std::uint32_t>(mesh));
    frame.baseColours.push_back(glm::vec3(scenes::BaseColour(scene, mesh, glm::vec2(0.0f))));
  }
  return frame;
}

sim::FrameGeometry FrameScene::Geometry() const {
  return {.clipPositions = clip.positions,
          .previousClipPositions = {},
          .normals = normals,
          .indices = clip.indices,
          .objectIds = objectIds,
          .baseColours = baseColours};
}

}  // namespace cli
