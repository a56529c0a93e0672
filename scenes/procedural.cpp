// Built-in scenes generated in code: each aims at a coverage case (overlaps at many depths,
// slivers, wires, sub-pixel triangles, stair steps, texture aliasing, motion) and needs no file.
// Pure arithmetic with no randomness, so every call yields bit-identical geometry.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

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

// ---------------------------------------------------------------------------------------------
// Shared pieces of the stress scenes

// Linear base colours: the stress scenes put bright thin things on dark backdrops so that every
// partially covered pixel shows, and neighbouring triangles get different colours.
const glm::vec3 kBackdropColour{0.04f, 0.05f, 0.08f};
const glm::vec3 kBright{0.92f, 0.90f, 0.82f};
const glm::vec3 kCool{0.55f, 0.80f, 0.95f};
const glm::vec3 kWarm{0.95f, 0.55f, 0.15f};
const glm::vec3 kGrey{0.45f, 0.45f, 0.45f};
const std::array<glm::vec3, 4> kContrasting = {
    glm::vec3{0.90f, 0.20f, 0.15f}, glm::vec3{0.20f, 0.80f, 0.25f},
    glm::vec3{0.20f, 0.35f, 0.95f}, glm::vec3{0.95f, 0.85f, 0.20f}};
const glm::vec3 kUp{0.0f, 1.0f, 0.0f};

// Deterministic, well-spread phases in [0, 1): multiples of an irrational number mod 1.
float Phase(int i, float irrational = 0.6180340f) {
  const float x = static_cast<float>(i) * irrational;
  return x - std::floor(x);
}

// Appends a mesh with its own single-colour material. The reference is valid until the next
// mesh is added.
Mesh& AddMesh(Scene& scene, const std::string& name, const glm::vec3& colour) {
  scene.materials.push_back(Material{.name = name, .baseColourFactor = glm::vec4(colour, 1.0f)});
  Mesh mesh;
  mesh.name = name;
  mesh.material = static_cast<int>(scene.materials.size()) - 1;
  scene.meshes.push_back(std::move(mesh));
  return scene.meshes.back();
}

// Triangle abc facing `normal`: the corners are reordered if needed so that they run
// counter-clockwise seen from the side the normal points to.
void AddFacingTriangle(Mesh& mesh, const glm::vec3& a, glm::vec3 b, glm::vec3 c,
                       const glm::vec3& normal) {
  if (glm::dot(glm::cross(b - a, c - a), normal) < 0.0f) std::swap(b, c);
  const std::uint32_t base = NextIndex(mesh);
  AddVertex(mesh, a, normal);
  AddVertex(mesh, b, normal);
  AddVertex(mesh, c, normal);
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
}

// A convex quad given in order around its outline, facing `normal` (reversed if needed).
void AddFacingQuad(Mesh& mesh, std::array<glm::vec3, 4> corners, const glm::vec3& normal) {
  if (glm::dot(glm::cross(corners[1] - corners[0], corners[2] - corners[0]), normal) < 0.0f) {
    std::swap(corners[1], corners[3]);
  }
  AddQuad(mesh, corners, normal);
}

// A triangle from a base of 2 * halfWidth centred on `base` to the apex `tip`, in the plane
// perpendicular to `normal`.
void AddSpike(Mesh& mesh, const glm::vec3& base, const glm::vec3& tip, float halfWidth,
              const glm::vec3& normal) {
  const glm::vec3 side = glm::normalize(glm::cross(normal, tip - base)) * halfWidth;
  AddFacingTriangle(mesh, base - side, tip, base + side, normal);
}

// Scenes whose promises are in pixels ("wires 1 px wide") are laid out for the reference view:
// a 1920x1080 image looking straight down -z at the z = 0 plane, where one world unit spans 100
// pixels. Pixel coordinates have their origin at the image's top-left corner, y down.
constexpr float kReferenceWidth = 1920.0f;
constexpr float kReferenceHeight = 1080.0f;
constexpr float kUnitsPerPixel = 0.01f;
// The backdrop behind the pixel-plane scenes, in reference pixels.
constexpr glm::vec2 kBackdropTopLeft{40.0f, 20.0f};
constexpr glm::vec2 kBackdropBottomRight{1880.0f, 1060.0f};

float ReferenceDistance() {
  return 0.5f * kReferenceHeight * kUnitsPerPixel / std::tan(0.5f * Camera{}.verticalFovRadians);
}

// The point the reference view shows at pixel `pixel`, placed at height z above the plane:
// nearer points are pulled towards the axis so that they still land on that pixel.
glm::vec3 AtPixel(const glm::vec2& pixel, float z = 0.0f) {
  const float distance = ReferenceDistance();
  const float scale = kUnitsPerPixel * (distance - z) / distance;
  return {(pixel.x - 0.5f * kReferenceWidth) * scale, (0.5f * kReferenceHeight - pixel.y) * scale,
          z};
}

Camera ReferenceCamera(const Bounds& bounds, float aspect) {
  if (!(std::isfinite(aspect) && aspect > 0.0f)) {
    throw SceneError("camera framing: aspect ratio must be positive, got " +
                     std::to_string(aspect));
  }
  Camera camera;
  // A narrower image steps back until the reference width fits; pixel sizes shrink with it.
  const float stepBack = std::max(1.0f, kReferenceWidth / kReferenceHeight / aspect);
  camera.eye = {0.0f, 0.0f, ReferenceDistance() * stepBack};
  EncloseBounds(camera, bounds);
  return camera;
}

// A straight strip `width` pixels wide from pixel a to pixel b at height z: one quad, four
// consecutive vertices.
void AddPixelStrip(Mesh& mesh, const glm::vec2& a, const glm::vec2& b, float width, float z) {
  const glm::vec2 along = glm::normalize(b - a);
  const glm::vec2 half = glm::vec2(-along.y, along.x) * (0.5f * width);
  AddFacingQuad(mesh, {AtPixel(a - half, z), AtPixel(b - half, z), AtPixel(b + half, z),
                       AtPixel(a + half, z)},
                kFacingCamera);
}

void AddBackdrop(Scene& scene) {
  Mesh& backdrop = AddMesh(scene, "backdrop", kBackdropColour);
  const glm::vec2 lo = kBackdropTopLeft;
  const glm::vec2 hi = kBackdropBottomRight;
  AddFacingQuad(backdrop, {AtPixel(lo), AtPixel({hi.x, lo.y}), AtPixel(hi), AtPixel({lo.x, hi.y})},
                kFacingCamera);
}

Scene FinishReferenceScene(Scene scene, float aspect) {
  scene.bounds = ComputeBounds(scene.meshes);
  scene.camera = ReferenceCamera(scene.bounds, aspect);
  return scene;
}

Scene FinishWithCamera(Scene scene, const glm::vec3& eye, const glm::vec3& target) {
  scene.bounds = ComputeBounds(scene.meshes);
  scene.camera.eye = eye;
  scene.camera.target = target;
  EncloseBounds(scene.camera, scene.bounds);
  return scene;
}

// ---------------------------------------------------------------------------------------------
// spike-room: long thin triangles at many slopes

// Spikes on a wall and a floor lie this far in front of them, so they never share a depth.
constexpr float kSpikeLift = 0.01f;

Scene MakeSpikeRoomScene(float) {
  constexpr float kHalfWidth = 4.0f;
  constexpr float kDepth = 8.0f;
  constexpr float kHeight = 5.0f;
  Scene scene;
  scene.name = "spike-room";
  AddFacingQuad(AddMesh(scene, "floor", kGrey),
                {glm::vec3{-kHalfWidth, 0.0f, 0.0f}, {kHalfWidth, 0.0f, 0.0f},
                 {kHalfWidth, 0.0f, -kDepth}, {-kHalfWidth, 0.0f, -kDepth}},
                kUp);
  AddFacingQuad(AddMesh(scene, "back wall", {0.10f, 0.16f, 0.24f}),
                {glm::vec3{-kHalfWidth, 0.0f, -kDepth}, {kHalfWidth, 0.0f, -kDepth},
                 {kHalfWidth, kHeight, -kDepth}, {-kHalfWidth, kHeight, -kDepth}},
                kFacingCamera);
  for (float side : {-1.0f, 1.0f}) {
    const float x = side * kHalfWidth;
    AddFacingQuad(AddMesh(scene, side < 0.0f ? "left wall" : "right wall", {0.22f, 0.13f, 0.10f}),
                  {glm::vec3{x, 0.0f, 0.0f}, {x, 0.0f, -kDepth}, {x, kHeight, -kDepth},
                   {x, kHeight, 0.0f}},
                  glm::vec3{-side, 0.0f, 0.0f});
  }
  const std::size_t light = scene.meshes.size();
  AddMesh(scene, "spikes light", kBright);
  AddMesh(scene, "spikes red", kContrasting[0]);
  const auto spikes = [&](int k) -> Mesh& {
    return scene.meshes[light + static_cast<std::size_t>(k % 2)];
  };
  // Back wall: a full circle of spikes every 5 degrees with staggered lengths; neighbours
  // overlap near the hub, so alternate ones stand a little further out.
  const glm::vec3 hub{0.0f, 2.5f, -kDepth};
  for (int k = 0; k < 72; ++k) {
    const float angle = glm::radians(5.0f * static_cast<float>(k));
    const glm::vec3 along{std::cos(angle), std::sin(angle), 0.0f};
    const glm::vec3 lift = kFacingCamera * (kSpikeLift * static_cast<float>(1 + k % 2));
    AddSpike(spikes(k), hub + lift + along * 0.35f,
             hub + lift + along * (1.6f + 0.7f * Phase(k)), 0.02f, kFacingCamera);
  }
  // Floor: spikes running into the room, fanning out slightly, so perspective turns them
  // through a range of screen slopes.
  for (int k = 0; k < 36; ++k) {
    const float x = -3.5f + 7.0f * static_cast<float>(k) / 35.0f;
    const glm::vec3 base{x, kSpikeLift, -0.3f};
    AddSpike(spikes(k), base, glm::vec3{1.1f * x, kSpikeLift, -6.8f}, 0.03f, kUp);
  }
  // Side walls: spikes rising from the floor at pitches from 15 to 75 degrees, leaning towards
  // the middle of the room; each at its own distance from the wall, since some cross.
  for (float side : {-1.0f, 1.0f}) {
    const glm::vec3 inward{-side, 0.0f, 0.0f};
    for (int k = 0; k < 20; ++k) {
      const float z = -7.6f + 7.2f * static_cast<float>(k) / 19.0f;
      const float pitch = glm::radians(15.0f + 60.0f * static_cast<float>(k) / 19.0f);
      const float lean = z < -0.5f * kDepth ? 1.0f : -1.0f;
      const float x = side * (kHalfWidth - kSpikeLift * static_cast<float>(1 + k));
      const glm::vec3 base{x, 0.05f, z};
      const glm::vec3 along{0.0f, std::sin(pitch), lean * std::cos(pitch)};
      AddSpike(spikes(k), base, base + along * 3.4f, 0.025f, inward);
    }
  }
  return FinishWithCamera(std::move(scene), {0.0f, 2.5f, 8.0f}, {0.0f, 2.2f, -4.0f});
}

// ---------------------------------------------------------------------------------------------
// fence: wire grids one pixel wide and thinner

struct FenceColumn {
  float wireWidth;  // reference pixels
  std::string_view label;
};
constexpr std::array<FenceColumn, 4> kFenceColumns = {
    FenceColumn{1.0f, "1px"}, FenceColumn{0.5f, "0.5px"}, FenceColumn{0.25f, "0.25px"},
    FenceColumn{0.1f, "0.1px"}};
// Not a whole number of pixels, so successive wires cross pixels at every phase.
constexpr float kFencePitch = 7.75f;
// Crossing wires sit at different heights so that they never share a depth.
constexpr float kLowWire = 0.02f;
constexpr float kHighWire = 0.04f;

std::string WireMeshName(const FenceColumn& column, std::string_view family) {
  std::string name = "wires ";
  return name.append(column.label).append(" ").append(family);
}

void AddGridPanel(Scene& scene, const FenceColumn& column, const glm::vec2& lo,
                  const glm::vec2& hi) {
  Mesh& vertical = AddMesh(scene, WireMeshName(column, "vertical"), kBright);
  for (int k = 0;; ++k) {
    const float x = lo.x + 4.0f + kFencePitch * static_cast<float>(k);
    if (x > hi.x - 4.0f) break;
    AddPixelStrip(vertical, {x, lo.y}, {x, hi.y}, column.wireWidth, kLowWire);
  }
  Mesh& horizontal = AddMesh(scene, WireMeshName(column, "horizontal"), kCool);
  for (int k = 0;; ++k) {
    const float y = lo.y + 4.0f + kFencePitch * static_cast<float>(k);
    if (y > hi.y - 4.0f) break;
    AddPixelStrip(horizontal, {lo.x, y}, {hi.x, y}, column.wireWidth, kHighWire);
  }
}

// Two families of parallel wires at +45 and -45 degrees (a chain-link fence), cut to the panel.
void AddChainLinkPanel(Scene& scene, const FenceColumn& column, const glm::vec2& lo,
                       const glm::vec2& hi) {
  // Lines x - y = c (or x + y = c) this far apart in c are kFencePitch apart on screen.
  constexpr float kStep = kFencePitch * std::numbers::sqrt2_v<float>;
  constexpr float kShortest = 2.0f;
  Mesh& rising = AddMesh(scene, WireMeshName(column, "diagonal rising"), kBright);
  for (int k = 0;; ++k) {
    const float c = lo.x - hi.y + 0.37f + kStep * static_cast<float>(k);
    if (c >= hi.x - lo.y) break;
    const float x0 = std::max(lo.x, lo.y + c);
    const float x1 = std::min(hi.x, hi.y + c);
    if (x1 - x0 >= kShortest) {
      AddPixelStrip(rising, {x0, x0 - c}, {x1, x1 - c}, column.wireWidth, kLowWire);
    }
  }
  Mesh& falling = AddMesh(scene, WireMeshName(column, "diagonal falling"), kCool);
  for (int k = 0;; ++k) {
    const float c = lo.x + lo.y + 0.37f + kStep * static_cast<float>(k);
    if (c >= hi.x + hi.y) break;
    const float x0 = std::max(lo.x, c - hi.y);
    const float x1 = std::min(hi.x, c - lo.y);
    if (x1 - x0 >= kShortest) {
      AddPixelStrip(falling, {x0, c - x0}, {x1, c - x1}, column.wireWidth, kHighWire);
    }
  }
}

Scene MakeFenceScene(float aspect) {
  Scene scene;
  scene.name = "fence";
  AddBackdrop(scene);
  for (std::size_t c = 0; c < kFenceColumns.size(); ++c) {
    const float left = 100.0f + 440.0f * static_cast<float>(c);
    AddGridPanel(scene, kFenceColumns[c], {left, 80.0f}, {left + 400.0f, 520.0f});
    AddChainLinkPanel(scene, kFenceColumns[c], {left, 560.0f}, {left + 400.0f, 1000.0f});
  }
  return FinishReferenceScene(std::move(scene), aspect);
}

// ---------------------------------------------------------------------------------------------
// subpixel: isolated triangles smaller than a pixel

Scene MakeSubpixelScene(float aspect) {
  constexpr int kColumns = 112;
  constexpr int kRows = 60;
  constexpr float kPitch = 16.0f;
  constexpr float kSmallest = 0.02f;  // px^2
  constexpr float kLargest = 0.9f;    // px^2
  Scene scene;
  scene.name = "subpixel";
  AddBackdrop(scene);
  Mesh& specks = AddMesh(scene, "specks", kBright);
  for (int row = 0; row < kRows; ++row) {
    for (int column = 0; column < kColumns; ++column) {
      // Area grows left to right, elongation cycles 1:1, 2:1, 3:1 down the rows, and the
      // orientation and the position inside the pixel both vary.
      const float area = kSmallest + (kLargest - kSmallest) * static_cast<float>(column) /
                                         static_cast<float>(kColumns - 1);
      const float elongation = static_cast<float>(1 + row % 3);
      const float height = std::sqrt(2.0f * area / elongation);
      const float base = elongation * height;
      const float angle = glm::radians(7.3f * static_cast<float>(row) +
                                       13.1f * static_cast<float>(column));
      const glm::vec2 centre{64.0f + kPitch * static_cast<float>(column) + Phase(column),
                             48.0f + kPitch * static_cast<float>(row) + Phase(row, 0.4142136f)};
      const glm::vec2 u{std::cos(angle), std::sin(angle)};
      const glm::vec2 v{-u.y, u.x};
      const auto at = [&](float along, float across) {
        return AtPixel(centre + u * along + v * across, kLowWire);
      };
      AddFacingTriangle(specks, at(-0.5f * base, -height / 3.0f), at(0.5f * base, -height / 3.0f),
                        at(0.0f, 2.0f * height / 3.0f), kFacingCamera);
    }
  }
  return FinishReferenceScene(std::move(scene), aspect);
}

// ---------------------------------------------------------------------------------------------
// pixel-crossing: pixels covered by three or more triangles

constexpr int kCrossingColumns = 16;
constexpr int kCrossingRows = 9;
constexpr float kCrossingPitch = 110.0f;

// Colour of triangle j of a k-triangle fan such that neighbours (including last and first)
// always differ.
int FanColour(int j, int k) { return j == k - 1 && (k - 1) % 3 == 0 ? 3 : j % 3; }

Scene MakePixelCrossingScene(float aspect) {
  Scene scene;
  scene.name = "pixel-crossing";
  AddBackdrop(scene);
  const std::size_t first = scene.meshes.size();
  for (std::size_t c = 0; c < kContrasting.size(); ++c) {
    AddMesh(scene, "crossing colour " + std::to_string(c), kContrasting[c]);
  }
  const auto coloured = [&](int colour) -> Mesh& {
    return scene.meshes[first + static_cast<std::size_t>(colour)];
  };
  for (int site = 0; site < kCrossingColumns * kCrossingRows; ++site) {
    // The hub lies strictly inside one pixel, at a different sub-pixel position per site.
    const glm::vec2 pixel{135.0f + kCrossingPitch * static_cast<float>(site % kCrossingColumns),
                          100.0f + kCrossingPitch * static_cast<float>(site / kCrossingColumns)};
    const glm::vec2 hub =
        pixel + glm::vec2(0.15f + 0.7f * Phase(site), 0.15f + 0.7f * Phase(site, 0.4142136f));
    const float start = glm::radians(11.0f * static_cast<float>(site));
    if (site % 2 == 0) {
      // A watertight fan of 3 to 8 triangles around the hub, all at one depth.
      const int k = 3 + (site / 2) % 6;
      const auto rim = [&](int j) {
        const float angle = start + 2.0f * kPi * static_cast<float>(j) / static_cast<float>(k);
        return AtPixel(hub + 7.0f * glm::vec2(std::cos(angle), std::sin(angle)), kLowWire);
      };
      for (int j = 0; j < k; ++j) {
        AddFacingTriangle(coloured(FanColour(j, k)), AtPixel(hub, kLowWire), rim(j), rim(j + 1),
                          kFacingCamera);
      }
    } else {
      // 3 to 5 slivers crossing at the hub, each at its own depth.
      const int k = 3 + (site / 2) % 3;
      for (int j = 0; j < k; ++j) {
        const float angle = start + kPi * static_cast<float>(j) / static_cast<float>(k);
        const glm::vec2 along{std::cos(angle), std::sin(angle)};
        const glm::vec2 across{-along.y, along.x};
        const float z = kLowWire + 0.01f * static_cast<float>(j);
        AddFacingTriangle(coloured(j % 4), AtPixel(hub - 18.0f * along - across, z),
                          AtPixel(hub + 18.0f * along, z), AtPixel(hub - 18.0f * along + across, z),
                          kFacingCamera);
      }
    }
  }
  return FinishReferenceScene(std::move(scene), aspect);
}

// ---------------------------------------------------------------------------------------------
// intersecting-planes: edges made by depth, not by triangle edges

// A rectangle centred on `centre` with half-extent vectors u and v, facing cross(u, v).
void AddRectangle(Mesh& mesh, const glm::vec3& centre, const glm::vec3& u, const glm::vec3& v) {
  AddQuad(mesh, {centre - u - v, centre + u - v, centre + u + v, centre - u + v},
          glm::normalize(glm::cross(u, v)));
}

glm::vec3 Tilted(float length, float degrees, const glm::vec3& level, const glm::vec3& raised) {
  const float angle = glm::radians(degrees);
  return length * (std::cos(angle) * level + std::sin(angle) * raised);
}

Scene MakeIntersectingPlanesScene(float aspect) {
  const glm::vec3 x{1.0f, 0.0f, 0.0f};
  const glm::vec3 awayZ{0.0f, 0.0f, -1.0f};
  Scene scene;
  scene.name = "intersecting-planes";
  AddRectangle(AddMesh(scene, "ground", kGrey), glm::vec3(0.0f), 2.6f * x, 2.6f * awayZ);
  // Leaning back 60 degrees through the ground.
  AddRectangle(AddMesh(scene, "leaning", kContrasting[0]), {0.0f, 0.6f, 0.2f}, 2.2f * x,
               Tilted(1.5f, 60.0f, awayZ, kUp));
  // Upright, turned 35 degrees about the vertical, through the ground and the leaning plane.
  AddRectangle(AddMesh(scene, "upright", kContrasting[1]), {0.4f, 0.9f, -0.2f},
               Tilted(2.0f, 35.0f, x, awayZ), 1.3f * kUp);
  // Two planes rising away from the camera 2 degrees apart, sharing the horizontal line
  // through (x, 1.1, 0): a long, shallow intersection where depth decides every sample.
  for (float degrees : {25.0f, 27.0f}) {
    AddRectangle(AddMesh(scene, degrees < 26.0f ? "shallow a" : "shallow b",
                         degrees < 26.0f ? kContrasting[2] : kContrasting[3]),
                 {0.0f, 1.1f, 0.0f}, 1.8f * x, Tilted(1.8f, degrees, awayZ, kUp));
  }
  // Grazing the ground at 3 degrees: a wide band where two near-coplanar surfaces cross.
  AddRectangle(AddMesh(scene, "grazing", kWarm), {0.5f, 0.0f, 1.0f}, 1.6f * x,
               Tilted(1.6f, 3.0f, awayZ, kUp));
  scene.bounds = ComputeBounds(scene.meshes);
  scene.camera = FrameBounds(scene.bounds, aspect);
  return scene;
}

// ---------------------------------------------------------------------------------------------
// wheel: thin spokes turning slowly

constexpr int kWheelSpokes = 48;
constexpr float kWheelDegreesPerFrame = 0.25f;

Scene MakeWheelScene(float aspect) {
  constexpr glm::vec2 kCentre{960.0f, 540.0f};
  constexpr float kHubRadius = 50.0f;
  constexpr float kRimInner = 400.0f;
  constexpr float kRimOuter = 430.0f;
  constexpr int kRimSegments = 120;
  constexpr int kHubSegments = 48;
  // The wheel turns about the view axis through its centre, which AtPixel puts on the z axis.
  const MeshMotion turning{.pivot = glm::vec3(0.0f),
                           .axis = kFacingCamera,
                           .degreesPerFrame = kWheelDegreesPerFrame};
  const auto onCircle = [&](float radius, float angle, float z) {
    return AtPixel(kCentre + radius * glm::vec2(std::cos(angle), std::sin(angle)), z);
  };
  Scene scene;
  scene.name = "wheel";
  AddBackdrop(scene);
  // Spokes taper from 2 px under the hub to 0.75 px under the rim, which both cover their ends.
  Mesh& spokes = AddMesh(scene, "spokes", kBright);
  for (int k = 0; k < kWheelSpokes; ++k) {
    const float angle = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(kWheelSpokes);
    const glm::vec2 along{std::cos(angle), std::sin(angle)};
    const glm::vec2 across{-along.y, along.x};
    const glm::vec2 inner = kCentre + along * (kHubRadius - 5.0f);
    const glm::vec2 outer = kCentre + along * (kRimInner + 5.0f);
    AddFacingQuad(spokes,
                  {AtPixel(inner - across, kLowWire), AtPixel(outer - 0.375f * across, kLowWire),
                   AtPixel(outer + 0.375f * across, kLowWire), AtPixel(inner + across, kLowWire)},
                  kFacingCamera);
  }
  spokes.motion = turning;
  Mesh& rim = AddMesh(scene, "rim", kWarm);
  for (int k = 0; k < kRimSegments; ++k) {
    const float a0 = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(kRimSegments);
    const float a1 = 2.0f * kPi * static_cast<float>(k + 1) / static_cast<float>(kRimSegments);
    AddFacingQuad(rim,
                  {onCircle(kRimInner, a0, kHighWire), onCircle(kRimOuter, a0, kHighWire),
                   onCircle(kRimOuter, a1, kHighWire), onCircle(kRimInner, a1, kHighWire)},
                  kFacingCamera);
  }
  rim.motion = turning;
  Mesh& hub = AddMesh(scene, "hub", kGrey);
  for (int k = 0; k < kHubSegments; ++k) {
    const float a0 = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(kHubSegments);
    const float a1 = 2.0f * kPi * static_cast<float>(k + 1) / static_cast<float>(kHubSegments);
    AddFacingTriangle(hub, AtPixel(kCentre, kHighWire), onCircle(kHubRadius, a0, kHighWire),
                      onCircle(kHubRadius, a1, kHighWire), kFacingCamera);
  }
  hub.motion = turning;
  return FinishReferenceScene(std::move(scene), aspect);
}

// ---------------------------------------------------------------------------------------------
// stair-steps: edges a little off horizontal and vertical

// Degrees off the axis, alternating in sign; 0 is the axis-aligned control.
constexpr std::array<float, 10> kStairAngles = {0.0f, 0.25f, -0.5f, 1.0f, -1.5f,
                                                2.0f, -3.0f, 4.0f,  -6.0f, 8.0f};

Scene MakeStairStepsScene(float aspect) {
  constexpr float kHalfLength = 240.0f;  // short enough that 8 and 6 degree neighbours never touch
  constexpr float kThickness = 30.0f;
  Scene scene;
  scene.name = "stair-steps";
  AddBackdrop(scene);
  Mesh& flat = AddMesh(scene, "near-horizontal bars", kBright);
  for (std::size_t i = 0; i < kStairAngles.size(); ++i) {
    const float angle = glm::radians(kStairAngles[i]);
    const glm::vec2 centre{400.0f, 90.0f + 100.0f * static_cast<float>(i)};
    const glm::vec2 along{std::cos(angle), std::sin(angle)};
    AddPixelStrip(flat, centre - along * kHalfLength, centre + along * kHalfLength, kThickness,
                  kLowWire);
  }
  Mesh& upright = AddMesh(scene, "near-vertical bars", kCool);
  for (std::size_t i = 0; i < kStairAngles.size(); ++i) {
    const float angle = glm::radians(kStairAngles[i]);
    const glm::vec2 centre{880.0f + 100.0f * static_cast<float>(i), 540.0f};
    const glm::vec2 along{std::sin(angle), std::cos(angle)};
    AddPixelStrip(upright, centre - along * kHalfLength, centre + along * kHalfLength, kThickness,
                  kLowWire);
  }
  return FinishReferenceScene(std::move(scene), aspect);
}

// ---------------------------------------------------------------------------------------------
// textured-plane: texture detail finer than the pixels

// 8x8 checks of 8x8 texels each.
Texture MakeCheckerTexture() {
  constexpr int kSize = 64;
  constexpr int kCell = 8;
  Texture texture{.name = "checker", .width = kSize, .height = kSize, .texels = {}};
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const float value = ((x / kCell + y / kCell) % 2 == 0) ? 0.9f : 0.05f;
      texture.texels.emplace_back(value, value, value, 1.0f);
    }
  }
  return texture;
}

// cos(pi r^2 / 724): the local frequency r / 724 cycles per texel grows from 0 at the centre to
// the texture's own Nyquist limit (0.5) in the corners.
Texture MakeZonePlateTexture() {
  constexpr int kSize = 512;
  Texture texture{.name = "zone plate", .width = kSize, .height = kSize, .texels = {}};
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const float dx = static_cast<float>(x) + 0.5f - 0.5f * kSize;
      const float dy = static_cast<float>(y) + 0.5f - 0.5f * kSize;
      const float wave = std::cos(kPi * (dx * dx + dy * dy) / 724.0f);
      const float value = 0.05f + 0.85f * (0.5f + 0.5f * wave);
      texture.texels.emplace_back(value, value, value, 1.0f);
    }
  }
  return texture;
}

Scene MakeTexturedPlaneScene(float) {
  Scene scene;
  scene.name = "textured-plane";
  scene.textures = {MakeCheckerTexture(), MakeZonePlateTexture()};
  scene.materials = {Material{.name = "checker floor", .baseColourTexture = 0},
                     Material{.name = "zone plate", .baseColourTexture = 1}};
  // A floor running 62 units into the distance, one texture repeat per unit: towards the
  // horizon its 0.125-unit checks are far less than a pixel deep.
  Mesh floor;
  floor.name = "checker floor";
  floor.material = 0;
  AddQuad(floor, {glm::vec3{-12.0f, 0.0f, 2.0f}, {12.0f, 0.0f, 2.0f}, {12.0f, 0.0f, -60.0f},
                  {-12.0f, 0.0f, -60.0f}},
          kUp);
  for (const glm::vec3& p : floor.positions) floor.texcoords.emplace_back(p.x, p.z);
  // An upright panel showing the zone plate at about one texel per pixel.
  Mesh panel;
  panel.name = "zone plate";
  panel.material = 1;
  AddQuad(panel, {glm::vec3{-3.0f, 0.5f, -10.0f}, {3.0f, 0.5f, -10.0f}, {3.0f, 6.5f, -10.0f},
                  {-3.0f, 6.5f, -10.0f}},
          kFacingCamera);
  panel.texcoords = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
  scene.meshes = {std::move(floor), std::move(panel)};
  return FinishWithCamera(std::move(scene), {0.0f, 1.6f, 4.0f}, {0.0f, 2.0f, -10.0f});
}

struct BuiltinScene {
  std::string_view name;
  Scene (*make)(float aspect);
};

constexpr std::array<BuiltinScene, 11> kBuiltinScenes = {
    BuiltinScene{kDefaultSceneName, &MakeDefaultScene},
    BuiltinScene{"thin-fan", &MakeThinFanScene},
    BuiltinScene{"subpixel-grid", &MakeSubpixelGridScene},
    BuiltinScene{"spike-room", &MakeSpikeRoomScene},
    BuiltinScene{"fence", &MakeFenceScene},
    BuiltinScene{"subpixel", &MakeSubpixelScene},
    BuiltinScene{"pixel-crossing", &MakePixelCrossingScene},
    BuiltinScene{"intersecting-planes", &MakeIntersectingPlanesScene},
    BuiltinScene{"wheel", &MakeWheelScene},
    BuiltinScene{"stair-steps", &MakeStairStepsScene},
    BuiltinScene{"textured-plane", &MakeTexturedPlaneScene}};

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
