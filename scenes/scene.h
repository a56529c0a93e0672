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
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

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

// Linear RGBA texels, row-major, top row first; colour textures are sRGB-decoded on load.
// Sampling wraps (glTF's default sampler).
struct Texture {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;
};

// glTF metallic-roughness base colour only: the shading model is Lambert (see shading.h).
struct Material {
  std::string name;
  glm::vec4 baseColourFactor{1.0f};  // linear
  int baseColourTexture = -1;        // index into Scene::textures, -1 for none
};

// Rigid motion of a mesh over frames, for temporal passes (motion.h evaluates it). Frame 0 is
// the mesh as stored; at frame t the mesh is turned by t * degreesPerFrame about `axis` through
// `pivot` (counter-clockwise looking against `axis`), then moved by t * unitsPerFrame.
struct MeshMotion {
  glm::vec3 pivot{0.0f};
  glm::vec3 axis{0.0f, 0.0f, 1.0f};
  float degreesPerFrame = 0.0f;
  glm::vec3 unitsPerFrame{0.0f};
  bool IsStatic() const;
};

// All node transforms applied; triangle list; indices index `positions`.
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // empty or one per position
  std::vector<glm::vec2> texcoords;  // TEXCOORD_0: empty or one per position
  std::vector<std::uint32_t> indices;
  int material = -1;  // index into Scene::materials, -1 for the default material
  MeshMotion motion{};  // static unless a built-in scene animates the mesh
};

// One directional light plus an ambient term, shared by the raster material kernel and the
// ground truth so both shade the same function (shading.h).
struct Lighting {
  glm::vec3 towardsLight{0.4f, 0.8f, 0.45f};  // world space, normalised on use
  float ambient = 0.15f;
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
  std::vector<Material> materials;
  std::vector<Texture> textures;
  Lighting lighting;
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
// Sets zNear/zFar to enclose the bounding sphere seen from camera.eye, the rule FrameBoundsAlong
// uses (5% slack; zNear at least 1/1000 of the distance to the centre, for depth precision).
void EncloseBounds(Camera& camera, const Bounds& bounds);

// glTF 2.0, .gltf or .glb: geometry, TEXCOORD_0, base colour materials and textures, and the
// first perspective camera in the node tree (else FrameBounds). Throws SceneError ("FILE:
// problem") for malformed files, non-finite vertices, out-of-range indices; features aasim does
// not model (points and lines, other material maps, animations, ...) are skipped with one
// warning line each on stderr. docs/scenes.md lists them.
Scene LoadGltf(const std::filesystem::path& path, float aspect);

// Built-in scenes, no file needed. Throws SceneError listing the names for an unknown one.
Scene MakeBuiltinScene(std::string_view name, float aspect);
std::vector<std::string> BuiltinSceneNames();
inline constexpr std::string_view kDefaultSceneName = "default";

// "builtin:NAME" or a path to a glTF file.
Scene LoadScene(std::string_view spec, float aspect);

}  // namespace scenes
