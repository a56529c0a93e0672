// HRAA: temporal FLIPQUAD + TAA with the frequency-based acceptance metric (see hraa.h).

#include "passes/hraa/hraa.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "passes/hraa/history_resample.h"
#include "passes/hraa/tfq.h"
#include "sim/colour.h"
#include "sim/formats.h"

namespace passes::hraa {
namespace {

// Hand counts per form of the history read: the window (9 loads, 9 YCoCg conversions, mean, min,
// max: about 80), t and the exponential (25), the blend and store (15), plus the read: one
// bilinear sample (bilinear, maccormack: 10), three loads and the correction (bfecc: 15), four
// bilinear samples, their weights and the correction (gpu-bfecc: 45).
sim::KernelInfo TaaKernel(Resampling mode) {
  constexpr std::string_view kSource = "hand count: 3x3 window in YCoCg, mean/min/max, t, exp, blend; plus the "
                                       "history read of the resampling form";
  const double read = mode == Resampling::GpuBfecc ? 45.0 : mode == Resampling::Bfecc ? 15.0 : 10.0;
  return {.vgprs = mode == Resampling::GpuBfecc ? 48 : 40, .sgprs = 24, .ldsBytesPerGroup = 0,
          .valuInstructionsPerWave = 120.0 + read, .source = kSource};
}

// One 8-bit step: keeps a flat window's zero range from dividing by zero (hraa.h).
constexpr float kRangeEpsilon = 1.0f / 256.0f;

struct TaaParams {
  float feedbackMean, feedbackBound, falloff;
  Resampling resampling;
  bool tfq;
};

// The history weight of hraa.h's acceptance metric.
float Feedback(const TaaParams& params, float t) {
  if (t <= 1.0f) return params.feedbackMean + (params.feedbackBound - params.feedbackMean) * t;
  return params.feedbackBound * std::exp(-params.falloff * (t - 1.0f));
}

// Normalised distance of the history from the window's mean, against the min/max box.
float Distance(const glm::vec3& h, const glm::vec3& mean, const glm::vec3& lo, const glm::vec3& hi) {
  float t = 0.0f;
  for (int c = 0; c < 3; ++c) {
    const float range = h[c] >= mean[c] ? hi[c] - mean[c] : mean[c] - lo[c];
    t = std::max(t, std::abs(h[c] - mean[c]) / (range + kRangeEpsilon));
  }
  return t;
}

class HraaPass final : public Pass {
 public:
  explicit HraaPass(const PassSettings& settings)
      : params_{.feedbackMean = static_cast<float>(settings.Get("feedback_mean")),
                .feedbackBound = static_cast<float>(settings.Get("feedback_bound")),
                .falloff = static_cast<float>(settings.Get("falloff")),
                .resampling = static_cast<Resampling>(static_cast<int>(settings.Get("resample"))),
                .tfq = settings.Get("tfq") != 0.0},
        stage_(TfqParamsOf(settings)) {}

  const PassInfo& Info() const override { return HraaInfo(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy) override {
    const int width = frame.Width(), height = frame.Height();
    const sim::Texture2D<glm::vec4>* current = nullptr;
    if (params_.tfq) {
      current = &stage_.Run(machine, frame);
    } else {
      stage_.Ring().Store(frame);
      current = &stage_.Ring().Colour(0);
    }
    const FrameRing& ring = stage_.Ring();
    for (std::size_t i = 0; i < history_.size(); ++i) {
      FrameTexture(history_[i], "hraa/history-" + std::to_string(i), width, height, sim::Format::RGBA16Float);
    }
    // Frame 0 of a sequence: the current image is the history.
    const bool haveHistory = ring.Frames() >= 2;
    if (!haveHistory) read_ = 0;
    const sim::Texture2D<glm::vec4>& previous = *history_[read_];
    sim::Texture2D<glm::vec4>& next = *history_[1 - read_];
    if (haveHistory) resampler_.Prepare(machine, params_.resampling, previous, ring.Velocity(0));
    feedback_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0f);
    Blend(machine, *current, ring.Velocity(0), haveHistory ? &previous : nullptr, next);
    read_ = 1 - read_;

    PassOutput output;
    output.colour = sim::Texture2D<glm::vec4>("hraa/output", width, height, 8);
    std::copy(next.Texels().begin(), next.Texels().end(), output.colour.Texels().begin());
    output.layers.push_back(Validity(width, height));
    output.layers.push_back(PassLayer{"feedback", {"Y"}, width, height, feedback_, {}, 0});
    output.SetWorkSet(FullScreenShape(width, height));
    return output;
  }

 private:
  void Blend(sim::Machine& machine, const sim::Texture2D<glm::vec4>& current, const sim::Texture2D<glm::vec2>& velocity,
             const sim::Texture2D<glm::vec4>* history, sim::Texture2D<glm::vec4>& out) {
    const int width = current.Width(), height = current.Height();
    sim::Dispatch d(std::string(kTaaDispatch), TaaKernel(params_.resampling));
    const sim::TextureView<glm::vec4> fresh = d.Read(current);
    const sim::TextureView<glm::vec2> motion = d.Read(velocity);
    std::optional<HistoryFetch> fetch;
    if (history != nullptr) fetch = resampler_.Bind(d, params_.resampling, *history);
    const sim::RwTextureView<glm::vec4> target = d.ReadWrite(out);
    const TaaParams params = params_;
    float* feedback = feedback_.data();
    machine.FullScreen(d, {.width = width, .height = height}, [&](sim::PixelLane& lane) {
      std::array<glm::vec3, 9> window{};
      glm::vec4 centre(0.0f);
      for (int i = 0; i < 9; ++i) {
        const int x = std::clamp(lane.x + i % 3 - 1, 0, width - 1), y = std::clamp(lane.y + i / 3 - 1, 0, height - 1);
        const glm::vec4 c = fresh.Load(lane, x, y);
        if (i == 4) centre = c;
        window[static_cast<std::size_t>(i)] = sim::RgbToYCoCg(glm::vec3(c));
      }
      float beta = 0.0f;
      glm::vec3 blended(centre);
      const glm::vec2 v = fetch ? motion.Load(lane, lane.x, lane.y) : glm::vec2(0.0f);
      const glm::vec2 from = glm::vec2(lane.x, lane.y) + 0.5f - v;
      if (fetch && from.x >= 0.0f && from.y >= 0.0f && from.x <= width && from.y <= height) {
        const glm::vec3 h((*fetch)(lane, lane.x, lane.y, v));
        glm::vec3 mean(0.0f), lo = window[0], hi = window[0];
        for (const glm::vec3& w : window) {
          mean += w;
          lo = glm::min(lo, w);
          hi = glm::max(hi, w);
        }
        mean /= 9.0f;
        beta = Feedback(params, Distance(sim::RgbToYCoCg(h), mean, lo, hi));
        blended = glm::max(glm::vec3(centre) + beta * (h - glm::vec3(centre)), glm::vec3(0.0f));
      }
      target.Store(lane, lane.x, lane.y, glm::vec4(blended, centre.a));
      if (!lane.helper) feedback[static_cast<std::size_t>(lane.y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(lane.x)] = beta;
    });
  }

  // The TFQ's validity per pixel; all NoHistory (0) when the TFQ is off.
  PassLayer Validity(int width, int height) const {
    if (params_.tfq) return stage_.ValidityLayer();
    return PassLayer{"validity", {"Y"}, width, height, std::vector<float>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0f), {}, 0};
  }

  TaaParams params_;
  TfqStage stage_;
  HistoryResampler resampler_;
  std::array<std::optional<sim::Texture2D<glm::vec4>>, 2> history_;
  int read_ = 0;
  std::vector<float> feedback_;
};

std::vector<SettingInfo> Settings() {
  std::vector<SettingInfo> settings = {
      {.name = "tfq", .defaultValue = 1.0, .min = 0.0, .max = 1.0, .integer = true,
       .doc = "1: temporal FLIPQUAD feeds the TAA (seed 001 'TFQ + TAA'); 0: the TAA reads the frame itself"},
      {.name = "resample", .defaultValue = 3.0, .min = 0.0, .max = 3.0, .integer = true,
       .doc = "history resampling: 0 bilinear, 1 MacCormack, 2 BFECC, 3 GPU BFECC (seed 001 'Higher Order "
              "Resampling'; GPU BFECC is the form the seed times, 0.3 ms)"},
      {.name = "feedback_mean", .defaultValue = 0.85, .min = 0.0, .max = 1.0,
       .doc = "history weight at the window's mean (seed 001 acceptance metric: 'close to mean doesn't bring new "
              "information'; value ours)"},
      {.name = "feedback_bound", .defaultValue = 0.95, .min = 0.0, .max = 1.0,
       .doc = "history weight on the 3x3 min/max box ('further away brings more information'; value ours)"},
      {.name = "falloff", .defaultValue = 4.0, .min = 0.0, .max = 64.0,
       .doc = "exponential decay of the history weight per box-range beyond the min/max soft bound ('too far might "
              "be a fluctuation'; value ours)"},
  };
  for (SettingInfo& setting : TfqSettings()) settings.push_back(setting);
  return settings;
}

}  // namespace

const PassInfo& HraaInfo() {
  static const std::vector<SettingInfo> settings = Settings();
  static const PassInfo info{
      .name = "hraa",
      .description = "HRAA temporal: temporal FLIPQUAD + TAA with the frequency-based acceptance metric and BFECC "
                     "history resampling (seed 001)",
      .source = "passes/hraa/hraa.h",
      .settings = settings,
      .presets = {{"taa", {{"tfq", 0.0}}},
                  {"exponential", {{"tfq", 0.0}, {"feedback_mean", 0.9}, {"feedback_bound", 0.9}, {"falloff", 0.0}}}},
      .inputs = {FrameInput::Colour, FrameInput::Velocity},
      .studiedDispatches = {kTaaDispatch},
      .strategies = {Strategy::StencilCulled},
      // tfq's (colour ring, velocity ring, resolved, sharpened, validity byte), two histories,
      // three intermediates, the output, the validity and feedback layers.
      .bytesPerPixel = 3 * 16 + 2 * 8 + 2 * 16 + 1 + 2 * 16 + 3 * 16 + 16 + 2 * 4,
      .layerBytesPerPixel = 2 * sizeof(float),
      .temporal = true,
      .jitter = "flipquad-split",
  };
  return info;
}

std::unique_ptr<Pass> MakeHraa(const PassSettings& settings) { return std::make_unique<HraaPass>(settings); }

}  // namespace passes::hraa
