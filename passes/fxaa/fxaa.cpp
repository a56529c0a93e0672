// FXAA 3.11 PC quality on the pass framework (see fxaa.h).

#include "passes/fxaa/fxaa.h"

#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "passes/fxaa/fxaa_kernels.h"
#include "passes/work_set.h"
#include "sim/check.h"
#include "sim/formats.h"

namespace passes::fxaa {
namespace {

constexpr std::string_view kLumaDispatch = "fxaa/luma";
constexpr std::string_view kEarlyExitDispatch = "fxaa/early-exit";
constexpr std::string_view kEdgeDispatch = "fxaa/edge-search";

// Hand counts of Fxaa3_11.h's PC quality shader and the header's luma pre-pass as GCN VALU
// instructions (the header publishes no counts).
constexpr sim::KernelInfo kLumaKernel{
    .vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 10,
    .source = "hand count of the header's pre-pass example: one load's address, the dot (3 multiplies, 2 adds), "
              "the UNORM pack and the export"};
constexpr WorkSetKernels kKernels{
    .detectDispatch = kEarlyExitDispatch,
    .consumeDispatch = kEdgeDispatch,
    .detectPixel = {.vgprs = 12, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 24,
                    .source = "hand count of FxaaPixelShader up to the early exit: 5 point fetches' addresses (5), "
                              "the min/max tree (8), scaled max, range, clamp and compare (4), the stencil or colour "
                              "export and branch (~7)"},
    .detectCompute = {.vgprs = 12, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 32,
                      .source = "the pixel form's 24 plus the thread-to-pixel mapping, bounds test and the append's "
                                "mbcnt and address (~8)"},
    .consume = {.vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 150,
                .source = "hand count of FxaaPixelShader after the early exit, preset 12, on an edge pixel whose "
                          "search ends after 2-3 fetches per side: the 5 texels again and the early-exit maths "
                          "(~20), 4 diagonal fetches (4), span, gradient and sub-pixel maths (~45), per search "
                          "block 2 fetch addresses, 2 subtracts, 2 abs-compares, 4 position updates and the "
                          "branch (~14, 3 blocks ~42), span length, offset and the final fetch (~25), the store (~4)"},
};

// The preset names, one per step table (kStepTables' order).
constexpr std::string_view kPresetNames[] = {"10", "11", "12", "13", "14", "15", "20", "21", "22",
                                             "23", "24", "25", "26", "27", "28", "29", "39"};
static_assert(std::size(kPresetNames) == kStepTables.size());

Params ParamsOf(const PassSettings& settings) {
  const int preset = static_cast<int>(settings.Get("quality_preset"));
  // The schema admits only the header's presets (SettingInfo::allowed).
  const StepTable* table = FindStepTable(preset);
  AASIM_CHECK(table != nullptr);
  return {.width = 1,
          .height = 1,
          .subpix = static_cast<float>(settings.Get("subpix")),
          .edgeThreshold = static_cast<float>(settings.Get("edge_threshold")),
          .edgeThresholdMin = static_cast<float>(settings.Get("edge_threshold_min")),
          .table = *table};
}

class FxaaPass final : public Pass {
 public:
  explicit FxaaPass(const Params& params) : params_(params) {}

  const PassInfo& Info() const override { return fxaa::Info(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.Width(), height = frame.Height();
    params_.width = width;
    params_.height = height;
    const sim::Texture2D<glm::vec4>& colour = frame.ColourSrgb8();
    // The pass's render targets, kept across frames as a renderer keeps them.
    sim::Texture2D<glm::vec4>& rgbl = FrameTexture(rgbl_, "fxaa/rgbl", width, height, sim::Format::RGBA8Unorm);
    sim::Texture2D<glm::vec4>& target = FrameTexture(output_, "fxaa/output", width, height, sim::Format::RGBA8Unorm);
    spans_.assign(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0f);

    RunLuma(machine, colour, rgbl);
    PassOutput output;
    output.SetWorkSet(RunFxaa(machine, strategy, rgbl, target));
    output.colour = DecodedSrgb8("fxaa/output", target);
    const std::span<glm::vec4> decoded = output.colour.Texels();
    const std::span<const glm::vec4> input = frame.colour->Texels();
    ByRows(width, height, [&](std::size_t i) { decoded[i].a = input[i].a; });
    output.layers.push_back(AlphaLayer(rgbl));
    // The record moves into its layer; the next frame fills a new one.
    output.layers.push_back({"span", {"direction", "dstN", "dstP", "offset"}, width, height, std::move(spans_), {}, 0});
    return output;
  }

 private:
  static void RunLuma(sim::Machine& machine, const sim::Texture2D<glm::vec4>& colour, sim::Texture2D<glm::vec4>& rgbl) {
    sim::Dispatch d(std::string(kLumaDispatch), kLumaKernel);
    const sim::TextureView<glm::vec4> gamma = d.Read(colour).As(sim::Format::RGBA8Unorm);
    const sim::RwTextureView<glm::vec4> out = d.ReadWrite(rgbl);
    machine.FullScreen(d, {.width = colour.Width(), .height = colour.Height()}, [&](sim::PixelLane& lane) {
      const glm::vec4 c = gamma.Load(lane, lane.x, lane.y);
      out.Store(lane, lane.x, lane.y, glm::vec4(c.x, c.y, c.z, PrepassLuma(glm::vec3(c))));
    });
  }

  WorkSetShape RunFxaa(sim::Machine& machine, Strategy strategy, const sim::Texture2D<glm::vec4>& rgbl,
                       sim::Texture2D<glm::vec4>& target) {
    auto makeDetect = [&](sim::Dispatch& d, auto) {
      const FxaaQuality fxaa(params_, d.Read(rgbl));
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(target);
      return [=](const sim::LaneBase& lane, int x, int y) {
        const Cross cross = fxaa.Contrast(lane, x, y);
        if (cross.earlyExit) out.Store(lane, x, y, cross.rgbyM);
        return !cross.earlyExit;
      };
    };
    auto makeEdge = [&](sim::Dispatch& d) {
      const FxaaQuality fxaa(params_, d.Read(rgbl));
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(target);
      const sim::CounterView searchFetches = d.Counter("search_fetches");
      float* spans = spans_.data();
      const int width = rgbl.Width(), height = rgbl.Height();
      return [=](const sim::LaneBase& lane, int x, int y) {
        const EdgeResult result = fxaa.Edge(lane, x, y, fxaa.Contrast(lane, x, y));
        out.Store(lane, x, y, result.colour);
        searchFetches.Add(lane, static_cast<std::uint64_t>(result.span.fetches));
        if (lane.helper) return;
        const Span& s = result.span;
        const float size = static_cast<float>(s.horizontal ? width : height);
        const glm::vec4 record(s.horizontal ? 1.0f : 2.0f, s.dstN * size, s.dstP * size, s.pixelOffset);
        std::memcpy(spans + 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)),
                    &record, sizeof record);
      };
    };
    return workSet_.Run(machine, strategy, kKernels, rgbl.Width(), rgbl.Height(), makeDetect, makeEdge);
  }

  // rgbl's alpha codes, read back as k / 255 like the texture's UNORM view.
  static PassLayer AlphaLayer(const sim::Texture2D<glm::vec4>& rgbl) {
    const std::span<const std::uint8_t> codes = rgbl.Codes();  // RGBA8: alpha is every fourth byte
    std::vector<std::uint8_t> alpha(codes.size() / 4);
    for (std::size_t i = 0; i < alpha.size(); ++i) alpha[i] = codes[4 * i + 3];
    return {.name = "luma", .channels = {"Y"}, .width = rgbl.Width(), .height = rgbl.Height(), .values = {},
            .codes = std::move(alpha), .codeChannels = 1};
  }

  Params params_;
  WorkSet workSet_{"fxaa"};
  std::optional<sim::Texture2D<glm::vec4>> rgbl_, output_;
  std::vector<float> spans_;  // the consume's inspection record: direction, dstN, dstP, offset per pixel
};

// The quality_preset values Fxaa3_11.h defines: its step tables' presets.
std::vector<double> PresetNumbers() {
  std::vector<double> numbers;
  for (const StepTable& table : kStepTables) numbers.push_back(table.preset);
  return numbers;
}

std::vector<Preset> QualityPresets() {
  std::vector<Preset> presets;
  for (std::size_t i = 0; i < kStepTables.size(); ++i) {
    presets.push_back({kPresetNames[i], {{"quality_preset", static_cast<double>(kStepTables[i].preset)}}});
  }
  return presets;
}

}  // namespace

const PassInfo& Info() {
  // FxaaPixelShader's quality inputs: defaults and ranges from their comments in Fxaa3_11.h.
  static const PassInfo info{
      .name = "fxaa",
      .description = "FXAA 3.11 PC quality: luma pre-pass into alpha, early exit, end-of-edge search with the "
                     "preset's step table, one bilinear blend",
      .source = "passes/fxaa/fxaa.h",
      .settings =
          {
              {.name = "subpix", .defaultValue = 0.75, .min = 0.0, .max = 1.0,
               .doc = "fxaaQualitySubpix: sub-pixel aliasing removal, 1 softer .. 0.75 default .. 0 off"},
              {.name = "edge_threshold", .defaultValue = 0.166, .min = 0.063, .max = 0.333,
               .doc = "fxaaQualityEdgeThreshold: local contrast (relative to the brightest) needed to run, 0.333 "
                      "too little .. 0.166 default .. 0.063 overkill"},
              {.name = "edge_threshold_min", .defaultValue = 0.0833, .min = 0.0312, .max = 0.0833,
               .doc = "fxaaQualityEdgeThresholdMin: absolute contrast needed (trims darks), 0.0833 upper limit "
                      "(default) .. 0.0312 visible limit"},
              {.name = "quality_preset", .defaultValue = kDefaultPreset, .min = 10, .max = 39, .integer = true,
               .doc = "FXAA_QUALITY__PRESET: the end search's step table, 10-15 medium dither, 20-29 low dither, 39 "
                      "no dither (default 12)",
               .allowed = PresetNumbers()},
          },
      .presets = QualityPresets(),
      .inputs = {FrameInput::Colour},
      .studiedDispatches = {kEdgeDispatch},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // The sRGB colour target, rgbl, the output and its decoded copy (vec4 each), the span record
      // (vec4, moved into its layer), the luma layer's code, the stencil byte and a queue entry.
      .bytesPerPixel = 5 * sizeof(glm::vec4) + 1 + 1 + sizeof(std::uint32_t),
      .layerBytesPerPixel = 1 + 4 * sizeof(float),  // luma (codes), span
      .temporal = false,
  };
  return info;
}

std::unique_ptr<Pass> Make(const PassSettings& settings) { return std::make_unique<FxaaPass>(ParamsOf(settings)); }

}  // namespace passes::fxaa
