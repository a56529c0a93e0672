// PS3 MLAA on the pass framework (see mlaa.h).

#include "passes/mlaa/mlaa.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "passes/mlaa/mlaa_kernels.h"
#include "passes/work_set.h"
#include "sim/formats.h"

namespace passes::mlaa {
namespace {

// One pass of the two: the horizontal pass blends across horizontal edges (lines along x), the
// vertical pass is the same kernel on the transposed image, as the PS3's pseudo-transpose made
// it. u runs along the lines, v across them.
struct Axis {
  bool vertical = false;
  glm::ivec2 Pixel(int u, int v) const { return vertical ? glm::ivec2(v, u) : glm::ivec2(u, v); }
  // edges texel channels: the edge to the next pixel across the lines (v + 1) and its gradient
  // class; the crossing edge to the next pixel along them (u + 1).
  int Primary() const { return vertical ? 1 : 0; }
  int Class() const { return vertical ? 3 : 2; }
  int Crossing() const { return vertical ? 0 : 1; }
};

struct AxisNames {
  std::string_view workSet, detect, consume;
};
constexpr AxisNames kHorizontal{"mlaa/h", "mlaa/h-edges", "mlaa/h-blend"};
constexpr AxisNames kVertical{"mlaa/v", "mlaa/v-edges", "mlaa/v-blend"};

// Hand counts as GCN VALU instructions; the talk gives SPU cycles only ("2.4cy/pixel for T(),
// 1.5cy/pixel for Edge()"), no shader exists.
constexpr sim::KernelInfo kDetectPixel{
    .vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 100,
    .source = "hand count of passes/mlaa detect: 4 colour fetches' addresses (6), T() on 4 pixels (4 x 4), 3 "
              "pair tests (max |diff| 6, min and compare 3 each: 27), 2 gradient sums on codes (2 x 12), the "
              "predicated form's 4 depth fetches and 3 tests (~16), the edges and copy stores and the stencil "
              "export (~10)"};
constexpr sim::KernelInfo kDetectCompute{
    .vgprs = 24, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 108,
    .source = "the pixel form's 100 plus the thread-to-pixel mapping, bounds test and the append (~8)"};
constexpr sim::KernelInfo kBlend{
    .vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 260,
    .source = "hand count of passes/mlaa blend: per traced edge (one on most pixels, ~1.2 on average) two "
              "searches of ~8 steps at ~7 each (fetch address, 3 compares, loop, ~110), 2 end classifications "
              "with 4 crossing fetches (~20), the half-line areas (~20); the blend with 2 fetches (~20); ~260 "
              "with the second edge's share"};

constexpr WorkSetKernels KernelsOf(const AxisNames& names) {
  return {.detectDispatch = names.detect, .consumeDispatch = names.consume, .detectPixel = kDetectPixel,
          .detectCompute = kDetectCompute, .consume = kBlend};
}

// A variant reads only the settings it declares (SettingsOf); the others keep Config's values.
Config ConfigOf(Thresholding thresholding, const PassSettings& settings) {
  Config config{.thresholding = thresholding};
  const auto has = [&](std::string_view key) {
    return std::any_of(settings.Schema().begin(), settings.Schema().end(),
                       [&](const SettingInfo& info) { return info.name == key; });
  };
  const auto read = [&](std::string_view key, float& value) {
    if (has(key)) value = static_cast<float>(settings.Get(key));
  };
  read("threshold", config.threshold);
  read("scale", config.scale);
  read("lower_bound", config.lowerBound);
  read("predication_lower_bound", config.predicationLowerBound);
  read("predication_relative", config.predicationRelative);
  read("predication_scale", config.predicationScale);
  read("predication_strength", config.predicationStrength);
  config.maxSearch = static_cast<int>(settings.Get("max_search"));
  config.featureSplitting = settings.Get("feature_splitting") != 0.0;
  config.linearBlend = settings.Get("linear_blend") != 0.0;
  return config;
}

// One line through a pixel, as the blend traces it: pixels to each end and the end heights.
struct Line {
  int left = 0, right = 0;
  float hLeft = 0.0f, hRight = 0.0f;
};

// The blend's reads: the edges texture in the pass's (u, v) coordinates.
class LineTracer {
 public:
  LineTracer(const Config& config, Axis axis, sim::TextureView<glm::vec4> edges, sim::CounterView steps)
      : config_(config), axis_(axis), edges_(std::move(edges)), steps_(std::move(steps)),
        extent_(axis.vertical ? edges_.Height() : edges_.Width()) {}

  glm::vec4 Edges(const sim::LaneBase& lane, int u, int v) const {
    const glm::ivec2 p = axis_.Pixel(u, v);
    return edges_.Load(lane, p.x, p.y);
  }
  bool HasPrimary(const glm::vec4& texel) const { return texel[axis_.Primary()] > 0.5f; }

  // The line on the boundary between rows v and v + 1 through column u, whose texel is `at`.
  Line Trace(const sim::LaneBase& lane, int u, int v, const glm::vec4& at) const {
    Line line;
    line.hLeft = End(lane, u, v, at, -1, line.left);
    line.hRight = End(lane, u, v, at, +1, line.right);
    return line;
  }

 private:
  // Walks from u in direction `dir` while the line continues (an edge on the same boundary, of
  // the same gradient class when splitting); `count` gets the pixels walked, the result the end
  // height. Reaching max_search with the line still going leaves the end open (height 0).
  float End(const sim::LaneBase& lane, int u, int v, const glm::vec4& at, int dir, int& count) const {
    count = 0;
    for (;;) {
      const int next = u + dir * (count + 1);
      if (next < 0 || next >= extent_) break;
      const glm::vec4 texel = Edges(lane, next, v);
      steps_.Add(lane);
      const bool continues =
          HasPrimary(texel) && (!config_.featureSplitting || texel[axis_.Class()] == at[axis_.Class()]);
      if (!continues) break;
      if (count == config_.maxSearch) return 0.0f;
      ++count;
    }
    // The crossing edges at the end sit between the end pixel and the next one along the line,
    // in the row before the boundary and the row after it.
    const int end = u + dir * count;
    const int column = dir < 0 ? end - 1 : end;
    if (column < 0 || column + 1 >= extent_) return 0.0f;
    const bool prev = Edges(lane, column, v)[axis_.Crossing()] > 0.5f;
    const bool next = Edges(lane, column, v + 1)[axis_.Crossing()] > 0.5f;
    return EndHeight(prev, next);
  }

  Config config_;
  Axis axis_;
  sim::TextureView<glm::vec4> edges_;
  sim::CounterView steps_;
  int extent_;
};

struct AxisTargets {
  const sim::Texture2D<glm::vec4>& in;
  sim::Texture2D<glm::vec4>& out;
  sim::Texture2D<glm::vec4>& edges;
  sim::Texture2D<glm::vec2>& weights;
};

class MlaaPass final : public Pass {
 public:
  MlaaPass(const PassInfo& info, const Config& config)
      : info_(info), config_(config), horizontalSet_(kHorizontal.workSet), verticalSet_(kVertical.workSet) {}

  const PassInfo& Info() const override { return info_; }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.Width(), height = frame.Height();
    const sim::Texture2D<glm::vec4>& colour = frame.ColourSrgb8();
    sim::Texture2D<glm::vec4>& horizontal =
        FrameTexture(horizontal_, "mlaa/horizontal", width, height, sim::Format::RGBA8Srgb);
    sim::Texture2D<glm::vec4>& output = FrameTexture(output_, "mlaa/output", width, height, sim::Format::RGBA8Srgb);
    sim::Texture2D<glm::vec4>& edgesH = FrameTexture(edgesH_, "mlaa/edges-h", width, height, sim::Format::RGBA8Unorm);
    sim::Texture2D<glm::vec4>& edgesV = FrameTexture(edgesV_, "mlaa/edges-v", width, height, sim::Format::RGBA8Unorm);
    sim::Texture2D<glm::vec2>& weightsH =
        FrameTexture(weightsH_, "mlaa/weights-h", width, height, sim::Format::RG16Float);
    sim::Texture2D<glm::vec2>& weightsV =
        FrameTexture(weightsV_, "mlaa/weights-v", width, height, sim::Format::RG16Float);
    // Only the blends write weights, on their work sets.
    weightsH.Fill(glm::vec2(0.0f));
    weightsV.Fill(glm::vec2(0.0f));
    const sim::Texture2D<float>* depth = config_.thresholding == Thresholding::Predicated ? frame.depth : nullptr;
    const WorkSetShape h = RunAxis(machine, strategy, Axis{false}, kHorizontal, horizontalSet_,
                                   {colour, horizontal, edgesH, weightsH}, depth);
    const WorkSetShape v =
        RunAxis(machine, strategy, Axis{true}, kVertical, verticalSet_, {horizontal, output, edgesV, weightsV}, depth);
    PassOutput result;
    result.SetWorkSet({.pixels = h.pixels + v.pixels, .quads = h.quads + v.quads, .tiles = h.tiles + v.tiles});
    result.colour = DecodedSrgb8("mlaa/output", output);
    result.layers.push_back(LayerOf("edges-h", edgesH, {"R", "G", "B", "A"}));
    result.layers.push_back(LayerOf("edges-v", edgesV, {"R", "G", "B", "A"}));
    result.layers.push_back(LayerOf("weights-h", weightsH, {"R", "G"}));
    result.layers.push_back(LayerOf("weights-v", weightsV, {"R", "G"}));
    return result;
  }

 private:
  WorkSetShape RunAxis(sim::Machine& machine, Strategy strategy, Axis axis, const AxisNames& names, WorkSet& workSet,
                       const AxisTargets& targets, const sim::Texture2D<float>* depth) const {
    const int width = targets.in.Width(), height = targets.in.Height();
    const Config config = config_;
    auto makeDetect = [&](sim::Dispatch& d, auto) {
      const sim::TextureView<glm::vec4> in = d.Read(targets.in).As(sim::Format::RGBA8Unorm);
      const sim::RwTextureView<glm::vec4> copy = d.ReadWrite(targets.out).As(sim::Format::RGBA8Unorm);
      const sim::RwTextureView<glm::vec4> edges = d.ReadWrite(targets.edges);
      std::optional<sim::TextureView<float>> z;
      if (depth != nullptr) z = d.Read(*depth);
      return [=](const sim::LaneBase& lane, int x, int y) {
        const glm::vec4 texel = in.Load(lane, x, y);
        copy.Store(lane, x, y, texel);
        const glm::vec3 c(texel);
        // Each pixel's depth is loaded once, as a shader compiler would merge the repeated load.
        const auto depthAt = [&](int px, int py) __attribute__((always_inline)) {
          return z ? z->Load(lane, px, py) : 0.0f;
        };
        const float zc = depthAt(x, y);
        // The edge between p0 (upper or left) and p1. Forced inline (GCC's spelling for a lambda):
        // GCC kept it as a call, about a sixth of each detect dispatch (docs/PERFORMANCE.md, "Stop 28").
        const auto test = [&](glm::vec3 c0, float z0, glm::vec3 c1, float z1) __attribute__((always_inline)) {
          return IsEdge(config, c0, c1, z && DepthEdge(config, z0, z1));
        };
        glm::vec4 e(0.0f);
        if (y + 1 < height) {
          const glm::vec3 below(in.Load(lane, x, y + 1));
          if (test(c, zc, below, depthAt(x, y + 1))) e = {1.0f, e.y, GradientClass(c, below), e.w};
        }
        if (x + 1 < width) {
          const glm::vec3 right(in.Load(lane, x + 1, y));
          if (test(c, zc, right, depthAt(x + 1, y))) e = {e.x, 1.0f, e.z, GradientClass(c, right)};
        }
        edges.Store(lane, x, y, e);
        // A pixel joins the work set when a line of this pass runs along one of its sides.
        const int u = axis.vertical ? y : x, v = axis.vertical ? x : y;
        const glm::ivec2 prev = axis.Pixel(u, v - 1);
        const bool prevEdge = prev.x >= 0 && prev.y >= 0 &&
                              test(glm::vec3(in.Load(lane, prev.x, prev.y)), depthAt(prev.x, prev.y), c, zc);
        return prevEdge || e[axis.Primary()] > 0.5f;
      };
    };
    auto makeBlend = [&](sim::Dispatch& d) {
      const LineTracer tracer{config, axis, d.Read(targets.edges), d.Counter("trace_steps")};
      // The PS3 blended the frame buffer's gamma codes; linear_blend reads and writes through
      // sRGB views instead, as SMAA's neighbourhood blending does (aa-facts §1.9).
      const sim::Format view = config.linearBlend ? sim::Format::RGBA8Srgb : sim::Format::RGBA8Unorm;
      const sim::TextureView<glm::vec4> in = d.Read(targets.in).As(view);
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(targets.out).As(view);
      const sim::RwTextureView<glm::vec2> weights = d.ReadWrite(targets.weights);
      return [=](const sim::LaneBase& lane, int x, int y) {
        const int u = axis.vertical ? y : x, v = axis.vertical ? x : y;
        float towardsNext = 0.0f, towardsPrev = 0.0f;
        if (const glm::vec4 here = tracer.Edges(lane, u, v); tracer.HasPrimary(here)) {
          const Line line = tracer.Trace(lane, u, v, here);
          towardsNext = PixelAreas(line.left, line.right, line.hLeft, line.hRight).towardsNext;
        }
        if (v > 0) {
          if (const glm::vec4 before = tracer.Edges(lane, u, v - 1); tracer.HasPrimary(before)) {
            const Line line = tracer.Trace(lane, u, v - 1, before);
            towardsPrev = PixelAreas(line.left, line.right, line.hLeft, line.hRight).towardsPrev;
          }
        }
        const glm::vec4 c = in.Load(lane, x, y);
        const auto pull = [&](float area, int dv) {
          if (area == 0.0f) return glm::vec4(0.0f);
          const glm::ivec2 q = axis.Pixel(u, v + dv);
          return area * (in.Load(lane, q.x, q.y) - c);
        };
        // The sum of the two pulls first: addition commutes, so a mirrored image blends
        // bit-identically.
        out.Store(lane, x, y, c + (pull(towardsPrev, -1) + pull(towardsNext, +1)));
        weights.Store(lane, x, y, {towardsPrev, towardsNext});
      };
    };
    return workSet.Run(machine, strategy, KernelsOf(names), width, height, makeDetect, makeBlend);
  }

  const PassInfo& info_;
  Config config_;
  WorkSet horizontalSet_, verticalSet_;
  std::optional<sim::Texture2D<glm::vec4>> horizontal_, output_, edgesH_, edgesV_;
  std::optional<sim::Texture2D<glm::vec2>> weightsH_, weightsV_;
};

// Each variant declares the tunables its test uses and no others (nothing silently ignored).
std::vector<SettingInfo> SettingsOf(Thresholding thresholding) {
  // The talk publishes the tests, not their parameters: every default below is ours
  // (docs/mlaa.md "Parameters").
  std::vector<SettingInfo> settings;
  if (thresholding == Thresholding::Absolute) {
    settings.push_back({.name = "threshold", .defaultValue = 0.1, .min = 0.0, .max = 1.0, .minExclusive = true,
                        .doc = "an edge when the largest channel difference exceeds it (SMAA_THRESHOLD's value)"});
  } else {
    settings.push_back({.name = "scale", .defaultValue = 0.2, .min = 0.0, .max = 1.0,
                        .doc = "T(p) = max(lower_bound, scale x max channel of p) (seed 004; not published)"});
    settings.push_back({.name = "lower_bound", .defaultValue = 0.04, .min = 0.0, .max = 1.0,
                        .doc = "the threshold's floor, the cut-off for very dark regions (seed 004; not published)"});
  }
  if (thresholding == Thresholding::Predicated) {
    settings.push_back({.name = "predication_lower_bound", .defaultValue = 0.01, .min = 0.0, .max = 1.0,
                        .doc = "depth edge floor (SMAA_PREDICATION_THRESHOLD's value)"});
    settings.push_back({.name = "predication_relative", .defaultValue = 0.01, .min = 0.0, .max = 1.0,
                        .doc = "depth edge threshold's scale of the depth (the talk's relative test on one channel)"});
    settings.push_back({.name = "predication_scale", .defaultValue = 2.0, .min = 1.0, .max = 5.0,
                        .doc = "colour threshold x this everywhere (SMAA_PREDICATION_SCALE's value and range)"});
    settings.push_back({.name = "predication_strength", .defaultValue = 0.75, .min = 0.0, .max = 1.0,
                        .doc = "and x (1 - this) at depth edges: 0.75 halves the relative threshold there"});
  }
  settings.push_back({.name = "max_search", .defaultValue = 32, .min = 0, .max = 254, .integer = true,
                      .doc = "pixels traced along a line on each side of a pixel (SMAA HIGH's 16 steps x 2 px)"});
  settings.push_back({.name = "feature_splitting", .defaultValue = 1, .min = 0, .max = 1, .integer = true,
                      .doc = "1: split lines where the gradient of the channel sum changes sign (seed 004)"});
  settings.push_back({.name = "linear_blend", .defaultValue = 0, .min = 0, .max = 1, .integer = true,
                      .doc = "0: blend the 8-bit gamma codes as the PS3's SPUs did; 1: blend linear values through "
                             "sRGB views"});
  return settings;
}

struct VariantNames {
  std::string_view name, description;
};

constexpr VariantNames NamesOf(Thresholding thresholding) {
  switch (thresholding) {
    case Thresholding::Absolute:
      return {"mlaa-absolute", "PS3 MLAA with absolute thresholding (largest channel difference over a threshold)"};
    case Thresholding::Relative:
      return {"mlaa", "PS3 MLAA: relative thresholding, feature splitting, L/Z/U revectorisation, horizontal then "
                      "vertical pass"};
    case Thresholding::Predicated:
      return {"mlaa-predicated", "PS3 MLAA with relative thresholds predicated by the frame's depth edges"};
  }
  return {};
}

PassInfo MakeInfo(Thresholding thresholding) {
  std::vector<FrameInput> inputs{FrameInput::Colour};
  if (thresholding == Thresholding::Predicated) inputs.push_back(FrameInput::Depth);
  return {
      .name = NamesOf(thresholding).name,
      .description = NamesOf(thresholding).description,
      .source = "passes/mlaa/mlaa.h",
      .settings = SettingsOf(thresholding),
      .presets = {},
      .inputs = inputs,
      .studiedDispatches = {kHorizontal.consume, kVertical.consume},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // Colour, horizontal and output targets and the decoded output (vec4 each), two edges
      // textures (vec4) and their layers (4 floats), two weights textures (vec2) and their layers
      // (2 floats), and per pass a stencil byte and a queue entry.
      .bytesPerPixel = 4 * sizeof(glm::vec4) + 2 * (sizeof(glm::vec4) + 4 * sizeof(float)) +
                       2 * (sizeof(glm::vec2) + 2 * sizeof(float)) + 2 * (1 + sizeof(std::uint32_t)),
      .layerBytesPerPixel = 2 * 4 + 2 * 2 * sizeof(float),  // edges-h, edges-v (RGBA8 codes), weights-h, weights-v
      .temporal = false,
      .variantOf = thresholding == Thresholding::Relative ? "" : "mlaa",
  };
}

}  // namespace

template <Thresholding T>
const PassInfo& Info() {
  static const PassInfo info = MakeInfo(T);
  return info;
}

template <Thresholding T>
std::unique_ptr<Pass> Make(const PassSettings& settings) {
  return std::make_unique<MlaaPass>(Info<T>(), ConfigOf(T, settings));
}

template const PassInfo& Info<Thresholding::Absolute>();
template const PassInfo& Info<Thresholding::Relative>();
template const PassInfo& Info<Thresholding::Predicated>();
template std::unique_ptr<Pass> Make<Thresholding::Absolute>(const PassSettings&);
template std::unique_ptr<Pass> Make<Thresholding::Relative>(const PassSettings&);
template std::unique_ptr<Pass> Make<Thresholding::Predicated>(const PassSettings&);

}  // namespace passes::mlaa
