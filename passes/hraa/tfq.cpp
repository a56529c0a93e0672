// Temporal FLIPQUAD (see tfq.h).

#include "passes/hraa/tfq.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "sim/colour.h"
#include "sim/formats.h"

namespace passes::hraa {
namespace {

constexpr std::string_view kUnsharpDispatch = "tfq/unsharp";

// Hand counts per wave of the kernels below (one instruction per lane-wide operation): the
// resolve's 40 loads (3x3 of N, two 3x3 velocity windows, 3x3 of N-2, the N-1 pair, two
// velocities) and their addressing, 18 lumas, 9 velocity differences, the box, pairs and blend.
constexpr sim::KernelInfo kResolveKernel{.vgprs = 48, .sgprs = 24, .ldsBytesPerGroup = 0,
                                         .valuInstructionsPerWave = 260,
                                         .source = "hand count: 40 loads' addressing, 18 lumas, two 3x3 SADs, the 3x3 "
                                                   "box, pairs and tent, the limit"};
constexpr sim::KernelInfo kUnsharpKernel{.vgprs = 16, .sgprs = 16, .ldsBytesPerGroup = 0,
                                         .valuInstructionsPerWave = 30,
                                         .source = "hand count: 5 loads' addressing, a 5-tap weighted sum, max"};

// FLIPQUAD's left-edge point of quad pixel 0 (raster/sample_pattern.cpp kFlipQuadEven sample 0)
// and its top-edge point (sample 1): which half of the pattern a frame drew.
constexpr raster::SampleOffset kLeftPoint{-8, -3};
constexpr raster::SampleOffset kTopPoint{3, -8};

bool IsPhaseB(const FrameInputs& frame) {
  if (frame.pattern != nullptr && frame.pattern->Count() == 1) {
    const raster::SampleOffset first = frame.pattern->Offset(0, 0);
    if (first == kLeftPoint) return false;
    if (first == kTopPoint) return true;
  }
  return (frame.frameIndex & 1) != 0;
}

glm::ivec2 Clamped(glm::ivec2 p, int width, int height) {
  return {std::clamp(p.x, 0, width - 1), std::clamp(p.y, 0, height - 1)};
}

bool Inside(glm::ivec2 p, int width, int height) { return p.x >= 0 && p.y >= 0 && p.x < width && p.y < height; }

glm::ivec2 Rounded(glm::vec2 v) { return {static_cast<int>(std::floor(v.x + 0.5f)), static_cast<int>(std::floor(v.y + 0.5f))}; }

// The luma the colour-flow SAD compares: Rec. 709 weights on the 8-bit sRGB codes. Frame N is
// loaded decoded (the resolve needs linear values), so re-encoding gives its stored codes back;
// N-2 is read through the UNORM view, which returns the codes.
float SadLuma(const glm::vec4& linear) {
  const auto code = [](float c) __attribute__((always_inline)) { return sim::Unorm8ToFloat(sim::FloatToSrgb8(c)); };
  return sim::Rec709Luma({code(linear.r), code(linear.g), code(linear.b)});
}

// The resolve of one pixel. `along` pairs the current frame's samples (X for A, Y for B),
// `missing` the previous frame's.
struct Resolver {
  sim::TextureView<glm::vec4> cur;
  std::optional<sim::TextureView<glm::vec4>> prev1, prev2;
  sim::TextureView<glm::vec2> vel;
  std::optional<sim::TextureView<glm::vec2>> prevVel;
  glm::ivec2 along, missing;
  TfqParams params;
  int width, height;

  std::pair<glm::vec4, TfqValidity> operator()(const sim::LaneBase& lane, int x, int y) const {
    const glm::ivec2 p(x, y);
    std::array<glm::vec4, 9> n{};  // frame N's 3x3, row-major from (x-1, y-1)
    for (int i = 0; i < 9; ++i) n[i] = LoadAt(lane, cur, p + glm::ivec2(i % 3 - 1, i / 3 - 1));
    const auto at = [&](glm::ivec2 d) { return n[static_cast<std::size_t>((d.y + 1) * 3 + d.x + 1)]; };
    const auto pair = [&](glm::ivec2 d) { return 0.5f * (at(d) + at(d + along)); };
    const glm::vec4 own = pair({0, 0});
    const glm::vec4 interpolated = 0.25f * pair(-missing) + 0.5f * own + 0.25f * pair(missing);
    if (!prev1) return {Combine(own, interpolated, n[4]), TfqValidity::NoHistory};

    const glm::vec2 v = vel.Load(lane, x, y);
    const glm::ivec2 q = p - Rounded(v);
    if (!Inside(q, width, height) || MotionSad(lane, p, q) > params.motionThreshold) {
      return {Combine(own, interpolated, n[4]), TfqValidity::MotionRejected};
    }
    glm::vec4 previous = 0.5f * (prev1->Load(lane, q.x, q.y) + LoadAt(lane, *prev1, q + missing));
    if (ColourFlowFails(lane, q, n)) {
      glm::vec4 lo = n[0], hi = n[0];
      for (const glm::vec4& c : n) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
      }
      previous = glm::clamp(previous, lo, hi);
      return {Combine(own, previous, n[4]), TfqValidity::ColourLimited};
    }
    return {Combine(own, previous, n[4]), TfqValidity::Accepted};
  }

  // Inlined: called, GCC returned the vec4 through the stack (docs/PERFORMANCE.md, "Stop 29").
  [[gnu::always_inline]] glm::vec4 LoadAt(const sim::LaneBase& lane, const sim::TextureView<glm::vec4>& view,
                                          glm::ivec2 p) const {
    const glm::ivec2 c = Clamped(p, width, height);
    return view.Load(lane, c.x, c.y);
  }

  static glm::vec4 Combine(const glm::vec4& current, const glm::vec4& previous, const glm::vec4& centre) {
    return {0.5f * (glm::vec3(current) + glm::vec3(previous)), centre.a};
  }

  float MotionSad(const sim::LaneBase& lane, glm::ivec2 p, glm::ivec2 q) const {
    float sad = 0.0f;
    for (int i = 0; i < 9; ++i) {
      const glm::ivec2 d(i % 3 - 1, i / 3 - 1);
      const glm::ivec2 a = Clamped(p + d, width, height), b = Clamped(q + d, width, height);
      const glm::vec2 diff = glm::abs(vel.Load(lane, a.x, a.y) - prevVel->Load(lane, b.x, b.y));
      sad += diff.x + diff.y;
    }
    return sad / 9.0f;
  }

  bool ColourFlowFails(const sim::LaneBase& lane, glm::ivec2 q, const std::array<glm::vec4, 9>& n) const {
    if (!prev2) return true;  // no N-2 yet: unvalidated, so limited
    const glm::ivec2 r = q - Rounded(prevVel->Load(lane, q.x, q.y));
    if (!Inside(r, width, height)) return true;
    float sad = 0.0f;
    for (int i = 0; i < 9; ++i) {
      const glm::ivec2 d(i % 3 - 1, i / 3 - 1);
      sad += std::abs(SadLuma(n[static_cast<std::size_t>(i)]) - sim::Rec709Luma(glm::vec3(LoadAt(lane, *prev2, r + d))));
    }
    return sad / 9.0f > params.colourThreshold;
  }
};

}  // namespace

// ---- FrameRing ------------------------------------------------------------------------------

void FrameRing::Store(const FrameInputs& frame) {
  const int width = frame.Width(), height = frame.Height();
  if (frame.frameIndex == 0 || !colour_[0] || colour_[0]->Width() != width || colour_[0]->Height() != height) frames_ = 0;
  const std::size_t slot = static_cast<std::size_t>(frames_ % 3), velocitySlot = static_cast<std::size_t>(frames_ % 2);
  for (std::size_t i = 0; i < colour_.size(); ++i) {
    FrameTexture(colour_[i], "tfq/history-colour-" + std::to_string(i), width, height, sim::Format::RGBA8Srgb);
  }
  for (std::size_t i = 0; i < velocity_.size(); ++i) {
    FrameTexture(velocity_[i], "tfq/history-velocity-" + std::to_string(i), width, height, sim::Format::RG16Float);
  }
  CopySrgb8Frame(frame, *colour_[slot]);
  sim::Texture2D<glm::vec2>& velocity = *velocity_[velocitySlot];
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec2 v = frame.velocity != nullptr ? frame.velocity->At(x, y) : glm::vec2(0.0f);
      velocity.At(x, y) = sim::Quantize(sim::Format::RG16Float, v);
    }
  }
  phaseB_[slot] = IsPhaseB(frame);
  ++frames_;
}

const sim::Texture2D<glm::vec4>& FrameRing::Colour(int age) const {
  return *colour_[static_cast<std::size_t>((frames_ - 1 - age + 3) % 3)];
}

const sim::Texture2D<glm::vec2>& FrameRing::Velocity(int age) const {
  return *velocity_[static_cast<std::size_t>((frames_ - 1 - age + 2) % 2)];
}

bool FrameRing::PhaseB(int age) const { return phaseB_[static_cast<std::size_t>((frames_ - 1 - age + 3) % 3)]; }

// ---- TfqStage -------------------------------------------------------------------------------

const sim::Texture2D<glm::vec4>& TfqStage::Run(sim::Machine& machine, const FrameInputs& frame) {
  ring_.Store(frame);
  const int width = frame.Width(), height = frame.Height();
  sim::Texture2D<glm::vec4>& resolved = FrameTexture(resolved_, "tfq/resolved", width, height, sim::Format::RGBA16Float);
  Resolve(machine, resolved);
  if (params_.unsharp == 0.0f) return resolved;
  sim::Texture2D<glm::vec4>& sharpened = FrameTexture(sharpened_, "tfq/sharpened", width, height, sim::Format::RGBA16Float);
  Unsharp(machine, resolved, sharpened);
  return sharpened;
}

void TfqStage::Resolve(sim::Machine& machine, sim::Texture2D<glm::vec4>& out) {
  const int width = out.Width(), height = out.Height();
  sim::Dispatch d(std::string(kTfqResolveDispatch), kResolveKernel);
  const bool phaseB = ring_.PhaseB(0);
  // N-1 completes the pattern only when it drew the other half.
  const bool havePrevious = ring_.Frames() >= 2 && ring_.PhaseB(1) != phaseB;
  Resolver resolver{.cur = d.Read(ring_.Colour(0)),
                    .prev1 = std::nullopt,
                    .prev2 = std::nullopt,
                    .vel = d.Read(ring_.Velocity(0)),
                    .prevVel = std::nullopt,
                    .along = phaseB ? glm::ivec2(0, 1) : glm::ivec2(1, 0),
                    .missing = phaseB ? glm::ivec2(1, 0) : glm::ivec2(0, 1),
                    .params = params_,
                    .width = width,
                    .height = height};
  if (havePrevious) {
    resolver.prev1 = d.Read(ring_.Colour(1));
    resolver.prevVel = d.Read(ring_.Velocity(1));
    // N-2 only feeds the SAD: read through the UNORM view, its codes as they are (aa-facts §1.9).
    if (ring_.Frames() >= 3 && ring_.PhaseB(2) == phaseB) resolver.prev2 = d.Read(ring_.Colour(2)).As(sim::Format::RGBA8Unorm);
  }
  const sim::RwTextureView<glm::vec4> target = d.ReadWrite(out);
  validity_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  std::uint8_t* validity = validity_.data();
  machine.FullScreen(d, {.width = width, .height = height}, [&](sim::PixelLane& lane) {
    const auto [colour, why] = resolver(lane, lane.x, lane.y);
    target.Store(lane, lane.x, lane.y, colour);
    if (!lane.helper) validity[static_cast<std::size_t>(lane.y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(lane.x)] = static_cast<std::uint8_t>(why);
  });
}

void TfqStage::Unsharp(sim::Machine& machine, const sim::Texture2D<glm::vec4>& in, sim::Texture2D<glm::vec4>& out) const {
  const int width = in.Width(), height = in.Height();
  sim::Dispatch d(std::string(kUnsharpDispatch), kUnsharpKernel);
  const sim::TextureView<glm::vec4> source = d.Read(in);
  const sim::RwTextureView<glm::vec4> target = d.ReadWrite(out);
  const float s = params_.unsharp;
  machine.FullScreen(d, {.width = width, .height = height}, [&](sim::PixelLane& lane) {
    const auto load = [&](int dx, int dy) {
      const glm::ivec2 c = Clamped({lane.x + dx, lane.y + dy}, width, height);
      return source.Load(lane, c.x, c.y);
    };
    const glm::vec4 centre = load(0, 0);
    const glm::vec3 cross = glm::vec3(load(-1, 0)) + glm::vec3(load(1, 0)) + glm::vec3(load(0, -1)) + glm::vec3(load(0, 1));
    // c + s (c - K c), K = 1/2 centre + 1/8 per 4-neighbour (the FLIPQUAD box on the pixel grid).
    const glm::vec3 blurred = 0.5f * glm::vec3(centre) + 0.125f * cross;
    const glm::vec3 sharp = glm::max(glm::vec3(centre) + s * (glm::vec3(centre) - blurred), glm::vec3(0.0f));
    target.Store(lane, lane.x, lane.y, glm::vec4(sharp, centre.a));
  });
}

PassLayer TfqStage::ValidityLayer() const {
  const sim::Texture2D<glm::vec4>& any = *resolved_;
  PassLayer layer{"validity", {"Y"}, any.Width(), any.Height(), {}, {}, 0};
  layer.values.assign(validity_.begin(), validity_.end());
  return layer;
}

// ---- settings and the tfq pass --------------------------------------------------------------

std::vector<SettingInfo> TfqSettings() {
  return {
      {.name = "motion_threshold", .defaultValue = 0.5, .min = 0.0, .max = 64.0,
       .doc = "motion flow: largest mean |v_N - v_N-1| (px, L1) over 3x3 for the N-1 sample to be valid (seed 001 "
              "'Temporal Super Sampling' publishes none: ours)"},
      {.name = "colour_threshold", .defaultValue = 0.04, .min = 0.0, .max = 1.0,
       .doc = "colour flow: largest mean |luma N - luma N-2| (8-bit sRGB luma in [0, 1]) over 3x3 before N-1 is limited "
              "to N's 3x3 box (seed 001 publishes none: ours, about 10 codes)"},
      {.name = "unsharp", .defaultValue = 0.0, .min = 0.0, .max = 2.0,
       .doc = "0.5-px unsharp mask strength after the FLIPQUAD box resolve, 0 = off (seed 001 'Hi Frequency Recovery')"},
  };
}

TfqParams TfqParamsOf(const PassSettings& settings) {
  return {.motionThreshold = static_cast<float>(settings.Get("motion_threshold")),
          .colourThreshold = static_cast<float>(settings.Get("colour_threshold")),
          .unsharp = static_cast<float>(settings.Get("unsharp"))};
}

WorkSetShape FullScreenShape(int width, int height) {
  const auto cells = [](int n, int size) { return static_cast<std::uint64_t>((n + size - 1) / size); };
  return {.pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height),
          .quads = cells(width, 2) * cells(height, 2),
          .tiles = cells(width, 8) * cells(height, 8)};
}

namespace {

// The linear output of a resolved RGBA16F texture (host copy, not a dispatch).
sim::Texture2D<glm::vec4> OutputOf(std::string name, const sim::Texture2D<glm::vec4>& texture) {
  sim::Texture2D<glm::vec4> output(std::move(name), texture.Width(), texture.Height(), 8);
  std::copy(texture.Texels().begin(), texture.Texels().end(), output.Texels().begin());
  return output;
}

class TfqPass final : public Pass {
 public:
  explicit TfqPass(const PassSettings& settings) : stage_(TfqParamsOf(settings)) {}
  const PassInfo& Info() const override { return TfqInfo(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy) override {
    PassOutput output;
    output.colour = OutputOf("tfq/output", stage_.Run(machine, frame));
    output.layers.push_back(stage_.ValidityLayer());
    output.SetWorkSet(FullScreenShape(frame.Width(), frame.Height()));
    return output;
  }

 private:
  TfqStage stage_;
};

}  // namespace

const PassInfo& TfqInfo() {
  static const std::vector<SettingInfo> settings = TfqSettings();
  static const PassInfo info{
      .name = "tfq",
      .description = "temporal FLIPQUAD: the 2x FLIPQUAD pattern split over two frames, resolved per pixel with the "
                     "reprojected previous frame and the motion-flow / colour-flow tests (seed 001, HRAA)",
      .source = "passes/hraa/tfq.h",
      .settings = settings,
      .presets = {},
      .inputs = {FrameInput::Colour, FrameInput::Velocity},
      .studiedDispatches = {kTfqResolveDispatch},
      .strategies = {Strategy::StencilCulled},
      // Colour ring 3 x vec4, velocity ring 2 x vec2, resolved and sharpened vec4, output vec4,
      // validity byte, the validity layer's float.
      .bytesPerPixel = 3 * 16 + 2 * 8 + 2 * 16 + 16 + 1 + 4,
      .layerBytesPerPixel = sizeof(float),
      .temporal = true,
      .jitter = "flipquad-split",
  };
  return info;
}

std::unique_ptr<Pass> MakeTfq(const PassSettings& settings) { return std::make_unique<TfqPass>(settings); }

}  // namespace passes::hraa
