// The colour block: the seed 001 2F4S worked example step by step, where each alternative
// arbitration policy departs from it, and invariants on random triangle soups.

#include <gtest/gtest.h>

#include <algorithm>

#include <bit>
#include <stdexcept>

#include <tbb/global_control.h>

#include "fmask/eqaa_surface.h"
#include "raster/sample_pattern.h"
#include "raster_test_util.h"

namespace fmask {
namespace {

constexpr Colour kBlue{0, 0, 1, 1}, kRed{1, 0, 0, 1}, kGreen{0, 1, 0, 1}, kWhite{1, 1, 1, 1};
constexpr std::uint32_t kBlueId = 1, kRedId = 2, kGreenId = 3, kRed2Id = 4;

// A quad at the origin whose pixel 0 has the given sample masks (bit s = sample s).
raster::QuadFragment PixelFragment(std::uint32_t primitive, raster::SampleMask covered, raster::SampleMask passed,
                                   raster::SampleMask exact) {
  raster::QuadFragment q;
  q.primitiveId = primitive;
  q.covered.SetPixel(0, covered);
  q.passed.SetPixel(0, passed);
  q.depthExact.SetPixel(0, exact);
  return q;
}

void Apply(EqaaSurface& surface, const raster::QuadFragment& quad, Colour colour) {
  FragmentCounters counters;
  surface.Update(quad, {colour, colour, colour, colour}, counters);
}

std::vector<int> Codes(const EqaaSurface& surface) {
  std::vector<int> codes;
  for (int s = 0; s < surface.Config().coverageSamples; ++s) codes.push_back(surface.Layout().Code(surface.Fmask(0, 0), s));
  return codes;
}

// Slot primitive ids, 0 for an empty slot.
std::vector<std::uint32_t> Slots(const EqaaSurface& surface) {
  std::vector<std::uint32_t> ids;
  for (int k = 0; k < surface.Config().fragments; ++k) {
    ids.push_back(surface.Slot(0, 0, k).occupied ? surface.Slot(0, 0, k).primitiveId : 0);
  }
  return ids;
}

constexpr int U = 2;  // UNKNOWN code of a 2-fragment surface

// Seed 001, "Example : Color/Depth : 2F 4S": samples 0 and 1 anchored, the FMASK starts all
// UNKNOWN. BLUE covers s0, s2, s3; RED covers s1; GREEN covers s1, s3; then a second RED
// covers s0 and s3 while the depth tile is no longer compressed, so s3 (unanchored) cannot be
// depth-tested.
EqaaSurface RunTalkExampleUpToGreen(const ArbitrationPolicy& policy) {
  EqaaSurface surface(2, 2, {4, 2, 2}, policy, InitialState::Unknown);
  EXPECT_EQ(Codes(surface), (std::vector<int>{U, U, U, U}));
  Apply(surface, PixelFragment(kBlueId, 0b1101, 0b1101, 0b1111), kBlue);
  EXPECT_EQ(Slots(surface), (std::vector<std::uint32_t>{kBlueId, 0}));
  EXPECT_EQ(Codes(surface), (std::vector<int>{0, U, 0, 0}));
  Apply(surface, PixelFragment(kRedId, 0b0010, 0b0010, 0b0011), kRed);
  EXPECT_EQ(Slots(surface), (std::vector<std::uint32_t>{kBlueId, kRedId}));
  EXPECT_EQ(Codes(surface), (std::vector<int>{0, 1, 0, 0}));
  // RED keeps no sample once GREEN takes s1, so its slot is freed for GREEN ("evict RED").
  Apply(surface, PixelFragment(kGreenId, 0b1010, 0b1010, 0b0011), kGreen);
  EXPECT_EQ(Slots(surface), (std::vector<std::uint32_t>{kBlueId, kGreenId}));
  EXPECT_EQ(Codes(surface), (std::vector<int>{0, 1, 0, 1}));
  return surface;
}

TEST(EqaaTalkExample, DefaultPolicyReproducesTheFinalState) {
  EqaaSurface surface = RunTalkExampleUpToGreen(PolicyByName("hraa"));
  surface.TracePixels(std::vector<TracedPixel>{{0, 0}});
  Apply(surface, PixelFragment(kRed2Id, 0b1001, 0b1001, 0b0011), kRed);
  // Fragment 0 = RED, fragment 1 = GREEN; FMASK s0 = 0, s1 = 1, s2 = UNKNOWN, s3 = 0.
  EXPECT_EQ(Slots(surface), (std::vector<std::uint32_t>{kRed2Id, kGreenId}));
  EXPECT_EQ(surface.Slot(0, 0, 0).colour, kRed);
  EXPECT_EQ(surface.Slot(0, 0, 1).colour, kGreen);
  EXPECT_EQ(Codes(surface), (std::vector<int>{0, 1, U, 0}));
  EXPECT_EQ(surface.Cause(0, 0, 2), UnknownCause::Eviction);
  ASSERT_EQ(surface.Trace().size(), 1u);
  const TraceEvent& event = surface.Trace()[0];
  EXPECT_EQ(event.victim, 0);  // BLUE: 1 sample left (s2) against GREEN's 2 (s1, s3)
  EXPECT_EQ(event.slot, 0);
  EXPECT_EQ(event.fmaskBefore, 0b01000100u);  // codes 0,1,0,1 at 2 bits
  EXPECT_EQ(event.fmaskAfter, 0b00100100u);   // codes 0,1,2,0
  // Box resolve drops s2; the fetch path reads fragment 0 (RED) for it.
  const Colour resolved = surface.BoxResolve(0, 0);
  EXPECT_FLOAT_EQ(resolved.r, 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(resolved.g, 1.0f / 3.0f);
  EXPECT_EQ(surface.FetchSample(0, 0, 2), kRed);
}

// The slides show s3's discard before BLUE's eviction; read literally, the tie BLUE{s2} vs
// GREEN{s1} keeps BLUE and evicts GREEN, which contradicts the talk's final picture.
TEST(EqaaTalkExample, DiscardFirstEvictsGreenInstead) {
  EqaaSurface surface = RunTalkExampleUpToGreen(PolicyByName("discard-first"));
  Apply(surface, PixelFragment(kRed2Id, 0b1001, 0b1001, 0b0011), kRed);
  EXPECT_EQ(Slots(surface), (std::vector<std::uint32_t>{kBlueId, kRed2Id}));
  EXPECT_EQ(Codes(surface), (std::vector<int>{1, U, 0, 1}));
  EXPECT_EQ(surface.Cause(0, 0, 1), UnknownCause::Eviction);
}

// Counting before the incoming fragment takes s0 gives BLUE{s0,s2} = GREEN{s1,s3}: the tie keeps
// BLUE (lower index) and GREEN is evicted.
TEST(EqaaTalkExample, CountBeforeIncomingEvictsGreenInstead) {
  EqaaSurface surface = RunTalkExampleUpToGreen(PolicyByName("count-before-incoming"));
  Apply(surface, PixelFragment(kRed2Id, 0b1001, 0b1001, 0b0011), kRed);
  EXPECT_EQ(Slots(surface), (std::vector<std::uint32_t>{kBlueId, kRed2Id}));
  EXPECT_EQ(Codes(surface), (std::vector<int>{1, U, 0, 1}));
}

// No tie in the talk's last step, so the tie rule shows on a tie: a fragment taking s0 and s1
// leaves BLUE{s2} and GREEN{s3}.
TEST(EqaaTalkExample, TieBreakDecidesBetweenEqualCounts) {
  for (const char* name : {"hraa", "tie-keeps-higher"}) {
    EqaaSurface surface = RunTalkExampleUpToGreen(PolicyByName(name));
    Apply(surface, PixelFragment(kRed2Id, 0b0011, 0b0011, 0b0011), kWhite);
    if (std::string(name) == "hraa") {
      EXPECT_EQ(Slots(surface), (std::vector<std::uint32_t>{kBlueId, kRed2Id}));  // GREEN evicted
      EXPECT_EQ(Codes(surface), (std::vector<int>{1, 1, 0, U}));
    } else {
      EXPECT_EQ(Slots(surface), (std::vector<std::uint32_t>{kRed2Id, kGreenId}));  // BLUE evicted
      EXPECT_EQ(Codes(surface), (std::vector<int>{0, 0, U, 1}));
    }
  }
}

// With the tile still compressed, s3's Z-plane test says RED is behind GREEN there: rescue
// keeps GREEN's association; without rescue s3 is untestable and discarded.
TEST(EqaaTalkExample, ZPlaneRescueKeepsTheAssociation) {
  for (const char* name : {"hraa", "no-zplane-rescue"}) {
    EqaaSurface surface = RunTalkExampleUpToGreen(PolicyByName(name));
    FragmentCounters counters;
    surface.Update(PixelFragment(kRed2Id, 0b1001, 0b0001, 0b1111), {kRed, kRed, kRed, kRed}, counters);
    const bool rescue = std::string(name) == "hraa";
    EXPECT_EQ(Codes(surface), (std::vector<int>{0, 1, U, rescue ? 1 : U})) << name;
    EXPECT_EQ(counters.zPlaneRescues, rescue ? 1u : 0u);
    EXPECT_EQ(counters.samplesUnknownByUntestable, rescue ? 0u : 1u);
    if (!rescue) {
      EXPECT_EQ(surface.Cause(0, 0, 3), UnknownCause::Untestable);
    }
  }
}

// A fragment hidden at its anchor and at the nearest-anchor guess for s3 claims nothing; read
// literally the talk still drops s3's association, keep-on-reject leaves it alone.
TEST(EqaaTalkExample, RejectedFragmentDiscardsOnlyUnderTheLiteralReading) {
  for (const char* name : {"hraa", "keep-on-reject"}) {
    EqaaSurface surface = RunTalkExampleUpToGreen(PolicyByName(name));
    FragmentCounters counters;
    surface.Update(PixelFragment(kRed2Id, 0b1001, 0b0000, 0b0011), {kRed, kRed, kRed, kRed}, counters);
    const bool literal = std::string(name) == "hraa";
    EXPECT_EQ(Codes(surface), (std::vector<int>{0, 1, 0, literal ? U : 1})) << name;
    EXPECT_EQ(counters.fragmentsRejected, 1u);
    EXPECT_EQ(counters.samplesUnknownByUntestable, literal ? 1u : 0u);
  }
}

// Per-quad arbitration picks one slot index from the quad's summed counts: pixel 0 (A: 3
// samples, B: 2) and pixel 1 (A: 1, B: 4) then disagree with their own per-pixel choice.
TEST(EqaaPolicies, PerQuadSharesOneVictimAcrossTheQuad) {
  for (const char* name : {"hraa", "per-quad"}) {
    EqaaSurface surface(2, 2, {8, 8, 2}, PolicyByName(name), InitialState::Unknown);
    auto quad = [](std::uint32_t id, raster::SampleMask p0, raster::SampleMask p1) {
      raster::QuadFragment q;
      q.primitiveId = id;
      q.covered.SetPixel(0, p0);
      q.covered.SetPixel(1, p1);
      q.passed = q.depthExact = q.covered;
      return q;
    };
    Apply(surface, quad(10, 0b00111, 0b00001), kBlue);
    Apply(surface, quad(11, 0b11000, 0b11110), kRed);
    Apply(surface, quad(12, 0x80, 0x80), kGreen);
    const bool perQuad = std::string(name) == "per-quad";
    // Pixel 0 evicts B per pixel (2 < 3); per quad A (4 < 6) goes in both pixels.
    EXPECT_EQ(surface.Slot(0, 0, 0).primitiveId, perQuad ? 12u : 10u) << name;
    EXPECT_EQ(surface.Slot(1, 0, 0).primitiveId, 12u) << name;
  }
}

// FMASK expand (hw-facts §1.6) keeps every sample's colour and leaves the identity mapping.
TEST(EqaaSurfaceOps, ExpandKeepsPerSampleColours) {
  EqaaSurface surface(2, 2, {4, 4, 4}, PolicyByName("hraa"));
  Apply(surface, PixelFragment(kBlueId, 0b0110, 0b0110, 0b1111), kBlue);
  Apply(surface, PixelFragment(kRedId, 0b0100, 0b0100, 0b1111), kRed);
  std::vector<Colour> before;
  for (int s = 0; s < 4; ++s) before.push_back(surface.FetchSample(0, 0, s));
  surface.ExpandFmask();
  EXPECT_EQ(surface.Fmask(0, 0), surface.Layout().ExpandedValue());
  for (int s = 0; s < 4; ++s) EXPECT_EQ(surface.FetchSample(0, 0, s), before[s]) << s;
  EqaaSurface eqaa(2, 2, {4, 4, 2}, PolicyByName("hraa"));
  EXPECT_THROW(eqaa.ExpandFmask(), std::logic_error);
}

TEST(EqaaConfig, LegalModesAndClearErrors) {
  EXPECT_NO_THROW(ValidateEqaaConfig({8, 8, 1}));
  EXPECT_NO_THROW(ValidateEqaaConfig({8, 4, 2}));
  EXPECT_NO_THROW(ValidateEqaaConfig({16, 8, 4}));
  EXPECT_NO_THROW(ValidateEqaaConfig(kSingleSample));
  // The FMASK modes, for which fixtures are made, do not include the single-sample surface.
  const std::vector<EqaaConfig> legal = LegalEqaaConfigs();
  EXPECT_EQ(std::count(legal.begin(), legal.end(), kSingleSample), 0);
  for (EqaaConfig bad : {EqaaConfig{8, 8, 3}, EqaaConfig{4, 8, 4}, EqaaConfig{8, 1, 2}, EqaaConfig{16, 16, 8},
                         EqaaConfig{4, 4, 8}}) {
    try {
      ValidateEqaaConfig(bad);
      ADD_FAILURE() << EqaaName(bad) << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("legal: 1S/1Z/1F (single sample, no FMASK), 2S/1Z/1F"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(PolicyByName("nosuch"), std::invalid_argument);
  EXPECT_THROW(EqaaSurface(4, 4, {4, 4, 4}, PolicyByName("hraa"), InitialState::Unknown), std::invalid_argument);
}

// Random soups through the real rasterizer: no sample points at an empty slot, every UNKNOWN
// has a cause, at most F fragments, and every known sample belongs to the primitive that last
// passed its depth test.
TEST(EqaaInvariants, RandomSoups) {
  constexpr int kWidth = 40, kHeight = 32;
  for (const EqaaConfig& config : {EqaaConfig{8, 8, 1}, EqaaConfig{8, 4, 2}, EqaaConfig{16, 8, 4}, EqaaConfig{4, 2, 2},
                                   EqaaConfig{8, 2, 2}, EqaaConfig{16, 8, 8}, EqaaConfig{16, 2, 1}, kSingleSample}) {
    for (const std::string& policyName : PolicyNames()) {
      raster::testing::Random rng(static_cast<std::uint64_t>(config.coverageSamples * 100 + config.fragments));
      const raster::testing::Mesh mesh = raster::testing::RandomSoup(rng, 120, kWidth, kHeight, 9.0);
      raster::DepthSurfaceConfig depthConfig{kWidth, kHeight, config.coverageSamples, config.depthSamples};
      depthConfig.maxZPlanes = 2;
      raster::DepthStencilSurface depth(depthConfig, raster::MakeBuiltinPattern("eqaa", config.coverageSamples));
      raster::DrawState state;
      state.cull = raster::CullMode::None;
      const raster::RasterResult result = raster::Rasterize(mesh.Input(), state, depth);
      EqaaSurface surface(kWidth, kHeight, config, PolicyByName(policyName));
      const FragmentCounters counters = surface.UpdateAll(result, [](const raster::QuadFragment& q, int) {
        return Colour{static_cast<float>(q.primitiveId), 0, 0, 1};
      });
      EXPECT_GT(counters.pixelUpdates, 0u);
      // Replay: the last primitive whose quad passed each sample.
      std::vector<std::uint32_t> lastPass(static_cast<std::size_t>(kWidth) * kHeight * config.coverageSamples, kClearPrimitive);
      for (const auto& bin : result.quadsByBin) {
        for (const raster::QuadFragment& q : bin) {
          for (int p = 0; p < 4; ++p) {
            for (int s = 0; s < config.coverageSamples; ++s) {
              if (q.passed.Sample(p, s)) lastPass[((q.y + (p >> 1)) * kWidth + q.x + (p & 1)) * config.coverageSamples + s] = q.primitiveId;
            }
          }
        }
      }
      const FmaskLayout& layout = surface.Layout();
      for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
          ASSERT_LE(surface.FragmentCount(x, y), config.fragments);
          int known = 0;
          for (int s = 0; s < config.coverageSamples; ++s) {
            const int code = layout.Code(surface.Fmask(x, y), s);
            if (layout.IsEqaa() && code == layout.UnknownCode()) {
              ASSERT_NE(surface.Cause(x, y, s), UnknownCause::None) << EqaaName(config) << " " << policyName;
              continue;
            }
            ++known;
            ASSERT_TRUE(surface.Slot(x, y, code).occupied) << EqaaName(config) << " " << policyName;
            ASSERT_EQ(surface.Slot(x, y, code).primitiveId, lastPass[(y * kWidth + x) * config.coverageSamples + s])
                << EqaaName(config) << " " << policyName << " pixel " << x << "," << y << " sample " << s;
          }
          if (config.fragments == 1) {
            // CRAA (seed 001): the stored fragment's coverage is (S - popcount(FMASK)) / S.
            ASSERT_EQ(known, config.coverageSamples - std::popcount(surface.Fmask(x, y)));
          }
        }
      }
    }
  }
}

// Bins are applied in parallel; FMASK, slots, counters and traces must not depend on it.
TEST(EqaaDeterminism, IdenticalForAnyThreadCount) {
  constexpr int kWidth = 96, kHeight = 64;
  raster::testing::Random rng(9);
  const raster::testing::Mesh mesh = raster::testing::RandomSoup(rng, 800, kWidth, kHeight, 12.0);
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    raster::DepthStencilSurface depth({kWidth, kHeight, 8, 4}, raster::MakeBuiltinPattern("eqaa", 8));
    raster::DrawState state;
    state.cull = raster::CullMode::None;
    const raster::RasterResult result = raster::Rasterize(mesh.Input(), state, depth);
    EqaaSurface surface(kWidth, kHeight, {8, 4, 2}, PolicyByName("hraa"));
    surface.TracePixels(std::vector<TracedPixel>{{10, 10}, {50, 40}});
    const FragmentCounters counters = surface.UpdateAll(result, [](const raster::QuadFragment& q, int) {
      return Colour{static_cast<float>(q.primitiveId % 7), 0, 0, 1};
    });
    std::vector<FmaskElement> fmask;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) fmask.push_back(surface.Fmask(x, y));
    }
    return std::tuple{counters, fmask, surface.Trace().size()};
  };
  EXPECT_EQ(run(1), run(2));
}

}  // namespace
}  // namespace fmask
