#pragma once
// Counters of one dispatch, counted where the lanes run and merged in a fixed order (style.md
// habits 14-15): plain numerators and denominators, never ratios. The field tables below are
// the only list of names; JSON, CSV and the summary are generated from them.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "sim/wave.h"

namespace sim {

struct LaneCounters {
  std::uint64_t waves = 0;
  std::uint64_t groups = 0;        // compute groups (0 for pixel dispatches)
  std::uint64_t lanesLaunched = 0;  // waves * 64
  std::uint64_t lanesActive = 0;
  std::uint64_t lanesHelper = 0;
  std::uint64_t lanesDeadStencil = 0;
  std::uint64_t lanesDeadEmpty = 0;
  std::uint64_t quadsLaunched = 0;       // pixel dispatches: quads packed into waves
  std::uint64_t quadsCulled = 0;         // rasterized quads with no pixel passing depth/stencil
  std::uint64_t tilesHiStencilCulled = 0;  // 8x8 tiles dropped before any quad was formed
  std::uint64_t pixelsScanned = 0;       // pixels the scan converter walked (timing estimate)
  std::uint64_t ldsBytesRead = 0;
  std::uint64_t ldsBytesWritten = 0;
  std::uint64_t barriers = 0;            // group barriers executed (per group)
  std::uint64_t appendOverflow = 0;      // appends dropped because the buffer was full
  std::uint64_t slotOverflow = 0;        // reserved slots refused: the front and back fills met
  // Waves by active lanes, W0..W64.
  std::array<std::uint64_t, kWaveLanes + 1> wavesByActiveLanes{};
  // Rasterized quads by pixels passing depth/stencil, 0..4 (0 = culled, not launched).
  std::array<std::uint64_t, raster::kQuadPixels + 1> quadsByLivePixels{};
  // Pixel waves by the number of primitives they mix, 0..16 (index 0 unused).
  std::array<std::uint64_t, kQuadsPerWave + 1> wavesByPrimitives{};

  void Merge(const LaneCounters& other);
  friend bool operator==(const LaneCounters&, const LaneCounters&) = default;
};

struct LaneCounterField {
  const char* name;  // "category/name", stable: JSON keys and CSV columns
  std::uint64_t LaneCounters::*member;
  const char* description;
};

inline constexpr LaneCounterField kLaneCounterFields[] = {
    {"waves/launched", &LaneCounters::waves, "wave64s launched"},
    {"groups/launched", &LaneCounters::groups, "compute groups launched"},
    {"lanes/launched", &LaneCounters::lanesLaunched, "lanes of launched waves (64 per wave)"},
    {"lanes/active", &LaneCounters::lanesActive, "lanes that ran for a pixel or thread"},
    {"lanes/helper", &LaneCounters::lanesHelper,
     "helper lanes: uncovered pixels of live quads, run for derivatives"},
    {"lanes/dead_stencil", &LaneCounters::lanesDeadStencil,
     "dead lanes: stencil-failed pixels of live quads"},
    {"lanes/dead_empty", &LaneCounters::lanesDeadEmpty,
     "dead lanes: empty lanes of partial waves (no quad, outside grid or item count)"},
    {"quads/launched", &LaneCounters::quadsLaunched, "quads packed into pixel waves"},
    {"quads/culled", &LaneCounters::quadsCulled,
     "rasterized quads with no pixel passing depth/stencil"},
    {"tiles/histencil_culled", &LaneCounters::tilesHiStencilCulled,
     "8x8 tiles dropped by a hi-stencil pretest"},
    {"pixels/scanned", &LaneCounters::pixelsScanned, "pixels walked by the scan converter"},
    {"lds/bytes_read", &LaneCounters::ldsBytesRead, "LDS bytes read"},
    {"lds/bytes_written", &LaneCounters::ldsBytesWritten, "LDS bytes written"},
    {"groups/barriers", &LaneCounters::barriers, "group barriers"},
    {"append/overflow", &LaneCounters::appendOverflow, "appends dropped: buffer full"},
    {"slots/overflow", &LaneCounters::slotOverflow,
     "slots refused: the reservation did not fit between the front and back fills"},
};

// Histogram names; element i of "waves/by_active_lanes" is the number of waves with i active
// lanes, and so on.
inline constexpr const char* kWavesByActiveLanes = "waves/by_active_lanes";
inline constexpr const char* kQuadsByLivePixels = "quads/by_live_pixels";
inline constexpr const char* kWavesByPrimitives = "waves/by_primitives";

template <typename Counters, typename Fn>
void ForEachLaneHistogram(Counters& c, Fn&& fn) {
  fn(kWavesByActiveLanes, c.wavesByActiveLanes);
  fn(kQuadsByLivePixels, c.quadsByLivePixels);
  fn(kWavesByPrimitives, c.wavesByPrimitives);
}

template <std::size_t N>
void AddHistogram(std::array<std::uint64_t, N>& into, const std::array<std::uint64_t, N>& from) {
  for (std::size_t i = 0; i < N; ++i) into[i] += from[i];
}

inline void LaneCounters::Merge(const LaneCounters& other) {
  for (const auto& field : kLaneCounterFields) this->*field.member += other.*field.member;
  AddHistogram(wavesByActiveLanes, other.wavesByActiveLanes);
  AddHistogram(quadsByLivePixels, other.quadsByLivePixels);
  AddHistogram(wavesByPrimitives, other.wavesByPrimitives);
}

// A counter a pass declares for its own dispatch ("smaa/search_steps"), counted by its kernels
// through a CounterView (sim/views.h) and reported next to the machine's counters.
struct PassCounter {
  std::string name;
  std::uint64_t value = 0;
  friend bool operator==(const PassCounter&, const PassCounter&) = default;
};

// How a dispatch binds a resource, one bit per mode. A resource bound in several modes is one
// binding holding their union (its lines are counted once).
enum class Access : std::uint16_t {
  None = 0,
  Read = 1 << 0,
  Write = 1 << 1,
  ReadWrite = Read | Write,
  Append = 1 << 2,          // an append buffer's items
  AppendCounter = 1 << 3,   // its hidden counter
  IndirectArgs = 1 << 4,    // group counts the command processor reads
  StencilExport = 1 << 5,   // a pixel kernel's stencil export
  StencilTest = 1 << 6,     // the DB's per-pixel stencil test
  SlotCounter = 1 << 7,     // sim/atomics.h
  SlotWrite = 1 << 8,
};

constexpr Access operator|(Access a, Access b) {
  return static_cast<Access>(static_cast<std::uint16_t>(a) | static_cast<std::uint16_t>(b));
}

// The name reports print: a single mode's own name, and "read-write" for read + write and for
// any other mix (the names reports have always used).
constexpr std::string_view AccessName(Access access) {
  switch (access) {
    case Access::None: return "none";
    case Access::Read: return "read";
    case Access::Write: return "write";
    case Access::Append: return "append";
    case Access::AppendCounter: return "append-counter";
    case Access::IndirectArgs: return "indirect-args";
    case Access::StencilExport: return "stencil";
    case Access::StencilTest: return "stencil-test";
    case Access::SlotCounter: return "slot-counter";
    case Access::SlotWrite: return "slot-write";
    default: return "read-write";
  }
}

// Traffic of one bound resource in one dispatch: what lanes asked for, and the distinct
// 64-byte lines behind it (the compulsory DRAM traffic, before any cache reuse across dispatches).
struct ResourceTraffic {
  std::string name;
  Access access = Access::None;
  std::uint64_t bytesRead = 0;
  std::uint64_t bytesWritten = 0;
  std::uint64_t fetches = 0;  // load/sample instructions per lane (a bilinear sample is one)
  std::uint64_t atomics = 0;
  // Stores and atomics outside the resource, dropped as D3D requires of UAVs (aa-facts §3: the
  // FXAA queue's padding items rely on it), and slot stores of refused reservations.
  std::uint64_t storesDroppedOob = 0;
  std::uint64_t linesRead = 0;
  std::uint64_t linesWritten = 0;

  void MergeLaneTraffic(const ResourceTraffic& other) {
    bytesRead += other.bytesRead;
    bytesWritten += other.bytesWritten;
    fetches += other.fetches;
    atomics += other.atomics;
    storesDroppedOob += other.storesDroppedOob;
  }
  std::uint64_t DramBytes() const { return (linesRead + linesWritten) * kCacheLineBytes; }
  friend bool operator==(const ResourceTraffic&, const ResourceTraffic&) = default;
};

}  // namespace sim
