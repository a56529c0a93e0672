// Multi-frame runs (study/sequence.h, the sequence part of study.h): each frame is drawn with its
// schedule's pattern and carries its jitter, velocities follow the camera path exactly, and a
// whole sequence study gives bit-identical images, scores and counters on 1 and 2 threads.

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <oneapi/tbb/global_control.h>

#include "passes/registry.h"
#include "scenes/motion.h"
#include "study/study.h"

namespace study {
namespace {

constexpr int kStudyWidth = 64, kStudyHeight = 48;

SequenceConfig Frames(int frames) {
  SequenceConfig config;
  config.frames = frames;
  return config;
}

sim::FrameSettings StudySettings() {
  sim::FrameSettings settings;
  settings.width = kStudyWidth;
  settings.height = kStudyHeight;
  settings.eqaa = {1, 1, 1};
  settings.pattern = raster::MakeBuiltinPattern("centre", 1);
  return settings;
}

struct Loaded {
  scenes::Scene scene;
  FrameScene frame;
};

Loaded Load(const std::string& name) {
  const float aspect = float(kStudyWidth) / float(kStudyHeight);
  Loaded loaded{scenes::LoadScene(name, aspect), {}};
  loaded.frame = ToFrameScene(loaded.scene, aspect);
  return loaded;
}

TEST(SequenceRenderer, EachFrameUsesItsSchedulePatternAndReportsItsJitter) {
  const Loaded wheel = Load("builtin:wheel");
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  const raster::JitterSchedule schedule = raster::JitterSchedule::Make("halton8", StudySettings().pattern);
  SequenceRenderer renderer(machine, wheel.scene, wheel.frame, StudySettings(), schedule, Frames(3));
  for (int frame = 0; frame < 3; ++frame) {
    renderer.Render(frame);
    const passes::FrameInputs inputs = renderer.Inputs();
    EXPECT_EQ(inputs.frameIndex, frame);
    EXPECT_EQ(*inputs.pattern, schedule.At(frame));
    const raster::SampleOffset offset = schedule.At(frame).Offset(0, 0);
    EXPECT_EQ(inputs.jitter, glm::vec2(float(offset.x), float(offset.y)) / 16.0f);
    EXPECT_DOUBLE_EQ(inputs.frameSeconds, 1.0 / 60.0);
    // The wheel turns: its pixels move, the background does not.
    float fastest = 0.0f;
    for (int y = 0; y < kStudyHeight; ++y) {
      for (int x = 0; x < kStudyWidth; ++x) {
        const glm::vec2 v = inputs.velocity->At(x, y);
        if (inputs.objectId->At(x, y) == sim::kNoObject) {
          EXPECT_EQ(v, glm::vec2(0.0f));
        } else {
          fastest = std::max(fastest, std::abs(v.x) + std::abs(v.y));
        }
      }
    }
    EXPECT_GT(fastest, 0.0f) << "frame " << frame;
  }
  EXPECT_THROW(renderer.Render(-1), std::invalid_argument);
}

// Panning by one pixel per frame at the target's depth moves what lies at that depth by one pixel:
// exactly at the image centre (the target), within 2% elsewhere on the panel, whose plane is
// tilted ~1.6 degrees from the view plane (scenes/procedural.cpp's camera looks slightly up).
TEST(SequenceRenderer, PanVelocityIsThePathsPixelsPerFrame) {
  const Loaded plane = Load("builtin:textured-plane");
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  SequenceConfig config = Frames(2);
  config.cameraPath = {.kind = scenes::CameraPathKind::Pan, .panPixelsPerFrame = 1.0f, .panImageHeight = kStudyHeight};
  SequenceRenderer renderer(machine, plane.scene, plane.frame, StudySettings(),
                            raster::JitterSchedule::Make("none", StudySettings().pattern), config);
  renderer.Render(1);
  const passes::FrameInputs inputs = renderer.Inputs();
  int panelPixels = 0;
  for (int y = 0; y < kStudyHeight; ++y) {
    for (int x = 0; x < kStudyWidth; ++x) {
      if (inputs.objectId->At(x, y) != 1) continue;  // the zone-plate panel, at the target's depth
      ++panelPixels;
      EXPECT_NEAR(inputs.velocity->At(x, y).x, -1.0f, 0.02f) << x << "," << y;
      EXPECT_NEAR(inputs.velocity->At(x, y).y, 0.0f, 1e-3f) << x << "," << y;
    }
  }
  EXPECT_GT(panelPixels, 50);
  ASSERT_EQ(inputs.objectId->At(kStudyWidth / 2, kStudyHeight / 2), 1u);
  EXPECT_NEAR(inputs.velocity->At(kStudyWidth / 2, kStudyHeight / 2).x, -1.0f, 1e-3f);
}

// A one-sample pattern with sample-rate shading is a jittered projection: the frame equals the
// scene moved by minus the jitter and drawn at pixel centres, textures included, up to the two
// routes' different vertex snapping (1/256 px); compared on the zone-plate panel (about a texel a
// pixel), not on the floor, whose texels near the horizon are far smaller than the snapping step.
// With centroid shading the texture does not follow the jitter.
TEST(SampleRateShading, AMovedSampleShadesLikeAJitteredProjection) {
  const Loaded plane = Load("builtin:textured-plane");
  const raster::SamplePattern jittered = raster::MakeBuiltinPattern("halton:2", 1);
  const raster::SampleOffset offset = jittered.Offset(0, 0);
  ASSERT_NE(offset, (raster::SampleOffset{0, 0}));
  FrameScene moved = plane.frame;
  for (glm::vec4& p : moved.clip.positions) {
    p.x -= 2.0f * (static_cast<float>(offset.x) / 16.0f) / kStudyWidth * p.w;
    p.y += 2.0f * (static_cast<float>(offset.y) / 16.0f) / kStudyHeight * p.w;
  }
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  auto render = [&](const FrameScene& scene, const raster::SamplePattern& pattern, bool sampleRate) {
    sim::FrameSettings settings = StudySettings();
    settings.pattern = pattern;
    settings.sampleRateShading = sampleRate;
    sim::FramePipeline pipeline(machine, settings);
    pipeline.Render(scene.Geometry());
    return std::make_pair(std::vector<glm::vec4>(pipeline.Colour().Texels().begin(), pipeline.Colour().Texels().end()),
                          std::vector<std::uint32_t>(pipeline.ObjectId().Texels().begin(), pipeline.ObjectId().Texels().end()));
  };
  const auto reference = render(moved, raster::MakeBuiltinPattern("centre", 1), false);
  const auto sampleRate = render(plane.frame, jittered, true);
  const auto centroid = render(plane.frame, jittered, false);
  float worstSampleRate = 0.0f, worstCentroid = 0.0f;
  for (int y = 1; y + 1 < kStudyHeight; ++y) {
    for (int x = 1; x + 1 < kStudyWidth; ++x) {
      // Interior pixels: the same object in the pixel and its 8 neighbours in both routes.
      const std::size_t i = std::size_t(y) * kStudyWidth + std::size_t(x);
      bool interior = true;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const std::size_t j = std::size_t(y + dy) * kStudyWidth + std::size_t(x + dx);
          interior = interior && reference.second[j] == reference.second[i] && sampleRate.second[j] == reference.second[i];
        }
      }
      if (!interior || reference.second[i] != 1) continue;  // the zone-plate panel
      for (int c = 0; c < 3; ++c) {
        worstSampleRate = std::max(worstSampleRate, std::abs(sampleRate.first[i][c] - reference.first[i][c]));
        worstCentroid = std::max(worstCentroid, std::abs(centroid.first[i][c] - reference.first[i][c]));
      }
    }
  }
  EXPECT_LT(worstSampleRate, 2e-3f);
  EXPECT_GT(worstCentroid, 2e-2f);
  sim::FrameSettings multi = StudySettings();
  multi.eqaa = {2, 2, 2};
  multi.pattern = raster::MakeBuiltinPattern("standard", 2);
  multi.sampleRateShading = true;
  EXPECT_THROW(sim::FramePipeline(machine, multi), std::invalid_argument);
}

// With seed 000's half-resolution 8-bit buffer, passes read decoded velocities and the pack is a
// dispatch of the frame.
TEST(SequenceRenderer, PackedVelocityBuffersReachThePasses) {
  const Loaded wheel = Load("builtin:wheel");
  sim::Machine machine(sim::GpuConfigByName("ps4-class"));
  SequenceConfig config = Frames(2);
  config.velocityBuffer = VelocityBuffer::Rg8Half;
  SequenceRenderer renderer(machine, wheel.scene, wheel.frame, StudySettings(),
                            raster::JitterSchedule::Make("none", StudySettings().pattern), config);
  machine.ClearReports();
  renderer.Render(1);
  EXPECT_EQ(machine.Reports().back().name, "frame/velocity-pack");
  const passes::FrameInputs inputs = renderer.Inputs();
  ASSERT_NE(inputs.velocity, &renderer.Pipeline().Velocity());
  bool moving = false;
  for (const glm::vec2& v : inputs.velocity->Texels()) {
    EXPECT_EQ(v.x, DecodeVelocityComponent(EncodeVelocityComponent(v.x)));
    moving = moving || v != glm::vec2(0.0f);
  }
  EXPECT_TRUE(moving);
}

// By default a sequence follows the temporal passes only; a list names the passes it follows.
TEST(SequenceStudy, FollowsTheTemporalPassesUnlessTold) {
  SequenceConfig config;
  const passes::PassInfo& smaa = passes::PassByName("smaa").info();
  const passes::PassInfo& taa = passes::PassByName("taa-ue4").info();
  EXPECT_FALSE(Follows(config, smaa));
  EXPECT_TRUE(Follows(config, taa));
  config.followed = std::vector<std::string>{"smaa"};
  EXPECT_TRUE(Follows(config, smaa));
  EXPECT_FALSE(Follows(config, taa));
}

ExperimentConfig SequenceExperiment() {
  ExperimentConfig config;
  config.scene = "builtin:wheel";
  config.gpu = "ps4-class";
  config.width = kStudyWidth;
  config.height = kStudyHeight;
  config.modes = {{1, 1, 1}};
  config.resolves = {};
  config.passes = {passes::ResolvePass("copy"), passes::ResolvePass("smaa")};
  config.groundTruth.samplesPerPixel = 4;
  config.sequence.frames = 3;
  config.sequence.cameraPath.kind = scenes::CameraPathKind::Orbit;
  config.sequence.followed = std::vector<std::string>{"copy", "smaa"};
  return config;
}

struct StudySequenceRun {
  Study study;
  std::map<std::string, std::vector<std::vector<glm::vec4>>> images;  // per track folder, per frame
};

StudySequenceRun RunWithThreads(int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const ExperimentConfig config = SequenceExperiment();
  StudySequenceRun run;
  StudyObserver observer;
  observer.sequenceImage = [&](const SequenceGroup*, const SequenceTrack* track, int, const sim::Texture2D<glm::vec4>& image) {
    run.images[track ? track->folder : "truth"].emplace_back(image.Texels().begin(), image.Texels().end());
  };
  run.study = RunStudy(LoadStudyInputs(config), config, observer);
  return run;
}

bool SameCounters(const SequenceFrameCounters& a, const SequenceFrameCounters& b) {
  return a.lanes == b.lanes && a.dispatches == b.dispatches && a.dramBytes == b.dramBytes &&
         a.historyBytes == b.historyBytes && a.estimatedMicroseconds == b.estimatedMicroseconds;
}

TEST(SequenceStudy, OneAndTwoThreadsGiveTheSameSequence) {
  const StudySequenceRun one = RunWithThreads(1), two = RunWithThreads(2);
  ASSERT_TRUE(one.study.sequence && two.study.sequence);
  EXPECT_EQ(one.images, two.images);
  const StudySequence &a = *one.study.sequence, &b = *two.study.sequence;
  ASSERT_EQ(a.groups.size(), 1u);  // copy and smaa read the same unjittered frames
  ASSERT_EQ(a.groups[0].tracks.size(), 3u);
  EXPECT_EQ(a.groups[0].groundTruthFlicker.size(), 3u);
  for (std::size_t t = 0; t < a.groups[0].tracks.size(); ++t) {
    const SequenceTrack &x = a.groups[0].tracks[t], &y = b.groups[0].tracks[t];
    EXPECT_EQ(x.quality.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(x.quality[k].flip, y.quality[k].flip);
      if (k > 0) {
        EXPECT_EQ(x.flicker[k], y.flicker[k]);
      }
    }
    EXPECT_EQ(x.distanceToFinal, y.distanceToFinal);
    for (std::size_t r = 0; r < x.runs.size(); ++r) {
      for (std::size_t k = 0; k < 3; ++k) EXPECT_TRUE(SameCounters(x.runs[r].frames[k], y.runs[r].frames[k]));
    }
    EXPECT_FALSE(x.differenceFrame.has_value()) << x.technique;
  }
  // The copy pass is the frame itself, so it flickers exactly as the frames do.
  for (std::size_t k = 1; k < 3; ++k) EXPECT_EQ(a.groups[0].tracks[1].flicker[k], a.groups[0].tracks[0].flicker[k]);
  EXPECT_TRUE(std::isnan(a.groups[0].tracks[0].flicker[0]));
  EXPECT_EQ(a.groups[0].tracks[0].technique, "frames");
  EXPECT_EQ(a.groups[0].tracks[2].technique, "smaa");
}

}  // namespace
}  // namespace study
