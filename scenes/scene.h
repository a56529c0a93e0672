#pragma once
// Scenes: triangle meshes flattened to world space plus a camera. scenes/ uses nothing else of
// aasim; the command line turns a Scene into clip-space positions for raster/.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace scenes {

// One-line input error naming the file (or built-in) and the problem.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(const std::string& message) : std::runtime_error(message) {}
};

struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  glm::vec3 Centre() const { return (min + max) * 0.5f; }
  float Radius() const;  // half the diagonal
};

// All node transforms applied; triangle list; indices index `positions`.
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty or one per position
  std::vector<std::uint32_t> indices;
};

// Right-handed, looking down -z in view space; projection maps depth to [0, 1] (D3D), so
// clip = Projection(aspect) * View() * world feeds raster::SetupTriangle directly.
struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float verticalFovRadians = 0.8f;
  float zNear = 0.1f;
  float zFar = 100.0f;
  glm::mat4 View() const;
  glm::mat4 Projection(float aspect) const;
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  Camera camera;
  Bounds bounds;

  std::size_t TriangleCount() const;
  std::size_t VertexCount() const;
};

// Camera on the +z side of the bounds (slightly above), target the centre, near/far planes
// enclosing the bounds for the given aspect.
Camera FrameBounds(const Bounds& bounds, float aspect);
// Camera on the line from the bounds centre along `towardsEye` (need not be unit length),
// distanced so the bounding sphere spans `fill` of the narrower field of view (1 = touching its
// edges, smaller = more room around it); near/far enclose the sphere. Throws SceneError for a
// non-positive aspect or fill, or a zero direction.
Camera FrameBoundsAlong(const Bounds& bounds, float aspect, const glm::vec3& towardsEye,
                        float fill);
Bounds ComputeBounds(const std::vector<Mesh>& meshes);

// glTF 2.0, .gltf or .glb. Throws SceneError ("FILE: problem") for malformed files,
// non-finite vertices, out-of-range indices; primitives that are not triangles are skipped
// with one warning each on stderr.
Scene LoadGltf(const std::filesystem::path& path, float aspect);

// Built-in scenes, no file needed. Throws SceneError listing the names for an unknown one.
Scene MakeBuiltinScene(std::string_view name, float aspect);
std::vector<std::string> BuiltinSceneNames();
inline constexpr std::string_view kDefaultSceneName = "default";

// "builtin:NAME" or a path to a glTF file.
Scene LoadScene(std::string_view spec, float aspect);

}  // namespace scenes
