// Camera paths and mesh motion (see motion.h). Every pose is computed from frame 0 and the frame
// number in closed form, never by stepping, so frame t is the same whichever frames were asked
// for before it and velocities are exact differences of two poses.

#include "scenes/motion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/trigonometric.hpp>

namespace scenes {
namespace {

// As in EncloseBounds: zNear never drops below this fraction of the distance to the target.
constexpr float kMinNearFraction = 1e-3f;

struct PathName {
  CameraPathKind kind;
  std::string_view name;
};

constexpr std::array<PathName, 4> kPathNames = {PathName{CameraPathKind::Still, "still"},
                                                PathName{CameraPathKind::Orbit, "orbit"},
                                                PathName{CameraPathKind::Pan, "pan"},
                                                PathName{CameraPathKind::Dolly, "dolly"}};

void CheckPath(const CameraPath& path) {
  const auto fail = [](const std::string& problem) {
    throw SceneError("camera path: " + problem);
  };
  if (!std::isfinite(path.orbitDegreesPerFrame) || !std::isfinite(path.panPixelsPerFrame) ||
      !std::isfinite(path.dollyFractionPerFrame)) {
    fail("speeds must be finite");
  }
  if (path.kind == CameraPathKind::Pan && path.panImageHeight <= 0) {
    fail("pan image height must be positive, got " + std::to_string(path.panImageHeight));
  }
  if (path.kind == CameraPathKind::Dolly && path.dollyFractionPerFrame >= 1.0f) {
    fail("dolly fraction per frame must be below 1, got " +
         std::to_string(path.dollyFractionPerFrame));
  }
}

Camera Orbit(Camera camera, float degrees) {
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(degrees),
                                     glm::normalize(camera.up));
  camera.eye = camera.target + glm::vec3(turn * glm::vec4(camera.eye - camera.target, 0.0f));
  return camera;
}

Camera Pan(Camera camera, float pixels, int imageHeight) {
  const glm::vec3 towardsTarget = camera.target - camera.eye;
  const glm::vec3 right = glm::normalize(glm::cross(towardsTarget, camera.up));
  const float pixelSize = 2.0f * glm::length(towardsTarget) *
                          std::tan(0.5f * camera.verticalFovRadians) /
                          static_cast<float>(imageHeight);
  const glm::vec3 offset = right * (pixels * pixelSize);
  camera.eye += offset;
  camera.target += offset;
  return camera;
}

Camera Dolly(Camera camera, float fractionPerFrame, int frame) {
  const glm::vec3 towardsTarget = camera.target - camera.eye;
  const float startDistance = glm::length(towardsTarget);
  const float ratio = std::pow(1.0f - fractionPerFrame, static_cast<float>(frame));
  const float distance = startDistance * ratio;
  const float moved = startDistance - distance;
  camera.eye = camera.target - towardsTarget * ratio;
  // Every view depth changes by exactly `moved`; the floor keeps zNear positive (the rule
  // EncloseBounds uses) once the eye has come nearer than the old near plane.
  camera.zNear = std::max(camera.zNear - moved, distance * kMinNearFraction);
  camera.zFar = std::max(camera.zFar - moved, 2.0f * camera.zNear);
  return camera;
}

}  // namespace

std::string_view CameraPathKindName(CameraPathKind kind) {
  for (const PathName& entry : kPathNames) {
    if (entry.kind == kind) return entry.name;
  }
  throw SceneError("camera path: unknown kind " + std::to_string(static_cast<int>(kind)));
}

std::vector<std::string> CameraPathKindNames() {
  std::vector<std::string> names;
  for (const PathName& entry : kPathNames) names.emplace_back(entry.name);
  return names;
}

CameraPathKind ParseCameraPathKind(std::string_view name) {
  std::string available;
  for (const PathName& entry : kPathNames) {
    if (entry.name == name) return entry.kind;
    available.append(available.empty() ? "" : ", ").append(entry.name);
  }
  throw SceneError("camera path '" + std::string(name) + "': unknown; available: " + available);
}

Camera CameraAt(const Scene& scene, const CameraPath& path, int frame) {
  CheckPath(path);
  // Exactly the still camera, not one turned or moved by zero (which may round differently).
  if (frame == 0) return scene.camera;
  const float t = static_cast<float>(frame);
  switch (path.kind) {
    case CameraPathKind::Still: return scene.camera;
    case CameraPathKind::Orbit: return Orbit(scene.camera, path.orbitDegreesPerFrame * t);
    case CameraPathKind::Pan:
      return Pan(scene.camera, path.panPixelsPerFrame * t, path.panImageHeight);
    case CameraPathKind::Dolly: return Dolly(scene.camera, path.dollyFractionPerFrame, frame);
  }
  throw SceneError("camera path: unknown kind " + std::to_string(static_cast<int>(path.kind)));
}

glm::mat4 MeshTransformAt(const MeshMotion& motion, int frame) {
  if (motion.IsStatic() || frame == 0) return glm::mat4(1.0f);
  const float t = static_cast<float>(frame);
  const glm::mat4 toPivot = glm::translate(glm::mat4(1.0f), -motion.pivot);
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(motion.degreesPerFrame * t),
                                     glm::normalize(motion.axis));
  const glm::mat4 back = glm::translate(glm::mat4(1.0f), motion.pivot + motion.unitsPerFrame * t);
  return back * turn * toPivot;
}

std::vector<glm::mat4> MeshTransformsAt(const Scene& scene, int frame) {
  std::vector<glm::mat4> transforms;
  transforms.reserve(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes) transforms.push_back(MeshTransformAt(mesh.motion, frame));
  return transforms;
}

std::vector<glm::vec3> VertexVelocities(const Scene& scene, std::size_t meshIndex, int frame) {
  const Mesh& mesh = scene.meshes.at(meshIndex);
  const glm::mat4 now = MeshTransformAt(mesh.motion, frame);
  const glm::mat4 before = MeshTransformAt(mesh.motion, frame - 1);
  std::vector<glm::vec3> velocities;
  velocities.reserve(mesh.positions.size());
  for (const glm::vec3& p : mesh.positions) {
    velocities.push_back(glm::vec3(now * glm::vec4(p, 1.0f)) -
                         glm::vec3(before * glm::vec4(p, 1.0f)));
  }
  return velocities;
}

Scene SceneAt(const Scene& scene, const CameraPath& path, int frame) {
  Scene moved = scene;
  for (Mesh& mesh : moved.meshes) {
    if (mesh.motion.IsStatic()) continue;
    const glm::mat4 transform = MeshTransformAt(mesh.motion, frame);
    const glm::mat3 rotation(transform);
    for (glm::vec3& p : mesh.positions) p = glm::vec3(transform * glm::vec4(p, 1.0f));
    for (glm::vec3& n : mesh.normals) n = rotation * n;
    // Rotations about one axis commute, so turning about the moved pivot continues the motion.
    mesh.motion.pivot += mesh.motion.unitsPerFrame * static_cast<float>(frame);
  }
  moved.bounds = ComputeBounds(moved.meshes);
  moved.camera = CameraAt(scene, path, frame);
  return moved;
}

}  // namespace scenes
