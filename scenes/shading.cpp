// The shading model (see shading.h).

#include "scenes/shading.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace scenes {

namespace {
int Wrap(int i, int size) {
  const int r = i % size;
  return r < 0 ? r + size : r;
}
}  // namespace

glm::vec4 SampleBilinearRepeat(const Texture& texture, glm::vec2 uv) {
  const glm::vec2 texel = uv * glm::vec2(texture.width, texture.height) - 0.5f;
  const glm::vec2 base = glm::floor(texel);
  const glm::vec2 f = texel - base;
  const int x0 = static_cast<int>(base.x), y0 = static_cast<int>(base.y);
  auto at = [&](int x, int y) {
    return texture.texels[static_cast<std::size_t>(Wrap(y, texture.height)) * static_cast<std::size_t>(texture.width) +
                          static_cast<std::size_t>(Wrap(x, texture.width))];
  };
  const glm::vec4 top = at(x0, y0) * (1.0f - f.x) + at(x0 + 1, y0) * f.x;
  const glm::vec4 bottom = at(x0, y0 + 1) * (1.0f - f.x) + at(x0 + 1, y0 + 1) * f.x;
  return top * (1.0f - f.y) + bottom * f.y;
}

glm::vec4 BaseColour(const Scene& scene, std::size_t meshIndex, glm::vec2 uv) {
  const Mesh& mesh = scene.meshes[meshIndex];
  if (mesh.material < 0) return glm::vec4(kMeshPalette[meshIndex % kMeshPalette.size()], 1.0f);
  const Material& material = scene.materials[static_cast<std::size_t>(mesh.material)];
  if (material.baseColourTexture < 0) return material.baseColourFactor;
  return material.baseColourFactor *
         SampleBilinearRepeat(scene.textures[static_cast<std::size_t>(material.baseColourTexture)], uv);
}

glm::vec3 ShadeLambert(const Lighting& lighting, glm::vec3 baseColour, glm::vec3 normal) {
  const float lambert = std::max(0.0f, glm::dot(normal, glm::normalize(lighting.towardsLight)));
  return baseColour * (lighting.ambient + (1.0f - lighting.ambient) * lambert);
}

}  // namespace scenes
