// Per-vertex shading normals (see normals.h).

#include "scenes/normals.h"

#include <glm/geometric.hpp>

namespace scenes {

std::vector<glm::vec3> SmoothNormals(std::span<const glm::vec3> positions,
                                     std::span<const std::uint32_t> indices) {
  std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
  for (std::size_t corner = 0; corner + 2 < indices.size(); corner += 3) {
    const std::uint32_t a = indices[corner], b = indices[corner + 1], c = indices[corner + 2];
    // Twice the triangle's area in length, so large faces outweigh slivers.
    const glm::vec3 face = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
    normals[a] += face;
    normals[b] += face;
    normals[c] += face;
  }
  for (glm::vec3& normal : normals) {
    const float length = glm::length(normal);
    normal = length > 0.0f ? normal / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return normals;
}

std::vector<glm::vec3> VertexNormals(const Mesh& mesh) {
  return mesh.normals.empty() ? SmoothNormals(mesh.positions, mesh.indices) : mesh.normals;
}

}  // namespace scenes
