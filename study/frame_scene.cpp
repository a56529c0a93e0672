// Scene -> clip-space triangle list and frame-pipeline inputs (see frame_scene.h).

#include "study/frame_scene.h"

#include <algorithm>
#include <string>

#include <glm/mat4x4.hpp>

#include "scenes/normals.h"
#include "scenes/shading.h"
#include "sim/frame.h"

namespace study {

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

namespace {

// The texture scenes::BaseColour samples for this mesh, or -1: a material texture needs the
// mesh's texcoords (the loader already warned about a textured material without them).
int BaseColourTexture(const scenes::Scene& scene, const scenes::Mesh& mesh) {
  if (mesh.material < 0 || mesh.texcoords.empty()) return -1;
  return scene.materials[static_cast<std::size_t>(mesh.material)].baseColourTexture;
}

glm::vec3 BaseColourFactor(const scenes::Scene& scene, std::size_t meshIndex) {
  const scenes::Mesh& mesh = scene.meshes[meshIndex];
  if (mesh.material < 0) return glm::vec3(scenes::BaseColour(scene, meshIndex, glm::vec2(0.0f)));
  return glm::vec3(scene.materials[static_cast<std::size_t>(mesh.material)].baseColourFactor);
}

void AddTextures(const scenes::Scene& scene, FrameScene& frame) {
  frame.textures.reserve(scene.textures.size());
  for (std::size_t i = 0; i < scene.textures.size(); ++i) {
    const scenes::Texture& source = scene.textures[i];
    const std::string name = source.name.empty() ? "texture " + std::to_string(i) : source.name;
    // Modelled as RGBA8, the format glTF's PNG and JPEG images arrive in.
    sim::Texture2D<glm::vec4>& texture =
        frame.textures.emplace_back(name, source.width, source.height, 4);
    std::copy(source.texels.begin(), source.texels.end(), texture.Texels().begin());
  }
}

}  // namespace

namespace {
std::vector<glm::vec3> WorldNormals(const scenes::Scene& scene) {
  std::vector<glm::vec3> all;
  all.reserve(scene.VertexCount());
  for (const scenes::Mesh& mesh : scene.meshes) {
    const std::vector<glm::vec3> normals = scenes::VertexNormals(mesh);
    all.insert(all.end(), normals.begin(), normals.end());
  }
  return all;
}
}  // namespace

FrameScene ToFrameScene(const scenes::Scene& scene, float aspect) {
  FrameScene frame;
  frame.clip = ToClipSpace(scene, aspect);
  frame.normals = WorldNormals(scene);
  frame.objectIds.reserve(scene.TriangleCount());
  bool textured = false;
  for (const scenes::Mesh& mesh : scene.meshes) textured |= BaseColourTexture(scene, mesh) >= 0;
  for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
    const scenes::Mesh& source = scene.meshes[mesh];
    frame.objectIds.insert(frame.objectIds.end(), source.indices.size() / 3,
                           static_cast<std::uint32_t>(mesh));
    frame.baseColours.push_back(BaseColourFactor(scene, mesh));
    frame.baseColourTextures.push_back(BaseColourTexture(scene, source));
    if (!textured) continue;
    if (source.texcoords.empty()) {
      frame.texcoords.insert(frame.texcoords.end(), source.positions.size(), glm::vec2(0.0f));
    } else {
      frame.texcoords.insert(frame.texcoords.end(), source.texcoords.begin(), source.texcoords.end());
    }
  }
  if (textured) AddTextures(scene, frame);
  return frame;
}

void MoveFrameScene(const scenes::Scene& moved, float aspect, FrameScene& frame) {
  frame.clip = ToClipSpace(moved, aspect);
  frame.normals = WorldNormals(moved);
}

void ApplyLighting(const scenes::Lighting& lighting, sim::FrameSettings& settings) {
  settings.towardsLight = lighting.towardsLight;
  settings.ambient = lighting.ambient;
}

sim::FrameGeometry FrameScene::Geometry() const { return Geometry({}); }

sim::FrameGeometry FrameScene::Geometry(std::span<const glm::vec4> previousClip) const {
  return {.clipPositions = clip.positions,
          .previousClipPositions = previousClip,
          .normals = normals,
          .indices = clip.indices,
          .objectIds = objectIds,
          .baseColours = baseColours,
          .texcoords = texcoords,
          .baseColourTextures = baseColourTextures,
          .textures = textures};
}

}  // namespace study
