// Tests of scenes/motion.h: camera paths (frame 0 is the still camera, orbits keep their
// distance, dollies change it, pans move the image by the documented pixels) and mesh motion
// (the wheel turns by its documented angle per frame; velocities are differences of frames).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "scenes/motion.h"
#include "scenes/scene.h"

namespace {

constexpr float kMotionAspect = 16.0f / 9.0f;

bool SameCamera(const scenes::Camera& a, const scenes::Camera& b) {
  return a.eye == b.eye && a.target == b.target && a.up == b.up &&
         a.verticalFovRadians == b.verticalFovRadians && a.zNear == b.zNear && a.zFar == b.zFar;
}

float AngleDegrees(const glm::vec3& a, const glm::vec3& b) {
  const float cosine = glm::dot(glm::normalize(a), glm::normalize(b));
  return std::acos(std::min(1.0f, cosine)) * 180.0f / std::numbers::pi_v<float>;
}

scenes::CameraPath Path(scenes::CameraPathKind kind) {
  scenes::CameraPath path;
  path.kind = kind;
  return path;
}

TEST(CameraPath, FrameZeroIsTheStillCameraForEveryKind) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("default", kMotionAspect);
  for (const std::string& name : scenes::CameraPathKindNames()) {
    const scenes::CameraPath path = Path(scenes::ParseCameraPathKind(name));
    EXPECT_TRUE(SameCamera(scenes::CameraAt(scene, path, 0), scene.camera)) << name;
  }
  const scenes::CameraPath still = Path(scenes::CameraPathKind::Still);
  EXPECT_TRUE(SameCamera(scenes::CameraAt(scene, still, 37), scene.camera));
}

TEST(CameraPath, OrbitKeepsDistanceAndTurnsByTheDocumentedAngle) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("default", kMotionAspect);
  const scenes::CameraPath orbit = Path(scenes::CameraPathKind::Orbit);
  EXPECT_EQ(orbit.orbitDegreesPerFrame, 0.25f);  // docs/scenes.md
  const float distance = glm::distance(scene.camera.eye, scene.camera.target);
  for (int frame : {1, 10, 360, -20}) {
    const scenes::Camera camera = scenes::CameraAt(scene, orbit, frame);
    EXPECT_NEAR(glm::distance(camera.eye, camera.target), distance, 1e-4f * distance) << frame;
    EXPECT_EQ(camera.target, scene.camera.target);
    // The turn is about the vertical: compare the horizontal components of the offsets.
    glm::vec3 before = scene.camera.eye - scene.camera.target;
    glm::vec3 after = camera.eye - camera.target;
    EXPECT_NEAR(after.y, before.y, 1e-4f * distance);
    before.y = 0.0f;
    after.y = 0.0f;
    const float expected = std::fmod(std::abs(0.25f * static_cast<float>(frame)), 360.0f);
    EXPECT_NEAR(AngleDegrees(before, after), std::min(expected, 360.0f - expected), 1e-2f)
        << frame;
    EXPECT_EQ(camera.zNear, scene.camera.zNear);
    EXPECT_EQ(camera.zFar, scene.camera.zFar);
  }
}

TEST(CameraPath, DollyChangesTheDistanceGeometricallyAndKeepsTheSceneBetweenThePlanes) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("default", kMotionAspect);
  const scenes::CameraPath dolly = Path(scenes::CameraPathKind::Dolly);
  EXPECT_EQ(dolly.dollyFractionPerFrame, 0.005f);  // docs/scenes.md
  const float start = glm::distance(scene.camera.eye, scene.camera.target);
  for (int frame : {1, 30, 100, -50}) {
    const scenes::Camera camera = scenes::CameraAt(scene, dolly, frame);
    const float expected = start * std::pow(0.995f, static_cast<float>(frame));
    EXPECT_NEAR(glm::distance(camera.eye, camera.target), expected, 1e-4f * start) << frame;
    EXPECT_NEAR(AngleDegrees(camera.target - camera.eye, scene.camera.target - scene.camera.eye),
                0.0f, 1e-2f);
    for (const scenes::Mesh& mesh : scene.meshes) {
      for (const glm::vec3& p : mesh.positions) {
        const glm::vec4 clip = camera.Projection(kMotionAspect) * camera.View() * glm::vec4(p, 1.0f);
        ASSERT_GE(clip.z, 0.0f) << frame;
        ASSERT_LE(clip.z, clip.w) << frame;
      }
    }
  }
  EXPECT_LT(glm::distance(scenes::CameraAt(scene, dolly, 10).eye, scene.camera.target), start);
}

TEST(CameraPath, PanMovesTheImageByTheDocumentedPixelsPerFrame) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("default", kMotionAspect);
  const scenes::CameraPath pan = Path(scenes::CameraPathKind::Pan);
  EXPECT_EQ(pan.panPixelsPerFrame, 0.5f);  // docs/scenes.md
  const auto pixelOf = [&](const scenes::Camera& camera, const glm::vec3& p) {
    const glm::vec4 clip = camera.Projection(kMotionAspect) * camera.View() * glm::vec4(p, 1.0f);
    return glm::vec2(clip.x / clip.w * 960.0f, -clip.y / clip.w * 540.0f);
  };
  for (int frame : {1, 8, -4}) {
    const scenes::Camera camera = scenes::CameraAt(scene, pan, frame);
    // The camera moves right, so the old target appears further left by 0.5 px per frame.
    const glm::vec2 shift =
        pixelOf(camera, scene.camera.target) - pixelOf(scene.camera, scene.camera.target);
    EXPECT_NEAR(shift.x, -0.5f * static_cast<float>(frame), 1e-3f) << frame;
    EXPECT_NEAR(shift.y, 0.0f, 1e-3f) << frame;
    EXPECT_EQ(camera.zNear, scene.camera.zNear);
  }
}

TEST(CameraPath, NamesParseAndBadPathsAreSceneErrors) {
  EXPECT_EQ(scenes::CameraPathKindNames(),
            (std::vector<std::string>{"still", "orbit", "pan", "dolly"}));
  EXPECT_EQ(scenes::ParseCameraPathKind("dolly"), scenes::CameraPathKind::Dolly);
  EXPECT_EQ(scenes::CameraPathKindName(scenes::CameraPathKind::Pan), "pan");
  try {
    scenes::ParseCameraPathKind("spin");
    ADD_FAILURE() << "spin parsed";
  } catch (const scenes::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("still, orbit, pan, dolly"), std::string::npos);
  }
  const scenes::Scene scene = scenes::MakeBuiltinScene("thin-fan", kMotionAspect);
  scenes::CameraPath dolly = Path(scenes::CameraPathKind::Dolly);
  dolly.dollyFractionPerFrame = 1.0f;
  EXPECT_THROW(scenes::CameraAt(scene, dolly, 1), scenes::SceneError);
  scenes::CameraPath orbit = Path(scenes::CameraPathKind::Orbit);
  orbit.orbitDegreesPerFrame = std::nanf("");
  EXPECT_THROW(scenes::CameraAt(scene, orbit, 1), scenes::SceneError);
}

// ---------------------------------------------------------------------------------------------
// Mesh motion

TEST(MeshMotion, WheelTurnsByAQuarterDegreePerFrame) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("wheel", kMotionAspect);
  std::size_t spokes = scene.meshes.size();
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    if (scene.meshes[m].name == "spokes") spokes = m;
  }
  ASSERT_LT(spokes, scene.meshes.size());
  const glm::vec3 tip = scene.meshes[spokes].positions[1];
  for (int frame : {0, 1, 4, 100, -8}) {
    const std::vector<glm::mat4> transforms = scenes::MeshTransformsAt(scene, frame);
    ASSERT_EQ(transforms.size(), scene.meshes.size());
    const glm::vec3 moved = glm::vec3(transforms[spokes] * glm::vec4(tip, 1.0f));
    EXPECT_NEAR(moved.z, tip.z, 1e-6f);
    // Counter-clockwise about +z (towards the camera) for positive frames.
    const float turned = std::atan2(moved.y, moved.x) - std::atan2(tip.y, tip.x);
    EXPECT_NEAR(std::remainder(turned * 180.0f / std::numbers::pi_v<float>, 360.0f), 0.25f * static_cast<float>(frame),
                1e-3f)
        << frame;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      if (scene.meshes[m].motion.IsStatic()) {
        EXPECT_EQ(transforms[m], glm::mat4(1.0f));
      }
    }
  }
}

TEST(MeshMotion, VelocitiesAreTheDifferenceOfTwoFrames) {
  const scenes::Scene scene = scenes::MakeBuiltinScene("wheel", kMotionAspect);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const std::vector<glm::vec3> velocities = scenes::VertexVelocities(scene, m, 5);
    ASSERT_EQ(velocities.size(), scene.meshes[m].positions.size());
    for (std::size_t v = 0; v < velocities.size(); ++v) {
      const glm::vec3 p = scene.meshes[m].positions[v];
      // A point at radius r on a wheel turning 0.25 degrees moves 2 r sin(0.125 degrees).
      const float radius = glm::length(glm::vec2(p));
      const float expected = scene.meshes[m].motion.IsStatic()
                                 ? 0.0f
                                 : 2.0f * radius * std::sin(0.125f * std::numbers::pi_v<float> / 180.0f);
      ASSERT_NEAR(glm::length(velocities[v]), expected, 1e-5f) << scene.meshes[m].name;
    }
  }
}

TEST(MeshMotion, SceneAtMovesMeshesAndRebasesTheirMotion) {
  scenes::Scene scene = scenes::MakeBuiltinScene("thin-fan", kMotionAspect);
  scene.meshes[0].motion = {.pivot = {1, 0, 0},
                            .axis = {0, 1, 0},
                            .degreesPerFrame = 3.0f,
                            .unitsPerFrame = {0, 0.5f, 0}};
  const scenes::CameraPath orbit = Path(scenes::CameraPathKind::Orbit);
  const scenes::Scene at5 = scenes::SceneAt(scene, orbit, 5);
  const scenes::Scene at2then3 = scenes::SceneAt(scenes::SceneAt(scene, orbit, 2), orbit, 3);
  const glm::mat4 direct = scenes::MeshTransformAt(scene.meshes[0].motion, 5);
  for (std::size_t v = 0; v < scene.meshes[0].positions.size(); v += 17) {
    const glm::vec3 expected = glm::vec3(direct * glm::vec4(scene.meshes[0].positions[v], 1.0f));
    EXPECT_NEAR(glm::distance(at5.meshes[0].positions[v], expected), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(at2then3.meshes[0].positions[v], expected), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(at5.meshes[0].normals[v]), 1.0f, 1e-5f);
  }
  EXPECT_NEAR(at5.bounds.max.y, scene.bounds.max.y + 2.5f, 1e-4f);
  EXPECT_TRUE(SameCamera(at5.camera, scenes::CameraAt(scene, orbit, 5)));
}

}  // namespace
