#pragma once
// The colour block of an EQAA surface: per pixel F colour fragment slots and an FMASK element
// that names, per coverage sample, the slot holding its colour (or UNKNOWN). Fed by the
// rasterizer's quad stream; fragment arbitration follows the HRAA talk (seed 001, 2F4S example)
// with its ambiguous steps made explicit as named policies (docs/eqaa.md).

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fmask/layout.h"
#include "raster/rasterizer.h"

namespace fmask {

// S coverage samples, Z anchored (depth) samples, F colour fragments.
struct EqaaConfig {
  int coverageSamples = 8;
  int depthSamples = 8;
  int fragments = 1;
  friend bool operator==(const EqaaConfig&, const EqaaConfig&) = default;
};

// The aliased baseline: one sample, one anchor, one fragment, no FMASK (hw-facts §1.1 defines
// FMASK from 2 samples up). Accepted by ValidateEqaaConfig and EqaaSurface, but not one of the
// LegalEqaaConfigs, which are the FMASK modes (fixtures are made for those).
inline constexpr EqaaConfig kSingleSample{1, 1, 1};

// Legal: kSingleSample, or an FMASK layout exists for (S, F) (hw-facts §1.1) and F <= Z <=
// min(S, 8) with Z a power of two (hw-facts §2.2). Throws std::invalid_argument listing every
// legal S/Z/F.
void ValidateEqaaConfig(const EqaaConfig& config);
std::vector<EqaaConfig> LegalEqaaConfigs();
std::string EqaaName(const EqaaConfig& config);  // "8S/4Z/2F"

// --- Arbitration policy: each field is one reading of the talk (docs/eqaa.md). ---

// Whether covered samples that cannot be depth-tested lose their association before or after
// the victim is chosen (the talk shows the discard first but its final state needs it after).
enum class DiscardOrder : std::uint8_t { EvictThenDiscard, DiscardThenEvict };
// "If a tie occurs, lower index has higher priority" (seed 001): keep the lower index.
enum class TieBreak : std::uint8_t { KeepLowerIndex, KeepHigherIndex };
// Sample counts for the victim choice: after the incoming fragment took its depth-tested
// samples away from their owners, or as they were before it arrived.
enum class CountBasis : std::uint8_t { AfterIncoming, BeforeIncoming };
// One victim per pixel, or one slot index per quad chosen from the quad's summed counts.
enum class ArbitrationScope : std::uint8_t { Pixel, Quad };

struct ArbitrationPolicy {
  std::string name = "hraa";
  DiscardOrder order = DiscardOrder::EvictThenDiscard;
  TieBreak tieBreak = TieBreak::KeepLowerIndex;
  CountBasis countBasis = CountBasis::AfterIncoming;
  bool zPlaneRescue = true;  // unanchored samples use the exact Z-plane test when available
  // A fragment that claims no sample (hidden everywhere) still discards the untestable samples
  // it covers: the talk's rule read literally. Off: only accepted fragments discard.
  bool discardWhenRejected = true;
  ArbitrationScope scope = ArbitrationScope::Pixel;
};

// "hraa" (default), "discard-first", "tie-keeps-higher", "count-before-incoming",
// "no-zplane-rescue", "per-quad", "keep-on-reject". Throws std::invalid_argument listing them.
ArbitrationPolicy PolicyByName(std::string_view name);
std::vector<std::string> PolicyNames();

// --- Surface state ---

struct Colour {
  float r = 0.0f, g = 0.0f, b = 0.0f, a = 0.0f;
  friend bool operator==(const Colour&, const Colour&) = default;
};

// What the FMASK holds before the first draw (hw-facts §1.3, §1.5; seed 001).
enum class InitialState : std::uint8_t {
  Cleared,   // fast clear: every sample -> fragment 0, slot 0 holds the clear colour
  Expanded,  // sample i -> min(i, F); slots 0..F-1 hold the clear colour
  Unknown,   // every sample UNKNOWN, no slot used (the talk's 2F4S starting point)
};

// Why a sample is UNKNOWN (the last event that made it so).
enum class UnknownCause : std::uint8_t { None, Initial, Eviction, Untestable };

inline constexpr std::uint32_t kClearPrimitive = 0xFFFFFFFFu;

struct FragmentSlot {
  bool occupied = false;
  std::uint32_t primitiveId = kClearPrimitive;
  Colour colour;  // kept when the slot is freed: memory is not cleared
  friend bool operator==(const FragmentSlot&, const FragmentSlot&) = default;
};

// Counters modelled on the CB's per-quad fragment counters (hw-facts §3), counted per pixel
// update; table below is the only list of names.
struct FragmentCounters {
  std::uint64_t pixelUpdates = 0;
  std::array<std::uint64_t, 9> fragmentsBefore{};  // pixels holding k fragments before update
  std::array<std::uint64_t, 9> fragmentsAfter{};
  std::uint64_t fragmentsAdded = 0;
  std::uint64_t fragmentsRemoved = 0;  // freed because no sample referenced them any more
  std::uint64_t evictions = 0;
  std::uint64_t samplesUnknownByEviction = 0;
  std::uint64_t samplesUnknownByUntestable = 0;
  std::uint64_t zPlaneRescues = 0;  // unanchored covered samples decided by an exact Z-plane test
  std::uint64_t fragmentsRejected = 0;  // pixel updates where the incoming fragment claimed nothing

  void Merge(const FragmentCounters& other);
  // Visits every counter as ("category/name", value), in a fixed order.
  template <typename Fn>
  void ForEach(Fn&& fn) const;
  friend bool operator==(const FragmentCounters&, const FragmentCounters&) = default;
};

// One pixel update, recorded for traced pixels.
struct TraceEvent {
  int x = 0, y = 0;
  std::uint32_t primitiveId = 0;
  Colour colour;
  raster::SampleMask covered = 0, passed = 0, exact = 0;
  std::vector<FragmentSlot> slotsBefore, slotsAfter;
  FmaskElement fmaskBefore = 0, fmaskAfter = 0;
  int victim = -1;  // evicted slot, -1 if none
  int slot = -1;    // slot the incoming fragment got, -1 if it claimed nothing
  std::vector<UnknownCause> causesAfter;  // per sample
  std::vector<std::string> steps;         // what happened, in order, one line each
};

struct TracedPixel {
  int x = 0, y = 0;
  friend bool operator==(const TracedPixel&, const TracedPixel&) = default;
};

namespace detail {
// Which samples an incoming fragment claims at one pixel, and which it makes untestable.
struct PixelClaims {
  raster::SampleMask covered = 0, exact = 0, claimExact = 0, untestable = 0, claim = 0;
};
// One pixel while an incoming fragment is applied: the owner slot of every sample (UNKNOWN = F,
// -1 = taken by the incoming fragment) and the pixel's slots and causes.
struct PixelRef {
  std::array<int, raster::kMaxCoverageSamples> owner{};
  FragmentSlot* slots = nullptr;
  UnknownCause* causes = nullptr;
  int samples = 0, fragments = 0;
  int Count(int slot) const;
  int Occupied() const;
};
}  // namespace detail

class EqaaSurface {
 public:
  EqaaSurface(int width, int height, const EqaaConfig& config, ArbitrationPolicy policy,
              InitialState initial = InitialState::Cleared, Colour clearColour = {});

  int Width() const { return width_; }
  int Height() const { return height_; }
  const EqaaConfig& Config() const { return config_; }
  const FmaskLayout& Layout() const { return layout_; }
  const ArbitrationPolicy& Policy() const { return policy_; }

  FmaskElement Fmask(int x, int y) const { return fmask_[PixelIndex(x, y)]; }
  const FragmentSlot& Slot(int x, int y, int slot) const;
  int FragmentCount(int x, int y) const;  // occupied slots
  UnknownCause Cause(int x, int y, int sample) const;
  int UnknownSamples(int x, int y) const;

  // Back to the state the constructor left, without reallocating (a frame loop clears every
  // frame); the trace and traced pixels are dropped.
  void Reset(InitialState initial, Colour clearColour);

  // Traced pixels record every update into Trace(); set before Update.
  void TracePixels(std::span<const TracedPixel> pixels);
  const std::vector<TraceEvent>& Trace() const { return trace_; }

  // Applies one quad: colours[p] is the shaded colour of quad pixel p. Quads must arrive in
  // rasterization order per pixel. Trace events of traced pixels go to Trace().
  void Update(const raster::QuadFragment& quad, const std::array<Colour, 4>& colours,
              FragmentCounters& counters);
  // Every quad of a raster result, bins in parallel (each bin owns its pixels); colourOf
  // gives the colour of a quad pixel. Counters are merged in bin order.
  template <typename ColourFn>
  FragmentCounters UpdateAll(const raster::RasterResult& result, ColourFn&& colourOf);

  // hw-facts §1.6: the fixed-function CB resolve averages the known samples, dropping UNKNOWN
  // ones; a pixel with no known sample resolves to transparent black.
  Colour BoxResolve(int x, int y) const;
  // hw-facts §1.4: the shader fetch path; UNKNOWN reads fragment 0 (Mesa's 3-bit index).
  Colour FetchSample(int x, int y, int sample) const;

  // hw-facts §1.6 FMASK expand: every sample's colour is copied into its own slot and FMASK is
  // reset to the identity, so FMASK-unaware image stores see per-sample colour. Only defined
  // for F == S (RADV and radeonsi do not expand EQAA surfaces); throws std::logic_error
  // otherwise. FMASK_DECOMPRESS has no counterpart: aasim does not model CMASK compression,
  // so its FMASK is always in decompressed form.
  void ExpandFmask();

 private:
  // UpdateAll's colour callback, type-erased so the parallel loop (oneTBB) lives in
  // eqaa_surface.cpp rather than in a header every pass includes.
  struct ColourSource {
    const void* context;
    Colour (*colourOf)(const void* context, const raster::QuadFragment& quad, int pixel);
  };
  FragmentCounters UpdateAllBins(const raster::RasterResult& result, ColourSource source);
  int PixelIndex(int x, int y) const { return y * width_ + x; }
  static FmaskLayout ValidatedLayout(const EqaaConfig& config);
  void UpdateQuad(const raster::QuadFragment& quad, const std::array<Colour, 4>& colours,
                  FragmentCounters& counters, std::vector<TraceEvent>& trace);
  void UpdatePixel(const raster::QuadFragment& quad, int quadPixel, const Colour& colour,
                   int quadVictim, FragmentCounters& counters, TraceEvent* event);
  int ChooseQuadVictim(const raster::QuadFragment& quad) const;
  int AcquireSlot(detail::PixelRef& ref, const std::array<int, raster::kMaxCoverageSamples>& before,
                  const detail::PixelClaims& claims, int quadVictim, FragmentCounters& counters,
                  TraceEvent* event);
  void FreeUnreferenced(detail::PixelRef& ref, FragmentCounters& counters, TraceEvent* event);
  void Initialise(InitialState initial, Colour clearColour);

  int width_, height_;
  EqaaConfig config_;
  FmaskLayout layout_;
  ArbitrationPolicy policy_;
  std::vector<FmaskElement> fmask_;        // [pixel]
  std::vector<FragmentSlot> slots_;        // [pixel * F + slot]
  std::vector<UnknownCause> causes_;       // [pixel * S + sample]
  std::vector<std::uint8_t> traced_;       // [pixel], 1 when traced
  std::vector<TraceEvent> trace_;
};

}  // namespace fmask

#include "fmask/eqaa_surface_inl.h"
