#pragma once
// Per-vertex shading normals: the ones a mesh carries, or area-weighted smooth normals computed
// from its triangles. The raster frame pipeline and the Embree ground truth both take their
// normals from here, so the two shade the same surface.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace scenes {

// Area-weighted vertex normals: each triangle adds its unnormalised face normal (counter-
// clockwise = front, as glTF) to its three corners. A vertex whose sum is zero (unused, only in
// degenerate triangles, or between exactly opposite faces) gets +z so a shader never normalises
// a zero vector. Indices must be in range; a trailing partial triangle is ignored.
std::vector<glm::vec3> SmoothNormals(std::span<const glm::vec3> positions,
                                     std::span<const std::uint32_t> indices);

// mesh.normals where the mesh has them, else SmoothNormals of its positions.
std::vector<glm::vec3> VertexNormals(const Mesh& mesh);

}  // namespace scenes
