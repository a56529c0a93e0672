// UE4 temporal AA on the pass framework (see taa_ue4.h).

#include "passes/taa_ue4/taa_ue4.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "passes/taa_ue4/taa_ue4_math.h"
#include "passes/temporal/colour_box.h"
#include "passes/temporal/history_filter.h"
#include "passes/work_set.h"
#include "sim/formats.h"

namespace passes::taa_ue4 {
namespace {

constexpr std::string_view kResolveDispatch = "taa-ue4/resolve";

const sim::KernelInfo kResolveKernel{
    .vgprs = 64, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 300,
    .source = "hand count of the resolve per pixel: 9 colour and 9 depth loads with clamped addresses (~40), the "
              "front-most depth search (~20), 9 Gaussian weights with exp and luma weights (~70), the weighted "
              "sum (~40), 5-tap history addresses and weights (~40), 9 YCoCg conversions and the two min/max "
              "boxes (~50), the clip (~25), anti-flicker and the blend (~15)"};

struct Config {
  float alpha = 0.04f;
  float responsiveAlpha = 0.8f;
  std::int64_t responsiveObject = -1;
  float antiFlicker = 1.0f;
  Constraint constraint = Constraint::ClipShapedYCoCg;
  bool reconstruction = true;
  bool lumaWeight = true;
};

Config ConfigOf(const PassSettings& settings) {
  return {.alpha = static_cast<float>(settings.Get("alpha")),
          .responsiveAlpha = static_cast<float>(settings.Get("responsive_alpha")),
          .responsiveObject = static_cast<std::int64_t>(settings.Get("responsive_object")),
          .antiFlicker = static_cast<float>(settings.Get("anti_flicker")),
          .constraint = static_cast<Constraint>(static_cast<int>(settings.Get("constraint"))),
          .reconstruction = settings.Get("reconstruction") != 0.0,
          .lumaWeight = settings.Get("luma_weight") != 0.0};
}

// The 3x3 neighbourhood's current samples, centre first (temporal::kOffsets3x3 order).
using Neighbourhood = std::array<glm::vec3, 9>;

// The history constrained to the current neighbourhood, and the luma range the anti-flicker
// measures against.
struct Constrained {
  glm::vec3 history;
  float yMin, yMax;
  bool moved;
};

// The luma (YCoCg Y) range of the 3x3 samples.
std::pair<float, float> LumaRange(const Neighbourhood& rgb) {
  float yMin = sim::RgbToYCoCg(rgb[0]).x, yMax = yMin;
  for (const glm::vec3& c : rgb) {
    yMin = std::min(yMin, sim::RgbToYCoCg(c).x);
    yMax = std::max(yMax, sim::RgbToYCoCg(c).x);
  }
  return {yMin, yMax};
}

Constrained ClampRgb(const Neighbourhood& rgb, const glm::vec3& history) {
  temporal::ColourBox box{rgb[0], rgb[0]};
  for (const glm::vec3& c : rgb) box = {glm::min(box.min, c), glm::max(box.max, c)};
  const glm::vec3 clamped = temporal::ClampToBox(history, box);
  const auto [yMin, yMax] = LumaRange(rgb);
  return {clamped, yMin, yMax, clamped != history};
}

Constrained Constrain(const Neighbourhood& rgb, const glm::vec3& history, Constraint constraint) {
  if (constraint == Constraint::ClampRgb3x3) return ClampRgb(rgb, history);
  Neighbourhood ycocg;
  glm::vec3 mean(0.0f);
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    ycocg[i] = sim::RgbToYCoCg(rgb[i]);
    mean += ycocg[i];
  }
  mean /= static_cast<float>(rgb.size());
  const auto fetch = [&](glm::ivec2 o) {
    const auto i = static_cast<std::size_t>(std::ranges::find(temporal::kOffsets3x3, o) - temporal::kOffsets3x3.begin());
    return ycocg[i];
  };
  const temporal::ColourBox shaped = temporal::AverageBox(temporal::MinMaxBox(temporal::Neighbourhood::Box3x3, fetch),
                                                          temporal::MinMaxBox(temporal::Neighbourhood::Plus, fetch));
  if (constraint == Constraint::None) return {history, shaped.min.x, shaped.max.x, false};
  const glm::vec3 h = sim::RgbToYCoCg(history);
  // Seed 002: "constrain to a blend of history and neighborhood average": the segment from the
  // mean (brought into the shaped box, which need not hold it) to the history.
  const glm::vec3 clipped = temporal::ClipTowards(h, shaped, temporal::ClampToBox(mean, shaped));
  // An untouched history keeps its RGB bits (the YCoCg round trip rounds).
  if (clipped == h) return {history, shaped.min.x, shaped.max.x, false};
  return {sim::YCoCgToRgb(clipped), shaped.min.x, shaped.max.x, true};
}

// The resolve kernel: its bindings and the diagram's steps per pixel.
struct Resolve {
  sim::TextureView<glm::vec4> colour, history;
  std::optional<sim::TextureView<float>> depth;
  std::optional<sim::TextureView<glm::vec2>> velocity;
  std::optional<sim::TextureView<std::uint32_t>> objectId;  // bound when a responsive object is set
  sim::RwTextureView<glm::vec4> out;
  sim::CounterView clipped, offscreen, responsive;
  Config config;
  // Step 3's Gaussian weights of the nine samples: the jitter is the frame's, so they are the
  // same for every pixel (GaussianWeights).
  std::array<float, 9> gaussian;
  int width, height;
  bool useHistory;

  void operator()(const sim::PixelLane& lane) const {
    const int x = lane.x, y = lane.y;
    Neighbourhood samples;
    const glm::vec2 v = LoadNeighbourhood(lane, samples);
    const glm::vec3 current = config.reconstruction ? Reconstruct(samples) : samples[0];
    const glm::vec2 uv = temporal::HistoryUv(x, y, v, width, height);
    const bool onScreen = uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f;
    if (useHistory && !onScreen) offscreen.Add(lane);
    if (!useHistory || !onScreen) {
      out.Store(lane, x, y, glm::vec4(current, 1.0f));
      return;
    }
    const glm::vec3 reprojected(temporal::SampleHistoryFilmic(history, lane, uv, temporal::kCatmullRom));
    const Constrained constrained = Constrain(samples, reprojected, config.constraint);
    if (constrained.moved) clipped.Add(lane);
    const float alpha = Alpha(lane, constrained);
    const glm::vec3 h = constrained.history;
    const float beta = config.lumaWeight ? CurrentShare(alpha, LumaWeight(current), LumaWeight(h)) : alpha;
    out.Store(lane, x, y, glm::vec4(h + (current - h) * beta, 1.0f));
  }

  // Steps 1-2: the 3x3 samples (addresses clamped to the screen, as a clamp sampler's) and the
  // velocity of the front-most of them.
  glm::vec2 LoadNeighbourhood(const sim::PixelLane& lane, Neighbourhood& samples) const {
    glm::ivec2 front(lane.x, lane.y);
    float frontDepth = 0.0f;
    for (std::size_t i = 0; i < temporal::kOffsets3x3.size(); ++i) {
      const glm::ivec2 p(std::clamp(lane.x + temporal::kOffsets3x3[i].x, 0, width - 1),
                         std::clamp(lane.y + temporal::kOffsets3x3[i].y, 0, height - 1));
      samples[i] = glm::vec3(colour.Load(lane, p.x, p.y));
      if (!depth) continue;
      const float z = depth->Load(lane, p.x, p.y);
      // Strictly nearer only, so ties keep the earlier offset (the centre first).
      if (i == 0 || z < frontDepth) {
        frontDepth = z;
        front = p;
      }
    }
    return velocity ? velocity->Load(lane, front.x, front.y) : glm::vec2(0.0f);
  }

  // Step 3: the Gaussian-weighted (and luma-weighted) mean of the jittered samples around this
  // pixel's centre.
  glm::vec3 Reconstruct(const Neighbourhood& samples) const {
    glm::vec3 sum(0.0f);
    float weights = 0.0f;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const float w = gaussian[i] * (config.lumaWeight ? LumaWeight(samples[i]) : 1.0f);
      sum += samples[i] * w;
      weights += w;
    }
    return sum / weights;
  }

  // Step 6's current weight: responsive pixels take theirs, the rest the anti-flicker's.
  float Alpha(const sim::PixelLane& lane, const Constrained& constrained) const {
    if (objectId && objectId->Load(lane, lane.x, lane.y) == static_cast<std::uint32_t>(config.responsiveObject)) {
      responsive.Add(lane);
      return config.responsiveAlpha;
    }
    return AntiFlickerAlpha(config.alpha, sim::RgbToYCoCg(constrained.history).x, constrained.yMin, constrained.yMax,
                            config.antiFlicker);
  }
};

// The reconstruction weight of each 3x3 sample, offset from this pixel's centre by its texel
// offset plus the frame's jitter.
std::array<float, 9> GaussianWeights(glm::vec2 jitter) {
  std::array<float, 9> weights{};
  for (std::size_t i = 0; i < weights.size(); ++i) {
    weights[i] = ReconstructionWeight(glm::vec2(temporal::kOffsets3x3[i]) + jitter);
  }
  return weights;
}

template <typename T>
std::optional<sim::TextureView<T>> ReadIf(sim::Dispatch& d, const sim::Texture2D<T>* texture) {
  if (texture == nullptr) return std::nullopt;
  return d.Read(*texture);
}

class TaaUe4Pass final : public Pass {
 public:
  explicit TaaUe4Pass(const Config& config) : config_(config) {}

  const PassInfo& Info() const override { return taa_ue4::Info(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override;

 private:
  Config config_;
  std::array<std::optional<sim::Texture2D<glm::vec4>>, 2> history_;
  int current_ = 0;          // the history target this frame writes
  bool hasHistory_ = false;  // the other target holds the previous frame's output
};

PassOutput TaaUe4Pass::Run(sim::Machine& machine, const FrameInputs& frame, Strategy) {
  const int width = frame.Width(), height = frame.Height();
  const int previous = 1 - current_;
  const bool resized = !history_[previous] || history_[previous]->Width() != width || history_[previous]->Height() != height;
  const auto target = [&](int i) -> sim::Texture2D<glm::vec4>& {
    return FrameTexture(history_[static_cast<std::size_t>(i)], "taa-ue4/history-" + std::to_string(i), width, height,
                        sim::Format::RGBA16Float);
  };
  sim::Texture2D<glm::vec4>& read = target(previous);
  sim::Texture2D<glm::vec4>& write = target(current_);

  sim::Dispatch d(std::string(kResolveDispatch), kResolveKernel);
  const Resolve resolve{.colour = d.Read(*frame.colour),
                        .history = d.Read(read),
                        .depth = ReadIf(d, frame.depth),
                        .velocity = ReadIf(d, frame.velocity),
                        .objectId = config_.responsiveObject >= 0 ? ReadIf(d, frame.objectId) : std::nullopt,
                        .out = d.ReadWrite(write),
                        .clipped = d.Counter("taa-ue4/history_clipped"),
                        .offscreen = d.Counter("taa-ue4/history_offscreen"),
                        .responsive = d.Counter("taa-ue4/responsive_pixels"),
                        .config = config_,
                        .gaussian = GaussianWeights(frame.jitter),
                        .width = width,
                        .height = height,
                        .useHistory = hasHistory_ && !resized && frame.frameIndex != 0};
  machine.FullScreen(d, {.width = width, .height = height}, resolve);

  hasHistory_ = true;
  current_ = previous;
  PassOutput output{.colour = {"taa-ue4/output", width, height, sim::Format::RGBA16Float},
                    .layers = {},
                    .workItems = 0,
                    .workSet = {}};
  std::ranges::copy(write.Texels(), output.colour.Texels().begin());
  output.SetWorkSet(ShapeOf(std::vector<std::uint8_t>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 1),
                            width, height));
  return output;
}

std::vector<SettingInfo> Settings() {
  return {
      {.name = "alpha", .defaultValue = 0.04, .min = 0.0, .max = 1.0, .minExclusive = true,
       .doc = "current frame's weight in the exponential history blend (seed 002 \"Exponential smoothing\" gives the "
              "form; 0.04 is UE4's commonly reported value, aa-facts §5.1 [unverified])"},
      {.name = "responsive_alpha", .defaultValue = 0.8, .min = 0.0, .max = 1.0, .minExclusive = true,
       .doc = "current weight on responsive pixels: \"minimal feedback\", but > 0 history (seed 002 \"Responsive AA\"; "
              "0.8 is our choice, the talk gives no number)"},
      {.name = "responsive_object", .defaultValue = -1.0, .min = -1.0, .max = 4294967295.0, .integer = true,
       .doc = "object id whose pixels are responsive (the stencil UE4 sets when drawing translucency, here read from "
              "the object id target); -1: none"},
      {.name = "anti_flicker", .defaultValue = 1.0, .min = 0.0, .max = 1.0,
       .doc = "how far the current weight drops when the history sits on a face of the box's luma range: alpha * "
              "lerp(1, 3d / (d + range), strength) (seed 002 \"reduce blend factor when history is near clamping\"; "
              "formula ours, docs/temporal.md)"},
      {.name = "constraint", .defaultValue = 2.0, .min = 0.0, .max = 2.0, .integer = true,
       .doc = "0: none; 1: clamp to the 3x3 RGB min/max (seed 002 \"Neighborhood clamping\"); 2: clip towards the "
              "neighbourhood mean against the shaped YCoCg box (seed 002 \"Clip instead of clamp\")"},
      {.name = "reconstruction", .defaultValue = 1.0, .min = 0.0, .max = 1.0, .integer = true,
       .doc = "1: Gaussian e^(-2.29 x²) reconstruction of the jittered 3x3 samples (seed 002 \"Reconstruction "
              "filter\"); 0: the pixel's own sample"},
      {.name = "luma_weight", .defaultValue = 1.0, .min = 0.0, .max = 1.0, .integer = true,
       .doc = "1: weight samples and the history blend by 1 / (1 + luma) (seed 002 \"Better tone map solution\"); 0: off"},
  };
}

}  // namespace

const PassInfo& Info() {
  static const PassInfo info{
      .name = "taa-ue4",
      .description = "UE4 temporal AA (Karis 2014): Halton 8 jitter, Gaussian reconstruction, front-most velocity, "
                     "bicubic history clipped to the shaped YCoCg box, luma-weighted exponential blend, anti-flicker",
      .source = "passes/taa_ue4/taa_ue4.h",
      .settings = Settings(),
      .presets = {},
      .inputs = {FrameInput::Colour, FrameInput::Depth, FrameInput::Velocity, FrameInput::ObjectId},
      .studiedDispatches = {kResolveDispatch},
      .strategies = {Strategy::StencilCulled},
      // Two history targets and the output copy (vec4 each on the host).
      .bytesPerPixel = 3 * sizeof(glm::vec4),
      .layerBytesPerPixel = 0,
      .temporal = true,
      .jitter = "halton8",
  };
  return info;
}

std::unique_ptr<Pass> Make(const PassSettings& settings) { return std::make_unique<TaaUe4Pass>(ConfigOf(settings)); }

}  // namespace passes::taa_ue4
