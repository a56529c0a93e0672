// MiniEngine's compute FXAA on the pass framework (see fxaa_miniengine.h).

#include "passes/fxaa_miniengine/fxaa_miniengine.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "passes/fxaa_miniengine/fxaa_miniengine_math.h"
#include "passes/work_set.h"
#include "sim/formats.h"

namespace passes::fxaa_miniengine {
namespace {

constexpr std::string_view kPass1Dispatch = "fxaa-miniengine/pass1";
constexpr std::string_view kPass2HDispatch = "fxaa-miniengine/pass2-h";
constexpr std::string_view kPass2VDispatch = "fxaa-miniengine/pass2-v";

// FXAAPass1CS.hlsli: BOUNDARY_SIZE 1, ROW_WIDTH 10.
constexpr int kGroupSide = kWorkSetTileSide;
constexpr int kBoundary = 1;
constexpr int kRowWidth = kGroupSide + 2 * kBoundary;
constexpr int kTileBytes = kRowWidth * kRowWidth * static_cast<int>(sizeof(float));

// Queue slots: W*H/4 + 128 (aa-facts §3; FXAA's queue in BufferManager.cpp), the quadrant's pixels
// and two ends' padding.
std::size_t QueueCapacity(int width, int height) {
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) / 4 + 128;
}
glm::ivec2 UnpackItem(std::uint32_t item) { return WorkItemPixel(item); }

// Hand counts of MiniEngine's shaders as GCN VALU instructions.
constexpr PackedQueueLayout kLayout{
    .unpack = UnpackItem,
    .dummyItem = kDummyItem,
    .capacity = QueueCapacity,
    .resolveDispatch = "fxaa-miniengine/resolve-work-queue",
    .resolve = {.vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 24,
                .source = "hand count of FXAAResolveWorkQueueCS.hlsl: two counter loads, two round-ups, two "
                          "padding compares and stores, two argument stores, two counter resets"},
    .pixelPrologueDispatch = "fxaa-miniengine/luma",
    .pixelPrologue = {.vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 16,
                      .source = "hand count: the R11G11B10 load's unpack, the luminance dot, log2 and scale, "
                                "one R8 store"},
    .pixelPrologueApron = kBoundary,
};

constexpr WorkSetKernels KernelsFor(bool extreme) {
  return {
      .detectDispatch = kPass1Dispatch,
      .consumeDispatch = kPass2HDispatch,
      .detectPixel = {.vgprs = 32, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 150,
                      .source = "hand count of FXAAPass1CS.hlsli without LDS: 5 colour loads and log lumas (~70), "
                                "the range test (~15), 4 corner lumas (~55) and the classification and pack "
                                "(~45) on candidate waves, half of them"},
      .detectCompute = {.vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = kTileBytes, .valuInstructionsPerWave = 100,
                        .source = "hand count of FXAAPass1CS.hlsli (RGB path): two colour loads, log lumas and "
                                  "luma stores per filling thread (~35), 5 LDS lumas and the range test (~20), "
                                  "4 corner lumas, classification, pack, counter atomic and 2 queue stores (~55) "
                                  "on most waves"},
      .consume = {.vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = 0,
                  .valuInstructionsPerWave = extreme ? 180.0 : 130.0,
                  .source = "hand count of FXAAPass2CS.hlsli: item decode and 3 luma loads (~20), per sample "
                            "distance two uv, two SampleLevel and two compare/selects (~12; 7 samples, 11 "
                            "with FXAA_EXTREME_QUALITY), the shift (~10), load, lerp and store (~12)"},
      .secondConsumeDispatch = kPass2VDispatch,
      .secondConsume = {.vgprs = 32, .sgprs = 24, .ldsBytesPerGroup = 0,
                        .valuInstructionsPerWave = extreme ? 180.0 : 130.0,
                        .source = "hand count of FXAAPass2CS.hlsli (VERTICAL_ORIENTATION), as pass2-h"},
      .packed = &kLayout,
  };
}
constexpr WorkSetKernels kKernels = KernelsFor(false);
constexpr WorkSetKernels kExtremeKernels = KernelsFor(true);

struct Config {
  float contrastThreshold = 0.175f;
  float subpixelRemoval = 0.5f;
  bool extreme = false;
};

Config ConfigOf(const PassSettings& settings) {
  return {.contrastThreshold = static_cast<float>(settings.Get("contrast_threshold")),
          .subpixelRemoval = static_cast<float>(settings.Get("subpixel_removal")),
          .extreme = settings.Get("extreme_quality") != 0.0};
}

// Pass 1's decision from the nine lumas `luma(dx, dy)` gives (ordinals first, corners only past
// the contrast test, as the shader loads them); `fetch(x, y)` is the colour target's load.
template <typename Luma, typename Fetch>
PackedItem Decide(const Config& config, int x, int y, Luma&& luma, Fetch&& fetch) {
  Neighbourhood l{};
  l.n = luma(0, -1);
  l.w = luma(-1, 0);
  l.m = luma(0, 0);
  l.e = luma(1, 0);
  l.s = luma(0, 1);
  if (!PassesContrast(l.n, l.w, l.m, l.e, l.s, config.contrastThreshold)) return {};
  l.nw = luma(-1, -1);
  l.ne = luma(1, -1);
  l.sw = luma(-1, 1);
  l.se = luma(1, 1);
  const Classification c = Classify(l, config.subpixelRemoval);
  const int side = 2 * static_cast<int>(c.gradientDir) - 1;
  const glm::vec3 across = c.horizontal ? fetch(x, y + side) : fetch(x + side, y);
  return {.joins = c.horizontal ? 1 : 2, .item = PackWorkItem(x, y, c.subpix, c.gradientDir),
          .payload = PackR11G11B10(across)};
}

class FxaaMiniEnginePass final : public Pass {
 public:
  explicit FxaaMiniEnginePass(const Config& config) : config_(config), workSet_(fxaa_miniengine::Info().name) {}

  const PassInfo& Info() const override { return fxaa_miniengine::Info(); }

 private:
  // Dispatch2D launches ceil(block / 8) groups per axis and pass 1 checks no bounds: the block
  // rounded up to whole groups, clipped to the screen.
  static WorkRegion QuadrantRegion(int x0, int y0, int blockWidth, int blockHeight, int width, int height) {
    const auto whole = [](int side) { return (side + kGroupSide - 1) / kGroupSide * kGroupSide; };
    return {x0, y0, std::min(whole(blockWidth), width - x0), std::min(whole(blockHeight), height - y0)};
  }

  template <typename Form>
  auto MakeDetect(sim::Dispatch& d, Form, const WorkRegion& region, sim::Texture2D<glm::vec3>& colour,
                  sim::Texture2D<float>& luma) const {
    const sim::TextureView<glm::vec3> in = d.Read(colour);
    const Config config = config_;
    if constexpr (Form::value == DetectForm::PixelPrologue) {
      const sim::RwTextureView<float> lumaOut = d.ReadWrite(luma);
      return [=](sim::PixelLane& lane, int x, int y) { lumaOut.Store(lane, x, y, LogLuma(in.Load(lane, x, y))); };
    } else if constexpr (Form::value == DetectForm::Pixel) {
      // No LDS in a pixel shader: each pixel computes its nine lumas from the colour.
      return [=](sim::PixelLane& lane, int x, int y) {
        return Decide(config, x, y, [&](int dx, int dy) { return LogLuma(in.Load(lane, x + dx, y + dy)); },
                      [&](int fx, int fy) { return in.Load(lane, fx, fy); });
      };
    } else {
      const sim::RwTextureView<float> lumaOut = d.ReadWrite(luma);
      const glm::ivec2 start(region.x, region.y);
      // Threads 0..49 load two pixels each, rows r and r + 5 of the 10x10 tile, store their lumas
      // to the luma UAV (dropped off the screen) and to LDS.
      auto fillTile = [=](sim::ComputeLane& lane) {
        constexpr int kHalf = kRowWidth * kRowWidth / 2;
        if (lane.localIndex >= kHalf) return;
        for (const int index : {lane.localIndex, lane.localIndex + kHalf}) {
          const glm::ivec2 uav = start + glm::ivec2(lane.groupId) * kGroupSide +
                                 glm::ivec2(index % kRowWidth, index / kRowWidth) - kBoundary;
          const float value = LogLuma(in.Load(lane, uav.x, uav.y));
          lumaOut.Store(lane, uav.x, uav.y, value);
          lane.LdsStore<float>(static_cast<std::size_t>(index), value);
        }
      };
      auto detect = [=](sim::ComputeLane& lane, int x, int y) {
        const int centre = (lane.localId.x + kBoundary) + (lane.localId.y + kBoundary) * kRowWidth;
        return Decide(config, x, y,
                      [&](int dx, int dy) { return lane.LdsLoad<float>(static_cast<std::size_t>(centre + dy * kRowWidth + dx)); },
                      [&](int fx, int fy) { return in.Load(lane, fx, fy); });
      };
      return StagedDetect<decltype(fillTile), decltype(detect)>{fillTile, detect};
    }
  }

  auto MakeConsume(sim::Dispatch& d, bool vertical, sim::Texture2D<glm::vec3>& colour,
                   const sim::Texture2D<float>& luma) const {
    const sim::TextureView<float> lumaIn = d.Read(luma);
    const sim::RwTextureView<glm::vec3> out = d.ReadWrite(colour);
    const glm::vec2 rcp(1.0f / static_cast<float>(colour.Width()), 1.0f / static_cast<float>(colour.Height()));
    const std::span<const float> distances = SampleDistances(config_.extreme);
    return [=](const auto& lane, int x, int y, std::uint32_t item, auto&& loadPayload) {
      const auto dir = static_cast<int>(WorkItemGradientDir(item));
      const float subpix = WorkItemSubpix(item);
      const float fx = static_cast<float>(x), fy = static_cast<float>(y), fdir = static_cast<float>(dir);
      const float nextLuma = vertical ? lumaIn.Load(lane, x + 2 * dir - 1, y) : lumaIn.Load(lane, x, y + 2 * dir - 1);
      const glm::vec2 startUv = vertical ? glm::vec2((fx + fdir) * rcp.x, (fy + 0.5f) * rcp.y)
                                         : glm::vec2((fx + 0.5f) * rcp.x, (fy + fdir) * rcp.y);
      const float thisLuma = lumaIn.Load(lane, x, y);
      const float centerLuma = (nextLuma + thisLuma) * 0.5f;
      const float gradientSgn = Sign(nextLuma - thisLuma);
      const float gradientMag = std::abs(nextLuma - thisLuma) * 0.25f;
      // StartUV -/+ float2(RcpTextureSize.x, 0) * Distance (float2(0, RcpTextureSize.y) vertically).
      const glm::vec2 step = vertical ? glm::vec2(0.0f, rcp.y) : glm::vec2(rcp.x, 0.0f);
      const EdgeEnds ends = SearchEnds(distances, centerLuma, gradientSgn, gradientMag, [&](float distance, int side) {
        const glm::vec2 uv = side < 0 ? startUv - step * distance : startUv + step * distance;
        return lumaIn.SampleBilinear(lane, uv);
      });
      const float shift = PixelShift(ends, subpix);
      if (shift > 0.01f) {
        out.Store(lane, x, y, Lerp(out.Load(lane, x, y), UnpackR11G11B10(loadPayload()), shift));
      }
    };
  }

  void MarkItems(Strategy strategy, const WorkRegion& region, int width, std::vector<float>& items) const {
    const std::vector<std::uint8_t> joined = workSet_.Membership(strategy);
    for (int y = 0; y < region.height; ++y) {
      for (int x = 0; x < region.width; ++x) {
        const std::uint8_t j = joined[static_cast<std::size_t>(y) * static_cast<std::size_t>(region.width) +
                                      static_cast<std::size_t>(x)];
        if (j != 0) {
          items[static_cast<std::size_t>(y + region.y) * static_cast<std::size_t>(width) +
                static_cast<std::size_t>(x + region.x)] = j;
        }
      }
    }
  }

 public:
  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    const int width = frame.Width(), height = frame.Height();
    if (width > kMaxSide || height > kMaxSide) {
      throw std::invalid_argument("fxaa-miniengine: the work item holds 12-bit coordinates; " + std::to_string(width) +
                                  "x" + std::to_string(height) + " exceeds 4095");
    }
    sim::Texture2D<glm::vec3>& colour =
        FrameTexture(colour_, "fxaa-miniengine/colour", width, height, sim::Format::R11G11B10Float);
    sim::Texture2D<float>& luma = FrameTexture(luma_, "fxaa-miniengine/luma", width, height, sim::Format::R8Unorm);
    // The renderer's store of the frame (host side), and a luma target with nothing of an
    // earlier frame (MiniEngine's holds whatever last wrote it).
    const std::span<glm::vec3> stored = colour.Texels();
    const std::span<const glm::vec4> input = frame.colour->Texels();
    ByRows(width, height, [&](std::size_t i) { stored[i] = sim::Quantize(sim::Format::R11G11B10Float, glm::vec3(input[i])); });
    luma.Fill(0.0f);
    std::vector<float> items(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0f);
    WorkSetShape total;
    std::uint64_t padding = 0;
    const WorkSetKernels& kernels = config_.extreme ? kExtremeKernels : kKernels;
    // FXAA.cpp: for x in 0..1, for y in 0..1, StartPixel = (x * W/2, y * H/2), Dispatch2D(W/2, H/2).
    const int blockWidth = width / 2, blockHeight = height / 2;
    for (int bx = 0; bx < 2; ++bx) {
      for (int by = 0; by < 2; ++by) {
        const WorkRegion region = QuadrantRegion(bx * blockWidth, by * blockHeight, blockWidth, blockHeight, width, height);
        // A screen 1 pixel wide or high has empty blocks: Dispatch2D(0, ...) launches no group.
        if (region.width <= 0 || region.height <= 0) continue;
        auto makeDetect = [&](sim::Dispatch& d, auto form) { return MakeDetect(d, form, region, colour, luma); };
        auto makeConsume = [&](sim::Dispatch& d, int consume) { return MakeConsume(d, consume == 1, colour, luma); };
        const WorkSetShape shape = workSet_.Run(machine, strategy, kernels, width, height, region, makeDetect, makeConsume);
        total.pixels += shape.pixels;
        total.quads += shape.quads;
        total.tiles += shape.tiles;
        padding += workSet_.Padding();
        MarkItems(strategy, region, width, items);
      }
    }
    PassOutput output;
    output.SetWorkSet(total);
    output.paddingItems = padding;
    output.colour = sim::Texture2D<glm::vec4>("fxaa-miniengine/output", width, height, 4);
    const std::span<glm::vec4> out = output.colour.Texels();
    ByRows(width, height, [&](std::size_t i) { out[i] = glm::vec4(stored[i], 1.0f); });
    output.layers.push_back(LayerOf("luma", luma));
    output.layers.push_back({"items", {"Y"}, width, height, std::move(items), {}, 0});
    return output;
  }

 private:
  Config config_;
  WorkSet workSet_;
  std::optional<sim::Texture2D<glm::vec3>> colour_;
  std::optional<sim::Texture2D<float>> luma_;
};

}  // namespace

const PassInfo& Info() {
  static const PassInfo info{
      .name = "fxaa-miniengine",
      .description = "MiniEngine's compute FXAA: log2 luma, 10x10 LDS tile, one double-ended work queue padded to "
                     "64 with dummy items, per-direction indirect dispatches, per quadrant",
      .source = "passes/fxaa_miniengine/fxaa_miniengine.h",
      // FXAA.cpp's NumVars and FXAAPass2CS.hlsli's FXAA_EXTREME_QUALITY (aa-facts §3).
      .settings = {{.name = "contrast_threshold", .defaultValue = 0.175, .min = 0.05, .max = 0.5,
                    .doc = "ContrastThreshold on log2 luma (FXAA.cpp default 0.175, UI range 0.05-0.5)"},
                   {.name = "subpixel_removal", .defaultValue = 0.5, .min = 0.0, .max = 1.0,
                    .doc = "SubpixelRemoval: blur of isolated pixels (FXAA.cpp default 0.5)"},
                   {.name = "extreme_quality", .defaultValue = 0, .min = 0, .max = 1, .integer = true,
                    .doc = "FXAA_EXTREME_QUALITY: 1 uses preset 39's 11 step distances instead of preset 25's 7 "
                           "(off in MiniEngine's build)"}},
      // FXAA.cpp: "0.25 = low, 0.2 = medium, 0.15 = high, 0.1 = ultra".
      .presets = {{"low", {{"contrast_threshold", 0.25}}},
                  {"medium", {{"contrast_threshold", 0.2}}},
                  {"high", {{"contrast_threshold", 0.15}}},
                  {"ultra", {{"contrast_threshold", 0.1}}}},
      .inputs = {FrameInput::Colour},
      .studiedDispatches = {kPass2HDispatch, kPass2VDispatch},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // The colour target (vec3), luma target and layer, the items layer, the output and its
      // vec4, membership and stencil bytes, the stencil form's two R32 records, and the queue's
      // item and colour words (a quarter of the screen).
      .bytesPerPixel = sizeof(glm::vec3) + 3 * sizeof(float) + sizeof(glm::vec4) + 2 + 2 * sizeof(std::uint32_t) + 2,
      .layerBytesPerPixel = 1 + sizeof(float),  // luma (R8 codes), items
      .temporal = false,
      .variantOf = "fxaa",
  };
  return info;
}

std::unique_ptr<Pass> Make(const PassSettings& settings) {
  return std::make_unique<FxaaMiniEnginePass>(ConfigOf(settings));
}

}  // namespace passes::fxaa_miniengine
