// Built-in scenes generated in code: each aims at a coverage case (overlaps at many depths,
// slivers around a shared vertex, sub-pixel triangles) and needs no file. Pure arithmetic with
// no randomness, so every call yields bit-identical geometry.

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "scenes/scene.h"

namespace scenes {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
const glm::vec3 kFacingCamera{0.0f, 0.0f, 1.0f};
constexpr float kTightFill = 1.0f / 1.1f;

constexpr int kIcosphereSubdivisions = 3;
constexpr int kSpikeCount = 24;
constexpr std::uint32_t kThinFanSegments = 256;
constexpr std::uint32_t kGridCells = 400;
// The grid spans about 1/6 of a 1080p frame's height (~175 px), i.e. cells of ~0.44 px.
constexpr float kGridFill = 0.25f;

std::uint32_t NextIndex(const Mesh& mesh) {
  return static_cast<std::uint32_t>(mesh.positions.size());
}

void AddVertex(Mesh& mesh, const glm::vec3& position, const glm::vec3& normal) {
  mesh.positions.push_back(position);
  mesh.normals.push_back(normal);
}

// Corners in counter-clockwise order as seen from the side `normal` points to.
void AddQuad(Mesh& mesh, const std::array<glm::vec3, 4>& corners, const glm::vec3& normal) {
  const std::uint32_t base = NextIndex(mesh);
  for (const glm::vec3& corner : corners) AddVertex(mesh, corner, normal);
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

Mesh MakeGround(float halfSize) {
  Mesh ground;
  ground.name = "ground";
  const float h = halfSize;
  AddQuad(ground, {glm::vec3{-h, 0.0f, h}, {h, 0.0f, h}, {h, 0.0f, -h}, {-h, 0.0f, -h}},
          glm::vec3{0.0f, 1.0f, 0.0f});
  return ground;
}

// Faces are separate quads so each keeps its flat normal (sharp edges shade as edges).
Mesh MakeCube(const glm::vec3& centre, float halfSize, const glm::mat3& rotation) {
  Mesh cube;
  cube.name = "cube";
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 n(0.0f);
      glm::vec3 u(0.0f);
      glm::vec3 v(0.0f);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = 1.0f;
      if (sign < 0.0f) std::swap(u, v);  // keeps cross(u, v) == n, hence outward CCW
      std::array<glm::vec3, 4> corners = {n - u - v, n + u - v, n + u + v, n - u + v};
      for (glm::vec3& corner : corners) corner = centre + rotation * (corner * halfSize);
      AddQuad(cube, corners, rotation * n);
    }
  }
  return cube;
}

using Triangle = std::array<std::uint32_t, 3>;

// The icosahedron's faces are exactly the vertex triples at mutual edge length 2, oriented
// outwards; deriving them avoids a hand-typed face table.
std::vector<Triangle> IcosahedronFaces(const std::vector<glm::vec3>& vertices) {
  const auto isEdge = [&](std::uint32_t a, std::uint32_t b) {
    return std::abs(glm::distance(vertices[a], vertices[b]) - 2.0f) < 1e-3f;
  };
  std::vector<Triangle> faces;
  const auto count = static_cast<std::uint32_t>(vertices.size());
  for (std::uint32_t a = 0; a < count; ++a) {
    for (std::uint32_t b = a + 1; b < count; ++b) {
      for (std::uint32_t c = b + 1; c < count; ++c) {
        if (!isEdge(a, b) || !isEdge(b, c) || !isEdge(a, c)) continue;
        const glm::vec3 normal =
            glm::cross(vertices[b] - vertices[a], vertices[c] - vertices[a]);
        const bool outward = glm::dot(normal, vertices[a] + vertices[b] + vertices[c]) > 0.0f;
        faces.push_back(outward ? Triangle{a, b, c} : Triangle{a, c, b});
      }
    }
  }
  return faces;
}

std::vector<glm::vec3> IcosahedronVertices() {
  const float phi = std::numbers::phi_v<float>;
  std::vector<glm::vec3> vertices;
  for (float s : {-1.0f, 1.0f}) {
    for (float t : {-phi, phi}) {
      vertices.emplace_back(s, t, 0.0f);
      vertices.emplace_back(0.0f, s, t);
      vertices.emplace_back(t, 0.0f, s);
    }
  }
  return vertices;
}

// Splits every triangle into four, sharing each edge midpoint between its two triangles so
// the sphere stays watertight.
void Subdivide(std::vector<glm::vec3>& unitVertices, std::vector<Triangle>& faces) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
  const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    const auto [it, inserted] =
        midpoints.try_emplace(key, static_cast<std::uint32_t>(unitVertices.size()));
    if (inserted) unitVertices.push_back(glm::normalize(unitVertices[a] + unitVertices[b]));
    return it->second;
  };
  std::vector<Triangle> finer;
  finer.reserve(faces.size() * 4);
  for (const Triangle& f : faces) {
    const std::uint32_t ab = midpoint(f[0], f[1]);
    const std::uint32_t bc = midpoint(f[1], f[2]);
    const std::uint32_t ca = midpoint(f[2], f[0]);
    finer.insert(finer.end(), {Triangle{f[0], ab, ca}, Triangle{ab, f[1], bc},
                               Triangle{ca, bc, f[2]}, Triangle{ab, bc, ca}});
  }
  faces = std::move(finer);
}

Mesh MakeIcosphere(const glm::vec3& centre, float radius, int subdivisions) {
  std::vector<glm::vec3> unitVertices = IcosahedronVertices();
  std::vector<Triangle> faces = IcosahedronFaces(unitVertices);
  for (glm::vec3& v : unitVertices) v = glm::normalize(v);
  for (int level = 0; level < subdivisions; ++level) Subdivide(unitVertices, faces);
  Mesh sphere;
  sphere.name = "icosphere";
  for (const glm::vec3& v : unitVertices) AddVertex(sphere, centre + v * radius, v);
  for (const Triangle& f : faces) sphere.indices.insert(sphere.indices.end(), f.begin(), f.end());
  return sphere;
}

// Long slivers radiating from a hub, each a little nearer the camera than the last, so they
// overlap one another and the objects behind at many depths.
Mesh MakeSpikeFan(const glm::vec3& hub) {
  constexpr float kInnerRadius = 0.25f;
  constexpr float kOuterRadius = 1.9f;
  constexpr float kHalfWidth = 0.02f;
  constexpr float kDepthStep = 0.01f;
  constexpr float kFirstAngle = 10.0f * kPi / 180.0f;
  constexpr float kLastAngle = 170.0f * kPi / 180.0f;
  Mesh spikes;
  spikes.name = "spikes";
  for (int k = 0; k < kSpikeCount; ++k) {
    const float angle = kFirstAngle + (kLastAngle - kFirstAngle) * static_cast<float>(k) /
                                          static_cast<float>(kSpikeCount - 1);
    const glm::vec3 along{std::cos(angle), std::sin(angle), 0.0f};
    const glm::vec3 left{-along.y, along.x, 0.0f};
    const float depth = kDepthStep * static_cast<float>(k);
    const glm::vec3 base = hub + along * kInnerRadius + kFacingCamera * depth;
    const std::uint32_t first = NextIndex(spikes);
    AddVertex(spikes, base - left * kHalfWidth, kFacingCamera);
    AddVertex(spikes, base + along * (kOuterRadius - kInnerRadius), kFacingCamera);
    AddVertex(spikes, base + left * kHalfWidth, kFacingCamera);
    spikes.indices.insert(spikes.indices.end(), {first, first + 1, first + 2});
  }
  return spikes;
}

Scene Finish(std::string name, std::vector<Mesh> meshes) {
  Scene scene;
  scene.name = std::move(name);
  scene.meshes = std::move(meshes);
  scene.bounds = ComputeBounds(scene.meshes);
  return scene;
}

Scene MakeDefaultScene(float aspect) {
  const glm::mat4 yaw = glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3{0.0f, 1.0f, 0.0f});
  const glm::mat4 pitch = glm::rotate(glm::mat4(1.0f), 0.35f, glm::vec3{1.0f, 0.0f, 0.0f});
  const glm::mat3 tilt = glm::mat3(yaw * pitch);
  std::vector<Mesh> meshes;
  meshes.push_back(MakeGround(3.0f));
  meshes.push_back(MakeCube(glm::vec3{-1.3f, 1.1f, -0.4f}, 0.6f, tilt));
  meshes.push_back(MakeIcosphere(glm::vec3{1.0f, 0.95f, -1.0f}, 0.85f, kIcosphereSubdivisions));
  meshes.push_back(MakeSpikeFan(glm::vec3{0.0f, 0.1f, 1.2f}));
  Scene scene = Finish(std::string(kDefaultSceneName), std::move(meshes));
  scene.camera = FrameBounds(scene.bounds, aspect);
  return scene;
}

// Every triangle shares the centre vertex and both spokes with its neighbours, so each spoke
// is an interior edge owned by exactly two triangles.
Scene MakeThinFanScene(float aspect) {
  Mesh fan;
  fan.name = "thin-fan";
  AddVertex(fan, glm::vec3(0.0f), kFacingCamera);
  for (std::uint32_t k = 0; k < kThinFanSegments; ++k) {
    const float angle = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(kThinFanSegments);
    AddVertex(fan, glm::vec3{std::cos(angle), std::sin(angle), 0.0f}, kFacingCamera);
  }
  for (std::uint32_t k = 0; k < kThinFanSegments; ++k) {
    fan.indices.insert(fan.indices.end(), {0u, 1 + k, 1 + (k + 1) % kThinFanSegments});
  }
  Scene scene = Finish("thin-fan", {std::move(fan)});
  scene.camera = FrameBoundsAlong(scene.bounds, aspect, kFacingCamera, kTightFill);
  return scene;
}

Scene MakeSubpixelGridScene(float aspect) {
  constexpr std::uint32_t kSide = kGridCells + 1;
  Mesh grid;
  grid.name = "subpixel-grid";
  for (std::uint32_t j = 0; j < kSide; ++j) {
    for (std::uint32_t i = 0; i < kSide; ++i) {
      const float x = static_cast<float>(i) / static_cast<float>(kGridCells) - 0.5f;
      const float y = static_cast<float>(j) / static_cast<float>(kGridCells) - 0.5f;
      AddVertex(grid, glm::vec3{x, y, 0.0f}, kFacingCamera);
    }
  }
  for (std::uint32_t j = 0; j < kGridCells; ++j) {
    for (std::uint32_t i = 0; i < kGridCells; ++i) {
      const std::uint32_t v00 = j * kSide + i;
      const std::uint32_t v10 = v00 + 1;
      const std::uint32_t v01 = v00 + kSide;
      const std::uint32_t v11 = v01 + 1;
      grid.indices.insert(grid.indices.end(), {v00, v10, v11, v00, v11, v01});
    }
  }
  Scene scene = Finish("subpixel-grid", {std::move(grid)});
  scene.camera = FrameBoundsAlong(scene.bounds, aspect, kFacingCamera, kGridFill);
  return scene;
}

struct BuiltinScene {
  std::string_view name;
  Scene (*make)(float aspect);
};

constexpr std::array<BuiltinScene, 3> kBuiltinScenes = {
    BuiltinScene{kDefaultSceneName, &MakeDefaultScene},
    BuiltinScene{"thin-fan", &MakeThinFanScene},
    BuiltinScene{"subpixel-grid", &MakeSubpixelGridScene}};

}  // namespace

std::vector<std::string> BuiltinSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinScene& builtin : kBuiltinScenes) names.emplace_back(builtin.name);
  return names;
}

Scene MakeBuiltinScene(std::string_view name, float aspect) {
  for (const BuiltinScene& builtin : kBuiltinScenes) {
    if (builtin.name == name) return builtin.make(aspect);
  }
  std::string available;
  for (const BuiltinScene& builtin : kBuiltinScenes) {
    available += (available.empty() ? "" : ", ") + std::string(builtin.name);
  }
  throw SceneError("builtin:" + std::string(name) + ": unknown built-in scene; available: " +
                   available);
}

}  // namespace scenes
