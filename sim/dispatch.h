#pragma once
// The machine's front door (style.md habit 13): every kernel launch is a named Dispatch with its
// declared register/LDS use and resource bindings, run by Machine as one of four kinds:
//   Draw        raster -> quads -> pixel waves -> colour backend (EQAA surface)
//   FullScreen  a full-screen triangle with an optional stencil test: a quad runs when any of
//               its pixels passes, failing pixels of a live quad are dead lanes, hi-stencil drops
//               whole 8x8 tiles first (seed 000 "Stencil Culling Inefficiencies")
//   Compute     a grid of groups, each ceil(N/64) consecutive waves with LDS and barriers
//   IndirectCompute  group counts read from a buffer an earlier dispatch wrote (append counter ->
//               dispatch arguments), as deferred queues do (seed 000 "Deferred Queues", aa-facts §3)
// Each run returns a DispatchReport: lane counters, per-resource traffic, occupancy, a timing
// estimate and a per-tile utilization heat map.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

#include "fmask/eqaa_surface.h"
#include "raster/rasterizer.h"
#include "sim/atomics.h"
#include "sim/counters.h"
#include "sim/eqaa_resources.h"
#include "sim/gpu_config.h"
#include "sim/heat_map.h"
#include "sim/lanes.h"
#include "sim/occupancy.h"
#include "sim/resources.h"
#include "sim/timing.h"
#include "sim/views.h"

namespace sim {

// What a kernel declares about itself (RGP reports the same per event, hw-facts §6.3).
struct KernelInfo {
  int vgprs = 16;
  int sgprs = 16;
  int ldsBytesPerGroup = 0;
  // The author's estimate of VALU instructions one wave executes: the timing model's ALU input.
  double valuInstructionsPerWave = 0.0;
  // Where that estimate comes from (a hand count of the reference shader, and of what), emitted
  // next to it; the report also shows the estimate with it halved and doubled.
  std::string_view source = {};
};

// Read, ReadWrite and Counter register a binding in call order, and the report lists bindings in
// that order: several in one constructor call take braces ({...} evaluates left to right), since
// parenthesised arguments are evaluated in an unspecified order (GCC and clang differ).
class Dispatch {
 public:
  Dispatch(std::string name, KernelInfo kernel);

  const std::string& Name() const { return identity_->name; }
  const KernelInfo& Kernel() const { return kernel_; }

  template <typename T>
  TextureView<T> Read(const Texture2D<T>& texture) { return {texture, View(Bind(texture, Access::Read))}; }
  template <typename T>
  RwTextureView<T> ReadWrite(Texture2D<T>& texture) { return {texture, View(Bind(texture, Access::ReadWrite))}; }
  template <typename T>
  BufferView<T> Read(const Buffer<T>& buffer) { return {buffer, View(Bind(buffer, Access::Read))}; }
  template <typename T>
  RwBufferView<T> ReadWrite(Buffer<T>& buffer) { return {buffer, View(Bind(buffer, Access::ReadWrite))}; }
  template <typename T>
  AppendView<T> Append(AppendBuffer<T>& buffer);
  StencilView Stencil(StencilBuffer& stencil) { return {stencil, View(Bind(stencil, Access::StencilExport))}; }
  // FMASK and the colour fragments of an EQAA surface, two read bindings (sim/eqaa_resources.h).
  EqaaView Read(const EqaaResources& eqaa) {
    const int fmask = Bind(eqaa.FmaskResource(), Access::Read);
    return {eqaa, View(fmask), Bind(eqaa.FragmentResource(), Access::Read)};
  }
  // Slot reservations from `counter`, and stores into the reserved slots of `buffer`
  // (sim/atomics.h).
  SlotCounterView Slots(SlotCounter& counter);
  template <typename T>
  SlotView<T> SlotWrite(Buffer<T>& buffer);

  // A counter of this pass's own ("smaa/search_steps"), reported with the dispatch under
  // "pass_counters"; the same name twice is the same counter.
  CounterView Counter(const std::string& name);

  // Compute dispatches over an image: thread (x, y) is pixel origin + (x, y) in the heat map (a
  // dispatch over a part of the screen, as MiniEngine FXAA's quadrants, aa-facts §3, passes one).
  void SetPixelGrid(int width, int height, glm::ivec2 origin = {0, 0}) {
    pixelGrid_ = {width, height};
    pixelOrigin_ = origin;
  }
  // Runs the chunks (bins, or runs of compute groups) one after another in chunk order instead of
  // in parallel, so atomics that return a value (RwBufferView::Interlocked*, slot indices) are
  // deterministic: slower, for order-dependent kernels such as CMAA2's per-quad linked lists
  // (aa-facts §4.1).
  void SerialChunks() { serialChunks_ = true; }

 private:
  friend class Machine;
  struct Binding {
    const Resource* resource;
    Access access;
  };
  struct AppendTarget {
    std::size_t elementSize;
    // Commits staged items (in chunk order) into the buffer; returns how many did not fit.
    std::function<std::uint64_t(std::span<const std::byte>)> commit;
  };
  struct SlotCounterTarget {
    SlotCounter* counter;
    int slot;
  };
  struct SlotStoreTarget {
    int slot;
    // Writes one chunk's staged stores once its reservations are granted.
    std::function<void(std::span<const std::byte>, std::span<const std::vector<std::uint32_t>>, ResourceTraffic&)>
        commit;
  };
  int Bind(const Resource& resource, Access access);
  ViewBinding View(int slot) const { return {slot, identity_}; }

  std::shared_ptr<const DispatchIdentity> identity_;
  KernelInfo kernel_;
  std::vector<Binding> bindings_;
  std::vector<AppendTarget> appends_;
  std::vector<SlotCounterTarget> slotCounters_;
  std::vector<SlotStoreTarget> slotStores_;
  std::vector<std::string> passCounters_;
  std::optional<glm::ivec2> pixelGrid_;
  glm::ivec2 pixelOrigin_{0, 0};
  bool serialChunks_ = false;
};

struct DispatchReport {
  std::string name;
  DispatchKind kind = DispatchKind::Compute;
  KernelInfo kernel;
  glm::ivec3 groupSize{0};   // compute kinds
  glm::ivec3 groupCount{0};
  LaneCounters lanes;
  std::vector<ResourceTraffic> resources;
  Occupancy occupancy;
  TimeEstimate time;  // an estimate (docs/timing-model.md), labelled so in every output
  TileHeatMap heat;
  std::optional<raster::RasterCounters> raster;         // Draw and FullScreen
  std::optional<fmask::FragmentCounters> fragments;     // Draw into an EQAA surface
  std::vector<PassCounter> passCounters;                // Dispatch::Counter, in declaration order
  double hostMilliseconds = 0.0;  // wall time of the simulation; not part of determinism

  std::uint64_t DramBytes() const;
  // Everything the report says about the simulated machine, host wall time excluded: what a
  // determinism check compares.
  bool SameSimulation(const DispatchReport& other) const;
};

struct DrawCall {
  raster::DrawInput input;
  raster::DrawState state;
  raster::DepthStencilSurface* depth = nullptr;  // required; its pattern is the sample pattern
  fmask::EqaaSurface* colour = nullptr;          // optional colour target for the colour export
  WaveFlush flush = WaveFlush::MixPrimitives;
};

struct FullScreenCall {
  int width = 0, height = 0;
  StencilBuffer* stencil = nullptr;  // optional stencil test against this buffer
  raster::CompareFunc stencilFunc = raster::CompareFunc::Equal;
  std::uint8_t stencilRef = 1;
  std::uint8_t stencilMask = 0xFF;
  bool hiStencil = true;  // program a hi-stencil pretest matching the test (hw-facts §5.3)
  WaveFlush flush = WaveFlush::MixPrimitives;
};

struct ComputeGrid {
  glm::ivec3 threads{1, 1, 1};    // logical threads; the last group per dimension may be partial
  glm::ivec3 groupSize{64, 1, 1};
};

// A queued pixel as deferred queues store it (aa-facts §3 packs Y<<20 | X<<8 with extra bits;
// a plain pixel queue needs only the position): y in the high 16 bits, x in the low 16.
static_assert(raster::kMaxDimension <= 0x10000, "pixel items hold 16-bit coordinates");
constexpr std::uint32_t PackPixelItem(int x, int y) {
  return static_cast<std::uint32_t>(y) << 16 | static_cast<std::uint32_t>(x);
}
constexpr glm::ivec2 UnpackPixelItem(std::uint32_t item) {
  return {static_cast<int>(item & 0xFFFFu), static_cast<int>(item >> 16)};
}

struct IndirectCall {
  const Buffer<std::uint32_t>* arguments = nullptr;  // {groupsX, groupsY, groupsZ} at `offset`
  std::size_t offset = 0;                             // element index
  glm::ivec3 groupSize{64, 1, 1};
  // Optional item count (e.g. an append counter): threads whose linear index is >= it are
  // masked off by the kernel's bounds check and count as empty lanes.
  const Buffer<std::uint32_t>* itemCount = nullptr;
  std::size_t itemCountIndex = 0;
  // Optional queue of PackPixelItem items, one per thread: the machine loads thread i's item
  // (one fetch, counted as the kernel's own load would be), sets lane.pixel and attributes the
  // lane to that pixel in the heat map. Needs Dispatch::SetPixelGrid for the heat map's size.
  std::optional<BufferView<std::uint32_t>> pixelItems = std::nullopt;
  // A pass-defined item encoding (MiniEngine FXAA's Y << 20 | X << 8 | bits, aa-facts §3) instead
  // of PackPixelItem: its pixel, also set as lane.pixel; the raw item is lane.item either way.
  glm::ivec2 (*unpackItem)(std::uint32_t item) = nullptr;
  // Thread i loads item Size() - 1 - i: a queue filled from the back (aa-facts §3, vertical items).
  bool itemsFromBack = false;
};

class Machine {
 public:
  explicit Machine(GpuConfig gpu) : gpu_(std::move(gpu)) {}

  const GpuConfig& Gpu() const { return gpu_; }

  // Pixel kernels are one or more stages, each stage(PixelLane&); every lane of a wave finishes a
  // stage before the next starts, so a later stage can take derivatives of values the quad
  // computed earlier (PixelLane::Ddx). Draw: the last stage returns the fmask::Colour export of
  // active lanes, earlier stages return void. FullScreen: every stage returns void.
  template <typename... Stages>
  DispatchReport Draw(Dispatch& dispatch, const DrawCall& call, Stages&&... stages);
  // A draw without a pixel shader (a depth pre-pass): the rasterizer's depth and stencil tests
  // and writes only. No pixel wave launches and no colour block runs, so the report has raster
  // counters and the raster term of the time estimate but no lanes; call.colour must be null.
  DispatchReport DrawDepthOnly(Dispatch& dispatch, const DrawCall& call);
  template <typename... Stages>
  DispatchReport FullScreen(Dispatch& dispatch, const FullScreenCall& call, Stages&&... stages);
  // Each stage is kernel(ComputeLane&) -> void; a group barrier separates consecutive stages.
  template <typename... Stages>
  DispatchReport Compute(Dispatch& dispatch, const ComputeGrid& grid, Stages&&... stages);
  template <typename... Stages>
  DispatchReport ComputeIndirect(Dispatch& dispatch, const IndirectCall& call, Stages&&... stages);

  // Every report since the last take or clear, in dispatch order.
  const std::vector<DispatchReport>& Reports() const { return reports_; }
  void ClearReports() { reports_.clear(); }
  // Hands the reports over and keeps none, so a long run does not hold a second copy.
  std::vector<DispatchReport> TakeReports() { return std::exchange(reports_, {}); }

 private:
  // Compute groups are simulated in fixed runs of this many groups per chunk, independent of the
  // host thread count, so append order and counter merges are deterministic.
  static constexpr std::size_t kGroupsPerChunk = 16;
  // Which launched threads have work, and the bindings an indirect launch reads.
  struct GroupLimits {
    std::optional<std::uint32_t> itemCount;
    int itemCountSlot = -1;  // binding of the item count, read once per wave by the bounds check
    std::size_t itemCountByte = 0;
    int argumentSlot = -1;   // binding of the indirect arguments, read by the command processor
    std::size_t argumentByte = 0;
    const BufferView<std::uint32_t>* pixelItems = nullptr;
    glm::ivec2 (*unpackItem)(std::uint32_t item) = nullptr;
    bool itemsFromBack = false;
  };
  struct IndirectLaunch {
    glm::ivec3 groups{0};
    GroupLimits limits;
  };

  std::vector<detail::ChunkState> MakeChunks(Dispatch& dispatch, std::size_t count, TileHeatMap* heat) const;
  void ValidateKernel(const Dispatch& dispatch, int threadsPerGroup) const;
  void ValidateGroup(const Dispatch& dispatch, glm::ivec3 groupSize) const;
  IndirectLaunch ReadIndirectArguments(Dispatch& dispatch, const IndirectCall& call) const;
  void CountIndirectReads(Dispatch& dispatch, const GroupLimits& limits, detail::ChunkState& first) const;
  // A group's lanes as CountGroup counts them: which ran, the pixel each is attributed to, the
  // waves' EXEC masks, and when every lane of the group lies in one heat-map tile, a pixel of it.
  struct GroupLanes {
    const std::vector<std::uint8_t>& live;
    const std::vector<glm::ivec2>& attribution;
    const std::vector<std::uint64_t>& waveExec;
    std::optional<glm::ivec2> oneTilePixel;
  };
  static void CountGroup(detail::ChunkState& chunk, const GroupLanes& group, std::size_t barriers, int itemCountSlot);
  static void AddToHeatMap(detail::ChunkState& chunk, const GroupLanes& group);
  // A pixel-grid group without an item list covers a rectangle of pixels (clipped to the grid):
  // one of its pixels when the rectangle lies in one tile of `heat`, nothing otherwise.
  static std::optional<glm::ivec2> OneTilePixel(const Dispatch& dispatch, const GroupLimits& limits,
                                                glm::ivec3 groupOrigin, glm::ivec3 groupSize, glm::ivec3 threads,
                                                const TileHeatMap& heat);
  void Finish(Dispatch& dispatch, DispatchReport report, std::vector<detail::ChunkState>& chunks,
                               int threadsPerGroup);
  static void CommitSlots(Dispatch& dispatch, const detail::ChunkState& chunk, DispatchReport& report);
  const raster::RasterResult& RasterizeFullScreen(const FullScreenCall& call, Dispatch& dispatch);
  // Where a pixel dispatch's quads come from and where its exports go.
  struct PixelTargets {
    const raster::SamplePattern* pattern = nullptr;
    int width = 0, height = 0;
    WaveFlush flush = WaveFlush::MixPrimitives;
    fmask::EqaaSurface* colour = nullptr;     // Draw: colour export into the EQAA surface
    const StencilBuffer* stencil = nullptr;   // FullScreen: the buffer the DB tests per pixel
    int stencilSlot = -1;
  };
  template <typename... Stages>
  void RunPixelWaves(Dispatch& dispatch, DispatchReport report, const raster::RasterResult& result,
                                      const PixelTargets& targets, Stages&... stages);
  // Classifies every lane of a pixel wave and sets all of them up before any runs (a kernel reads
  // its quad neighbours), counting lanes, heat and the wave; returns the wave's EXEC mask.
  // What a pixel lane is within its wave does not change from wave to wave: set once per chunk.
  static void InitPixelLanes(detail::ChunkState& chunk, const PixelTargets& targets,
                             std::array<PixelLane, kWaveLanes>& lanes);
  static std::uint64_t SetUpPixelWave(detail::ChunkState& chunk, std::span<const raster::QuadFragment> quads,
                                      std::span<const std::uint32_t> waveQuads, const raster::RasterResult& result,
                                      const PixelTargets& targets, DispatchKind kind,
                                      std::array<PixelLane, kWaveLanes>& lanes);
  static void CountStencilReads(detail::ChunkState& chunk, const raster::QuadFragment& quad,
                                const PixelTargets& targets);
  template <typename... Stages>
  void RunGroups(Dispatch& dispatch, DispatchReport report, glm::ivec3 threads,
                                  glm::ivec3 groupSize, const GroupLimits& limits, Stages&... stages);

  GpuConfig gpu_;
  raster::Rasterizer rasterizer_;
  std::optional<raster::DepthStencilSurface> fullScreenSurface_;  // reused when no stencil is bound
  // Without a stencil a full-screen triangle rasterizes to the same quads every time: the first
  // result at this size is kept (a 1080p triangle is half a million quads).
  std::optional<raster::RasterResult> fullScreenRaster_;
  std::vector<std::vector<std::array<fmask::Colour, raster::kQuadPixels>>> shaded_;  // per bin, per quad
  std::vector<DispatchReport> reports_;
};

}  // namespace sim

#include "sim/dispatch_inl.h"
