// The colour block: fragment slots, FMASK codes and the arbitration rules of eqaa_surface.h.
// The step order of one pixel update is documented in docs/eqaa.md; each step below names the
// policy field that changes it.

#include "fmask/eqaa_surface.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace fmask {
namespace {

using raster::SampleMask;

constexpr int kDetached = -1;  // a sample the incoming fragment has taken from its owner

template <typename Fn>
void ForEachSample(SampleMask mask, Fn&& fn) {
  for (; mask != 0; mask &= static_cast<SampleMask>(mask - 1)) fn(std::countr_zero(mask));
}

std::string SampleList(SampleMask mask) {
  std::string list;
  ForEachSample(mask, [&](int s) { list += (list.empty() ? "s" : ", s") + std::to_string(s); });
  return list.empty() ? "none" : list;
}

}  // namespace

std::string EqaaName(const EqaaConfig& c) {
  return std::to_string(c.coverageSamples) + "S/" + std::to_string(c.depthSamples) + "Z/" +
         std::to_string(c.fragments) + "F";
}

std::vector<EqaaConfig> LegalEqaaConfigs() {
  std::vector<EqaaConfig> legal;
  for (const FmaskLayout& layout : FmaskLayout::AllLegal()) {
    for (int z = 1; z <= std::min(layout.CoverageSamples(), raster::kMaxDepthSamples); z *= 2) {
      if (z >= layout.Fragments()) legal.push_back({layout.CoverageSamples(), z, layout.Fragments()});
    }
  }
  return legal;
}

void ValidateEqaaConfig(const EqaaConfig& config) {
  if (config == kSingleSample) return;
  const std::vector<EqaaConfig> legal = LegalEqaaConfigs();
  if (std::find(legal.begin(), legal.end(), config) != legal.end()) return;
  std::string list = EqaaName(kSingleSample) + " (single sample, no FMASK)";
  for (const EqaaConfig& c : legal) list += ", " + EqaaName(c);
  throw std::invalid_argument(EqaaName(config) + " is not a supported EQAA mode (need an FMASK layout for S and F, " +
                              "and F <= Z <= min(S, 8)); legal: " + list);
}

ArbitrationPolicy PolicyByName(std::string_view name) {
  ArbitrationPolicy policy;
  policy.name = std::string(name);
  if (name == "hraa") return policy;
  if (name == "discard-first") {
    policy.order = DiscardOrder::DiscardThenEvict;
  } else if (name == "tie-keeps-higher") {
    policy.tieBreak = TieBreak::KeepHigherIndex;
  } else if (name == "count-before-incoming") {
    policy.countBasis = CountBasis::BeforeIncoming;
  } else if (name == "no-zplane-rescue") {
    policy.zPlaneRescue = false;
  } else if (name == "per-quad") {
    policy.scope = ArbitrationScope::Quad;
  } else if (name == "keep-on-reject") {
    policy.discardWhenRejected = false;
  } else {
    std::string list;
    for (const std::string& n : PolicyNames()) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown arbitration policy '" + std::string(name) + "'; known: " + list);
  }
  return policy;
}

std::vector<std::string> PolicyNames() {
  return {"hraa",     "discard-first", "tie-keeps-higher", "count-before-incoming", "no-zplane-rescue",
          "per-quad", "keep-on-reject"};
}

void FragmentCounters::Merge(const FragmentCounters& other) {
  std::vector<std::uint64_t> values;
  VisitFragmentCounters(other, [&](const char*, std::uint64_t v) { values.push_back(v); });
  std::size_t i = 0;
  VisitFragmentCounters(*this, [&](const char*, std::uint64_t& v) { v += values[i++]; });
}

EqaaSurface::EqaaSurface(int width, int height, const EqaaConfig& config, ArbitrationPolicy policy,
                         InitialState initial, Colour clearColour)
    : width_(width), height_(height), config_(config),
      layout_(ValidatedLayout(config)),
      policy_(std::move(policy)) {
  if (width < 1 || height < 1 || width > raster::kMaxDimension || height > raster::kMaxDimension) {
    throw std::invalid_argument("EQAA surface size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1.." + std::to_string(raster::kMaxDimension));
  }
  if (initial == InitialState::Unknown && !layout_.IsEqaa()) {
    throw std::invalid_argument("an all-UNKNOWN FMASK needs F < S; " + EqaaName(config) + " has no UNKNOWN code");
  }
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  fmask_.resize(pixels);
  slots_.resize(pixels * config.fragments);
  causes_.resize(pixels * config.coverageSamples);
  traced_.assign(pixels, 0);
  Initialise(initial, clearColour);
}

FmaskLayout EqaaSurface::ValidatedLayout(const EqaaConfig& config) {
  ValidateEqaaConfig(config);
  return FmaskLayout::For(config.coverageSamples, config.fragments);
}

void EqaaSurface::Reset(InitialState initial, Colour clearColour) {
  std::fill(traced_.begin(), traced_.end(), std::uint8_t{0});
  trace_.clear();
  Initialise(initial, clearColour);
}

void EqaaSurface::Initialise(InitialState initial, Colour clearColour) {
  const int samples = config_.coverageSamples, fragments = config_.fragments;
  FmaskElement element = FmaskLayout::ClearedValue();
  int usedSlots = 1;
  if (initial == InitialState::Expanded) {
    element = layout_.ExpandedValue();
    usedSlots = fragments;
  } else if (initial == InitialState::Unknown) {
    for (int s = 0; s < samples; ++s) element = layout_.WithCode(element, s, layout_.UnknownCode());
    usedSlots = 0;
  }
  std::fill(fmask_.begin(), fmask_.end(), element);
  for (std::size_t pixel = 0; pixel < fmask_.size(); ++pixel) {
    for (int k = 0; k < fragments; ++k) slots_[pixel * fragments + k] = {k < usedSlots, kClearPrimitive, clearColour};
    for (int s = 0; s < samples; ++s) {
      const bool unknown = layout_.IsEqaa() && layout_.Code(element, s) == layout_.UnknownCode();
      causes_[pixel * samples + s] = unknown ? UnknownCause::Initial : UnknownCause::None;
    }
  }
}

const FragmentSlot& EqaaSurface::Slot(int x, int y, int slot) const {
  return slots_[static_cast<std::size_t>(PixelIndex(x, y)) * config_.fragments + slot];
}

int EqaaSurface::FragmentCount(int x, int y) const {
  int count = 0;
  for (int k = 0; k < config_.fragments; ++k) count += Slot(x, y, k).occupied;
  return count;
}

UnknownCause EqaaSurface::Cause(int x, int y, int sample) const {
  return causes_[static_cast<std::size_t>(PixelIndex(x, y)) * config_.coverageSamples + sample];
}

int EqaaSurface::UnknownSamples(int x, int y) const {
  if (!layout_.IsEqaa()) return 0;
  int count = 0;
  for (int s = 0; s < config_.coverageSamples; ++s) count += layout_.Code(Fmask(x, y), s) == layout_.UnknownCode();
  return count;
}

void EqaaSurface::TracePixels(std::span<const TracedPixel> pixels) {
  for (const TracedPixel& p : pixels) {
    if (p.x < 0 || p.y < 0 || p.x >= width_ || p.y >= height_) {
      throw std::invalid_argument("traced pixel (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                                  ") is outside the " + std::to_string(width_) + "x" + std::to_string(height_) +
                                  " surface");
    }
    traced_[PixelIndex(p.x, p.y)] = 1;
  }
}

using detail::PixelClaims;
using detail::PixelRef;

int PixelRef::Count(int slot) const {
  return static_cast<int>(std::count(owner.begin(), owner.begin() + samples, slot));
}

int PixelRef::Occupied() const {
  int n = 0;
  for (int k = 0; k < fragments; ++k) n += slots[k].occupied;
  return n;
}

namespace {

PixelClaims ClaimsOf(const raster::QuadFragment& quad, int quadPixel, int depthSamples, bool rescue) {
  PixelClaims c;
  c.covered = quad.covered.Pixel(quadPixel);
  const SampleMask passed = quad.passed.Pixel(quadPixel);
  c.exact = quad.depthExact.Pixel(quadPixel);
  // Without rescue an unanchored sample's plane test is ignored: only anchors are testable.
  if (!rescue) c.exact &= raster::AllSamples(depthSamples);
  c.claimExact = passed & c.exact;
  c.untestable = c.covered & static_cast<SampleMask>(~c.exact);
  c.claim = c.claimExact | (c.untestable & passed);
  return c;
}

// Slot counts the victim choice sees (policy fields order and countBasis).
std::array<int, 8> VictimCounts(const std::array<int, raster::kMaxCoverageSamples>& before, const PixelClaims& c,
                                int samples, int fragments, const ArbitrationPolicy& policy) {
  std::array<int, 8> counts{};
  for (int s = 0; s < samples; ++s) {
    const int owner = before[s];
    if (owner < 0 || owner >= fragments) continue;
    const bool taken = (c.claimExact >> s) & 1;
    const bool discarded = policy.order == DiscardOrder::DiscardThenEvict && ((c.untestable >> s) & 1);
    if (policy.countBasis == CountBasis::BeforeIncoming || (!taken && !discarded)) ++counts[owner];
  }
  return counts;
}

int PickVictim(const std::array<int, 8>& counts, const FragmentSlot* slots, int fragments, TieBreak tie) {
  int victim = -1;
  for (int k = 0; k < fragments; ++k) {
    if (!slots[k].occupied) continue;
    const bool better = victim < 0 || counts[k] < counts[victim] ||
                        (counts[k] == counts[victim] && tie == TieBreak::KeepLowerIndex);
    if (better) victim = k;
  }
  return victim;
}

}  // namespace

int EqaaSurface::ChooseQuadVictim(const raster::QuadFragment& quad) const {
  std::array<int, 8> total{};
  std::array<FragmentSlot, 8> anyOccupied{};
  for (int p = 0; p < raster::kQuadPixels; ++p) {
    const PixelClaims c = ClaimsOf(quad, p, config_.depthSamples, policy_.zPlaneRescue);
    if (c.claim == 0) continue;
    const int x = quad.x + (p & 1), y = quad.y + (p >> 1);
    std::array<int, raster::kMaxCoverageSamples> owner{};
    for (int s = 0; s < config_.coverageSamples; ++s) owner[s] = layout_.Code(Fmask(x, y), s);
    const std::array<int, 8> counts = VictimCounts(owner, c, config_.coverageSamples, config_.fragments, policy_);
    for (int k = 0; k < config_.fragments; ++k) {
      total[k] += counts[k];
      anyOccupied[k].occupied |= Slot(x, y, k).occupied;
    }
  }
  return PickVictim(total, anyOccupied.data(), config_.fragments, policy_.tieBreak);
}

FragmentCounters EqaaSurface::UpdateAllBins(const raster::RasterResult& result, ColourSource source) {
  const std::size_t bins = result.quadsByBin.size();
  std::vector<FragmentCounters> binCounters(bins);
  std::vector<std::vector<TraceEvent>> binTraces(bins);
  tbb::parallel_for(std::size_t{0}, bins, [&](std::size_t bin) {
    for (const raster::QuadFragment& quad : result.quadsByBin[bin]) {
      std::array<Colour, 4> colours;
      for (int p = 0; p < raster::kQuadPixels; ++p) colours[p] = source.colourOf(source.context, quad, p);
      UpdateQuad(quad, colours, binCounters[bin], binTraces[bin]);
    }
  });
  FragmentCounters total;
  for (std::size_t bin = 0; bin < bins; ++bin) {
    total.Merge(binCounters[bin]);
    trace_.insert(trace_.end(), binTraces[bin].begin(), binTraces[bin].end());
  }
  return total;
}

void EqaaSurface::Update(const raster::QuadFragment& quad, const std::array<Colour, 4>& colours,
                         FragmentCounters& counters) {
  UpdateQuad(quad, colours, counters, trace_);
}

void EqaaSurface::UpdateQuad(const raster::QuadFragment& quad, const std::array<Colour, 4>& colours,
                             FragmentCounters& counters, std::vector<TraceEvent>& trace) {
  const int quadVictim = policy_.scope == ArbitrationScope::Quad ? ChooseQuadVictim(quad) : -1;
  for (int p = 0; p < raster::kQuadPixels; ++p) {
    if (quad.covered.Pixel(p) == 0) continue;
    const int pixel = PixelIndex(quad.x + (p & 1), quad.y + (p >> 1));
    if (!traced_[pixel]) {
      UpdatePixel(quad, p, colours[p], quadVictim, counters, nullptr);
      continue;
    }
    TraceEvent event;
    UpdatePixel(quad, p, colours[p], quadVictim, counters, &event);
    trace.push_back(std::move(event));
  }
}

void EqaaSurface::UpdatePixel(const raster::QuadFragment& quad, int quadPixel, const Colour& colour,
                              int quadVictim, FragmentCounters& counters, TraceEvent* event) {
  const int x = quad.x + (quadPixel & 1), y = quad.y + (quadPixel >> 1);
  const std::size_t pixel = static_cast<std::size_t>(PixelIndex(x, y));
  const int samples = config_.coverageSamples, fragments = config_.fragments, unknown = layout_.UnknownCode();
  PixelRef ref{{}, &slots_[pixel * fragments], &causes_[pixel * samples], samples, fragments};
  for (int s = 0; s < samples; ++s) ref.owner[s] = layout_.Code(fmask_[pixel], s);
  const std::array<int, raster::kMaxCoverageSamples> before = ref.owner;
  const PixelClaims c = ClaimsOf(quad, quadPixel, config_.depthSamples, policy_.zPlaneRescue);
  auto note = [&](const std::string& line) {
    if (event) event->steps.push_back(line);
  };
  if (event) {
    *event = TraceEvent{x, y, quad.primitiveId, colour, c.covered, quad.passed.Pixel(quadPixel), c.exact,
                        std::vector<FragmentSlot>(ref.slots, ref.slots + fragments), {}, fmask_[pixel], 0, -1, -1, {}, {}};
  }
  ++counters.pixelUpdates;
  ++counters.fragmentsBefore[ref.Occupied()];
  counters.zPlaneRescues += static_cast<std::uint64_t>(
      std::popcount(static_cast<SampleMask>(c.covered & c.exact & ~raster::AllSamples(config_.depthSamples))));

  // 1. Samples that passed an exact depth test leave their owner.
  ForEachSample(c.claimExact, [&](int s) { ref.owner[s] = kDetached; });
  if (event) note("depth-tested passes taken from their owners: " + SampleList(c.claimExact));

  // 2./3. Untestable covered samples lose their association (policy order decides whether
  // before or after the victim is chosen); the ones the incoming fragment keeps are claimed below.
  auto discard = [&] {
    ForEachSample(c.untestable, [&](int s) {
      if (ref.owner[s] == unknown || ref.owner[s] == kDetached) return;
      ref.owner[s] = unknown;
      if ((c.claim >> s) & 1) return;
      ref.causes[s] = UnknownCause::Untestable;
      ++counters.samplesUnknownByUntestable;
    });
    if (event && c.untestable) note("untestable samples discarded: " + SampleList(c.untestable));
  };
  if (policy_.order == DiscardOrder::DiscardThenEvict || (c.claim == 0 && policy_.discardWhenRejected)) discard();

  int slot = -1;
  if (c.claim != 0) {
    slot = AcquireSlot(ref, before, c, quadVictim, counters, event);
    if (policy_.order == DiscardOrder::EvictThenDiscard) discard();
    ref.slots[slot] = {true, quad.primitiveId, colour};
    ++counters.fragmentsAdded;
    ForEachSample(c.claim, [&](int s) {
      ref.owner[s] = slot;
      ref.causes[s] = UnknownCause::None;
    });
    if (event) note("slot " + std::to_string(slot) + " <- primitive " + std::to_string(quad.primitiveId) + ", samples " +
         SampleList(c.claim));
  } else {
    ++counters.fragmentsRejected;
    if (event) note("incoming fragment claims no sample");
  }
  FreeUnreferenced(ref, counters, event);

  FmaskElement element = 0;
  for (int s = 0; s < samples; ++s) element = layout_.WithCode(element, s, ref.owner[s]);
  fmask_[pixel] = element;
  ++counters.fragmentsAfter[ref.Occupied()];
  if (event) {
    event->slotsAfter.assign(ref.slots, ref.slots + fragments);
    event->fmaskAfter = element;
    event->slot = slot;
    event->causesAfter.assign(ref.causes, ref.causes + samples);
  }
}

// A slot for the incoming fragment: a free one (slots nobody references are freed first),
// otherwise the arbitration victim, whose remaining samples become UNKNOWN.
int EqaaSurface::AcquireSlot(PixelRef& ref, const std::array<int, raster::kMaxCoverageSamples>& before,
                             const PixelClaims& c, int quadVictim, FragmentCounters& counters, TraceEvent* event) {
  FreeUnreferenced(ref, counters, event);
  for (int k = 0; k < ref.fragments; ++k) {
    if (!ref.slots[k].occupied) return k;
  }
  const std::array<int, 8> counts = VictimCounts(before, c, ref.samples, ref.fragments, policy_);
  const int victim = quadVictim >= 0 ? quadVictim : PickVictim(counts, ref.slots, ref.fragments, policy_.tieBreak);
  SampleMask evicted = 0;
  for (int s = 0; s < ref.samples; ++s) {
    if (ref.owner[s] != victim) continue;
    ref.owner[s] = layout_.UnknownCode();
    if ((c.claim >> s) & 1) continue;
    evicted |= static_cast<SampleMask>(1u << s);
    ref.causes[s] = UnknownCause::Eviction;
    ++counters.samplesUnknownByEviction;
  }
  ++counters.evictions;
  ref.slots[victim].occupied = false;
  if (event) {
    event->victim = victim;
    event->steps.push_back("evict slot " + std::to_string(victim) + " (primitive " +
                           std::to_string(ref.slots[victim].primitiveId) + ", counted " +
                           std::to_string(counts[victim]) + " samples); UNKNOWN: " + SampleList(evicted));
  }
  return victim;
}

// The trace line is built only when tracing, as every other step's: slots are freed often (in 39 %
// of the pixel updates of 2CylinderEngine.glb at 1080p, 8S/4Z/2F: counters fragments/removed and
// pixels/updates), and building the line costs heap allocations.
void EqaaSurface::FreeUnreferenced(PixelRef& ref, FragmentCounters& counters, TraceEvent* event) {
  for (int k = 0; k < ref.fragments; ++k) {
    if (!ref.slots[k].occupied || ref.Count(k) > 0) continue;
    ref.slots[k].occupied = false;
    ++counters.fragmentsRemoved;
    if (event) event->steps.push_back("slot " + std::to_string(k) + " freed: no sample references it");
  }
}

Colour EqaaSurface::BoxResolve(int x, int y) const {
  Colour sum;
  int known = 0;
  for (int s = 0; s < config_.coverageSamples; ++s) {
    const int code = layout_.Code(Fmask(x, y), s);
    if (layout_.IsEqaa() && code == layout_.UnknownCode()) continue;
    const Colour& c = Slot(x, y, code).colour;
    sum = {sum.r + c.r, sum.g + c.g, sum.b + c.b, sum.a + c.a};
    ++known;
  }
  if (known == 0) return {};
  const float inv = 1.0f / static_cast<float>(known);
  return {sum.r * inv, sum.g * inv, sum.b * inv, sum.a * inv};
}

Colour EqaaSurface::FetchSample(int x, int y, int sample) const {
  const std::uint64_t visible = ShaderVisibleMask(layout_, Fmask(x, y));
  return Slot(x, y, FetchFragmentIndex(visible, sample)).colour;
}

void EqaaSurface::ExpandFmask() {
  if (layout_.IsEqaa()) {
    throw std::logic_error("FMASK expand needs F == S; " + EqaaName(config_) + " cannot hold a colour per sample");
  }
  const int samples = config_.coverageSamples;
  std::vector<FragmentSlot> expanded(static_cast<std::size_t>(samples));
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      for (int s = 0; s < samples; ++s) expanded[s] = Slot(x, y, layout_.Code(Fmask(x, y), s));
      const std::size_t pixel = static_cast<std::size_t>(PixelIndex(x, y));
      std::copy(expanded.begin(), expanded.end(), slots_.begin() + static_cast<std::ptrdiff_t>(pixel * samples));
      fmask_[pixel] = layout_.ExpandedValue();
    }
  }
}

}  // namespace fmask
