// FMASK fixtures (fmask/fixtures.h): derivation is deterministic, and the files decode with the
// documented layout alone (docs/fixtures.md) to the expected per-sample colours and resolve.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include "fmask/fixtures.h"
#include "raster/rasterizer.h"

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
  // docs/fixtures.md: 29 modes x 2 patterns x 14 cases.
  EXPECT_EQ(fmask::LegalEqaaConfigs().size(), 29u);
  EXPECT_EQ(fmask::CanonicalCases().size(), 14u);
  EXPECT_EQ(set.size(), 812u);
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

// docs/fixtures.md: after the clip transform every vertex is on the 1/256-px grid (snapping
// never has to round, so no tie rule is involved), inside the guard band |x|, |y| <= 7w (no
// clipping) and at a depth in [0, 1].
TEST(FmaskFixtures, VerticesNeedNoRoundingOrClipping) {
  for (const fmask::FixtureCase& c : fmask::CanonicalCases()) {
    for (const fmask::FixtureTriangle& t : c.triangles) {
      for (const fmask::FixtureVertex& v : t.vertices) {
        const float ndcX = static_cast<float>(v.x / c.width * 2.0 - 1.0);
        const float ndcY = static_cast<float>(1.0 - v.y / c.height * 2.0);
        const double x = (static_cast<double>(ndcX) * 0.5 + 0.5) * c.width * 256.0;
        const double y = (0.5 - static_cast<double>(ndcY) * 0.5) * c.height * 256.0;
        EXPECT_EQ(x, std::floor(x)) << c.name;
        EXPECT_EQ(y, std::floor(y)) << c.name;
        EXPECT_LE(std::abs(ndcX), 7.0f) << c.name;
        EXPECT_LE(std::abs(ndcY), 7.0f) << c.name;
        EXPECT_TRUE(v.z >= 0.0f && v.z <= 1.0f) << c.name;
      }
    }
  }
}

std::vector<fmask::FixtureSpec> SpecsOf(const std::string& caseName) {
  std::vector<fmask::FixtureSpec> specs;
  for (const fmask::FixtureSpec& spec : fmask::CanonicalFixtureSet()) {
    if (spec.caseName == caseName) specs.push_back(spec);
  }
  EXPECT_EQ(specs.size(), 58u) << caseName;
  return specs;
}

// docs/fixtures.md: three triangles fill the plane table (with the clear, still referenced
// above them), so the first band decompresses the tile in every variant, exactly once.
TEST(FmaskFixtures, EvictionCascadeDecompressesInEveryVariant) {
  for (const fmask::FixtureSpec& spec : SpecsOf("eviction-cascade")) {
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    EXPECT_EQ(data.rasterCounters.zPlaneDecompressions, 1u) << fmask::FixtureName(spec);
    EXPECT_EQ(data.rasterCounters.zTilesDecompressedAtEnd, 1u) << fmask::FixtureName(spec);
  }
}

// hi-Z rejects the last triangle's only tile in every variant, and the files are those of the
// same case without that triangle: the colour block never saw it. With hi-Z off it reaches the
// colour block, and where unanchored samples exist (Z < S) the decompressed tile makes them
// untestable, so the rejected fragment discards them (docs/eqaa.md step 2): FMASK differs.
TEST(FmaskFixtures, HiZRejectedTileNeverReachesTheColourBlock) {
  const fmask::FixtureCase& full = fmask::CanonicalCase("hiz-rejected");
  fmask::FixtureCase withoutLast = full;
  withoutLast.triangles.pop_back();
  for (const fmask::FixtureSpec& spec : SpecsOf("hiz-rejected")) {
    SCOPED_TRACE(fmask::FixtureName(spec));
    const fmask::ArbitrationPolicy policy = fmask::PolicyByName(spec.policy);
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    EXPECT_EQ(data.rasterCounters.tilesHiZRejected, 1u);
    EXPECT_EQ(data.rasterCounters.zPlaneDecompressions, 1u);
    const fmask::FixtureData before = fmask::DeriveFixture(withoutLast, spec.config, spec.pattern, policy);
    EXPECT_EQ(data.fmask, before.fmask);
    EXPECT_EQ(data.colours, before.colours);
    EXPECT_EQ(data.depth, before.depth);
    raster::DrawState noHiZ = fmask::FixtureDrawState();
    noHiZ.depth.hiZEnable = false;
    const fmask::FixtureData unculled = fmask::DeriveFixture(full, spec.config, spec.pattern, policy, noHiZ);
    EXPECT_EQ(unculled.rasterCounters.tilesHiZRejected, 0u);
    EXPECT_EQ(unculled.fmask != data.fmask, spec.config.depthSamples < spec.config.coverageSamples);
    EXPECT_EQ(unculled.depth, data.depth);  // the far triangle fails every depth test
  }
}

// Derived by hand from the case's geometry (fmask/fixtures.cpp, docs/fixtures.md): in the quad
// at (4, 4) the last triangle E (flat, z = 0.5) covers every sample with offset x >= -7 in
// column 4 (x > 4.03125), every sample of column 5, and likewise in y. A wall at z = 0.25
// covers each pixel's samples with offset y >= 1; the samples with y <= 0 still hold the clear.
// E's first write, in pixel (4, 4), decompresses the tile: that pixel was tested exactly, so E
// owns its covered samples with y <= 0. Pixels (5, 4), (4, 5), (5, 5) follow: an anchored
// sample as before, an unanchored one by its nearest anchor (Euclidean in the pixel's offsets,
// lower index on ties) — it passes when that anchor is above the wall.
TEST(FmaskFixtures, DecompressionInsideAQuadSplitsTheQuad) {
  int variantsWhereTheQuadDiffers = 0;
  for (const fmask::FixtureSpec& spec : SpecsOf("decompress-in-quad")) {
    SCOPED_TRACE(fmask::FixtureName(spec));
    const fmask::FixtureData data = fmask::DeriveFixture(spec);
    EXPECT_EQ(data.rasterCounters.zPlaneDecompressions, 1u);
    const Layout l = LayoutOf(data);
    const int anchors = spec.config.depthSamples;
    const std::uint8_t* colourE = fmask::CanonicalCase(spec.caseName).triangles.back().colour.data();
    bool differs = false;
    for (int p = 0; p < 4; ++p) {
      const int x = 4 + (p & 1), y = 4 + (p >> 1), pixel = y * data.width + x;
      auto offset = [&](int s) { return data.pattern.Offset(p, s); };
      auto upper = [&](int s) { return offset(s).y <= 0; };
      auto covered = [&](int s) { return (x == 5 || offset(s).x >= -7) && (y == 5 || offset(s).y >= -7); };
      auto nearest = [&](int s) {
        if (s < anchors) return s;
        int best = 0;
        for (int a = 1; a < anchors; ++a) {
          auto d2 = [&](int b) {
            const int dx = offset(s).x - offset(b).x, dy = offset(s).y - offset(b).y;
            return dx * dx + dy * dy;
          };
          if (d2(a) < d2(best)) best = a;
        }
        return best;
      };
      const std::uint64_t element = Element(data.fmask, l, pixel);
      for (int s = 0; s < l.samples; ++s) {
        const bool exact = covered(s) && upper(s);
        const bool expected = p == 0 ? exact : covered(s) && upper(nearest(s));
        differs |= expected != exact;
        const int code = Code(element, l, s);
        const bool ownedByE = !(l.hasUnknown && code == l.unknownCode) &&
                              std::memcmp(&data.colours[4 * (pixel * l.fragments + code)], colourE, 4) == 0;
        EXPECT_EQ(ownedByE, expected) << "pixel " << x << "," << y << " sample " << s;
      }
    }
    variantsWhereTheQuadDiffers += differs;
  }
  // docs/fixtures.md lists the variants where an unanchored sample's nearest anchor lies across
  // the wall, so the quad's later pixels differ from an exact test: every Z < S mode except
  // 8S/4Z and the standard 16S/8Z, 30 of the 58.
  EXPECT_EQ(variantsWhereTheQuadDiffers, 30);
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
