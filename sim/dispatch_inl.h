#pragma once
// Template members of dispatch.h: the wave loops. Kernels are inlined into them (DESIGN.md
// "Performance architecture"); chunks run in parallel and are merged in order by Machine::Finish.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>

#include "sim/parallel.h"
#include "sim/pixel_waves.h"

namespace sim {

template <typename T>
AppendView<T> Dispatch::Append(AppendBuffer<T>& buffer) {
  const int items = Bind(buffer.Storage(), Access::Append);
  const int counter = Bind(buffer.Counter(), Access::AppendCounter);
  const int staging = static_cast<int>(appends_.size());
  appends_.push_back({sizeof(T), [&buffer](std::span<const std::byte> staged) -> std::uint64_t {
                        Buffer<T>& storage = buffer.Storage();
                        const auto bytes = static_cast<std::size_t>(storage.ElementBytes());
                        std::uint32_t& count = buffer.Counter().At(0);
                        std::uint64_t overflow = 0;
                        for (std::size_t at = 0; at < staged.size(); at += sizeof(T)) {
                          if (count >= storage.Size()) {
                            ++overflow;
                            continue;
                          }
                          std::memcpy(&storage.At(count), staged.data() + at, sizeof(T));
                          storage.TouchWrite(count * bytes, bytes);
                          ++count;
                        }
                        if (!staged.empty()) buffer.Counter().TouchWrite(0, 4);
                        return overflow;
                      }});
  return {View(items), counter, staging, buffer.Storage().ElementBytes()};
}

template <typename T>
SlotView<T> Dispatch::SlotWrite(Buffer<T>& buffer) {
  const int slot = Bind(buffer, Access::SlotWrite);
  const int staging = static_cast<int>(slotStores_.size());
  slotStores_.push_back({slot, [&buffer](std::span<const std::byte> staged,
                                         std::span<const std::vector<std::uint32_t>> granted,
                                         ResourceTraffic& traffic) {
                           detail::CommitSlotStores(buffer, staged, granted, traffic);
                         }});
  return {buffer, View(slot), staging};
}

namespace detail {
// Runs body(chunk) for every chunk: in parallel, or in chunk order on the calling thread.
template <typename Body>
void ForEachChunk(std::size_t count, bool serial, const Body& body) {
  if (serial) {
    for (std::size_t chunk = 0; chunk < count; ++chunk) body(chunk);
  } else {
    ParallelFor(count, body);
  }
}

inline double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace detail

template <typename... Stages>
DispatchReport Machine::Draw(Dispatch& dispatch, const DrawCall& call, Stages&&... stages) {
  const auto start = std::chrono::steady_clock::now();
  if (call.depth == nullptr) throw std::invalid_argument(dispatch.Name() + ": a draw needs a depth/stencil surface");
  const raster::DepthSurfaceConfig& depth = call.depth->Config();
  if (call.colour != nullptr && (call.colour->Width() != depth.width || call.colour->Height() != depth.height)) {
    throw std::invalid_argument(dispatch.Name() + ": colour surface " + std::to_string(call.colour->Width()) + "x" +
                                std::to_string(call.colour->Height()) + " does not match depth surface " +
                                std::to_string(depth.width) + "x" + std::to_string(depth.height));
  }
  ValidateKernel(dispatch, kWaveLanes);
  const raster::RasterResult& result = rasterizer_.Run(call.input, call.state, *call.depth);
  DispatchReport report;
  report.kind = DispatchKind::Draw;
  report.raster = result.counters;
  PixelTargets targets;
  targets.pattern = &call.depth->Pattern();
  targets.width = depth.width;
  targets.height = depth.height;
  targets.flush = call.flush;
  targets.colour = call.colour;
  RunPixelWaves(dispatch, std::move(report), result, targets, stages...);
  reports_.back().hostMilliseconds = detail::MillisecondsSince(start);
  return reports_.back();
}

template <typename... Stages>
DispatchReport Machine::FullScreen(Dispatch& dispatch, const FullScreenCall& call, Stages&&... stages) {
  const auto start = std::chrono::steady_clock::now();
  ValidateKernel(dispatch, kWaveLanes);
  PixelTargets targets;
  targets.width = call.width;
  targets.height = call.height;
  targets.flush = call.flush;
  targets.stencil = call.stencil;
  if (call.stencil != nullptr) targets.stencilSlot = dispatch.Bind(*call.stencil, Access::StencilTest);
  const raster::RasterResult& result = RasterizeFullScreen(call, dispatch);
  DispatchReport report;
  report.kind = DispatchKind::FullScreen;
  report.raster = result.counters;
  report.lanes.tilesHiStencilCulled = result.counters.tilesHiStencilRejected;
  targets.pattern = call.stencil != nullptr ? &call.stencil->Surface().Pattern() : &fullScreenSurface_->Pattern();
  RunPixelWaves(dispatch, std::move(report), result, targets, stages...);
  reports_.back().hostMilliseconds = detail::MillisecondsSince(start);
  return reports_.back();
}

namespace detail {
template <typename Stage>
using PixelExport = std::invoke_result_t<Stage&, PixelLane&>;

template <typename... Stages, std::size_t... Earlier>
constexpr bool OnlyTheLastStageExports(std::index_sequence<Earlier...>) {
  using Last = std::tuple_element_t<sizeof...(Stages) - 1, std::tuple<Stages...>>;
  return (std::is_void_v<PixelExport<std::tuple_element_t<Earlier, std::tuple<Stages...>>>> && ...) &&
         (std::is_void_v<PixelExport<Last>> || std::is_same_v<PixelExport<Last>, fmask::Colour>);
}
}  // namespace detail

template <typename... Stages>
void Machine::RunPixelWaves(Dispatch& dispatch, DispatchReport report,
                                             const raster::RasterResult& result, const PixelTargets& targets,
                                             Stages&... stages) {
  static_assert(sizeof...(Stages) >= 1, "a pixel kernel has at least one stage");
  static_assert(detail::OnlyTheLastStageExports<Stages...>(std::make_index_sequence<sizeof...(Stages) - 1>{}),
                "earlier stages of a pixel kernel return void; the last returns void or its fmask::Colour export");
  const std::size_t bins = result.quadsByBin.size();
  fmask::EqaaSurface* const colour = targets.colour;
  report.heat = TileHeatMap(targets.width, targets.height);
  report.lanes.pixelsScanned += (result.counters.quadsFull + result.counters.quadsPartial) * raster::kQuadPixels;
  std::vector<detail::ChunkState> chunks = MakeChunks(dispatch, bins, &report.heat);
  if (colour != nullptr) {
    shaded_.resize(bins);
    for (std::size_t bin = 0; bin < bins; ++bin) shaded_[bin].assign(result.quadsByBin[bin].size(), {});
  }
  const DispatchKind kind = report.kind;
  detail::ForEachChunk(bins, dispatch.serialChunks_, [&](std::size_t bin) {
    detail::ChunkState& chunk = chunks[bin];
    chunk.groupThreads = kWaveLanes;  // Private<T>() keeps one T per lane of the wave
    const std::vector<raster::QuadFragment>& quads = result.quadsByBin[bin];
    PackedWaves packed;
    if (targets.stencil != nullptr) {
      for (const raster::QuadFragment& quad : quads) CountStencilReads(chunk, quad, targets);
    }
    PackPixelWaves(quads, targets.flush, packed, chunk.lanes);
    std::array<PixelLane, kWaveLanes> lanes;
    InitPixelLanes(chunk, targets, lanes);
    for (std::size_t wave = 0; wave < packed.WaveCount(); ++wave) {
      const std::span<const std::uint32_t> waveQuads(packed.quads.data() + packed.waveStarts[wave],
                                                     packed.waveStarts[wave + 1] - packed.waveStarts[wave]);
      const std::uint64_t exec = SetUpPixelWave(chunk, quads, waveQuads, result, targets, kind, lanes);
      std::fill(chunk.privates.begin(), chunk.privates.end(), std::byte{0});
      const int laneCount = static_cast<int>(waveQuads.size()) * raster::kQuadPixels;
      // Every running lane finishes a stage before the next starts: a wave's lanes run in
      // lockstep, so a stage boundary is where quad neighbours' values can be exchanged. Only
      // the last stage can export (static_assert above).
      auto runStage = [&](auto& stage) {
        for (int i = 0; i < laneCount; ++i) {
          PixelLane& lane = lanes[static_cast<std::size_t>(i)];
          if (((exec >> i) & 1U) == 0) continue;
          if constexpr (std::is_void_v<detail::PixelExport<decltype(stage)>>) {
            stage(lane);
          } else {
            const fmask::Colour exported = stage(lane);
            if (colour != nullptr && !lane.helper) {
              shaded_[bin][waveQuads[static_cast<std::size_t>(lane.quadInWave)]][static_cast<std::size_t>(lane.quadPixel)] =
                  exported;
            }
          }
        }
      };
      (runStage(stages), ...);
    }
  });
  if (colour != nullptr) {
    report.fragments = colour->UpdateAll(result, [&](const raster::QuadFragment& quad, int p) {
      const std::size_t bin = static_cast<std::size_t>(quad.y / raster::kBinSize) * static_cast<std::size_t>(result.binsX) +
                              static_cast<std::size_t>(quad.x / raster::kBinSize);
      const auto index = static_cast<std::size_t>(&quad - result.quadsByBin[bin].data());
      return shaded_[bin][index][static_cast<std::size_t>(p)];
    });
  }
  Finish(dispatch, std::move(report), chunks, kWaveLanes);
}

template <typename... Stages>
DispatchReport Machine::Compute(Dispatch& dispatch, const ComputeGrid& grid, Stages&&... stages) {
  static_assert(sizeof...(Stages) >= 1, "a compute kernel has at least one stage");
  const auto start = std::chrono::steady_clock::now();
  ValidateGroup(dispatch, grid.groupSize);
  if (grid.threads.x < 0 || grid.threads.y < 0 || grid.threads.z < 0) {
    throw std::invalid_argument(dispatch.Name() + ": negative thread count");
  }
  DispatchReport report;
  report.kind = DispatchKind::Compute;
  RunGroups(dispatch, std::move(report), grid.threads, grid.groupSize, GroupLimits{}, stages...);
  reports_.back().hostMilliseconds = detail::MillisecondsSince(start);
  return reports_.back();
}

template <typename... Stages>
DispatchReport Machine::ComputeIndirect(Dispatch& dispatch, const IndirectCall& call, Stages&&... stages) {
  static_assert(sizeof...(Stages) >= 1, "a compute kernel has at least one stage");
  const auto start = std::chrono::steady_clock::now();
  ValidateGroup(dispatch, call.groupSize);
  DispatchReport report;
  report.kind = DispatchKind::IndirectCompute;
  IndirectLaunch launch = ReadIndirectArguments(dispatch, call);
  if (call.pixelItems) launch.limits.pixelItems = &*call.pixelItems;
  launch.limits.unpackItem = call.unpackItem;
  launch.limits.itemsFromBack = call.itemsFromBack;
  RunGroups(dispatch, std::move(report), launch.groups * call.groupSize, call.groupSize, launch.limits, stages...);
  reports_.back().hostMilliseconds = detail::MillisecondsSince(start);
  return reports_.back();
}

template <typename... Stages>
void Machine::RunGroups(Dispatch& dispatch, DispatchReport report, glm::ivec3 threads,
                                         glm::ivec3 groupSize, const GroupLimits& limits, Stages&... stages) {
  const glm::ivec3 groups = (threads + groupSize - 1) / groupSize;
  const std::size_t groupCount = static_cast<std::size_t>(groups.x) * static_cast<std::size_t>(groups.y) *
                                 static_cast<std::size_t>(groups.z);
  const int groupThreads = groupSize.x * groupSize.y * groupSize.z;
  const int wavesPerGroup = (groupThreads + kWaveLanes - 1) / kWaveLanes;
  const glm::ivec3 launched = groups * groupSize;
  report.groupSize = groupSize;
  report.groupCount = groups;
  if (dispatch.pixelGrid_) report.heat = TileHeatMap(dispatch.pixelGrid_->x, dispatch.pixelGrid_->y);
  const std::size_t chunkCount = (groupCount + kGroupsPerChunk - 1) / kGroupsPerChunk;
  std::vector<detail::ChunkState> chunks = MakeChunks(dispatch, chunkCount, &report.heat);
  CountIndirectReads(dispatch, limits, chunks[0]);
  const auto ldsBytes = static_cast<std::size_t>(dispatch.Kernel().ldsBytesPerGroup);
  detail::ForEachChunk(chunkCount, dispatch.serialChunks_, [&](std::size_t chunkIndex) {
    detail::ChunkState& chunk = chunks[chunkIndex];
    chunk.lds.assign(ldsBytes, std::byte{0});
    chunk.groupThreads = groupThreads;
    std::vector<ComputeLane> lanes(static_cast<std::size_t>(groupThreads));
    std::vector<glm::ivec2> attribution(static_cast<std::size_t>(groupThreads));
    std::vector<std::uint8_t> live(static_cast<std::size_t>(groupThreads));
    std::vector<std::uint64_t> waveExec(static_cast<std::size_t>(wavesPerGroup));
    // What a lane is within its group does not change from group to group: set once per chunk.
    for (int i = 0; i < groupThreads; ++i) {
      ComputeLane& lane = lanes[static_cast<std::size_t>(i)];
      lane.chunk = &chunk;
      lane.localIndex = i;
      lane.waveInGroup = i / kWaveLanes;
      lane.lane = i % kWaveLanes;
      lane.localId = {i % groupSize.x, (i / groupSize.x) % groupSize.y, i / (groupSize.x * groupSize.y)};
    }
    const std::size_t end = std::min(groupCount, (chunkIndex + 1) * kGroupsPerChunk);
    const bool limited = limits.itemCount.has_value() || limits.pixelItems != nullptr;
    for (std::size_t g = chunkIndex * kGroupsPerChunk; g < end; ++g) {
      const auto gi = static_cast<int>(g);
      const glm::ivec3 groupId{gi % groups.x, (gi / groups.x) % groups.y, gi / (groups.x * groups.y)};
      std::fill(chunk.lds.begin(), chunk.lds.end(), std::byte{0});
      std::fill(chunk.privates.begin(), chunk.privates.end(), std::byte{0});
      std::fill(waveExec.begin(), waveExec.end(), std::uint64_t{0});
      const glm::ivec3 groupOrigin = groupId * groupSize;
      // A group inside the grid with no item limits runs every lane (most groups of a grid).
      const bool whole = !limited && glm::all(glm::lessThanEqual(groupOrigin + groupSize, threads));
      for (int i = 0; i < groupThreads; ++i) {
        ComputeLane& lane = lanes[static_cast<std::size_t>(i)];
        lane.groupId = groupId;
        lane.threadId = groupOrigin + lane.localId;
        lane.pixel = dispatch.pixelGrid_ ? glm::ivec2(lane.threadId) + dispatch.pixelOrigin_ : glm::ivec2(-1);
        bool isLive = whole;
        if (!whole) {
          const long long linear =
              lane.threadId.x + static_cast<long long>(launched.x) *
                                    (lane.threadId.y + static_cast<long long>(launched.y) * lane.threadId.z);
          isLive = glm::all(glm::lessThan(lane.threadId, threads)) && (!limits.itemCount || linear < *limits.itemCount);
          if (limits.pixelItems != nullptr && isLive) {
            const auto at = static_cast<std::size_t>(linear);
            lane.item = limits.pixelItems->Load(lane, limits.itemsFromBack ? limits.pixelItems->Size() - 1 - at : at);
            lane.pixel = limits.unpackItem != nullptr ? limits.unpackItem(lane.item) : UnpackPixelItem(lane.item);
          }
        }
        live[static_cast<std::size_t>(i)] = isLive;
        attribution[static_cast<std::size_t>(i)] = isLive ? lane.pixel : glm::ivec2(-1);
        waveExec[static_cast<std::size_t>(lane.waveInGroup)] |= std::uint64_t{isLive} << lane.lane;
      }
      // Every wave's mask is complete before the first stage runs any lane of it.
      for (int i = 0; i < groupThreads; ++i) {
        lanes[static_cast<std::size_t>(i)].exec = waveExec[static_cast<std::size_t>(i / kWaveLanes)];
      }
      auto runStage = [&](auto& stage) {
        for (int i = 0; i < groupThreads; ++i) {
          if (live[static_cast<std::size_t>(i)]) stage(lanes[static_cast<std::size_t>(i)]);
        }
      };
      (runStage(stages), ...);
      const std::optional<glm::ivec2> oneTile =
          OneTilePixel(dispatch, limits, groupOrigin, groupSize, threads, *chunk.heat);
      CountGroup(chunk, {live, attribution, waveExec, oneTile}, sizeof...(Stages) - 1, limits.itemCountSlot);
    }
  });
  Finish(dispatch, std::move(report), chunks, groupThreads);
}

}  // namespace sim
