// FMASK layout: the hw-facts §1.1 table, exhaustive code round trips, the §1.3 expanded values
// and the shader-visible fetch rule of §1.4.

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <stdexcept>

#include "fmask/layout.h"

namespace fmask {
namespace {

TEST(FmaskLayout, TableMatchesHwFacts) {
  // (S, F) -> {bits per sample, element bits}, typed from hw-facts §1.1.
  const std::map<std::pair<int, int>, std::pair<int, int>> expected = {
      {{2, 1}, {1, 8}},   {{2, 2}, {1, 8}},   {{4, 1}, {1, 8}},   {{4, 2}, {2, 8}},  {{4, 4}, {2, 8}},
      {{8, 1}, {1, 8}},   {{8, 2}, {2, 16}},  {{8, 4}, {4, 32}},  {{8, 8}, {4, 32}}, {{16, 1}, {1, 16}},
      {{16, 2}, {2, 32}}, {{16, 4}, {4, 64}}, {{16, 8}, {4, 64}},
  };
  EXPECT_EQ(FmaskLayout::AllLegal().size(), expected.size());
  for (const auto& [key, value] : expected) {
    const FmaskLayout layout = FmaskLayout::For(key.first, key.second);
    EXPECT_EQ(layout.BitsPerSample(), value.first) << layout.FormatName();
    EXPECT_EQ(layout.ElementBits(), value.second) << layout.FormatName();
    EXPECT_GE(layout.ElementBits(), layout.BitsPerSample() * layout.CoverageSamples());
  }
  EXPECT_EQ(FmaskLayout::For(8, 4).FormatName(), "FMASK32_S8_F4");
}

TEST(FmaskLayout, IllegalCombinationsListTheLegalOnes) {
  for (auto [s, f] : {std::pair{1, 2}, {2, 4}, {4, 8}, {8, 16}, {3, 1}, {16, 16}}) {
    try {
      FmaskLayout::For(s, f);
      ADD_FAILURE() << s << "S" << f << "F accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("legal: 2S1F, 2S2F, 4S1F"), std::string::npos) << e.what();
    }
  }
}

// A single-sample surface has one fragment and no codes to store.
TEST(FmaskLayout, SingleSampleStoresNothing) {
  const FmaskLayout layout = FmaskLayout::For(1, 1);
  EXPECT_EQ(layout.ElementBits(), 0);
  EXPECT_EQ(layout.BitsPerSample(), 0);
  EXPECT_FALSE(layout.IsEqaa());
  EXPECT_EQ(layout.FormatName(), "none");
  EXPECT_EQ(layout.Code(layout.WithCode(0, 0, 1), 0), 0);
  EXPECT_EQ(ShaderVisibleMask(layout, layout.ExpandedValue()), 0u);
  for (const FmaskLayout& legal : FmaskLayout::AllLegal()) EXPECT_GE(legal.CoverageSamples(), 2);
}

// Every code of every sample for every layout: written then read back, neighbours untouched.
TEST(FmaskLayout, EveryCodeOfEverySampleRoundTrips) {
  std::mt19937_64 rng(3);
  for (const FmaskLayout& layout : FmaskLayout::AllLegal()) {
    const FmaskElement used = layout.ElementBits() == 64 ? ~FmaskElement{0}
                                                         : (FmaskElement{1} << (layout.BitsPerSample() * layout.CoverageSamples())) - 1;
    for (int trial = 0; trial < 64; ++trial) {
      const FmaskElement base = rng() & used;
      for (int s = 0; s < layout.CoverageSamples(); ++s) {
        for (int code = 0; code < (1 << layout.BitsPerSample()); ++code) {
          const FmaskElement e = layout.WithCode(base, s, code);
          ASSERT_EQ(layout.Code(e, s), code) << layout.FormatName();
          for (int other = 0; other < layout.CoverageSamples(); ++other) {
            if (other == s) continue;
            ASSERT_EQ(layout.Code(e, other), layout.Code(base, other)) << layout.FormatName();
          }
        }
      }
    }
  }
}

// Layouts up to 16 bits: every element value decodes to codes that re-encode to it.
TEST(FmaskLayout, EveryElementOfSmallLayoutsRoundTrips) {
  for (const FmaskLayout& layout : FmaskLayout::AllLegal()) {
    const int bits = layout.BitsPerSample() * layout.CoverageSamples();
    if (bits > 16) continue;
    for (FmaskElement e = 0; e < (FmaskElement{1} << bits); ++e) {
      FmaskElement rebuilt = 0;
      for (int s = 0; s < layout.CoverageSamples(); ++s) rebuilt = layout.WithCode(rebuilt, s, layout.Code(e, s));
      ASSERT_EQ(rebuilt, e) << layout.FormatName();
    }
  }
}

TEST(FmaskLayout, ExpandedAndClearedStatesMatchHwFacts) {
  // hw-facts §1.3 table, one pixel's element.
  const std::map<std::pair<int, int>, FmaskElement> expanded = {
      {{2, 1}, 0x02},       {{4, 1}, 0x0E},       {{8, 1}, 0xFE},
      {{16, 1}, 0xFFFE},    {{2, 2}, 0x02},       {{4, 2}, 0xA4},
      {{8, 2}, 0xAAA4},     {{16, 2}, 0xAAAAAAA4}, {{4, 4}, 0xE4},
      {{8, 4}, 0x44443210}, {{16, 4}, 0x4444444444443210}, {{8, 8}, 0x76543210},
      {{16, 8}, 0x8888888876543210},
  };
  for (const auto& [key, value] : expanded) {
    const FmaskLayout layout = FmaskLayout::For(key.first, key.second);
    EXPECT_EQ(layout.ExpandedValue(), value) << layout.FormatName();
    EXPECT_EQ(layout.Code(FmaskLayout::ClearedValue(), layout.CoverageSamples() - 1), 0);
  }
}

TEST(FmaskLayout, ShaderVisibleFetchReportsUnknownAsEightAndReadsFragmentZero) {
  const FmaskLayout msaa = FmaskLayout::For(8, 8);
  EXPECT_EQ(ShaderVisibleMask(msaa, msaa.ExpandedValue()), 0x76543210u);  // hw-facts §1.2 identity
  for (const FmaskLayout& layout : FmaskLayout::AllLegal()) {
    const std::uint64_t visible = ShaderVisibleMask(layout, layout.ExpandedValue());
    for (int s = 0; s < layout.CoverageSamples(); ++s) {
      const bool unknown = layout.IsEqaa() && s >= layout.Fragments();
      EXPECT_EQ((visible >> (4 * s)) & 0xF, unknown ? 8u : static_cast<unsigned>(s)) << layout.FormatName();
      EXPECT_EQ(FetchFragmentIndex(visible, s), unknown ? 0 : s) << layout.FormatName();
    }
  }
}

}  // namespace
}  // namespace fmask
