// The frame pipeline: the material kernel's colour and pixel-rate targets on analytic geometry,
// velocity from previous positions, input validation, and thread-count determinism of a whole
// frame plus the demo post pass under both strategies.

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstddef>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "passes/registry.h"
#include "raster_test_util.h"
#include "sim/frame.h"
#include "sim_test_util.h"

namespace sim {
namespace {

using raster::testing::ScreenToClip;

// A screen-aligned rectangle [x0,x1]x[y0,y1] as two counter-clockwise triangles.
struct Rect {
  std::vector<glm::vec4> clip;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> indices, objects;
};

void AddRect(Rect& r, double x0, double y0, double x1, double y1, double z, glm::vec3 normal, std::uint32_t object,
             int w, int h) {
  const auto base = static_cast<std::uint32_t>(r.clip.size());
  r.clip.push_back(ScreenToClip(x0, y1, z, w, h));
  r.clip.push_back(ScreenToClip(x1, y1, z, w, h));
  r.clip.push_back(ScreenToClip(x1, y0, z, w, h));
  r.clip.push_back(ScreenToClip(x0, y0, z, w, h));
  for (int i = 0; i < 4; ++i) r.normals.push_back(normal);
  for (const std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) r.indices.push_back(base + i);
  r.objects.push_back(object);
  r.objects.push_back(object);
}

FrameSettings SmallSettings(int w, int h) {
  FrameSettings settings;
  settings.width = w;
  settings.height = h;
  settings.eqaa = {4, 4, 2};
  settings.pattern = raster::MakeBuiltinPattern("standard", 4);
  return settings;
}

TEST(SimFrame, MaterialKernelShadesLambertAndWritesPixelTargets) {
  const int w = 48, h = 32;
  Rect rect;
  const glm::vec3 normal = glm::normalize(glm::vec3(0.2f, 0.3f, 1.0f));
  AddRect(rect, 4, 4, 40, 28, 0.25, normal, 1, w, h);
  const std::vector<glm::vec3> colours = {glm::vec3(1, 0, 0), glm::vec3(0.2f, 0.6f, 0.9f)};
  Machine machine(GpuConfigByName("ps4-class"));
  FrameSettings settings = SmallSettings(w, h);
  FramePipeline frame(machine, settings);
  const DispatchReport& report = frame.Render({rect.clip, {}, rect.normals, rect.indices, rect.objects, colours});
  const float lambert = std::max(0.0f, glm::dot(normal, glm::normalize(settings.towardsLight)));
  const glm::vec3 expected = colours[1] * (settings.ambient + (1.0f - settings.ambient) * lambert);
  const glm::vec4 inside = frame.Colour().At(20, 15);
  EXPECT_NEAR(inside.r, expected.r, 1e-6f);
  EXPECT_NEAR(inside.g, expected.g, 1e-6f);
  EXPECT_NEAR(inside.b, expected.b, 1e-6f);
  EXPECT_EQ(frame.ObjectId().At(20, 15), 1u);
  EXPECT_NEAR(frame.Depth().At(20, 15), 0.25f, 1e-6f);
  EXPECT_NEAR(frame.Normal().At(20, 15).z, normal.z, 1e-5f);
  EXPECT_EQ(frame.ObjectId().At(1, 1), kNoObject);
  EXPECT_FLOAT_EQ(frame.Colour().At(1, 1).r, settings.clearColour.r);
  // 36x24 px covered; pixels on the shared diagonal run once per triangle, and the quads the
  // diagonal splits carry helpers.
  EXPECT_GE(report.lanes.lanesActive, 36u * 24u);
  EXPECT_GT(report.lanes.lanesHelper, 0u);
  EXPECT_EQ(report.lanes.lanesActive + report.lanes.lanesHelper, 4 * report.lanes.quadsLaunched);
  ASSERT_TRUE(report.fragments.has_value());
  EXPECT_GT(report.fragments->pixelUpdates, 0u);
}

// The 8-bit frame the passes read is the resolved colour through D3D's sRGB store: RGB by the
// double-precision curve (FloatToSrgb8ByCurve, not the tables the store uses), alpha UNORM.
TEST(SimFrame, TheSrgb8FrameIsTheResolvedColourStoredThroughTheSrgbCurve) {
  const int w = 48, h = 32;
  Rect rect;
  AddRect(rect, 4.3, 4.6, 40.2, 28.1, 0.25, glm::vec3(0.0f, 0.0f, 1.0f), 1, w, h);
  const std::vector<glm::vec3> colours = {glm::vec3(1, 0, 0), glm::vec3(0.2f, 0.6f, 0.9f)};
  Machine machine(GpuConfigByName("ps4-class"));
  FramePipeline frame(machine, SmallSettings(w, h));
  frame.Render({rect.clip, {}, rect.normals, rect.indices, rect.objects, colours});
  ASSERT_EQ(frame.ColourSrgb8().TexelFormat(), Format::RGBA8Srgb);
  const std::span<const std::uint8_t> codes = frame.ColourSrgb8().Codes();
  const auto green = [&](int x, int y) { return codes[4 * (static_cast<std::size_t>(y) * w + x) + 1]; };
  std::size_t between = 0;  // partly covered border pixels: green codes neither the clear's nor the inside's
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const glm::vec4 linear = frame.Colour().At(x, y);
      const std::size_t at = 4 * (static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x));
      for (int c = 0; c < 3; ++c) ASSERT_EQ(codes[at + c], FloatToSrgb8ByCurve(linear[c])) << x << "," << y;
      ASSERT_EQ(codes[at + 3], FloatToUnorm8(linear.a)) << x << "," << y;
      if (green(x, y) != green(1, 1) && green(x, y) != green(20, 15)) ++between;
    }
  }
  EXPECT_GT(between, 0u);
}

TEST(SimFrame, TexturedObjectsMultiplyTheFactorByABilinearSample) {
  const int w = 32, h = 32;
  Rect rect;
  AddRect(rect, 3.5, 3.5, 27.5, 27.5, 0.5, glm::vec3(0, 0, 1), 0, w, h);
  // AddRect's corners: (x0,y1), (x1,y1), (x1,y0), (x0,y0); v = 0 at the top edge.
  const std::vector<glm::vec2> texcoords = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  Texture2D<glm::vec4> texture("checker", 2, 2, 4);
  texture.At(0, 0) = glm::vec4(0.2f, 0.4f, 0.6f, 1.0f);
  texture.At(1, 0) = glm::vec4(1.0f);
  texture.At(0, 1) = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  texture.At(1, 1) = glm::vec4(0.5f);
  const std::vector<Texture2D<glm::vec4>> textures = {texture};
  const std::vector<glm::vec3> factors = {glm::vec3(0.5f, 1.0f, 1.0f)};
  const std::vector<int> objectTextures = {0};
  Machine machine(GpuConfigByName("ps4-class"));
  FrameSettings settings = SmallSettings(w, h);
  FramePipeline frame(machine, settings);
  const DispatchReport report = frame.Render({.clipPositions = rect.clip,
                                              .previousClipPositions = {},
                                              .normals = rect.normals,
                                              .indices = rect.indices,
                                              .objectIds = rect.objects,
                                              .baseColours = factors,
                                              .texcoords = texcoords,
                                              .baseColourTextures = objectTextures,
                                              .textures = textures});
  // Pixel (9, 9) has its centre at uv (0.25, 0.25): exactly texel (0, 0).
  const float lambert = std::max(0.0f, glm::dot(glm::vec3(0, 0, 1), glm::normalize(settings.towardsLight)));
  const glm::vec3 expected = factors[0] * glm::vec3(0.2f, 0.4f, 0.6f) * (settings.ambient + (1 - settings.ambient) * lambert);
  const glm::vec4 got = frame.Colour().At(9, 9);
  EXPECT_NEAR(got.r, expected.r, 1e-6f);
  EXPECT_NEAR(got.g, expected.g, 1e-6f);
  EXPECT_NEAR(got.b, expected.b, 1e-6f);
  // One bilinear fetch per shaded lane, four texels each.
  ASSERT_EQ(report.resources.back().name, "checker");
  EXPECT_EQ(report.resources.back().fetches, report.lanes.lanesActive + report.lanes.lanesHelper);
  EXPECT_EQ(report.resources.back().bytesRead, 16 * report.resources.back().fetches);

  const std::vector<int> missing = {3};
  EXPECT_THROW(frame.Render({.clipPositions = rect.clip, .previousClipPositions = {}, .normals = rect.normals,
                             .indices = rect.indices, .objectIds = rect.objects, .baseColours = factors,
                             .texcoords = texcoords, .baseColourTextures = missing, .textures = textures}),
               std::invalid_argument);
}

TEST(SimFrame, VelocityIsCurrentMinusPreviousScreenPosition) {
  const int w = 32, h = 32;
  Rect now, before;
  AddRect(now, 4, 4, 28, 28, 0.5, glm::vec3(0, 0, 1), 0, w, h);
  AddRect(before, 6.5, 3, 30.5, 27, 0.5, glm::vec3(0, 0, 1), 0, w, h);
  const std::vector<glm::vec3> colours = {glm::vec3(0.5f)};
  Machine machine(GpuConfigByName("ps4-class"));
  FramePipeline frame(machine, SmallSettings(w, h));
  frame.Render({now.clip, before.clip, now.normals, now.indices, now.objects, colours});
  const glm::vec2 v = frame.Velocity().At(15, 15);
  EXPECT_NEAR(v.x, -2.5f, 1e-4f);
  EXPECT_NEAR(v.y, 1.0f, 1e-4f);
}

TEST(SimFrame, RefusesInconsistentGeometry) {
  const int w = 16, h = 16;
  Rect rect;
  AddRect(rect, 2, 2, 14, 14, 0.5, glm::vec3(0, 0, 1), 3, w, h);
  const std::vector<glm::vec3> colours = {glm::vec3(1.0f)};
  Machine machine(GpuConfigByName("ps4-class"));
  FramePipeline frame(machine, SmallSettings(w, h));
  EXPECT_THROW(frame.Render({rect.clip, {}, rect.normals, rect.indices, rect.objects, colours}),
               std::invalid_argument);  // object 3 of 1
  EXPECT_THROW(frame.Render({rect.clip, {}, {}, rect.indices, rect.objects, colours}), std::invalid_argument);
  FrameSettings wrongPattern = SmallSettings(w, h);
  wrongPattern.pattern = raster::MakeBuiltinPattern("standard", 8);
  EXPECT_THROW(FramePipeline(machine, wrongPattern), std::invalid_argument);
  FrameSettings impossible = SmallSettings(w, h);
  impossible.eqaa = {4, 8, 2};
  EXPECT_THROW(FramePipeline(machine, impossible), std::invalid_argument);
}

// The bytes of an image, for bit-for-bit comparison (-0.0 vs 0.0 and NaN payloads count).
template <typename T>
std::vector<std::byte> TexelBytes(const Texture2D<T>& texture) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::span<const T> texels = texture.Texels();
  std::vector<std::byte> bytes(texels.size_bytes());
  std::memcpy(bytes.data(), texels.data(), bytes.size());
  return bytes;
}

template <typename T>
void AppendBytes(std::vector<std::byte>& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

// The EQAA surface field by field (FragmentSlot has padding, so no whole-struct copies): per
// pixel the FMASK element, every fragment slot and every sample's UNKNOWN cause.
std::vector<std::byte> EqaaBytes(const fmask::EqaaSurface& surface) {
  std::vector<std::byte> out;
  for (int y = 0; y < surface.Height(); ++y) {
    for (int x = 0; x < surface.Width(); ++x) {
      AppendBytes(out, surface.Fmask(x, y));
      for (int slot = 0; slot < surface.Config().fragments; ++slot) {
        const fmask::FragmentSlot& fragment = surface.Slot(x, y, slot);
        AppendBytes(out, static_cast<std::uint8_t>(fragment.occupied));
        AppendBytes(out, fragment.primitiveId);
        AppendBytes(out, fragment.colour);
      }
      for (int sample = 0; sample < surface.Config().coverageSamples; ++sample) {
        AppendBytes(out, surface.Cause(x, y, sample));
      }
    }
  }
  return out;
}

// A frame of random overlapping rectangles, then the demo pass under both strategies.
struct FrameRun {
  std::vector<DispatchReport> reports;
  std::vector<glm::vec4> colour, stencilOutput, queueOutput;
  // Every other image the frame and the passes produce, as raw bytes.
  std::vector<std::pair<std::string, std::vector<std::byte>>> images;
  int pixelsWithTwoFragments = 0;
  std::uint64_t edgePixels = 0;
};

FrameRun RunFrame(int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const int w = 200, h = 120;
  raster::testing::Random rng(7);
  Rect rect;
  std::vector<glm::vec3> colours;
  std::vector<glm::vec4> previous;
  for (std::uint32_t i = 0; i < 40; ++i) {
    const double x = rng.Uniform(-10, w), y = rng.Uniform(-10, h);
    AddRect(rect, x, y, x + rng.Uniform(1, 60), y + rng.Uniform(0.3, 40), rng.Uniform(0.1, 0.9),
            glm::normalize(glm::vec3(rng.Uniform(-1, 1), rng.Uniform(-1, 1), 1.0)), i, w, h);
    colours.emplace_back(rng.Uniform(0, 1), rng.Uniform(0, 1), rng.Uniform(0, 1));
  }
  // Previous positions shifted per vertex, so velocity is not one constant.
  for (std::size_t v = 0; v < rect.clip.size(); ++v) {
    previous.push_back(rect.clip[v] + glm::vec4(0.01f * static_cast<float>(v % 7), -0.02f * static_cast<float>(v % 5), 0, 0));
  }
  Machine machine(GpuConfigByName("ps4-class"));
  FramePipeline frame(machine, SmallSettings(w, h));
  frame.Render({rect.clip, previous, rect.normals, rect.indices, rect.objects, colours});
  const passes::PassConfig demo = passes::ResolvePass("demo");
  const passes::PassOutput stencil =
      demo.Make()->Run(machine, passes::FrameInputsOf(frame), passes::Strategy::StencilCulled);
  const passes::PassOutput queue = demo.Make()->Run(machine, passes::FrameInputsOf(frame), passes::Strategy::DeferredQueue);
  auto layerBytes = [](const passes::PassOutput& output) {
    const std::vector<float> values = output.layers.at(0).Floats();
    std::vector<std::byte> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
  };
  FrameRun run{{machine.Reports().begin(), machine.Reports().end()},
               {frame.Colour().Texels().begin(), frame.Colour().Texels().end()},
               {stencil.colour.Texels().begin(), stencil.colour.Texels().end()},
               {queue.colour.Texels().begin(), queue.colour.Texels().end()},
               {{"colour", TexelBytes(frame.Colour())},
                {"depth", TexelBytes(frame.Depth())},
                {"normal", TexelBytes(frame.Normal())},
                {"object id", TexelBytes(frame.ObjectId())},
                {"velocity", TexelBytes(frame.Velocity())},
                {"eqaa surface", EqaaBytes(frame.Eqaa())},
                {"stencil output", TexelBytes(stencil.colour)},
                {"stencil edges", layerBytes(stencil)},
                {"queue output", TexelBytes(queue.colour)},
                {"queue edges", layerBytes(queue)}},
               0,
               stencil.workItems};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) run.pixelsWithTwoFragments += frame.Eqaa().FragmentCount(x, y) >= 2;
  }
  return run;
}

TEST(SimFrame, CountersAndImagesDoNotDependOnTheThreadCount) {
  const FrameRun one = RunFrame(1);
  const FrameRun two = RunFrame(2);
  testing::ExpectSameReports(one.reports, two.reports);
  EXPECT_EQ(one.colour, two.colour);
  EXPECT_EQ(one.stencilOutput, two.stencilOutput);
  EXPECT_EQ(one.queueOutput, two.queueOutput);
  EXPECT_EQ(one.stencilOutput, one.queueOutput);
  ASSERT_EQ(one.reports.size(), 2u + 2u + 3u);  // draw and resolve, then the demo pass
  // Bit for bit, every target and the EQAA surface; the scene must exercise them, or equality
  // would prove nothing (edges found, pixels holding two fragments).
  EXPECT_GT(one.edgePixels, 0u);
  EXPECT_GT(one.pixelsWithTwoFragments, 0);
  ASSERT_EQ(one.images.size(), two.images.size());
  for (std::size_t i = 0; i < one.images.size(); ++i) {
    const std::vector<std::byte>& a = one.images[i].second;
    const std::vector<std::byte>& b = two.images[i].second;
    ASSERT_EQ(one.images[i].first, two.images[i].first);
    ASSERT_EQ(a.size(), b.size()) << one.images[i].first;
    EXPECT_GT(a.size(), 0u) << one.images[i].first;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size()), 0) << one.images[i].first;
  }
  const auto image = [&](const std::string& name) -> const std::vector<std::byte>& {
    for (const auto& [imageName, bytes] : one.images) {
      if (imageName == name) return bytes;
    }
    throw std::logic_error("no image " + name);
  };
  ASSERT_EQ(image("stencil edges").size(), image("queue edges").size());
  EXPECT_EQ(std::memcmp(image("stencil edges").data(), image("queue edges").data(), image("queue edges").size()), 0)
      << "both strategies find the same edges";
}

}  // namespace
}  // namespace sim

namespace sim {
namespace {

// A sequence moves its samples from frame to frame (a jitter schedule): the pipeline keeps its
// surfaces and renders what a pipeline built for the new pattern renders, bit for bit.
TEST(SimFrame, APerFramePatternReusesTheSurfacesAndMatchesAFreshPipeline) {
  const int w = 96, h = 64;
  Rect rect;
  const std::vector<glm::vec3> colours{{0.9f, 0.2f, 0.1f}, {0.1f, 0.8f, 0.3f}};
  AddRect(rect, 10.3, 5.7, 70.1, 50.2, 0.4, {0, 0, 1}, 0, w, h);
  AddRect(rect, 40.6, 20.4, 90.9, 60.8, 0.6, glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)), 1, w, h);
  const FrameGeometry geometry{rect.clip, {}, rect.normals, rect.indices, rect.objects, colours};
  const raster::SamplePattern rotated = raster::MakeBuiltinPattern("rotated-grid", 4);

  Machine reused(GpuConfigByName("ps4-class"));
  FramePipeline sequence(reused, SmallSettings(w, h));
  sequence.Render(geometry);
  const fmask::EqaaSurface* surfaceBefore = &sequence.Eqaa();
  reused.ClearReports();
  sequence.Render(geometry, {.pattern = &rotated, .frameIndex = 1});

  Machine fresh(GpuConfigByName("ps4-class"));
  FrameSettings settings = SmallSettings(w, h);
  settings.pattern = rotated;
  FramePipeline single(fresh, settings);
  single.Render(geometry);

  EXPECT_EQ(&sequence.Eqaa(), surfaceBefore);
  EXPECT_EQ(sequence.FrameIndex(), 1);
  EXPECT_EQ(sequence.DepthSurface().Pattern().Name(), rotated.Name());
  EXPECT_EQ(TexelBytes(sequence.Colour()), TexelBytes(single.Colour()));
  EXPECT_EQ(TexelBytes(sequence.Depth()), TexelBytes(single.Depth()));
  EXPECT_EQ(EqaaBytes(sequence.Eqaa()), EqaaBytes(single.Eqaa()));
  testing::ExpectSameReports(reused.Reports(), fresh.Reports());
  // The standard and rotated-grid patterns differ, so the frames must too (or the test shows nothing).
  Machine other(GpuConfigByName("ps4-class"));
  FramePipeline standard(other, SmallSettings(w, h));
  standard.Render(geometry);
  EXPECT_NE(EqaaBytes(standard.Eqaa()), EqaaBytes(single.Eqaa()));

  const raster::SamplePattern eight = raster::MakeBuiltinPattern("standard", 8);
  EXPECT_THROW(sequence.Render(geometry, {.pattern = &eight}), std::invalid_argument);
}


// A resolve kernel reads the EQAA surface through a view: the same colours as the host's fetch
// path, FMASK read once per pixel and one fragment per sample, every byte counted on its resource.
TEST(SimFrame, AKernelReadsFmaskAndFragmentsAsCountedResources) {
  const int w = 40, h = 24;
  Rect rect;
  const std::vector<glm::vec3> colours{{0.9f, 0.2f, 0.1f}, {0.1f, 0.8f, 0.3f}, {0.2f, 0.3f, 0.9f}};
  AddRect(rect, 3.3, 2.7, 30.1, 20.2, 0.4, {0, 0, 1}, 0, w, h);
  AddRect(rect, 12.6, 6.4, 38.9, 22.8, 0.6, {0, 0, 1}, 1, w, h);
  AddRect(rect, 20.2, 0.3, 26.7, 23.5, 0.2, {0, 0, 1}, 2, w, h);
  Machine machine(GpuConfigByName("ps4-class"));
  FrameSettings settings = SmallSettings(w, h);
  settings.eqaa = {4, 4, 1};  // 1F4S: samples of other primitives are UNKNOWN
  FramePipeline frame(machine, settings);
  frame.Render({rect.clip, {}, rect.normals, rect.indices, rect.objects, colours});
  machine.ClearReports();

  const EqaaResources eqaa(frame.Eqaa());
  Texture2D<glm::vec4> resolved("resolved", w, h);
  Dispatch d("test/fetch-resolve", {.vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 8,
                                    .source = "test"});
  const EqaaView in = d.Read(eqaa);
  const RwTextureView<glm::vec4> out = d.ReadWrite(resolved);
  d.SetPixelGrid(w, h);
  const DispatchReport report = machine.Compute(d, {.threads = {w, h, 1}, .groupSize = {8, 8, 1}}, [&](ComputeLane& lane) {
    const int x = lane.pixel.x, y = lane.pixel.y;
    const std::uint64_t visible = fmask::ShaderVisibleMask(in.Surface().Layout(), in.Fmask(lane, x, y));
    glm::vec4 sum(0.0f);
    for (int s = 0; s < 4; ++s) {
      const fmask::Colour c = in.Fragment(lane, x, y, fmask::FetchFragmentIndex(visible, s));
      sum += glm::vec4(c.r, c.g, c.b, c.a);
    }
    out.Store(lane, x, y, sum / 4.0f);
  });

  int withUnknown = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      glm::vec4 expected(0.0f);
      for (int s = 0; s < 4; ++s) {
        const fmask::Colour c = frame.Eqaa().FetchSample(x, y, s);
        expected += glm::vec4(c.r, c.g, c.b, c.a);
        withUnknown += fmask::ShaderVisibleMask(frame.Eqaa().Layout(), frame.Eqaa().Fmask(x, y)) >> (4 * s) & 8 ? 1 : 0;
      }
      ASSERT_EQ(resolved.At(x, y), expected / 4.0f) << x << "," << y;
    }
  }
  EXPECT_GT(withUnknown, 0);  // the scene exercises the UNKNOWN path
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  const std::size_t fmaskBytes = eqaa.FmaskBytesPerPixel();
  ASSERT_GT(fmaskBytes, 0u);
  ASSERT_EQ(report.resources.size(), 3u);
  EXPECT_EQ(report.resources[0].name, "eqaa/fmask");
  EXPECT_EQ(report.resources[0].fetches, pixels);
  EXPECT_EQ(report.resources[0].bytesRead, pixels * fmaskBytes);
  EXPECT_EQ(report.resources[0].linesRead, (pixels * fmaskBytes + 63) / 64);
  EXPECT_EQ(report.resources[1].name, "eqaa/fragments");
  EXPECT_EQ(report.resources[1].fetches, pixels * 4);
  EXPECT_EQ(report.resources[1].bytesRead, pixels * 4 * 4);
  // One fragment plane (1F): every line of it is read.
  EXPECT_EQ(report.resources[1].linesRead, (pixels * 4 + 63) / 64);
}

}  // namespace
}  // namespace sim
