#pragma once
// Motion over frames, for temporal passes: camera paths (still, orbit, pan, dolly) and the rigid
// per-mesh motion stored in Mesh::motion. Frame 0 is the scene as built; evaluating frames t and
// t - 1 gives every vertex's world velocity and, through the two cameras, its screen velocity.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace scenes {

enum class CameraPathKind { Still, Orbit, Pan, Dolly };

// Speeds are per frame and each kind reads only its own; frames may be negative (before frame
// 0). Frame 0 of every path is Scene::camera exactly.
struct CameraPath {
  CameraPathKind kind = CameraPathKind::Still;
  // Orbit: the eye turns about the camera's up axis through its target by this many degrees per
  // frame (positive = counter-clockwise seen from above). Distance to the target, field of view
  // and clip planes stay as they are.
  float orbitDegreesPerFrame = 0.25f;
  // Pan: eye and target slide along the camera's right vector by this many pixels per frame,
  // measured at the target's depth in an image panImageHeight pixels tall (negative = left).
  // View-space depths do not change, so neither do the clip planes.
  float panPixelsPerFrame = 0.5f;
  int panImageHeight = 1080;
  // Dolly: the eye moves along its view direction so that its distance to the target shrinks by
  // this fraction every frame, d(t) = d(0) * (1 - f)^t (negative f moves away). Both clip
  // planes shift by the distance moved, so geometry keeps its place between them; once the eye
  // has passed the old near plane, zNear stays at 1/1000 of d(t).
  float dollyFractionPerFrame = 0.005f;
};

// "still", "orbit", "pan", "dolly".
std::string_view CameraPathKindName(CameraPathKind kind);
std::vector<std::string> CameraPathKindNames();
// Throws SceneError listing the names for an unknown one.
CameraPathKind ParseCameraPathKind(std::string_view name);

// The scene's camera moved along `path` to `frame`. Throws SceneError for non-finite speeds, a
// dolly fraction of 1 or more, or a non-positive pan image height.
Camera CameraAt(const Scene& scene, const CameraPath& path, int frame);

// Object-to-world transform of a mesh's stored positions at `frame` (identity at frame 0 and for
// static meshes). Normals take its upper 3x3, a rotation.
glm::mat4 MeshTransformAt(const MeshMotion& motion, int frame);
// One transform per Scene::meshes entry.
std::vector<glm::mat4> MeshTransformsAt(const Scene& scene, int frame);

// World-space displacement of every vertex of scene.meshes[meshIndex] from frame - 1 to frame.
std::vector<glm::vec3> VertexVelocities(const Scene& scene, std::size_t meshIndex, int frame);

// The scene as it stands at `frame`: moving meshes transformed (positions, normals), bounds
// recomputed, camera from CameraAt. Each mesh's motion is re-based so that frame k of the result
// is frame `frame` + k of `scene`.
Scene SceneAt(const Scene& scene, const CameraPath& path, int frame);

}  // namespace scenes
