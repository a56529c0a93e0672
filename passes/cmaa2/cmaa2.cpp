// CMAA2 v2.3 on the pass framework (see cmaa2.h).

#include "passes/cmaa2/cmaa2.h"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "passes/cmaa2/cmaa2_kernels.h"
#include "passes/work_set.h"
#include "sim/formats.h"

namespace passes::cmaa2 {
namespace {

constexpr std::string_view kEdgeDispatch = "cmaa2/edge-detection";
constexpr std::string_view kCandidatesDispatch = "cmaa2/process-candidates";
constexpr std::string_view kArgumentsDispatch = "cmaa2/dispatch-args";
constexpr std::string_view kApplyDispatch = "cmaa2/deferred-colour-apply";

// DeferredColorApply2x2CS's group with CMAA2_DEFERRED_APPLY_THREADGROUP_SWAP 1: 4 pixels of a quad
// by CMAA2_DEFERRED_APPLY_NUM_THREADS (32) quads (aa-facts §4.1).
constexpr int kApplyQuadsPerGroup = 32;
constexpr glm::ivec3 kApplyGroup{4, kApplyQuadsPerGroup, 1};

// The compute detect's LDS luma tile: the 8x8 group, one pixel before and two after in each
// direction (the window of docs/cmaa2.md "Waves").
constexpr int kLumaTileWidth = kWorkSetTileSide + 3, kLumaTileHeight = kWorkSetTileSide + 3;
constexpr int kLumaTileSize = kLumaTileWidth * kLumaTileHeight;
using LumaWindow = std::array<std::array<float, 4>, 4>;

// Hand counts of CMAA2.hlsl's kernels as GCN VALU instructions per wave.
const sim::KernelInfo kDetectPixelKernel{
    .vgprs = 40, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 150,
    .source = "hand count of EdgesColor2x2CS's per-pixel share: 9 loads' addresses and lumas (3 sqrt, 3 mul/add, "
              "~8 each, ~75), 12 contrasts (~24), 4 local-contrast maxima and threshold tests (~24), the "
              "candidate test and stencil export (~10), the head reset and, on even lanes, the neighbour's "
              "lumas and edges and the packed store (~35 averaged over lanes)"};
const sim::KernelInfo kDetectComputeKernel{
    .vgprs = 40, .sgprs = 24, .ldsBytesPerGroup = kLumaTileSize * static_cast<int>(sizeof(float)),
    .valuInstructionsPerWave = 105,
    .source = "hand count of EdgesColor2x2CS's per-pixel share with the lumas from LDS: the tile fill (110 "
              "lumas over 64 lanes, ~15), 9-12 LDS addresses (~15), contrasts, adaptation and tests (~48), the "
              "candidate test and append (~10), the head reset and the even lanes' neighbour edges and packed "
              "store (~17 averaged)"};
const sim::KernelInfo kCandidatesKernel{
    .vgprs = 48, .sgprs = 24, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 260,
    .source = "hand count of ProcessCandidatesCS: 7 edge loads and unpacks (~45), the simple shape (~50) and "
              "its blend (~25), two Z scores per direction (~40), the item's atomics and E4 packing (~25), the "
              "line trace and Z items on the waves holding a Z (~75 averaged)"};
const sim::KernelInfo kArgumentsKernel{
    .vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 20,
    .source = "hand count of ComputeDispatchArgsCS's group y == 1 branch: load, clamp, divide, 7 stores"};
const sim::KernelInfo kApplyKernel{
    .vgprs = 32, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 110,
    .source = "hand count of DeferredColorApply2x2CS: location and head loads (~10), the list walk (~12 per "
              "item, ~4 items), the mean (~8), LINEAR_to_SRGB (3 pow, ~30) and the packed store (~12)"};

const WorkSetKernels kKernels{
    .detectDispatch = kEdgeDispatch,
    .consumeDispatch = kCandidatesDispatch,
    .detectPixel = kDetectPixelKernel,
    .detectCompute = kDetectComputeKernel,
    .consume = kCandidatesKernel,
};

// The item list and location list capacities (vaCMAA2DX11.cpp UpdateResources; aa-facts §4.1):
// the reference's default "99.99% safe" sizes, or its "enough in all cases" ones made to hold what
// they do not (docs/cmaa2.md "Queue sizing"): two items per pixel (4-level noise makes 1.3) and
// one location per quad (the reference's (W*H + 3) / 4 is short of the quads when W or H is odd).
struct Capacities {
  std::size_t items = 0, locations = 0;
  static Capacities Of(int width, int height, bool reference) {
    const auto pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const auto quads = static_cast<std::size_t>((width + 1) / 2) * static_cast<std::size_t>((height + 1) / 2);
    return reference ? Capacities{pixels / 2, (pixels + 3) / 6} : Capacities{2 * pixels, quads};
  }
};

// The working buffers, kept across frames as the reference keeps them until the size changes.
struct Working {
  int width, height;
  int headsWidth;
  sim::Buffer<std::uint32_t> heads;
  sim::Buffer<glm::uvec2> items;
  sim::Buffer<std::uint32_t> locations;

  Working(int w, int h, const Capacities& capacities)
      : width(w), height(h), headsWidth((w + 1) / 2),
        heads("cmaa2/list-heads", static_cast<std::size_t>((w + 1) / 2) * static_cast<std::size_t>((h + 1) / 2),
              sizeof(std::uint32_t), kEmptyList),
        items("cmaa2/blend-items", capacities.items),
        locations("cmaa2/blend-locations", capacities.locations) {}
};

Config ConfigOf(const PassSettings& settings) {
  Config config;
  config.edgeThreshold = static_cast<float>(settings.Get("threshold"));
  config.localContrastAdaptation = static_cast<float>(settings.Get("local_contrast_adaptation"));
  config.referenceBufferSizes = settings.Get("reference_buffers") != 0.0;
  return config;
}

class Cmaa2Pass final : public Pass, public Stage {
 public:
  explicit Cmaa2Pass(const Config& config)
      : config_(config), workSet_(cmaa2::Info().name), control_("cmaa2/control", 16),
        arguments_("cmaa2/apply-args", 4) {}

  const PassInfo& Info() const override { return cmaa2::Info(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override;
  Targets Process(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override;
  PassLayer EdgesLayer() const override;
  PassLayer CandidatesLayer(Strategy strategy) const override;

 private:
  // EdgesColor2x2CS's arithmetic per pixel (docs/cmaa2.md "Waves").
  template <typename Form>
  auto MakeDetect(sim::Dispatch& d, Form, const sim::Texture2D<glm::vec4>& colour,
                  sim::Texture2D<std::uint32_t>& edges) {
    const sim::TextureView<glm::vec4> linear = d.Read(colour);
    const sim::RwTextureView<std::uint32_t> edgesOut = d.ReadWrite(edges);
    const sim::RwBufferView<std::uint32_t> heads = d.ReadWrite(working_->heads);
    const int headsWidth = working_->headsWidth;
    const Config config = config_;
    // The pixel's edges from its luma window (rows y-1..y+2, columns x-1..x+2: the last column
    // read only on even lanes, for their neighbour's half of the edges texel; the last row only on
    // a quad's top-left lane, for the block's head reset), then the candidate test.
    auto finish = [=](const auto& lane, int x, int y, const LumaWindow& lumas) {
      const auto at = [&](int ox) { return [&, ox](int dx, int dy) { return lumas[dy + 1][ox + dx + 1]; }; };
      const std::uint32_t own = EdgesOf(at(0), config);
      if (x % 2 == 0) {
        if (y % 2 == 0 && BlockHasContrast(at(0))) {
          heads.Store(lane, static_cast<std::size_t>(y / 2 * headsWidth + x / 2), kEmptyList);
        }
        edgesOut.Store(lane, x / 2, y, own | EdgesOf(at(1), config) << 4);
      }
      return IsCandidate(own);
    };
    // Fills the window from `luma(column, row)` (0-based in the window).
    const auto window = [](int x, int y, auto&& luma) {
      LumaWindow lumas{};
      const int columns = x % 2 == 0 ? 4 : 3, rows = x % 2 == 0 && y % 2 == 0 ? 4 : 3;
      for (int row = 0; row < rows; ++row) {
        for (int column = 0; column < columns; ++column) lumas[row][column] = luma(column, row);
      }
      return lumas;
    };
    if constexpr (Form::value == DetectForm::Pixel) {
      return [=](const sim::PixelLane& lane, int x, int y) {
        return finish(lane, x, y, window(x, y, [&](int column, int row) {
                        return LumaForEdges(glm::vec3(linear.Load(lane, x - 1 + column, y - 1 + row)));
                      }));
      };
    } else {
      // The group's lumas in LDS, as the reference's group shares its fractional edges: the 8x8
      // pixels with one column and row before and two after (kLumaTileWidth x kLumaTileHeight).
      auto fillTile = [=](sim::ComputeLane& lane) {
        for (int i = lane.localIndex; i < kLumaTileSize; i += kWorkSetTileSide * kWorkSetTileSide) {
          const int x = lane.groupId.x * kWorkSetTileSide - 1 + i % kLumaTileWidth;
          const int y = lane.groupId.y * kWorkSetTileSide - 1 + i / kLumaTileWidth;
          lane.LdsStore<float>(static_cast<std::size_t>(i), LumaForEdges(glm::vec3(linear.Load(lane, x, y))));
        }
      };
      auto detect = [=](sim::ComputeLane& lane, int x, int y) {
        return finish(lane, x, y, window(x, y, [&](int column, int row) {
                        return lane.LdsLoad<float>(
                            static_cast<std::size_t>((lane.localId.y + row) * kLumaTileWidth + lane.localId.x + column));
                      }));
      };
      return StagedDetect<decltype(fillTile), decltype(detect)>{fillTile, detect};
    }
  }

  auto MakeProcessCandidates(sim::Dispatch& d, const sim::Texture2D<glm::vec4>& colour,
                             const sim::Texture2D<std::uint32_t>& edges) {
    d.SerialChunks();  // the lists' InterlockedAdd / InterlockedExchange return values
    const BlendItemWriter writer{.control = d.ReadWrite(control_),
                                 .heads = d.ReadWrite(working_->heads),
                                 .items = d.ReadWrite(working_->items),
                                 .locations = d.ReadWrite(working_->locations),
                                 .stored = d.Counter("cmaa2/blend_items"),
                                 .itemsDropped = d.Counter("cmaa2/blend_items_dropped"),
                                 .locationsDropped = d.Counter("cmaa2/blend_locations_dropped"),
                                 .headsWidth = working_->headsWidth};
    return ProcessCandidates<sim::TextureView<glm::vec4>, sim::TextureView<std::uint32_t>>{
        d.Read(colour), d.Read(edges), writer, d.Counter("cmaa2/z_shapes")};
  }

  // ComputeDispatchArgsCS on Dispatch(1, 2, 1).
  void WriteApplyArguments(sim::Machine& machine) {
    sim::Dispatch d(std::string(kArgumentsDispatch), kArgumentsKernel);
    const sim::RwBufferView<std::uint32_t> control = d.ReadWrite(control_);
    const sim::RwBufferView<std::uint32_t> arguments = d.ReadWrite(arguments_);
    const auto capacity = static_cast<std::uint32_t>(working_->locations.Size());
    machine.Compute(d, {.threads = {1, 2, 1}, .groupSize = {1, 1, 1}}, [=](sim::ComputeLane& lane) {
      if (lane.groupId.y != 1) return;
      const std::uint32_t locations = std::min(control.Load(lane, 8), capacity);
      arguments.Store(lane, 0, 1u);
      arguments.Store(lane, 1, (locations + kApplyQuadsPerGroup - 1) / kApplyQuadsPerGroup);
      arguments.Store(lane, 2, 1u);
      control.Store(lane, 3, locations);
      // Word 4, the reference's candidate counter, is never counted here: the work set's queue
      // holds the candidates.
      control.Store(lane, 8, 0u);
      control.Store(lane, 12, 0u);
    });
  }

  void Apply(sim::Machine& machine, sim::Texture2D<glm::vec4>& colour) {
    sim::Dispatch d(std::string(kApplyDispatch), kApplyKernel);
    const DeferredColourApply apply{.control = d.Read(control_),
                                    .locations = d.Read(working_->locations),
                                    .heads = d.Read(working_->heads),
                                    .items = d.Read(working_->items),
                                    .output = d.ReadWrite(colour).As(sim::Format::RGBA8Unorm),
                                    .longLists = d.Counter("cmaa2/apply_lists_over_32"),
                                    .headsWidth = working_->headsWidth};
    machine.ComputeIndirect(d, {.arguments = &arguments_, .offset = 0, .groupSize = kApplyGroup}, apply);
  }

  Config config_;
  WorkSet workSet_;
  sim::Buffer<std::uint32_t> control_;
  sim::Buffer<std::uint32_t> arguments_;
  std::optional<sim::Texture2D<glm::vec4>> colour_;
  std::optional<sim::Texture2D<std::uint32_t>> edges_;
  std::optional<Working> working_;
};

Stage::Targets Cmaa2Pass::Process(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) {
  const int width = frame.Width(), height = frame.Height();
  sim::Texture2D<glm::vec4>& colour = FrameTexture(colour_, "cmaa2/colour", width, height, sim::Format::RGBA8Srgb);
  CopySrgb8Frame(frame, colour);
  sim::Texture2D<std::uint32_t>& edges = FrameTexture(edges_, "cmaa2/edges", (width + 1) / 2, height, 1);
  if (!working_ || working_->width != width || working_->height != height) {
    working_.emplace(width, height, Capacities::Of(width, height, config_.referenceBufferSizes));
  }
  auto makeDetect = [&](sim::Dispatch& d, auto form) { return MakeDetect(d, form, colour, edges); };
  auto makeConsume = [&](sim::Dispatch& d) { return MakeProcessCandidates(d, colour, edges); };
  const WorkSetShape workSet = workSet_.Run(machine, strategy, kKernels, width, height, makeDetect, makeConsume);
  WriteApplyArguments(machine);
  Apply(machine, colour);
  return {colour, edges, workSet};
}

PassOutput Cmaa2Pass::Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) {
  const Targets targets = Process(machine, frame, strategy);
  PassOutput output;
  output.SetWorkSet(targets.workSet);
  output.colour = DecodedSrgb8("cmaa2/output", targets.colour);
  output.layers.push_back(EdgesLayer());
  output.layers.push_back(CandidatesLayer(strategy));
  return output;
}

PassLayer Cmaa2Pass::EdgesLayer() const {
  const sim::Texture2D<std::uint32_t>& edges = *edges_;
  const int width = colour_->Width(), height = colour_->Height();
  const auto row = static_cast<std::size_t>(width), texelsPerRow = static_cast<std::size_t>(edges.Width());
  PassLayer layer{"edges", {"Y"}, width, height, std::vector<float>(row * static_cast<std::size_t>(height)), {}, 0};
  const std::span<const std::uint32_t> texels = edges.Texels();
  ByRows(width, height, [&](std::size_t i) {
    const std::size_t x = i % row;
    layer.values[i] = static_cast<float>((texels[i / row * texelsPerRow + x / 2] >> (x % 2 * 4)) & 0xFu);
  });
  return layer;
}

PassLayer Cmaa2Pass::CandidatesLayer(Strategy strategy) const {
  return MembershipLayer("candidates", workSet_.Membership(strategy), colour_->Width(), colour_->Height());
}

std::vector<SettingInfo> Settings() {
  return {
      {.name = "threshold", .defaultValue = 0.07, .min = 0.0, .max = 1.0, .minExclusive = true,
       .doc = "g_CMAA2_EdgeThreshold: luma contrast an edge must exceed after local contrast adaptation "
              "(CMAA2_STATIC_QUALITY_PRESET 2, HIGH; aa-facts §4.2)"},
      {.name = "local_contrast_adaptation", .defaultValue = 0.10, .min = 0.0, .max = 3.0,
       .doc = "g_CMAA2_LocalContrastAdaptationAmount: times the largest perpendicular contrast, subtracted "
              "from an edge's (aa-facts §4.2); range of TSCMAA's nonDominantEdgeRemovalAmount (seed 003)"},
      {.name = "reference_buffers", .defaultValue = 0.0, .min = 0.0, .max = 1.0, .integer = true,
       .doc = "1: the reference's default \"99.99% safe\" item and location lists (W*H/2, (W*H+3)/6); 0: its "
              "\"enough in all cases\" sizes made to hold a checkerboard and noise: 2*W*H items, a location per quad "
              "(aa-facts §4.1; docs/cmaa2.md)"},
  };
}

std::vector<Preset> Presets() {
  return {
      {"low", {{"threshold", 0.15}}},
      {"medium", {{"threshold", 0.10}}},
      {"high", {{"threshold", 0.07}}},
      {"ultra", {{"threshold", 0.05}}},
      // TSCMAA's SetEdgeThresholds defaults (seed 003): edge threshold 1/22, non-dominant edge
      // removal 0.5, read as CMAA2's local contrast adaptation amount (docs/cmaa2.md).
      {"tscmaa", {{"threshold", 1.0 / 22.0}, {"local_contrast_adaptation", 0.5}}},
  };
}

}  // namespace

const PassInfo& Info() {
  static const PassInfo info{
      .name = "cmaa2",
      .description = "CMAA2 v2.3: 2x2-style luma edges with local contrast adaptation, simple and Z shapes with line "
                     "tracing, per-quad linked lists of packed colours, in-place deferred apply",
      .source = "passes/cmaa2/cmaa2.h",
      .settings = Settings(),
      .presets = Presets(),
      .inputs = {FrameInput::Colour},
      .studiedDispatches = {kCandidatesDispatch},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // The colour target and its decoded copy (vec4 each), the edges (a u32 per texel of two
      // pixels), heads (a u32 per quad), items (2*W*H uint2), locations (a u32 per quad), the
      // two layers, membership and shape bytes, the stencil byte and the work-set queue.
      .bytesPerPixel = 2 * sizeof(glm::vec4) + 2 + 1 + 2 * sizeof(glm::uvec2) + 1 + 2 * sizeof(float) + 2 + 1 +
                       sizeof(std::uint32_t),
      .layerBytesPerPixel = 2 * sizeof(float),  // edges, candidates
      .temporal = false,
  };
  return info;
}

std::unique_ptr<Pass> Make(const PassSettings& settings) { return std::make_unique<Cmaa2Pass>(ConfigOf(settings)); }
std::unique_ptr<Stage> MakeStage(const PassSettings& settings) { return std::make_unique<Cmaa2Pass>(ConfigOf(settings)); }

}  // namespace passes::cmaa2
