// Non-template parts of the machine (see dispatch.h): bindings, validation, the full-screen
// triangle, indirect arguments, per-group lane counting, and merging chunks into a report.

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/dispatch.h"

namespace sim {

std::array<float, 3> PixelLane::Barycentrics() const {
  return raster::PerspectiveBarycentrics(*triangle, x + 0.5, y + 0.5);
}

std::array<float, 3> PixelLane::CentroidBarycentrics() const {
  const std::array<double, 2> at = raster::CentroidPosition(*quad, quadPixel, *pattern);
  return raster::PerspectiveBarycentrics(*triangle, at[0], at[1]);
}

std::array<float, 3> PixelLane::SampleBarycentrics(int sample) const {
  const std::array<double, 2> at = raster::SamplePosition(x, y, *pattern, sample);
  return raster::PerspectiveBarycentrics(*triangle, at[0], at[1]);
}

void ComputeLane::ThrowLdsOutOfRange(std::size_t byteOffset) const {
  throw KernelError(chunk->dispatch->name + ": LDS access at byte " + std::to_string(byteOffset) +
                    " beyond the declared " + std::to_string(chunk->lds.size()) + " bytes");
}

std::byte* detail::ChunkState::PrivateAt(const void* type, std::size_t size, int thread) {
  if (privateType == nullptr) {
    privateType = type;
    privateStride = size;
    privates.assign(privateStride * static_cast<std::size_t>(groupThreads), std::byte{0});
  } else if (privateType != type) {
    throw KernelError(dispatch->name + ": Private<T>() with two different types; one dispatch keeps one T per thread");
  }
  return privates.data() + privateStride * static_cast<std::size_t>(thread);
}

void detail::StaleView(const LaneBase& lane, const DispatchIdentity& origin) {
  const DispatchIdentity& running = *lane.chunk->dispatch;
  throw KernelError(running.name + ": a view created by dispatch '" + origin.name + "' (#" +
                    std::to_string(origin.serial) + ") is used by dispatch '" + running.name + "' (#" +
                    std::to_string(running.serial) + "); create a kernel's views from the Dispatch it runs under");
}

std::uint64_t DispatchReport::DramBytes() const {
  std::uint64_t bytes = 0;
  for (const ResourceTraffic& traffic : resources) bytes += traffic.DramBytes();
  return bytes;
}

bool DispatchReport::SameSimulation(const DispatchReport& other) const {
  return name == other.name && kind == other.kind && groupSize == other.groupSize &&
         groupCount == other.groupCount && lanes == other.lanes && resources == other.resources &&
         occupancy.wavesPerSimd == other.occupancy.wavesPerSimd && occupancy.limiter == other.occupancy.limiter &&
         time.totalMicroseconds == other.time.totalMicroseconds && heat == other.heat && raster == other.raster &&
         fragments == other.fragments && passCounters == other.passCounters;
}

Dispatch::Dispatch(std::string name, KernelInfo kernel) : kernel_(kernel) {
  static std::atomic<std::uint64_t> lastSerial{0};
  identity_ = std::make_shared<const DispatchIdentity>(DispatchIdentity{++lastSerial, std::move(name)});
}

int Dispatch::Bind(const Resource& resource, Access access) {
  for (std::size_t slot = 0; slot < bindings_.size(); ++slot) {
    if (bindings_[slot].resource != &resource) continue;
    // One resource bound twice is one binding, so its lines are counted once.
    bindings_[slot].access = bindings_[slot].access | access;
    return static_cast<int>(slot);
  }
  bindings_.push_back({&resource, access});
  return static_cast<int>(bindings_.size() - 1);
}

SlotCounterView Dispatch::Slots(SlotCounter& counter) {
  for (std::size_t i = 0; i < slotCounters_.size(); ++i) {
    if (slotCounters_[i].counter == &counter) return {counter, static_cast<int>(i), View(slotCounters_[i].slot)};
  }
  const int slot = Bind(counter.Counters(), Access::SlotCounter);
  slotCounters_.push_back({&counter, slot});
  return {counter, static_cast<int>(slotCounters_.size() - 1), View(slot)};
}

CounterView Dispatch::Counter(const std::string& name) {
  if (name.empty()) throw std::invalid_argument(Name() + ": a pass counter needs a name");
  const auto found = std::find(passCounters_.begin(), passCounters_.end(), name);
  const auto index = static_cast<int>(found - passCounters_.begin());
  if (found == passCounters_.end()) passCounters_.push_back(name);
  return CounterView(View(index));
}

std::vector<detail::ChunkState> Machine::MakeChunks(Dispatch& dispatch, std::size_t count, TileHeatMap* heat) const {
  for (const Dispatch::Binding& binding : dispatch.bindings_) const_cast<Resource*>(binding.resource)->BeginDispatch();
  std::vector<detail::ChunkState> chunks(std::max<std::size_t>(count, 1));
  for (detail::ChunkState& chunk : chunks) {
    chunk.dispatch = dispatch.identity_.get();
    chunk.traffic.resize(dispatch.bindings_.size());
    chunk.appends.resize(dispatch.appends_.size());
    chunk.reservations.resize(dispatch.slotCounters_.size());
    chunk.slotStores.resize(dispatch.slotStores_.size());
    chunk.passCounters.assign(dispatch.passCounters_.size(), 0);
    chunk.heat = heat;
    chunk.serial = dispatch.serialChunks_;
  }
  return chunks;
}

void Machine::ValidateKernel(const Dispatch& dispatch, int threadsPerGroup) const {
  const KernelInfo& kernel = dispatch.Kernel();
  try {
    TheoreticalOccupancy(gpu_, {kernel.vgprs, kernel.sgprs, kernel.ldsBytesPerGroup, threadsPerGroup});
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(dispatch.Name() + ": " + error.what());
  }
  if (!(kernel.valuInstructionsPerWave >= 0.0)) {
    throw std::invalid_argument(dispatch.Name() + ": VALU instruction estimate must be >= 0");
  }
}

void Machine::ValidateGroup(const Dispatch& dispatch, glm::ivec3 groupSize) const {
  const long long threads = static_cast<long long>(groupSize.x) * groupSize.y * groupSize.z;
  if (groupSize.x < 1 || groupSize.y < 1 || groupSize.z < 1 || threads > kMaxGroupThreads) {
    throw std::invalid_argument(dispatch.Name() + ": group size " + std::to_string(groupSize.x) + "x" +
                                std::to_string(groupSize.y) + "x" + std::to_string(groupSize.z) +
                                " must be positive with at most " + std::to_string(kMaxGroupThreads) +
                                " threads (hw-facts §6.2)");
  }
  ValidateKernel(dispatch, static_cast<int>(threads));
}

Machine::IndirectLaunch Machine::ReadIndirectArguments(Dispatch& dispatch, const IndirectCall& call) const {
  if (call.arguments == nullptr || call.offset + 3 > call.arguments->Size()) {
    throw std::invalid_argument(dispatch.Name() + ": indirect arguments need three group counts at element " +
                                std::to_string(call.offset));
  }
  IndirectLaunch launch;
  launch.limits.argumentSlot = dispatch.Bind(*call.arguments, Access::IndirectArgs);
  launch.limits.argumentByte = call.offset * 4;
  for (int axis = 0; axis < 3; ++axis) {
    const std::uint32_t count = call.arguments->At(call.offset + static_cast<std::size_t>(axis));
    // GCN takes group counts as 32-bit values; more than 2^31 - 1 is beyond any real grid and
    // beyond glm::ivec3, so it is refused rather than wrapped.
    if (count > static_cast<std::uint32_t>(std::numeric_limits<int>::max() / std::max(1, call.groupSize[axis]))) {
      throw std::invalid_argument(dispatch.Name() + ": indirect group count " + std::to_string(count) +
                                  " too large");
    }
    launch.groups[axis] = static_cast<int>(count);
  }
  if (call.itemCount != nullptr) {
    if (call.itemCountIndex >= call.itemCount->Size()) {
      throw std::invalid_argument(dispatch.Name() + ": item count index " + std::to_string(call.itemCountIndex) +
                                  " outside its buffer");
    }
    launch.limits.itemCount = call.itemCount->At(call.itemCountIndex);
    launch.limits.itemCountSlot = dispatch.Bind(*call.itemCount, Access::Read);
    launch.limits.itemCountByte = call.itemCountIndex * 4;
  }
  return launch;
}

void Machine::CountIndirectReads(Dispatch& dispatch, const GroupLimits& limits, detail::ChunkState& first) const {
  if (limits.argumentSlot >= 0) {
    // The command processor reads the three group counts (hw-facts §6.2 PKT3_DISPATCH_INDIRECT).
    const auto slot = static_cast<std::size_t>(limits.argumentSlot);
    first.traffic[slot].bytesRead += 12;
    dispatch.bindings_[slot].resource->TouchRead(limits.argumentByte, 12);
  }
  if (limits.itemCountSlot >= 0) {
    // Every wave loads the count (CountGroup adds those bytes); one line holds it.
    dispatch.bindings_[static_cast<std::size_t>(limits.itemCountSlot)].resource->TouchRead(limits.itemCountByte, 4);
  }
}

void Machine::CountGroup(detail::ChunkState& chunk, const GroupLanes& group, std::size_t barriers,
                         int itemCountSlot) {
  LaneCounters& counters = chunk.lanes;
  ++counters.groups;
  counters.barriers += barriers;
  int groupActive = 0;
  for (const std::uint64_t exec : group.waveExec) {
    const int active = std::popcount(exec);
    groupActive += active;
    counters.lanesActive += static_cast<std::uint64_t>(active);
    counters.lanesDeadEmpty += static_cast<std::uint64_t>(kWaveLanes - active);
    ++counters.waves;
    counters.lanesLaunched += kWaveLanes;
    ++counters.wavesByActiveLanes[static_cast<std::size_t>(active)];
  }
  if (group.oneTilePixel) {
    if (groupActive != 0) chunk.heat->Add(group.oneTilePixel->x, group.oneTilePixel->y, LaneKind::Active,
                                          static_cast<std::uint32_t>(groupActive));
  } else {
    AddToHeatMap(chunk, group);
  }
  if (itemCountSlot >= 0) {
    const auto waves = static_cast<std::uint64_t>(group.waveExec.size());
    ResourceTraffic& traffic = chunk.traffic[static_cast<std::size_t>(itemCountSlot)];
    traffic.fetches += waves;
    traffic.bytesRead += 4 * waves;
  }
}

// Active lanes go to the heat map in runs of one tile, one atomic add per run.
void Machine::AddToHeatMap(detail::ChunkState& chunk, const GroupLanes& group) {
  long long runTile = -1;
  std::uint32_t runLanes = 0;
  glm::ivec2 runPixel{0};
  const auto flush = [&] {
    if (runLanes != 0) chunk.heat->Add(runPixel.x, runPixel.y, LaneKind::Active, runLanes);
    runLanes = 0;
  };
  for (std::size_t i = 0; i < group.live.size(); ++i) {
    if (group.live[i] == 0) continue;
    const long long tile = chunk.heat->TileOf(group.attribution[i].x, group.attribution[i].y);
    if (tile < 0) continue;
    if (tile != runTile) {
      flush();
      runTile = tile;
      runPixel = group.attribution[i];
    }
    ++runLanes;
  }
  flush();
}

std::optional<glm::ivec2> Machine::OneTilePixel(const Dispatch& dispatch, const GroupLimits& limits,
                                                glm::ivec3 groupOrigin, glm::ivec3 groupSize, glm::ivec3 threads,
                                                const TileHeatMap& heat) {
  if (!dispatch.pixelGrid_ || limits.pixelItems != nullptr) return std::nullopt;
  const glm::ivec2 first = glm::ivec2(groupOrigin) + dispatch.pixelOrigin_;
  const glm::ivec2 last = glm::ivec2(glm::min(groupOrigin + groupSize, threads)) - 1 + dispatch.pixelOrigin_;
  const long long tile = heat.TileOf(first.x, first.y);
  if (tile < 0 || heat.TileOf(last.x, last.y) != tile) return std::nullopt;
  return first;
}

void Machine::InitPixelLanes(detail::ChunkState& chunk, const PixelTargets& targets,
                             std::array<PixelLane, kWaveLanes>& lanes) {
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    PixelLane& lane = lanes[i];
    lane.lane = static_cast<int>(i);
    lane.chunk = &chunk;
    lane.quadPixel = static_cast<int>(i) % raster::kQuadPixels;
    lane.quadInWave = static_cast<int>(i) / raster::kQuadPixels;
    lane.pattern = targets.pattern;
    lane.quadLanes = &lanes[i - static_cast<std::size_t>(lane.quadPixel)];
  }
}

std::uint64_t Machine::SetUpPixelWave(detail::ChunkState& chunk, std::span<const raster::QuadFragment> quads,
                                      std::span<const std::uint32_t> waveQuads, const raster::RasterResult& result,
                                      const PixelTargets& targets, DispatchKind kind,
                                      std::array<PixelLane, kWaveLanes>& lanes) {
  // Every lane's kind and the wave's EXEC mask exist before any lane runs, so a kernel reading a
  // quad neighbour's helper flag or the mask sees the final value, as on the hardware where EXEC
  // is set before the shader starts (hw-facts §6.1).
  static_assert(raster::kBinSize % kTileSize == 0, "a bin holds whole heat-map tiles");
  std::uint64_t exec = 0;
  int active = 0;
  for (std::size_t k = 0; k < waveQuads.size(); ++k) {
    const raster::QuadFragment& quad = quads[waveQuads[k]];
    const QuadLaneKinds kinds = ClassifyQuad(quad, kind);
    const unsigned passed = kinds.active, helper = kinds.helper, dead = kinds.deadStencil;
    const auto count = [](unsigned mask) { return static_cast<std::uint32_t>(std::popcount(mask)); };
    chunk.lanes.lanesActive += count(passed);
    chunk.lanes.lanesHelper += count(helper);
    chunk.lanes.lanesDeadStencil += count(dead);
    active += static_cast<int>(count(passed));
    // A quad lies in one 8x8 tile; its pixels past the map's edge are not counted there.
    if (quad.x + 1 < targets.width && quad.y + 1 < targets.height) {
      if (passed != 0) chunk.heat->AddOwned(quad.x, quad.y, LaneKind::Active, count(passed));
      if (helper != 0) chunk.heat->AddOwned(quad.x, quad.y, LaneKind::Helper, count(helper));
      if (dead != 0) chunk.heat->AddOwned(quad.x, quad.y, LaneKind::DeadStencil, count(dead));
    } else {
      for (int p = 0; p < raster::kQuadPixels; ++p) {
        chunk.heat->AddOwned(quad.x + (p & 1), quad.y + (p >> 1), kinds.Of(p));
      }
    }
    exec |= std::uint64_t{passed | helper} << (k * raster::kQuadPixels);
    const raster::TriangleSetup* triangle = kind == DispatchKind::Draw ? &result.triangles[quad.setupIndex] : nullptr;
    for (int p = 0; p < raster::kQuadPixels; ++p) {
      PixelLane& lane = lanes[k * raster::kQuadPixels + static_cast<std::size_t>(p)];
      lane.helper = (helper >> p & 1u) != 0;
      lane.x = quad.x + (p & 1);
      lane.y = quad.y + (p >> 1);
      lane.quad = &quad;
      lane.triangle = triangle;
    }
  }
  for (std::size_t i = 0; i < waveQuads.size() * raster::kQuadPixels; ++i) lanes[i].exec = exec;
  chunk.lanes.lanesDeadEmpty += static_cast<std::uint64_t>(kWaveLanes) - waveQuads.size() * raster::kQuadPixels;
  chunk.lanes.lanesLaunched += kWaveLanes;
  ++chunk.lanes.wavesByActiveLanes[static_cast<std::size_t>(active)];
  return exec;
}

void Machine::CountStencilReads(detail::ChunkState& chunk, const raster::QuadFragment& quad,
                                const PixelTargets& targets) {
  // The DB reads one stencil byte per covered pixel of a quad that reached the per-pixel test.
  ResourceTraffic& traffic = chunk.traffic[static_cast<std::size_t>(targets.stencilSlot)];
  for (int p = 0; p < raster::kQuadPixels; ++p) {
    if (quad.covered.Pixel(p) == 0) continue;
    const int x = quad.x + (p & 1), y = quad.y + (p >> 1);
    ++traffic.bytesRead;
    targets.stencil->TouchRead(static_cast<std::size_t>(y) * static_cast<std::size_t>(targets.width) +
                                   static_cast<std::size_t>(x),
                               1);
  }
}

const raster::RasterResult& Machine::RasterizeFullScreen(const FullScreenCall& call, Dispatch& dispatch) {
  if (call.width < 1 || call.height < 1 || call.width > raster::kMaxDimension || call.height > raster::kMaxDimension) {
    throw std::invalid_argument(dispatch.Name() + ": full-screen size " + std::to_string(call.width) + "x" +
                                std::to_string(call.height) + " outside 1.." + std::to_string(raster::kMaxDimension));
  }
  raster::DrawState state;
  state.cull = raster::CullMode::None;
  state.depth.testEnable = false;
  state.depth.writeEnable = false;
  state.depth.hiZEnable = false;
  raster::DepthStencilSurface* surface = nullptr;
  if (call.stencil != nullptr) {
    if (call.stencil->Width() != call.width || call.stencil->Height() != call.height) {
      throw std::invalid_argument(dispatch.Name() + ": stencil buffer '" + call.stencil->Name() + "' is " +
                                  std::to_string(call.stencil->Width()) + "x" + std::to_string(call.stencil->Height()) +
                                  ", the pass is " + std::to_string(call.width) + "x" + std::to_string(call.height));
    }
    surface = &call.stencil->Surface();
    state.stencil.enable = true;
    state.stencil.func = call.stencilFunc;
    state.stencil.ref = call.stencilRef;
    state.stencil.readMask = call.stencilMask;
    state.stencil.writeMask = 0;
    // A driver that knows the compare programs a matching pretest (hw-facts §5.3), so tiles with
    // no passing pixel are dropped before quads are formed.
    std::array<raster::HiStencilPretest, raster::kHiStencilPretests> pretests{};
    pretests[0] = {call.hiStencil, call.stencilFunc, call.stencilRef, call.stencilMask};
    surface->SetHiStencilPretests(pretests);
  } else {
    if (!fullScreenSurface_ || fullScreenSurface_->Config().width != call.width ||
        fullScreenSurface_->Config().height != call.height) {
      raster::DepthSurfaceConfig config;
      config.width = call.width;
      config.height = call.height;
      fullScreenSurface_.emplace(config, raster::MakeBuiltinPattern("centre", 1));
      fullScreenRaster_.reset();
    }
    if (fullScreenRaster_) return *fullScreenRaster_;
    surface = &*fullScreenSurface_;
  }
  // One triangle covering the viewport: clip (-1,-1), (3,-1), (-1,3).
  static constexpr std::array<glm::vec4, 3> kTriangle = {glm::vec4(-1, -1, 0, 1), glm::vec4(3, -1, 0, 1),
                                                         glm::vec4(-1, 3, 0, 1)};
  static constexpr std::array<std::uint32_t, 3> kIndices = {0, 1, 2};
  const raster::RasterResult& result = rasterizer_.Run({kTriangle, kIndices, 0}, state, *surface);
  if (call.stencil != nullptr) return result;
  fullScreenRaster_ = result;
  return *fullScreenRaster_;
}

DispatchReport Machine::DrawDepthOnly(Dispatch& dispatch, const DrawCall& call) {
  const auto start = std::chrono::steady_clock::now();
  if (call.depth == nullptr) throw std::invalid_argument(dispatch.Name() + ": a draw needs a depth/stencil surface");
  if (call.colour != nullptr) throw std::invalid_argument(dispatch.Name() + ": a depth-only draw has no colour target");
  ValidateKernel(dispatch, kWaveLanes);
  const raster::RasterResult& result = rasterizer_.Run(call.input, call.state, *call.depth);
  DispatchReport report;
  report.kind = DispatchKind::Draw;
  report.raster = result.counters;
  // The scan converter still walks every quad it emits (the raster term of the estimate). No lane
  // launches, so the heat map stays empty (and costs no memory).
  report.lanes.pixelsScanned += (result.counters.quadsFull + result.counters.quadsPartial) * raster::kQuadPixels;
  std::vector<detail::ChunkState> chunks = MakeChunks(dispatch, 0, nullptr);
  Finish(dispatch, std::move(report), chunks, kWaveLanes);
  reports_.back().hostMilliseconds = detail::MillisecondsSince(start);
  return reports_.back();
}

void Machine::CommitSlots(Dispatch& dispatch, const detail::ChunkState& chunk, DispatchReport& report) {
  std::vector<std::vector<std::uint32_t>> granted(dispatch.slotCounters_.size());
  for (std::size_t c = 0; c < granted.size(); ++c) {
    granted[c] = detail::GrantReservations(*dispatch.slotCounters_[c].counter, chunk.reservations[c],
                                           report.lanes.slotOverflow);
  }
  for (std::size_t s = 0; s < dispatch.slotStores_.size(); ++s) {
    const Dispatch::SlotStoreTarget& target = dispatch.slotStores_[s];
    target.commit(chunk.slotStores[s], granted, report.resources[static_cast<std::size_t>(target.slot)]);
  }
}

void Machine::Finish(Dispatch& dispatch, DispatchReport report,
                                      std::vector<detail::ChunkState>& chunks, int threadsPerGroup) {
  report.name = dispatch.Name();
  report.kernel = dispatch.Kernel();
  report.resources.resize(dispatch.bindings_.size());
  report.passCounters.clear();
  for (const std::string& name : dispatch.passCounters_) report.passCounters.push_back({name, 0});
  for (detail::ChunkState& chunk : chunks) {
    report.lanes.Merge(chunk.lanes);
    for (std::size_t c = 0; c < chunk.passCounters.size(); ++c) report.passCounters[c].value += chunk.passCounters[c];
    for (std::size_t slot = 0; slot < chunk.traffic.size(); ++slot) {
      report.resources[slot].MergeLaneTraffic(chunk.traffic[slot]);
    }
    for (std::size_t a = 0; a < chunk.appends.size(); ++a) {
      report.lanes.appendOverflow += dispatch.appends_[a].commit(chunk.appends[a]);
    }
    // Chunk order: the prefix sum that makes slot indices independent of the thread count.
    CommitSlots(dispatch, chunk, report);
  }
  for (std::size_t slot = 0; slot < dispatch.bindings_.size(); ++slot) {
    const Dispatch::Binding& binding = dispatch.bindings_[slot];
    ResourceTraffic& traffic = report.resources[slot];
    traffic.name = binding.resource->Name();
    traffic.access = binding.access;
    traffic.linesRead = binding.resource->LinesRead();
    traffic.linesWritten = binding.resource->LinesWritten();
  }
  const KernelInfo& kernel = dispatch.Kernel();
  report.occupancy =
      TheoreticalOccupancy(gpu_, {kernel.vgprs, kernel.sgprs, kernel.ldsBytesPerGroup, threadsPerGroup});
  WorkEstimate work;
  work.waves = report.lanes.waves;
  work.valuInstructionsPerWave = kernel.valuInstructionsPerWave;
  work.dramBytes = report.DramBytes();
  work.rasterPixels = report.lanes.pixelsScanned;
  work.hiStencilTiles = report.lanes.tilesHiStencilCulled;
  work.occupancy = report.occupancy;
  report.time = EstimateTime(gpu_, work);
  WorkEstimate scaled = work;
  scaled.valuInstructionsPerWave = work.valuInstructionsPerWave * 0.5;
  report.time.totalValuHalvedMicroseconds = EstimateTime(gpu_, scaled).totalMicroseconds;
  scaled.valuInstructionsPerWave = work.valuInstructionsPerWave * 2.0;
  report.time.totalValuDoubledMicroseconds = EstimateTime(gpu_, scaled).totalMicroseconds;
  reports_.push_back(std::move(report));
}

}  // namespace sim
