#pragma once
// What a kernel sees when it runs on one lane: its lane index, whether it is a helper, its
// wave's EXEC mask, and the pixel (with quad neighbours for derivatives) or the compute thread
// (with group shared memory).
// Kernels are C++ callables taking a PixelLane& or ComputeLane&; resource views (sim/views.h)
// take the lane so they can count traffic into the lane's chunk without locks.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "raster/rasterizer.h"
#include "sim/check.h"
#include "sim/counters.h"
#include "sim/heat_map.h"

namespace sim {

// A kernel broke a rule of the machine (LDS access outside its declared size, a stencil export
// from a compute kernel...). The message names the dispatch.
class KernelError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// The dispatch a view was created by. Views share ownership of it, so a view used after its
// Dispatch is gone still names it, and its address cannot be reused by a later dispatch.
struct DispatchIdentity {
  std::uint64_t serial;  // 1, 2, ... in creation order, per process
  std::string name;
};

// Which end of a slot range a reservation takes from (sim/atomics.h).
enum class End : std::uint8_t { Front, Back };

namespace detail {
// One slot reservation a lane made in a chunk that runs in parallel with others; granted when the
// chunk is committed (sim/atomics.h).
struct SlotReservation {
  End end;
  std::uint32_t count;
};

// Everything the lanes of one chunk (a scan-converter bin or a fixed run of compute groups)
// accumulate; chunks are merged in order after the dispatch, so results do not depend on which
// host thread ran which chunk.
struct ChunkState {
  const DispatchIdentity* dispatch = nullptr;
  std::vector<ResourceTraffic> traffic;          // per binding
  std::vector<std::vector<std::byte>> appends;   // per append binding, staged items
  std::vector<std::vector<SlotReservation>> reservations;  // per slot counter, in lane order
  std::vector<std::vector<std::byte>> slotStores;          // per slot view, staged stores
  std::vector<std::uint64_t> passCounters;                 // per Dispatch::Counter
  // Chunks of this dispatch run one after another in chunk order (Dispatch::SerialChunks), so
  // atomics may return values and slots are granted when reserved.
  bool serial = false;
  LaneCounters lanes;
  TileHeatMap* heat = nullptr;
  std::vector<std::byte> lds;                    // the current group's shared memory
  // Per-thread values that persist across the stages of one group or pixel wave (Private<T>()):
  // one T per thread of the group (lane of the wave), sized by the first Private<T>() call and
  // zeroed per group (wave).
  int groupThreads = 0;
  const void* privateType = nullptr;
  std::size_t privateStride = 0;
  std::vector<std::byte> privates;

  // Thread `thread`'s private T (identified by `type`); a KernelError for a second type.
  std::byte* PrivateAt(const void* type, std::size_t size, int thread);
};

// One address per type: identifies the T of Private<T>() without RTTI.
template <typename T>
inline constexpr char kTypeTag = 0;

// Thread (or pixel lane) `index`'s private T in `chunk`.
template <typename T>
T& PrivateOf(ChunkState& chunk, int index) {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  // The storage comes from operator new; sizeof(T) is a multiple of alignof(T).
  static_assert(alignof(T) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__);
  return *std::launder(reinterpret_cast<T*>(chunk.PrivateAt(&kTypeTag<T>, sizeof(T), index)));
}
}  // namespace detail

struct LaneBase {
  int lane = 0;         // 0..63 within the wave
  bool helper = false;  // helper lanes run for derivatives; views drop their stores
  // The wave's EXEC mask while the kernel runs: bit i set when lane i runs it (active or helper;
  // whole-quad mode, hw-facts §6.1). The same for every lane of a wave, so a kernel can ask
  // whether a quad neighbour or any other lane executes.
  std::uint64_t exec = 0;
  detail::ChunkState* chunk = nullptr;
};

// What a view counts into: its binding slot in the dispatch that created it, and that dispatch.
struct ViewBinding {
  int slot = -1;
  std::shared_ptr<const DispatchIdentity> origin;
};

namespace detail {
// A view from another dispatch (created for an earlier Dispatch and captured by a later kernel)
// would count into the wrong binding: a KernelError naming both dispatches.
[[noreturn]] void StaleView(const LaneBase& lane, const DispatchIdentity& origin);
inline void CheckOrigin(const LaneBase& lane, const ViewBinding& binding) {
  if (binding.origin.get() != lane.chunk->dispatch) [[unlikely]] StaleView(lane, *binding.origin);
}

// Refuses an operation whose result depends on the order in which lanes of different chunks run,
// unless the chunks run serially.
inline void RequireSerialChunks(const LaneBase& lane, const char* what) {
  if (lane.chunk->serial) return;
  throw KernelError(lane.chunk->dispatch->name + ": " + what +
                    " depends on the order lanes run in; call Dispatch::SerialChunks() so the dispatch runs its "
                    "chunks one after another (slower, but deterministic)");
}
}  // namespace detail

struct PixelLane : LaneBase {
  int x = 0, y = 0;
  int quadPixel = 0;   // raster::QuadPixelIndex order
  int quadInWave = 0;  // 0..15
  const raster::QuadFragment* quad = nullptr;
  const raster::TriangleSetup* triangle = nullptr;  // draws only
  const raster::SamplePattern* pattern = nullptr;
  const PixelLane* quadLanes = nullptr;  // the quad's four lanes, in QuadPixelIndex order

  glm::vec2 Centre() const { return {static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f}; }
  raster::SampleMask Covered() const { return quad->covered.Pixel(quadPixel); }
  raster::SampleMask Passed() const { return quad->passed.Pixel(quadPixel); }
  // Perspective-correct barycentrics of the drawn triangle at the pixel centre, or at the
  // centroid location (hw-facts §4.2) for attributes that must not extrapolate.
  std::array<float, 3> Barycentrics() const;
  std::array<float, 3> CentroidBarycentrics() const;
  // At sample `sample`'s position of the pattern (HLSL's `sample` interpolation modifier).
  std::array<float, 3> SampleBarycentrics(int sample) const;

  // Every lane of the quad, helper flag included, is set up before any of them runs, so a
  // neighbour read here is never stale.
  const PixelLane& QuadLane(int pixel) const {
    AASIM_DCHECK(pixel >= 0 && pixel < raster::kQuadPixels);
    return quadLanes[pixel];
  }

  // This lane's T, kept across the stages of the pixel kernel (as ComputeLane::Private): zeroed
  // per wave, one T per dispatch, not counted (registers).
  template <typename T>
  T& Private() const {
    return detail::PrivateOf<T>(*chunk, lane);
  }
  // Fine derivatives within the quad (ddx_fine/ddy_fine, quad-permute differences on GCN) of a
  // value every lane of the quad computed in an earlier stage and kept in its Private<T>(): the
  // quad exchanges values, it does not re-run their loads. Differences along this lane's own row
  // (Ddx) or column (Ddy), +x and +y positive. A neighbour that does not run (dead stencil)
  // contributes its zeroed T.
  template <typename T>
  T Ddx() const {
    const int row = quadPixel & 2;
    return QuadPrivate<T>(row + 1) - QuadPrivate<T>(row);
  }
  template <typename T>
  T Ddy() const {
    const int column = quadPixel & 1;
    return QuadPrivate<T>(column + 2) - QuadPrivate<T>(column);
  }
  // The same for one member of the private T: lane.Ddx(&Varyings::uv).
  template <typename T, typename V>
  V Ddx(V T::*member) const {
    const int row = quadPixel & 2;
    return QuadPrivate<T>(row + 1).*member - QuadPrivate<T>(row).*member;
  }
  template <typename T, typename V>
  V Ddy(V T::*member) const {
    const int column = quadPixel & 1;
    return QuadPrivate<T>(column + 2).*member - QuadPrivate<T>(column).*member;
  }

 private:
  template <typename T>
  const T& QuadPrivate(int pixel) const {
    return detail::PrivateOf<T>(*chunk, QuadLane(pixel).lane);
  }
};

struct ComputeLane : LaneBase {
  glm::ivec3 threadId{0};  // global
  glm::ivec3 groupId{0};
  glm::ivec3 localId{0};
  int localIndex = 0;      // wave * 64 + lane (hw-facts §6.2)
  int waveInGroup = 0;
  // The pixel this thread works on, also its heat-map pixel: threadId.xy in a dispatch over a
  // pixel grid, the queued item's pixel in an indirect dispatch over pixel items, else (-1, -1).
  glm::ivec2 pixel{-1};
  // The queued item an indirect dispatch over pixel items loaded for this thread (IndirectCall).
  std::uint32_t item = 0;

  // Group shared memory, indexed in elements of T; bounds-checked against the kernel's declared
  // LDS size.
  template <typename T>
  T LdsLoad(std::size_t index) const {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, LdsAddress(index * sizeof(T), sizeof(T)), sizeof(T));
    chunk->lanes.ldsBytesRead += sizeof(T);
    return value;
  }
  template <typename T>
  void LdsStore(std::size_t index, const T& value) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::memcpy(LdsAddress(index * sizeof(T), sizeof(T)), &value, sizeof(T));
    chunk->lanes.ldsBytesWritten += sizeof(T);
  }
  // LDS atomics returning the value before the operation (InterlockedAdd/Min/Max/Exchange on
  // groupshared memory). A group runs on one host thread with its lanes in order, so the returned
  // values are deterministic in any dispatch. Each reads and writes sizeof(T) LDS bytes.
  template <typename T>
  T LdsAtomicAdd(std::size_t index, T value) const {
    return LdsRmw<T>(index, [value](T old) { return static_cast<T>(old + value); });
  }
  template <typename T>
  T LdsAtomicMin(std::size_t index, T value) const {
    return LdsRmw<T>(index, [value](T old) { return std::min(old, value); });
  }
  template <typename T>
  T LdsAtomicMax(std::size_t index, T value) const {
    return LdsRmw<T>(index, [value](T old) { return std::max(old, value); });
  }
  template <typename T>
  T LdsAtomicExchange(std::size_t index, T value) const {
    return LdsRmw<T>(index, [value](T) { return value; });
  }

  // This thread's T, kept across the stages (barriers) of its group: what a shader keeps in
  // registers across a barrier, without going through LDS. Every thread's T starts zeroed in
  // every group; a dispatch uses one T for all its stages. Registers are not memory: nothing is
  // counted (the kernel's VGPR count declares their cost).
  template <typename T>
  T& Private() const {
    return detail::PrivateOf<T>(*chunk, localIndex);
  }

 private:
  // Inline, with the error path out of line: every LDS access computes an address, and as a call
  // it cost CMAA2's queue form about a third of its time (docs/PERFORMANCE.md, "Stop 28").
  [[gnu::always_inline]] std::byte* LdsAddress(std::size_t byteOffset, std::size_t bytes) const {
    if (byteOffset + bytes > chunk->lds.size()) [[unlikely]] ThrowLdsOutOfRange(byteOffset);
    return chunk->lds.data() + byteOffset;
  }
  [[noreturn, gnu::cold, gnu::noinline]] void ThrowLdsOutOfRange(std::size_t byteOffset) const;
  template <typename T, typename Op>
  T LdsRmw(std::size_t index, Op op) const {
    static_assert(std::is_integral_v<T>, "LDS atomics are defined on integers");
    std::byte* address = LdsAddress(index * sizeof(T), sizeof(T));
    T old;
    std::memcpy(&old, address, sizeof(T));
    const T updated = op(old);
    std::memcpy(address, &updated, sizeof(T));
    chunk->lanes.ldsBytesRead += sizeof(T);
    chunk->lanes.ldsBytesWritten += sizeof(T);
    return old;
  }
};

}  // namespace sim
