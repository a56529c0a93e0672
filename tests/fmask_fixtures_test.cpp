// FMASK fixtures (fmask/fixtures.h): derivation is deterministic, and the files decode with the
// documented layout alone (docs/fixtures.md) to the expected per-sample colours and resolve.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include "fmask/fixtures.h"

namespace {

using Bytes = std::vector<std::uint8_t>;

// What docs/fixtures.md says a reader needs, copied out of the fixture (the manifest fields).
struct Layout {
  int samples, fragments, bitsPerSample, elementBytes;
  bool hasUnknown;
  int unknownCode;
};

Layout LayoutOf(const fmask::FixtureData& data) {
  const fmask::FmaskLayout& l = data.layout;
  return {l.CoverageSamples(), l.Fragments(), l.BitsPerSample(),
          l.ElementBits() / 8, l.IsEqaa(),    l.UnknownCode()};
}

std::uint64_t Element(const Bytes& fmask, const Layout& layout, int pixel) {
  std::uint64_t element = 0;
  for (int i = 0; i < layout.elementBytes; ++i) {
    element |= std::uint64_t{fmask[pixel * layout.elementBytes + i]} << (8 * i);
  }
  return element;
}

int Code(std::uint64_t element, const Layout& layout, int sample) {
  return static_cast<int>((element >> (sample * layout.bitsPerSample)) &
                          ((std::uint64_t{1} << layout.bitsPerSample) - 1));
}

float Float(const Bytes& bytes, std::size_t offset) {
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= std::uint32_t{bytes[offset + i]} << (8 * i);
  return std::bit_cast<float>(bits);
}

bool IsOneOf(const std::string& name, std::initializer_list<const char*> names) {
  for (const char* n : names) {
    if (name == n) return true;
  }
  return false;
}

TEST(FmaskFixtures, ChecksumIsFnv1a64) {
  EXPECT_EQ(fmask::Fnv1a64({}), 0xcbf29ce484222325ull);
  const std::uint8_t a[] = {'a'};
  EXPECT_EQ(fmask::Fnv1a64(a), 0xaf63dc4c8601ec8cull);
}

TEST(FmaskFixtures, SetCoversEveryLegalConfigBothPatternsAndEveryCase) {
  const std::vector<fmask::FixtureSpec> set = fmask::CanonicalFixtureSet();
  EXPECT_EQ(set.size(), fmask::LegalEqaaConfigs().size() * 2 * fmask::CanonicalCases().size());
  EXPECT_GE(fmask::CanonicalCases().size(), 12u);
  EXPECT_EQ(fmask::FixtureName({{8, 4, 2}, "standard", "t-junction"}),
            "8S4Z2F-standard-t-junction");
}

TEST(FmaskFixtures, DerivationIsDeterministic) {
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    const fmask::FixtureData a = fmask::DeriveFixture(spec), b = fmask::DeriveFixture(spec);
    SCOPED_TRACE(fmask::FixtureName(spec));
    EXPECT_EQ(a.fmask, b.fmask);
    EXPECT_EQ(a.colours, b.colours);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.decoded, b.decoded);
    EXPECT_EQ(a.resolve, b.resolve);
  }
}

TEST(FmaskFixtures, FileSizesFollowTheLayout) {
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    const Layout l = LayoutOf(data);
    const std::size_t pixels = static_cast<std::size_t>(data.width) * data.height;
    SCOPED_TRACE(fmask::FixtureName(spec));
    EXPECT_EQ(data.fmask.size(), pixels * l.elementBytes);
    EXPECT_EQ(data.colours.size(), pixels * l.fragments * 4);
    EXPECT_EQ(data.depth.size(), pixels * l.samples * 4);
    EXPECT_EQ(data.decoded.size(), pixels * l.samples * 4);
    EXPECT_EQ(data.resolve.size(), pixels * 16);
  }
}

// The decode rule of docs/fixtures.md, written from the document: code -> slot, UNKNOWN ->
// slot 0; the resolve averages the known samples' slot colours (float32, sample order).
TEST(FmaskFixtures, IndependentDecodeReproducesDecodedAndResolve) {
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    const Layout l = LayoutOf(data);
    SCOPED_TRACE(fmask::FixtureName(spec));
    for (int pixel = 0; pixel < data.width * data.height; ++pixel) {
      const std::uint64_t element = Element(data.fmask, l, pixel);
      float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      int known = 0;
      for (int s = 0; s < l.samples; ++s) {
        const int code = Code(element, l, s);
        const bool unknown = l.hasUnknown && code == l.unknownCode;
        ASSERT_TRUE(unknown || code < l.fragments) << "pixel " << pixel << " sample " << s;
        const int slot = unknown ? 0 : code;
        const std::size_t colour = 4 * (static_cast<std::size_t>(pixel) * l.fragments + slot);
        ASSERT_EQ(std::memcmp(&data.decoded[4 * (pixel * l.samples + s)], &data.colours[colour], 4),
                  0)
            << "pixel " << pixel << " sample " << s;
        if (unknown) continue;
        for (int c = 0; c < 4; ++c) sum[c] += data.colours[colour + c] / 255.0f;
        ++known;
      }
      const float inverse = known == 0 ? 0.0f : 1.0f / static_cast<float>(known);
      for (int c = 0; c < 4; ++c) {
        ASSERT_EQ(Float(data.resolve, 16 * pixel + 4 * c), sum[c] * inverse)
            << "pixel " << pixel << " channel " << c;
      }
      const int usedBits = l.samples * l.bitsPerSample;  // a shift by 64 would be undefined
      const std::uint64_t padding = usedBits < 64 ? element >> usedBits : 0;
      ASSERT_EQ(padding, 0u) << "padding bits set, pixel " << pixel;
    }
  }
}

TEST(FmaskFixtures, EvictionCascadeLeavesUnknownSamplesInEveryEqaaMode) {
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    if (spec.caseName != "eviction-cascade") continue;
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    const Layout l = LayoutOf(data);
    int unknown = 0;
    for (int pixel = 0; pixel < data.width * data.height; ++pixel) {
      for (int s = 0; s < l.samples; ++s) {
        unknown += l.hasUnknown && Code(Element(data.fmask, l, pixel), l, s) == l.unknownCode;
      }
    }
    EXPECT_EQ(unknown > 0, l.hasUnknown) << fmask::FixtureName(spec);
  }
}

// 1F: one bit per sample, 0 = the pixel's only stored fragment, 1 = UNKNOWN, so the stored
// fragment covers (S - popcount) / S of the pixel. With one triangle on the cleared surface
// (exact depth everywhere) those are exactly the samples whose depth is that fragment's depth.
TEST(FmaskFixtures, OneFragmentCodesGiveTheVisibleFragmentsCoverage) {
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    if (spec.config.fragments != 1 ||
        !IsOneOf(spec.caseName, {"edge-horizontal", "edge-shallow", "edge-diagonal",
                                         "edge-steep", "corner", "subpixel-triangle"})) {
      continue;
    }
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    const fmask::FixtureCase& fixtureCase = fmask::CanonicalCase(spec.caseName);
    const Layout l = LayoutOf(data);
    SCOPED_TRACE(fmask::FixtureName(spec));
    for (int pixel = 0; pixel < data.width * data.height; ++pixel) {
      const std::uint64_t element = Element(data.fmask, l, pixel);
      const bool slotIsClear =
          std::memcmp(&data.colours[4 * pixel], fmask::kFixtureClearColour.data(), 4) == 0;
      const float visibleDepth =
          slotIsClear ? fmask::kFixtureClearDepth : fixtureCase.triangles[0].vertices[0].z;
      int visibleSamples = 0;
      for (int s = 0; s < l.samples; ++s) {
        visibleSamples += Float(data.depth, 4 * (pixel * l.samples + s)) == visibleDepth;
      }
      const int codeZero = l.samples - std::popcount(element);
      EXPECT_EQ(codeZero, visibleSamples) << "pixel " << pixel;
    }
  }
}

}  // namespace
