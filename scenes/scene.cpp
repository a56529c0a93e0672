// Scene basics shared by the loaders: bounds, camera matrices and framing, and the one entry
// point (LoadScene) that turns a user's scene spec into a Scene.

#include "scenes/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

namespace scenes {
namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";
// Near/far sit this far outside the bounding sphere so depth never clips the geometry.
constexpr float kDepthSlack = 1.05f;
// Keeps zNear away from zero, which would waste all depth precision.
constexpr float kMinNearFraction = 1e-3f;
constexpr float kFrameBoundsFill = 1.0f / 1.1f;

bool IsPositiveFinite(float value) { return std::isfinite(value) && value > 0.0f; }

// A point-sized or empty scene still needs a frustum of non-zero size.
float FramingRadius(const Bounds& bounds) {
  const glm::vec3 centre = bounds.Centre();
  const float scale = std::max({1.0f, std::abs(centre.x), std::abs(centre.y), std::abs(centre.z)});
  return std::max(bounds.Radius(), scale * 1e-6f);
}

// lookAt degenerates when the view direction is parallel to up.
glm::vec3 UpFor(const glm::vec3& towardsEye) {
  const glm::vec3 worldUp{0.0f, 1.0f, 0.0f};
  return std::abs(glm::dot(towardsEye, worldUp)) > 0.999f ? glm::vec3{0.0f, 0.0f, -1.0f} : worldUp;
}

void SetDepthRange(Camera& camera, float distance, float radius) {
  camera.zNear = std::max(distance - radius * kDepthSlack, distance * kMinNearFraction);
  camera.zFar = distance + radius * kDepthSlack;
}

}  // namespace

bool MeshMotion::IsStatic() const {
  return degreesPerFrame == 0.0f && unitsPerFrame == glm::vec3(0.0f);
}

float Bounds::Radius() const { return 0.5f * glm::length(max - min); }

glm::mat4 Camera::View() const { return glm::lookAtRH(eye, target, up); }

glm::mat4 Camera::Projection(float aspect) const {
  return glm::perspectiveRH_ZO(verticalFovRadians, aspect, zNear, zFar);
}

std::size_t Scene::TriangleCount() const {
  std::size_t count = 0;
  for (const Mesh& mesh : meshes) count += mesh.indices.size() / 3;
  return count;
}

std::size_t Scene::VertexCount() const {
  std::size_t count = 0;
  for (const Mesh& mesh : meshes) count += mesh.positions.size();
  return count;
}

Bounds ComputeBounds(const std::vector<Mesh>& meshes) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  glm::vec3 lo{kInf};
  glm::vec3 hi{-kInf};
  for (const Mesh& mesh : meshes) {
    for (const glm::vec3& p : mesh.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  if (lo.x > hi.x) return Bounds{};
  return Bounds{lo, hi};
}

Camera FrameBoundsAlong(const Bounds& bounds, float aspect, const glm::vec3& towardsEye,
                        float fill) {
  if (!IsPositiveFinite(aspect)) {
    throw SceneError("camera framing: aspect ratio must be positive, got " +
                     std::to_string(aspect));
  }
  if (!IsPositiveFinite(fill)) {
    throw SceneError("camera framing: fill must be positive, got " + std::to_string(fill));
  }
  const float directionLength = glm::length(towardsEye);
  if (!IsPositiveFinite(directionLength)) {
    throw SceneError("camera framing: view direction must be non-zero and finite");
  }
  Camera camera;
  const glm::vec3 direction = towardsEye / directionLength;
  const float radius = FramingRadius(bounds);
  const float halfVertical = 0.5f * camera.verticalFovRadians;
  const float halfHorizontal = std::atan(std::tan(halfVertical) * aspect);
  // A sphere at distance d subtends asin(r / d): fit it to the narrower half-angle.
  const float distance = radius / (fill * std::sin(std::min(halfVertical, halfHorizontal)));
  camera.target = bounds.Centre();
  camera.eye = camera.target + direction * distance;
  camera.up = UpFor(direction);
  SetDepthRange(camera, distance, radius);
  return camera;
}

void EncloseBounds(Camera& camera, const Bounds& bounds) {
  const float radius = FramingRadius(bounds);
  // An eye at the very centre would get zNear = 0, which the projection cannot take.
  const float distance =
      std::max(glm::distance(camera.eye, bounds.Centre()), radius * kMinNearFraction);
  SetDepthRange(camera, distance, radius);
}

Camera FrameBounds(const Bounds& bounds, float aspect) {
  return FrameBoundsAlong(bounds, aspect, glm::vec3{0.3f, 0.35f, 1.0f}, kFrameBoundsFill);
}

Scene LoadScene(std::string_view spec, float aspect) {
  if (spec.starts_with(kBuiltinPrefix)) {
    return MakeBuiltinScene(spec.substr(kBuiltinPrefix.size()), aspect);
  }
  if (spec.empty()) {
    throw SceneError("empty scene spec: expected builtin:NAME or a .gltf/.glb file");
  }
  return LoadGltf(std::filesystem::path(spec), aspect);
}

}  // namespace scenes
