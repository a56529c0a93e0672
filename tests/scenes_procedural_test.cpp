// Tests of the procedural stress scenes: each builds finite, consistent data and has the property
// its name promises, measured in pixels of the default 1920x1080 view through the scene's own
// camera (wire widths, triangle areas, pixels crossed by several triangles, edge slopes).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "scenes/scene.h"
#include "scenes/shading.h"

namespace {

constexpr float kProceduralWidth = 1920.0f;
constexpr float kProceduralHeight = 1080.0f;
constexpr float kProceduralAspect = kProceduralWidth / kProceduralHeight;

const std::vector<std::string> kStressScenes = {"spike-room",          "fence", "subpixel",
                                                "pixel-crossing",      "wheel", "stair-steps",
                                                "intersecting-planes", "textured-plane"};

// Pixel coordinates in the 1920x1080 image: origin top-left, y down.
glm::vec2 ToPixel(const scenes::Camera& camera, const glm::vec3& p) {
  const glm::vec4 clip = camera.Projection(kProceduralAspect) * camera.View() * glm::vec4(p, 1.0f);
  return {(clip.x / clip.w * 0.5f + 0.5f) * kProceduralWidth, (0.5f - clip.y / clip.w * 0.5f) * kProceduralHeight};
}

struct ScreenTriangle {
  std::array<glm::vec2, 3> corners;
  float Area() const {
    const glm::vec2 u = corners[1] - corners[0];
    const glm::vec2 v = corners[2] - corners[0];
    return 0.5f * std::abs(u.x * v.y - u.y * v.x);
  }
  bool Contains(const glm::vec2& p) const {
    float sign = 0.0f;
    for (int k = 0; k < 3; ++k) {
      const glm::vec2 a = corners[static_cast<std::size_t>(k)];
      const glm::vec2 b = corners[static_cast<std::size_t>((k + 1) % 3)];
      const float side = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      if (side == 0.0f) continue;
      if (sign == 0.0f) sign = side;
      if ((side > 0.0f) != (sign > 0.0f)) return false;
    }
    return true;
  }
};

std::vector<ScreenTriangle> ScreenTriangles(const scenes::Scene& scene, const scenes::Mesh& mesh) {
  std::vector<ScreenTriangle> triangles;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    ScreenTriangle triangle;
    for (std::size_t k = 0; k < 3; ++k) {
      triangle.corners[k] = ToPixel(scene.camera, mesh.positions[mesh.indices[t + k]]);
    }
    triangles.push_back(triangle);
  }
  return triangles;
}

// A quad of four consecutive vertices (two triangles) seen on screen: its long side and the
// width across it.
struct ScreenStrip {
  float length;
  float width;
  glm::vec2 direction;  // along the long side
};

std::vector<ScreenStrip> ScreenStrips(const scenes::Scene& scene, const scenes::Mesh& mesh) {
  std::vector<ScreenStrip> strips;
  const std::vector<ScreenTriangle> triangles = ScreenTriangles(scene, mesh);
  for (std::size_t q = 0; q + 3 < mesh.positions.size(); q += 4) {
    std::array<glm::vec2, 4> p;
    for (std::size_t k = 0; k < 4; ++k) p[k] = ToPixel(scene.camera, mesh.positions[q + k]);
    const glm::vec2 side0 = p[1] - p[0];
    const glm::vec2 side1 = p[2] - p[1];
    const glm::vec2 along = glm::length(side0) > glm::length(side1) ? side0 : side1;
    const float area = triangles[q / 2].Area() + triangles[q / 2 + 1].Area();
    strips.push_back({glm::length(along), area / glm::length(along), glm::normalize(along)});
  }
  return strips;
}

const scenes::Mesh& MeshNamed(const scenes::Scene& scene, const std::string& name) {
  for (const scenes::Mesh& mesh : scene.meshes) {
    if (mesh.name == name) return mesh;
  }
  ADD_FAILURE() << scene.name << " has no mesh '" << name << "'";
  return scene.meshes.front();
}

bool IsFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Angle of a screen direction in degrees, folded to [0, 180).
float DirectionDegrees(const glm::vec2& d) {
  float degrees = std::atan2(d.y, d.x) * 180.0f / std::numbers::pi_v<float>;
  if (degrees < 0.0f) degrees += 180.0f;
  return degrees >= 180.0f ? degrees - 180.0f : degrees;
}

// ---------------------------------------------------------------------------------------------
// Every stress scene

TEST(ProceduralScenes, BuildFiniteConsistentData) {
  for (const std::string& name : kStressScenes) {
    const scenes::Scene scene = scenes::LoadScene("builtin:" + name, kProceduralAspect);
    EXPECT_EQ(scene.name, name);
    EXPECT_GT(scene.TriangleCount(), 0u) << name;
    for (const scenes::Mesh& mesh : scene.meshes) {
      ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << name << " " << mesh.name;
      EXPECT_TRUE(mesh.texcoords.empty() || mesh.texcoords.size() == mesh.positions.size());
      ASSERT_EQ(mesh.indices.size() % 3, 0u);
      for (std::uint32_t index : mesh.indices) ASSERT_LT(index, mesh.positions.size());
      for (const glm::vec3& p : mesh.positions) ASSERT_TRUE(IsFinite(p)) << name;
      for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f) << name;
      // Every mesh has a material of its own colour, so edges between meshes have contrast.
      ASSERT_GE(mesh.material, 0) << name << " " << mesh.name;
      ASSERT_LT(mesh.material, static_cast<int>(scene.materials.size()));
    }
    for (const scenes::Texture& texture : scene.textures) {
      EXPECT_EQ(texture.texels.size(), static_cast<std::size_t>(texture.width * texture.height));
    }
  }
}

// Back faces are culled by default, so every triangle must wind counter-clockwise on screen and
// agree with its vertex normals.
TEST(ProceduralScenes, EveryTriangleFacesTheCameraAndItsNormals) {
  for (const std::string& name : kStressScenes) {
    const scenes::Scene scene = scenes::MakeBuiltinScene(name, kProceduralAspect);
    for (const scenes::Mesh& mesh : scene.meshes) {
      for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]];
        const glm::vec3 b = mesh.positions[mesh.indices[t + 1]];
        const glm::vec3 c = mesh.positions[mesh.indices[t + 2]];
        ASSERT_GT(glm::dot(glm::cross(b - a, c - a), mesh.normals[mesh.indices[t]]), 0.0f)
            << name << " " << mesh.name << " triangle " << t / 3;
        const glm::vec2 pa = ToPixel(scene.camera, a);
        const glm::vec2 pb = ToPixel(scene.camera, b);
        const glm::vec2 pc = ToPixel(scene.camera, c);
        // y points down in pixels, so counter-clockwise on screen is a negative cross product.
        const float winding = (pb.x - pa.x) * (pc.y - pa.y) - (pb.y - pa.y) * (pc.x - pa.x);
        ASSERT_LT(winding, 0.0f) << name << " " << mesh.name << " triangle " << t / 3;
      }
    }
  }
}

TEST(ProceduralScenes, PixelScenesPlaceTheirBackdropExactlyInPixels) {
  for (const char* name : {"fence", "subpixel", "pixel-crossing", "wheel", "stair-steps"}) {
    const scenes::Scene scene = scenes::MakeBuiltinScene(name, kProceduralAspect);
    const scenes::Mesh& backdrop = MeshNamed(scene, "backdrop");
    glm::vec2 lo(1e9f);
    glm::vec2 hi(-1e9f);
    for (const glm::vec3& p : backdrop.positions) {
      lo = glm::min(lo, ToPixel(scene.camera, p));
      hi = glm::max(hi, ToPixel(scene.camera, p));
    }
    EXPECT_NEAR(glm::distance(lo, glm::vec2(40, 20)), 0.0f, 2e-3f) << name;
    EXPECT_NEAR(glm::distance(hi, glm::vec2(1880, 1060)), 0.0f, 2e-3f) << name;
  }
}

TEST(ProceduralScenes, NarrowerImagesStillShowThePixelScenesWhole) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("fence", 4.0f / 3.0f);
  for (const scenes::Mesh& mesh : scene.meshes) {
    for (const glm::vec3& p : mesh.positions) {
      const glm::vec4 clip = scene.camera.Projection(4.0f / 3.0f) * scene.camera.View() *
                             glm::vec4(p, 1.0f);
      ASSERT_LE(std::abs(clip.x), clip.w);
      ASSERT_LE(std::abs(clip.y), clip.w);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// What each name promises

TEST(ProceduralScenes, SpikeRoomHasLongThinSpikesAtEverySlope) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("spike-room", kProceduralAspect);
  std::set<int> tenDegreeBins;
  std::size_t spikes = 0;
  for (const char* name : {"spikes light", "spikes red"}) {
    for (const ScreenTriangle& triangle : ScreenTriangles(scene, MeshNamed(scene, name))) {
      ++spikes;
      // The apex is the corner farthest from the other two; the base is short.
      std::array<float, 3> sides{};
      for (std::size_t k = 0; k < 3; ++k) {
        sides[k] = glm::distance(triangle.corners[k], triangle.corners[(k + 1) % 3]);
      }
      const float longest = *std::max_element(sides.begin(), sides.end());
      const float shortest = *std::min_element(sides.begin(), sides.end());
      EXPECT_GT(longest / shortest, 15.0f) << "spike " << spikes;
      const glm::vec2 baseMiddle = 0.5f * (triangle.corners[0] + triangle.corners[2]);
      const float degrees = DirectionDegrees(triangle.corners[1] - baseMiddle);
      tenDegreeBins.insert(static_cast<int>(degrees / 10.0f));
    }
  }
  EXPECT_EQ(spikes, 72u + 36u + 40u);
  EXPECT_EQ(tenDegreeBins.size(), 18u);  // every slope, in 10-degree steps
}

TEST(ProceduralScenes, FenceWiresAreOnePixelWideAndThinner) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("fence", kProceduralAspect);
  const std::map<std::string, float> widths = {
      {"1px", 1.0f}, {"0.5px", 0.5f}, {"0.25px", 0.25f}, {"0.1px", 0.1f}};
  std::size_t wires = 0;
  for (const auto& [label, width] : widths) {
    for (const char* family :
         {"vertical", "horizontal", "diagonal rising", "diagonal falling"}) {
      const scenes::Mesh& mesh = MeshNamed(scene, "wires " + label + " " + family);
      const std::vector<ScreenStrip> strips = ScreenStrips(scene, mesh);
      EXPECT_GT(strips.size(), 40u) << label << " " << family;
      for (const ScreenStrip& strip : strips) {
        ++wires;
        EXPECT_NEAR(strip.width, width, 1e-3f) << label << " " << family;
        EXPECT_LE(strip.width, 1.0f + 1e-3f);
        EXPECT_GT(strip.length, 2.0f);
      }
    }
  }
  EXPECT_GT(wires, 1000u);
}

TEST(ProceduralScenes, SubpixelTrianglesAreSmallerThanAPixel) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("subpixel", kProceduralAspect);
  const std::vector<ScreenTriangle> specks = ScreenTriangles(scene, MeshNamed(scene, "specks"));
  EXPECT_EQ(specks.size(), 112u * 60u);
  float smallest = 1.0f;
  float largest = 0.0f;
  for (const ScreenTriangle& triangle : specks) {
    smallest = std::min(smallest, triangle.Area());
    largest = std::max(largest, triangle.Area());
  }
  EXPECT_NEAR(smallest, 0.02f, 1e-3f);
  EXPECT_NEAR(largest, 0.9f, 1e-3f);
  EXPECT_LT(largest, 1.0f);
}

// Counts, per pixel, the triangles that cover at least one of 16x16 points spread over it.
TEST(ProceduralScenes, PixelCrossingHasManyPixelsCoveredByThreeOrMoreTriangles) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("pixel-crossing", kProceduralAspect);
  std::map<std::pair<int, int>, int> trianglesPerPixel;
  std::size_t triangles = 0;
  for (const scenes::Mesh& mesh : scene.meshes) {
    if (mesh.name == "backdrop") continue;
    for (const ScreenTriangle& triangle : ScreenTriangles(scene, mesh)) {
      ++triangles;
      const std::array<glm::vec2, 3>& c = triangle.corners;
      const glm::vec2 lo = glm::min(c[0], glm::min(c[1], c[2]));
      const glm::vec2 hi = glm::max(c[0], glm::max(c[1], c[2]));
      for (int y = static_cast<int>(std::floor(lo.y)); y <= static_cast<int>(hi.y); ++y) {
        for (int x = static_cast<int>(std::floor(lo.x)); x <= static_cast<int>(hi.x); ++x) {
          bool covers = false;
          for (int s = 0; s < 256 && !covers; ++s) {
            const glm::vec2 point =
                glm::vec2(static_cast<float>(x), static_cast<float>(y)) +
                (glm::vec2(static_cast<float>(s % 16), static_cast<float>(s / 16)) + 0.5f) / 16.0f;
            covers = triangle.Contains(point);
          }
          if (covers) ++trianglesPerPixel[{x, y}];
        }
      }
    }
  }
  std::size_t crowded = 0;
  int most = 0;
  for (const auto& [pixel, count] : trianglesPerPixel) {
    crowded += count >= 3 ? 1 : 0;
    most = std::max(most, count);
  }
  EXPECT_GT(triangles, 500u);
  EXPECT_GE(crowded, 144u);  // at least the hub pixel of every one of the 16x9 sites
  EXPECT_GE(most, 8);        // the 8-triangle fans
}

// Segment-triangle intersection: does an edge of one plane pierce a triangle of the other?
bool EdgePierces(const glm::vec3& p, const glm::vec3& q, const glm::vec3& a, const glm::vec3& b,
                 const glm::vec3& c) {
  const glm::vec3 normal = glm::cross(b - a, c - a);
  const float dp = glm::dot(p - a, normal);
  const float dq = glm::dot(q - a, normal);
  if ((dp > 0.0f) == (dq > 0.0f)) return false;
  const glm::vec3 hit = p + (q - p) * (dp / (dp - dq));
  const std::array<glm::vec3, 3> corners = {a, b, c};
  for (std::size_t k = 0; k < 3; ++k) {
    const glm::vec3 edge = corners[(k + 1) % 3] - corners[k];
    if (glm::dot(glm::cross(edge, hit - corners[k]), normal) < 0.0f) return false;
  }
  return true;
}

bool MeshesIntersect(const scenes::Mesh& first, const scenes::Mesh& second) {
  for (const auto& [edges, faces] : {std::pair{&first, &second}, std::pair{&second, &first}}) {
    for (std::size_t e = 0; e + 2 < edges->indices.size(); e += 3) {
      for (std::size_t k = 0; k < 3; ++k) {
        const glm::vec3 p = edges->positions[edges->indices[e + k]];
        const glm::vec3 q = edges->positions[edges->indices[e + (k + 1) % 3]];
        for (std::size_t f = 0; f + 2 < faces->indices.size(); f += 3) {
          if (EdgePierces(p, q, faces->positions[faces->indices[f]],
                          faces->positions[faces->indices[f + 1]],
                          faces->positions[faces->indices[f + 2]])) {
            return true;
          }
        }
      }
    }
  }
  return false;
}

TEST(ProceduralScenes, IntersectingPlanesCrossEachOther) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("intersecting-planes", kProceduralAspect);
  ASSERT_EQ(scene.meshes.size(), 6u);
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    int crossings = 0;
    for (std::size_t j = 0; j < scene.meshes.size(); ++j) {
      if (i != j && MeshesIntersect(scene.meshes[i], scene.meshes[j])) ++crossings;
    }
    EXPECT_GE(crossings, 2) << scene.meshes[i].name;
  }
  EXPECT_TRUE(MeshesIntersect(MeshNamed(scene, "shallow a"), MeshNamed(scene, "shallow b")));
  EXPECT_TRUE(MeshesIntersect(MeshNamed(scene, "grazing"), MeshNamed(scene, "ground")));
  const float shallow = std::acos(glm::dot(MeshNamed(scene, "shallow a").normals[0],
                                           MeshNamed(scene, "shallow b").normals[0]));
  EXPECT_NEAR(shallow * 180.0f / std::numbers::pi_v<float>, 2.0f, 1e-2f);
}

TEST(ProceduralScenes, WheelHasThinSpokesAndTurnsAsDocumented) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("wheel", kProceduralAspect);
  const std::vector<ScreenStrip> spokes = ScreenStrips(scene, MeshNamed(scene, "spokes"));
  EXPECT_EQ(spokes.size(), 48u);
  for (const ScreenStrip& spoke : spokes) {
    EXPECT_LT(spoke.width, 2.0f);
    EXPECT_GT(spoke.length, 350.0f);
  }
  for (const char* part : {"spokes", "rim", "hub"}) {
    const scenes::MeshMotion& motion = MeshNamed(scene, part).motion;
    EXPECT_EQ(motion.degreesPerFrame, 0.25f) << part;  // docs/scenes.md
    EXPECT_EQ(motion.axis, glm::vec3(0, 0, 1)) << part;
  }
  EXPECT_TRUE(MeshNamed(scene, "backdrop").motion.IsStatic());
}

TEST(ProceduralScenes, StairStepsCoverNearHorizontalAndNearVerticalSlopes) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("stair-steps", kProceduralAspect);
  const std::vector<float> expected = {0.0f, 0.25f, 0.5f, 1.0f, 1.5f, 2.0f, 3.0f, 4.0f, 6.0f, 8.0f};
  for (const auto& [name, axisDegrees] :
       {std::pair{"near-horizontal bars", 0.0f}, std::pair{"near-vertical bars", 90.0f}}) {
    std::vector<float> offAxis;
    for (const ScreenStrip& bar : ScreenStrips(scene, MeshNamed(scene, name))) {
      float off = DirectionDegrees(bar.direction) - axisDegrees;
      if (off > 90.0f) off -= 180.0f;
      offAxis.push_back(std::abs(off));
      EXPECT_GT(bar.length, 400.0f);
    }
    std::sort(offAxis.begin(), offAxis.end());
    ASSERT_EQ(offAxis.size(), expected.size()) << name;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      EXPECT_NEAR(offAxis[i], expected[i], 1e-3f) << name;
    }
  }
}

TEST(ProceduralScenes, TexturedPlaneHasTexcoordsAndDetailFinerThanAPixel) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("textured-plane", kProceduralAspect);
  ASSERT_EQ(scene.textures.size(), 2u);
  for (const scenes::Mesh& mesh : scene.meshes) {
    EXPECT_EQ(mesh.texcoords.size(), mesh.positions.size());
    const scenes::Material& material = scene.materials.at(static_cast<std::size_t>(mesh.material));
    EXPECT_GE(material.baseColourTexture, 0);
  }
  // Checks alternate dark and light every 8 texels, and the zone plate reaches the texture's
  // own Nyquist frequency (neighbouring texels far apart) in its corners.
  const scenes::Texture& checker = scene.textures[0];
  EXPECT_GT(checker.texels[0].r - checker.texels[8].r, 0.8f);
  const scenes::Texture& zone = scene.textures[1];
  const auto steepest = [&](std::size_t first) {
    float largest = 0.0f;
    for (std::size_t x = first; x < first + 16; ++x) {
      largest = std::max(largest, std::abs(zone.texels[x].r - zone.texels[x + 1].r));
    }
    return largest;
  };
  EXPECT_GT(steepest(0), 0.5f);                // the top-left corner
  EXPECT_LT(steepest(256 * 512 + 248), 0.01f);  // the centre
  // Shading through BaseColour samples the texture: two points one check apart differ.
  const glm::vec4 dark = scenes::BaseColour(scene, 0, {0.5f / 64.0f, 0.5f / 64.0f});
  const glm::vec4 light = scenes::BaseColour(scene, 0, {8.5f / 64.0f, 0.5f / 64.0f});
  EXPECT_GT(std::abs(dark.r - light.r), 0.8f);
  // Near the far end of the floor a check (0.125 units) is a fraction of a pixel deep.
  const float check = glm::distance(ToPixel(scene.camera, {0.0f, 0.0f, -59.0f}),
                                    ToPixel(scene.camera, {0.0f, 0.0f, -59.125f}));
  EXPECT_LT(check, 0.2f);
  EXPECT_GT(check, 0.01f);
}

}  // namespace
