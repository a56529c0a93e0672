// Filmic SMAA T2x (see filmic_t2x.h).

#include "passes/filmic_smaa/filmic_t2x.h"

#include <algorithm>
#include <array>
#include <optional>
#include <string>

#include "passes/filmic_smaa/edge_suppression.h"
#include "passes/filmic_smaa/morphological.h"
#include "passes/smaa/smaa.h"
#include "passes/smaa/smaa_kernels.h"
#include "passes/smaa/smaa_temporal.h"
#include "passes/smaa/temporal_resolve.h"
#include "passes/temporal/history_filter.h"
#include "passes/work_set.h"
#include "sim/colour.h"
#include "sim/formats.h"

namespace passes::filmic_smaa {

namespace {

constexpr std::string_view kPass = "filmic-smaa-t2x";

constexpr sim::KernelInfo kStoreLuma{
    .vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 8,
    .source = "hand count: one load's address (1), the luma dot (3), export (4)"};
constexpr sim::KernelInfo kDepthDownsample{
    .vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 10,
    .source = "hand count: one gather's address (2), three mins (3), export (5)"};
constexpr sim::KernelInfo kSupersample{
    .vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 90,
    .source = "hand count of the temporal supersampling: 2 velocity fetches and lengths (10), 5 luma gathers' "
              "addresses (10), 3 SADs of 4 (24), quincunx contrast and offset (10), smoothstep resampling (12), the "
              "weights (10), the lerp and export (14)"};
constexpr sim::KernelInfo kTemporalDetect{
    .vgprs = 24, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 40,
    .source = "hand count of the temporal-edge test: velocity and history fetches (6), 2 depth loads and the test "
              "(8), 2 lumas and the contrast (8), the branch and the non-edge store (10), stencil or append (8)"};
constexpr sim::KernelInfo kTemporalDetectCompute{
    .vgprs = 24, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 48,
    .source = "the pixel form's 40 plus the thread-to-pixel mapping, bounds test and the append's address (~8)"};
constexpr sim::KernelInfo kTemporalFilter{
    .vgprs = 40, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 110,
    .source = "hand count of SMAAFilterHistory (weights ~30, 5 taps and the sum ~25), the 3x3 min/max (9 loads, "
              "16 min/max ~30), the clamp and blend (~15), export (~10)"};

struct TemporalSettings {
  float temporalThreshold, convergenceTime, sharpness, depthTolerance, quincunxContrast, colourWeightScale,
      weightScale;
};

TemporalSettings TemporalSettingsOf(const PassSettings& s) {
  const auto get = [&](std::string_view key) { return static_cast<float>(s.Get(key)); };
  return {get("temporal_threshold"), get("convergence_time"), get("sharpness") / 100.0f, get("depth_tolerance"),
          get("quincunx_contrast"),  get("colour_weight_scale"), get("reprojection_weight_scale")};
}

// Rec. 709 luma of linear colour, the temporal contrast's measure.
float LinearLuma(const glm::vec4& c) { return sim::Rec709Luma(glm::vec3(c)); }

float Sad(const glm::vec4& a, const glm::vec4& b) {
  const glm::vec4 d = glm::abs(a - b);
  return d.x + d.y + d.z + d.w;
}

template <typename T, std::size_t N>
T& Ring(std::array<std::optional<T>, N>& ring, int index) {
  return *ring[static_cast<std::size_t>(index) % N];
}

class FilmicT2xPass final : public Pass {
 public:
  explicit FilmicT2xPass(const PassSettings& settings)
      : morphological_(kPass, ConfigOf(settings)), settings_(TemporalSettingsOf(settings)),
        temporalSet_(std::string(kPass) + "/temporal") {}

  const PassInfo& Info() const override { return FilmicT2xInfo(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.Width(), height = frame.Height();
    Prepare(frame, width, height);
    sim::Texture2D<glm::vec4>& colour = *colour_;
    CopySrgb8Frame(frame, colour);
    sim::Texture2D<glm::vec4>& morph = Ring(morph_, frames_);
    CopySrgb8Frame(frame, morph);  // the target starts as the frame, as CopyResource would make it
    edges_->Fill(glm::vec2(0.0f));
    morphological_.SetSubsampleIndices(smaa::T2xSubsampleIndices(frame.frameIndex));
    WorkSetShape shape = morphological_.Run(machine, strategy, colour, morph, *edges_);
    const std::vector<std::uint8_t> items = morphological_.Membership(strategy);
    const std::size_t slot = static_cast<std::size_t>(frames_ % 2);
    const std::string velocityName = std::string(kPass) + "/velocity" + std::to_string(slot);
    smaa::StoreUvVelocity(frame, velocity_[slot], velocityName, width, height);
    StoreLuma(machine);
    DownsampleDepth(machine, *frame.depth);
    Supersample(machine, frame.jitter);
    const WorkSetShape temporal = Filter(machine, strategy, frame.frameSeconds);
    shape.pixels += temporal.pixels;
    shape.quads += temporal.quads;
    shape.tiles += temporal.tiles;

    PassOutput output;
    output.SetWorkSet(shape);
    output.layers.push_back(LayerOf("edges", *edges_, {"R", "G"}));
    output.layers.push_back(MembershipLayer("items", items, width, height));
    output.layers.push_back(MembershipLayer("temporal-edges", temporalSet_.Membership(strategy), width, height));
    const sim::Texture2D<glm::vec4>& filtered = Ring(filtered_, frames_);
    output.colour = sim::Texture2D<glm::vec4>(std::string(kPass) + "/output", width, height, 16);
    std::copy(filtered.Texels().begin(), filtered.Texels().end(), output.colour.Texels().begin());
    previousJitter_ = frame.jitter;
    ++frames_;
    return output;
  }

 private:
  // (Re)makes the targets; a sequence's first frame or a new size drops the history.
  void Prepare(const FrameInputs& frame, int width, int height) {
    const bool resized = !colour_ || colour_->Width() != width || colour_->Height() != height;
    if (resized || frame.frameIndex == 0) frames_ = 0;
    const std::string pass(kPass);
    const int halfWidth = (width + 1) / 2, halfHeight = (height + 1) / 2;
    FrameTexture(colour_, pass + "/colour", width, height, sim::Format::RGBA8Srgb);
    FrameTexture(edges_, pass + "/edges", width, height, sim::Format::RG8Unorm);
    FrameTexture(resolved_, pass + "/resolved", width, height, sim::Format::RGBA8Srgb);
    for (std::size_t i = 0; i < 2; ++i) {
      const std::string n = std::to_string(i);
      FrameTexture(morph_[i], pass + "/history-morph" + n, width, height, sim::Format::RGBA8Srgb);
      FrameTexture(depth_[i], pass + "/history-depth" + n, halfWidth, halfHeight, sim::Format::R32Float);
      FrameTexture(filtered_[i], pass + "/history-filtered" + n, width, height, sim::Format::RGBA16Float);
    }
    for (std::size_t i = 0; i < 4; ++i) {
      FrameTexture(luma_[i], pass + "/history-luma" + std::to_string(i), width, height, sim::Format::R8Unorm);
    }
  }

  void StoreLuma(sim::Machine& machine) {
    const sim::Texture2D<glm::vec4>& morph = Ring(morph_, frames_);
    sim::Dispatch d(std::string(kPass) + "/store-luma", kStoreLuma);
    const sim::TextureView<glm::vec4> gamma = d.Read(morph).As(sim::Format::RGBA8Unorm);
    const sim::RwTextureView<float> out = d.ReadWrite(Ring(luma_, frames_));
    machine.FullScreen(d, {.width = morph.Width(), .height = morph.Height()}, [&](sim::PixelLane& lane) {
      out.Store(lane, lane.x, lane.y, Luma(glm::vec3(gamma.Load(lane, lane.x, lane.y))));
    });
  }

  void DownsampleDepth(sim::Machine& machine, const sim::Texture2D<float>& depth) {
    sim::Texture2D<float>& half = Ring(depth_, frames_);
    sim::Dispatch d(std::string(kPass) + "/depth-downsample", kDepthDownsample);
    const sim::TextureView<float> full = d.Read(depth);
    const sim::RwTextureView<float> out = d.ReadWrite(half);
    const glm::vec2 size(static_cast<float>(depth.Width()), static_cast<float>(depth.Height()));
    machine.FullScreen(d, {.width = half.Width(), .height = half.Height()}, [&](sim::PixelLane& lane) {
      // One gather at the shared corner of the 2x2 block (clamped at odd edges): its nearest depth.
      const glm::vec4 g = full.Gather(lane, glm::vec2(2 * lane.x + 1, 2 * lane.y + 1) / size);
      out.Store(lane, lane.x, lane.y, std::min(std::min(g.x, g.y), std::min(g.z, g.w)));
    });
  }

  void Supersample(sim::Machine& machine, glm::vec2 jitter) {
    const sim::Texture2D<glm::vec4>& current = Ring(morph_, frames_);
    const bool hasPrevious = frames_ >= 1;
    const sim::Texture2D<glm::vec4>& previous = hasPrevious ? Ring(morph_, frames_ + 1) : current;
    const int width = current.Width(), height = current.Height();
    const glm::vec2 size(static_cast<float>(width), static_cast<float>(height));
    const glm::vec2 quincunx = jitter - previousJitter_;
    const TemporalSettings s = settings_;
    // The luma of frames N-k, k = 0..3, where they exist (k <= frames_).
    const int known = std::min(frames_, 3);
    sim::Dispatch d(std::string(kPass) + "/supersample", kSupersample);
    const sim::TextureView<glm::vec4> now = d.Read(current), before = d.Read(previous);
    const sim::TextureView<glm::vec2> vNow = d.Read(Ring(velocity_, frames_));
    const sim::TextureView<glm::vec2> vBefore = d.Read(Ring(velocity_, frames_ + (hasPrevious ? 1 : 0)));
    std::vector<sim::TextureView<float>> luma;
    for (int k = 0; k <= known; ++k) luma.push_back(d.Read(Ring(luma_, frames_ + 4 - k)));
    const sim::RwTextureView<glm::vec4> out = d.ReadWrite(*resolved_);
    machine.FullScreen(d, {.width = width, .height = height}, [&](sim::PixelLane& lane) {
      const glm::vec2 uv = smaa::Metrics::Of(width, height).Texcoord(lane.x, lane.y);
      const glm::vec4 centre = now.Load(lane, lane.x, lane.y);
      if (!hasPrevious) {
        out.Store(lane, lane.x, lane.y, centre);
        return;
      }
      const glm::vec2 v = vNow.SamplePoint(lane, uv);
      const glm::vec2 back = uv - v;
      const float velocityWeight = smaa::Saturate(
          1.0f - std::sqrt(std::fabs(glm::length(v) - glm::length(vBefore.SamplePoint(lane, back)))) * s.weightScale);
      // Colour weights: frames of equal jitter compared, N with N-2 and N-1 with N-3.
      const auto colourWeight = [&](int newer, int older) {
        if (older > known) return 1.0f;
        const glm::vec2 at = uv - static_cast<float>(newer) * v, olderAt = uv - static_cast<float>(older) * v;
        const float sad = Sad(luma[static_cast<std::size_t>(newer)].Gather(lane, at),
                              luma[static_cast<std::size_t>(older)].Gather(lane, olderAt));
        return smaa::Saturate(1.0f - sad * s.colourWeightScale);
      };
      const float colourWeights = colourWeight(0, 2) * colourWeight(1, 3);
      // Contrast-aware quincunx: the previous frame's four samples around this frame's.
      const glm::vec4 around = luma[1].Gather(lane, back + quincunx / size);
      const float contrast = std::max(std::max(around.x, around.y), std::max(around.z, around.w)) -
                             std::min(std::min(around.x, around.y), std::min(around.z, around.w));
      const float t = smaa::Saturate(contrast / s.quincunxContrast);
      // Fast smootheststep resampling: the fraction through smoothstep, then one bilinear fetch.
      const glm::vec2 position = (back + t * quincunx / size) * size - 0.5f;
      const glm::vec2 base = glm::floor(position);
      glm::vec2 f = position - base;
      f = f * f * (3.0f - 2.0f * f);
      const glm::vec4 earlier = before.SampleBilinear(lane, (base + f + 0.5f) / size);
      out.Store(lane, lane.x, lane.y, smaa::Lerp(centre, earlier, 0.5f * velocityWeight * colourWeights));
    });
  }

  WorkSetShape Filter(sim::Machine& machine, Strategy strategy, double frameSeconds) {
    const bool hasHistory = frames_ >= 1;
    sim::Texture2D<glm::vec4>& target = Ring(filtered_, frames_);
    // Without history nothing reads it: the resolved frame stands in for the binding.
    const sim::Texture2D<glm::vec4>& historyTarget = hasHistory ? Ring(filtered_, frames_ + 1) : *resolved_;
    const sim::Texture2D<float>& depthNow = Ring(depth_, frames_);
    const sim::Texture2D<float>& depthBefore = hasHistory ? Ring(depth_, frames_ + 1) : depthNow;
    const sim::Texture2D<glm::vec2>& velocity = Ring(velocity_, frames_);
    const int width = target.Width(), height = target.Height();
    const glm::vec2 size(static_cast<float>(width), static_cast<float>(height));
    const TemporalSettings s = settings_;
    const float historyWeight = HistoryWeight(frameSeconds, static_cast<double>(s.convergenceTime));
    auto makeDetect = [&](sim::Dispatch& d, auto) {
      const sim::TextureView<glm::vec4> resolved = d.Read(*resolved_), history = d.Read(historyTarget);
      const sim::TextureView<glm::vec2> motion = d.Read(velocity);
      const sim::TextureView<float> dNow = d.Read(depthNow), dBefore = d.Read(depthBefore);
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(target);
      return [=](const auto& lane, int x, int y) {
        const glm::vec4 current = resolved.Load(lane, x, y);
        bool edge = hasHistory;
        if (edge) {
          const glm::vec2 uv = smaa::Metrics::Of(width, height).Texcoord(x, y);
          const glm::vec2 back = uv - motion.SamplePoint(lane, uv);
          // The half-resolution texels holding this pixel and its previous position.
          const int bx = std::clamp(static_cast<int>(std::floor(back.x * size.x)), 0, width - 1);
          const int by = std::clamp(static_cast<int>(std::floor(back.y * size.y)), 0, height - 1);
          const float nearest = dNow.Load(lane, x / 2, y / 2), before = dBefore.Load(lane, bx / 2, by / 2);
          edge = std::fabs(nearest - before) <= s.depthTolerance &&
                 std::fabs(LinearLuma(current) - LinearLuma(history.SampleBilinear(lane, back))) >= s.temporalThreshold;
        }
        if (!edge) out.Store(lane, x, y, current);
        return edge;
      };
    };
    auto makeConsume = [&](sim::Dispatch& d) {
      const sim::TextureView<glm::vec4> resolved = d.Read(*resolved_), before = d.Read(historyTarget);
      const sim::TextureView<glm::vec2> motion = d.Read(velocity);
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(target);
      return [=](const auto& lane, int x, int y) {
        const glm::vec2 uv = smaa::Metrics::Of(width, height).Texcoord(x, y);
        const glm::vec2 back = uv - motion.SamplePoint(lane, uv);
        const glm::vec3 filtered(temporal::SampleHistoryFilmic(before, lane, back, s.sharpness));
        glm::vec3 low(1e30f), high(-1e30f);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = std::clamp(x + dx, 0, width - 1), ny = std::clamp(y + dy, 0, height - 1);
            const glm::vec3 n(resolved.Load(lane, nx, ny));
            low = glm::min(low, n);
            high = glm::max(high, n);
          }
        }
        const glm::vec4 current = resolved.Load(lane, x, y);
        const glm::vec3 clamped = glm::clamp(filtered, low, high);
        const glm::vec3 blended = clamped * historyWeight + glm::vec3(current) * (1.0f - historyWeight);
        out.Store(lane, x, y, glm::vec4(blended, current.a));
      };
    };
    const WorkSetKernels kernels{.detectDispatch = "filmic-smaa-t2x/temporal-edges",
                                 .consumeDispatch = "filmic-smaa-t2x/temporal-filter",
                                 .detectPixel = kTemporalDetect, .detectCompute = kTemporalDetectCompute,
                                 .consume = kTemporalFilter};
    return temporalSet_.Run(machine, strategy, kernels, width, height, makeDetect, makeConsume);
  }

  Morphological morphological_;
  TemporalSettings settings_;
  WorkSet temporalSet_;
  std::optional<sim::Texture2D<glm::vec4>> colour_, resolved_;
  std::optional<sim::Texture2D<glm::vec2>> edges_;
  std::array<std::optional<sim::Texture2D<glm::vec4>>, 2> morph_, filtered_;
  std::array<std::optional<sim::Texture2D<glm::vec2>>, 2> velocity_;
  std::array<std::optional<sim::Texture2D<float>>, 2> depth_;
  std::array<std::optional<sim::Texture2D<float>>, 4> luma_;
  glm::vec2 previousJitter_{0.0f};
  int frames_ = 0;  // frames since the history was last dropped
};

std::vector<SettingInfo> FilmicT2xSettings() {
  std::vector<SettingInfo> settings = smaa::SearchSettings(
      "SMAA_THRESHOLD: edge contrast in gamma space; patterns through an edge must score 2x it");
  const std::vector<SettingInfo> temporal = {
      {.name = "temporal_threshold", .defaultValue = 0.02, .min = 0.0, .max = 1.0,
       .doc = "linear-luma difference between the supersampled frame and the history below which a pixel is not "
              "filtered (seed 000 gives no value; about 5 sRGB codes at mid grey)"},
      {.name = "convergence_time", .defaultValue = 0.158, .min = 0.001, .max = 10.0,
       .doc = "tau in seconds of the FPS-aware history weight exp(-dt / tau): 0.158 keeps 0.9 of the history at "
              "60 fps (the frame's weight 0.1, aa-facts §5.4's typical alpha)"},
      {.name = "sharpness", .defaultValue = 50, .min = 0, .max = 100,
       .doc = "SMAA_FILMIC_REPROJECTION_SHARPNESS: the history filter's cubic c x 100 (50 = Catmull-Rom; public "
              "ports use 40-60, aa-facts §2)"},
      {.name = "depth_tolerance", .defaultValue = 0.01, .min = 0.0, .max = 1.0,
       .doc = "half-resolution nearest-depth difference between the frames above which a pixel is a disocclusion "
              "(no value in the seed)"},
      {.name = "quincunx_contrast", .defaultValue = 0.1, .min = 0.001, .max = 1.0,
       .doc = "gamma-luma range of the previous frame's four samples at which the resolve is fully quincunx "
              "(SMAA's edge threshold; the seed gives no value)"},
      {.name = "colour_weight_scale", .defaultValue = 4, .min = 0, .max = 64,
       .doc = "colour weight = saturate(1 - SAD x this) over a 2x2 gamma-luma block: a mean change of 1/16 per "
              "texel rejects (no value in the seed)"},
      {.name = "reprojection_weight_scale", .defaultValue = static_cast<double>(smaa::kReprojectionWeightScale), .min = 0, .max = 80,
       .doc = "SMAA_REPROJECTION_WEIGHT_SCALE of the supersampling's velocity weight (SMAA.hlsl: 30)"},
  };
  settings.insert(settings.end(), temporal.begin(), temporal.end());
  return settings;
}

}  // namespace

const PassInfo& FilmicT2xInfo() {
  static const PassInfo info{
      .name = "filmic-smaa-t2x",
      .description = "Filmic SMAA T2x: Filmic SMAA's morphological part with T2x subsample indices, temporal "
                     "supersampling (contrast-aware quincunx, velocity and colour weights), then a temporal filter "
                     "on temporal edges only (deferred queue, Catmull-Rom history, depth test, FPS-aware alpha)",
      .source = "passes/filmic_smaa/filmic_t2x.h",
      .settings = FilmicT2xSettings(),
      .presets = smaa::SearchPresets(),
      .inputs = {FrameInput::Colour, FrameInput::Depth, FrameInput::Velocity},
      .studiedDispatches = {"filmic-smaa-t2x/vertical-edges", "filmic-smaa-t2x/horizontal-edges",
                            "filmic-smaa-t2x/temporal-filter"},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // Colour, resolved, two morph targets, two RGBA16F histories, the output copy (vec4 each);
      // edges and two velocities (vec2); four lumas, half-res depths, three layer floats; the
      // work sets' stencil bytes, memberships and queue entries.
      .bytesPerPixel =
          7 * sizeof(glm::vec4) + 3 * sizeof(glm::vec2) + 8 * sizeof(float) + 4 + 3 * sizeof(std::uint32_t),
      .layerBytesPerPixel = 2 + (1 + 1) * sizeof(float),  // edges (RG8 codes), two float layers
      .temporal = true,
      .jitter = "t2x",
      .variantOf = "filmic-smaa",
  };
  return info;
}

std::unique_ptr<Pass> MakeFilmicT2x(const PassSettings& settings) { return std::make_unique<FilmicT2xPass>(settings); }

}  // namespace passes::filmic_smaa
