// The canonical fixture scenes and their derivation: raster -> EqaaSurface -> byte files in the
// layout docs/fixtures.md describes.

#include "fmask/fixtures.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include <glm/vec4.hpp>

#include "raster/rasterizer.h"

namespace fmask {
namespace {

using Rgba8 = std::array<std::uint8_t, 4>;

// Distinct opaque colours; every channel is k/255 so RGBA8 files hold them exactly.
constexpr Rgba8 kPalette[] = {
    {230, 25, 75, 255},  {60, 180, 75, 255},   {255, 225, 25, 255}, {0, 130, 200, 255},
    {245, 130, 48, 255}, {145, 30, 180, 255},  {70, 240, 240, 255}, {240, 50, 230, 255},
    {210, 245, 60, 255}, {250, 190, 212, 255}, {0, 128, 128, 255},  {170, 110, 40, 255},
    {128, 0, 0, 255},    {0, 0, 128, 255},     {128, 128, 0, 255},
};

constexpr std::string_view kFixturePatterns[] = {"standard", "eqaa"};

// One 8x8 HTILE tile: every case fits, and the files stay small.
constexpr int kCaseSize = 8;

FixtureTriangle Triangle(FixtureVertex a, FixtureVertex b, FixtureVertex c, int colour) {
  return {{a, b, c}, kPalette[colour]};
}

FixtureCase Case(std::string name, std::string exercises, std::vector<FixtureTriangle> triangles) {
  return {std::move(name), std::move(exercises), kCaseSize, kCaseSize, std::move(triangles)};
}

// A half-plane bounded by the line through the point off the pixel grid (cx, cy) with direction
// (dirX, dirY): the triangle's other two edges lie outside the surface but inside the guard
// band (docs/raster.md), which `reach` must respect.
FixtureCase EdgeCase(std::string name, std::string exercises, double dirX, double dirY,
                     double reach) {
  const double cx = 4.03125, cy = 4.09375;
  const FixtureVertex a{cx - reach * dirX, cy - reach * dirY};
  const FixtureVertex b{cx + reach * dirX, cy + reach * dirY};
  const FixtureVertex c{cx - reach * dirY, cy + reach * dirX};
  return Case(std::move(name), std::move(exercises), {Triangle(a, b, c, 0)});
}

// Three flat triangles at the bottom of the tile, each with its own plane (depths in odd 32nds,
// unlike any band of the cascade) and clear of the rows above y = 4: with the clear depth still referenced by the rows above them, they fill
// the tile's four plane slots (docs/raster.md), so the next triangle with a new plane that
// writes depth decompresses the tile whatever the sample pattern.
std::vector<FixtureTriangle> FullPlaneTable(int firstColour) {
  return {Triangle({0.25, 4.75, 0.96875f}, {3.75, 4.75, 0.96875f}, {0.25, 7.75, 0.96875f}, firstColour),
          Triangle({4.25, 4.75, 0.90625f}, {7.75, 4.75, 0.90625f}, {7.75, 7.75, 0.90625f}, firstColour + 1),
          Triangle({2.0, 7.875, 0.84375f}, {4.0, 7.875, 0.84375f}, {3.0, 5.875, 0.84375f}, firstColour + 2)};
}

// Horizontal bands 1/16 px apart, each nearer than the last: a pixel of the band rows sees up
// to 12 fragments, more than any F. The first band finds the plane table full and
// decompresses the tile, so the cascade runs on per-sample depth: unanchored samples are
// tested against their anchors from then on.
FixtureCase EvictionCascade() {
  constexpr int kBands = 12;
  FixtureCase cascade = Case("eviction-cascade",
                             "three triangles fill the Z-plane table, then 12 overlapping bands "
                             "drawn back to front through one pixel row: the first band "
                             "decompresses the tile, then repeated evictions (UNKNOWN samples)",
                             FullPlaneTable(12));
  for (int band = 0; band < kBands; ++band) {
    const double top = 2.0 + band / 16.0;
    const float z = static_cast<float>(15 - band) / 16.0f;
    cascade.triangles.push_back(
        Triangle({-20.0, top, z}, {28.0, top, z}, {4.0, top + 0.375, z}, band));
  }
  return cascade;
}

// A full-tile triangle sets the tile's hi-Z bounds to its depth, four nearer ones fill and
// then overflow the plane table (the tile decompresses), and a far triangle behind all of them
// is rejected by hi-Z for the whole tile: it never reaches the colour block, so the untestable
// samples it covers keep their fragments (docs/eqaa.md, step 2).
FixtureCase HiZRejected() {
  return Case("hiz-rejected",
              "a far triangle behind a decompressed tile: hi-Z rejects the tile, so the colour "
              "block never sees it and no untestable sample is discarded",
              {Triangle({-20.0, -4.0, 0.25f}, {30.0, -4.0, 0.25f}, {5.0, 30.0, 0.25f}, 9),
               Triangle({0.25, 0.25, 0.1875f}, {3.75, 0.25, 0.1875f}, {0.25, 3.75, 0.1875f}, 0),
               Triangle({4.25, 0.25, 0.125f}, {7.75, 0.25, 0.125f}, {7.75, 3.75, 0.125f}, 1),
               Triangle({0.25, 4.25, 0.0625f}, {0.25, 7.75, 0.0625f}, {3.75, 7.75, 0.0625f}, 2),
               Triangle({7.75, 4.25, 0.03125f}, {7.75, 7.75, 0.03125f}, {4.25, 7.75, 0.03125f}, 3),
               Triangle({1.03125, 2.03125, 0.75f}, {6.96875, 2.03125, 0.75f}, {4.0, 7.0, 0.75f}, 4)});
}

// Three planes plus the clear fill the table; a near wall covers the lower half of each pixel
// of the quad at (4, 4) (two coplanar stripes, one plane). The last triangle covers that quad
// from its top-left pixel: its first depth write, in pixel (4, 4), decompresses the tile, so
// that pixel's samples were tested exactly and the quad's other three pixels test their
// unanchored samples against their nearest anchor (docs/raster.md).
FixtureCase DecompressInQuad() {
  auto stripe = [](double top, double bottom, int colour) {
    return std::vector<FixtureTriangle>{
        Triangle({3.5, top, 0.25f}, {6.5, top, 0.25f}, {6.5, bottom, 0.25f}, colour),
        Triangle({3.5, top, 0.25f}, {6.5, bottom, 0.25f}, {3.5, bottom, 0.25f}, colour)};
  };
  std::vector<FixtureTriangle> triangles{
      Triangle({0.25, 0.25, 0.625f}, {3.75, 0.25, 0.625f}, {0.25, 2.75, 0.625f}, 0),
      Triangle({4.25, 0.25, 0.6875f}, {7.75, 0.25, 0.6875f}, {7.75, 2.75, 0.6875f}, 1)};
  for (const FixtureTriangle& t : stripe(4.53125, 5.03125, 3)) triangles.push_back(t);
  for (const FixtureTriangle& t : stripe(5.53125, 6.03125, 3)) triangles.push_back(t);
  triangles.push_back(Triangle({4.03125, 4.03125, 0.5f}, {8.0, 4.03125, 0.5f}, {4.03125, 8.0, 0.5f}, 5));
  return Case("decompress-in-quad",
              "the clear and three planes fill the table; the last triangle decompresses the "
              "tile in the first pixel of a quad, so the quad's other pixels test unanchored "
              "samples against their anchors",
              std::move(triangles));
}

FixtureCase DepthOrder(std::string name, std::string exercises, bool frontFirst) {
  const FixtureTriangle nearTri =
      Triangle({1.25, 1.5, 0.25f}, {6.5, 2.25, 0.25f}, {2.75, 6.75, 0.25f}, 0);
  const FixtureTriangle farTri =
      Triangle({3.125, 0.75, 0.75f}, {7.5, 5.25, 0.75f}, {0.875, 6.25, 0.75f}, 3);
  return Case(std::move(name), std::move(exercises),
              frontFirst ? std::vector{nearTri, farTri} : std::vector{farTri, nearTri});
}

Colour ToColour(const Rgba8& rgba) {
  return {rgba[0] / 255.0f, rgba[1] / 255.0f, rgba[2] / 255.0f, rgba[3] / 255.0f};
}

std::uint8_t ToUnorm8(float value) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

void AppendLittleEndian(std::vector<std::uint8_t>& bytes, std::uint64_t value, int byteCount) {
  for (int i = 0; i < byteCount; ++i) bytes.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

void AppendFloat(std::vector<std::uint8_t>& bytes, float value) {
  AppendLittleEndian(bytes, std::bit_cast<std::uint32_t>(value), 4);
}

void AppendUnorm8(std::vector<std::uint8_t>& bytes, const Colour& colour) {
  for (float channel : {colour.r, colour.g, colour.b, colour.a}) bytes.push_back(ToUnorm8(channel));
}

raster::SamplePattern FixturePattern(std::string_view name, int samples) {
  if (std::ranges::find(kFixturePatterns, name) == std::end(kFixturePatterns)) {
    throw std::invalid_argument("fixture pattern '" + std::string(name) +
                                "' is not one of: standard, eqaa");
  }
  return raster::MakeBuiltinPattern(name, samples);
}

raster::RasterResult RasterizeCase(const FixtureCase& fixtureCase, const raster::DrawState& state,
                                   raster::DepthStencilSurface& depth) {
  std::vector<glm::vec4> clip;
  std::vector<std::uint32_t> indices;
  const double width = fixtureCase.width, height = fixtureCase.height;
  for (const FixtureTriangle& triangle : fixtureCase.triangles) {
    for (const FixtureVertex& v : triangle.vertices) {
      indices.push_back(static_cast<std::uint32_t>(clip.size()));
      clip.emplace_back(static_cast<float>(v.x / width * 2.0 - 1.0),
                        static_cast<float>(1.0 - v.y / height * 2.0), v.z, 1.0f);
    }
  }
  return raster::Rasterize({clip, indices, 0}, state, depth);
}

void ExtractFiles(const EqaaSurface& surface, const raster::DepthStencilSurface& depth,
                  FixtureData& data) {
  const int samples = data.layout.CoverageSamples();
  const int elementBytes = data.layout.ElementBits() / 8;
  for (int y = 0; y < data.height; ++y) {
    for (int x = 0; x < data.width; ++x) {
      AppendLittleEndian(data.fmask, surface.Fmask(x, y), elementBytes);
      for (int slot = 0; slot < data.layout.Fragments(); ++slot) {
        AppendUnorm8(data.colours, surface.Slot(x, y, slot).colour);
      }
      for (int s = 0; s < samples; ++s) {
        AppendFloat(data.depth, depth.TestDepth(x, y, s));
        AppendUnorm8(data.decoded, surface.FetchSample(x, y, s));
      }
      const Colour resolved = surface.BoxResolve(x, y);
      for (float channel : {resolved.r, resolved.g, resolved.b, resolved.a}) {
        AppendFloat(data.resolve, channel);
      }
    }
  }
}

}  // namespace

std::vector<FixtureCase> CanonicalCases() {
  std::vector<FixtureCase> cases{
      EdgeCase("edge-horizontal", "one horizontal edge crossing a pixel row", 1.0, 0.0, 20.0),
      EdgeCase("edge-shallow", "one edge at atan(1/2) = 26.6 degrees", 2.0, 1.0, 10.0),
      EdgeCase("edge-diagonal", "one edge at 45 degrees", 1.0, 1.0, 14.0),
      EdgeCase("edge-steep", "one edge at atan(4) = 76.0 degrees", 1.0, 4.0, 5.0),
      Case("corner", "an acute triangle corner inside a pixel",
           {Triangle({3.40625, 3.59375}, {20.0, -4.0}, {20.0, 12.0}, 1)}),
      Case("t-junction", "three triangles meeting in a T: a long edge and an edge ending on it",
           {Triangle({-16.0, 4.3125}, {24.0, 4.3125}, {4.0, -16.0}, 0),
            Triangle({-16.0, 4.3125}, {4.5625, 4.3125}, {4.5625, 24.0}, 1),
            Triangle({4.5625, 4.3125}, {24.0, 4.3125}, {4.5625, 24.0}, 2)}),
      Case("five-way-vertex", "five triangles sharing a vertex inside one pixel: five fragments",
           {Triangle({4.46875, 3.53125}, {20.0, 3.5}, {9.0, 20.0}, 0),
            Triangle({4.46875, 3.53125}, {9.0, 20.0}, {-12.0, 14.0}, 1),
            Triangle({4.46875, 3.53125}, {-12.0, 14.0}, {-12.0, -8.0}, 2),
            Triangle({4.46875, 3.53125}, {-12.0, -8.0}, {9.0, -13.0}, 3),
            Triangle({4.46875, 3.53125}, {9.0, -13.0}, {20.0, 3.5}, 4)}),
      Case("subpixel-triangle", "a triangle smaller than a pixel, covering a few samples only",
           {Triangle({2.1875, 2.1875}, {2.8125, 2.375}, {2.375, 2.8125}, 5)}),
      Case("intersecting", "two interpenetrating triangles: the visible edge comes from depth",
           {Triangle({-2.0, 0.5, 0.125f}, {10.0, 0.5, 0.875f}, {4.0, 7.5, 0.5f}, 6),
            Triangle({-2.0, 7.5, 0.875f}, {10.0, 7.5, 0.25f}, {4.0, 0.25, 0.375f}, 7)}),
      EvictionCascade(),
      DepthOrder("front-to-back", "a near triangle, then an overlapping far one (depth-rejected)",
                 true),
      DepthOrder("back-to-front", "the same two triangles, far one first (overdrawn)", false),
      HiZRejected(),
      DecompressInQuad(),
  };
  return cases;
}

const FixtureCase& CanonicalCase(std::string_view name) {
  static const std::vector<FixtureCase> kCases = CanonicalCases();
  const auto found = std::ranges::find(kCases, name, &FixtureCase::name);
  if (found != kCases.end()) return *found;
  std::string names;
  for (const FixtureCase& c : kCases) names += (names.empty() ? "" : ", ") + c.name;
  throw std::invalid_argument("unknown fixture case '" + std::string(name) + "'; cases: " + names);
}

std::string FixtureName(const FixtureSpec& spec) {
  std::string name = EqaaName(spec.config);
  std::erase(name, '/');
  name += "-" + spec.pattern + "-" + spec.caseName;
  if (spec.policy != "hraa") name += "-" + spec.policy;
  return name;
}

std::vector<FixtureSpec> CanonicalFixtureSet() {
  std::vector<FixtureSpec> set;
  const std::vector<FixtureCase> cases = CanonicalCases();
  for (const EqaaConfig& config : LegalEqaaConfigs()) {
    for (std::string_view pattern : kFixturePatterns) {
      for (const FixtureCase& c : cases) set.push_back({config, std::string(pattern), c.name});
    }
  }
  return set;
}

raster::DrawState FixtureDrawState() {
  raster::DrawState state;
  state.cull = raster::CullMode::None;
  state.depth.func = raster::CompareFunc::Less;
  state.depth.hiZEnable = true;
  return state;
}

FixtureData DeriveFixture(const FixtureCase& fixtureCase, const EqaaConfig& config,
                          std::string_view patternName, const ArbitrationPolicy& policy,
                          const raster::DrawState& state) {
  ValidateEqaaConfig(config);
  raster::SamplePattern pattern = FixturePattern(patternName, config.coverageSamples);
  raster::DepthStencilSurface depth({.width = fixtureCase.width,
                                     .height = fixtureCase.height,
                                     .coverageSamples = config.coverageSamples,
                                     .depthSamples = config.depthSamples,
                                     .maxZPlanes = kFixtureMaxZPlanes,
                                     .clearDepth = kFixtureClearDepth},
                                    pattern);
  const raster::RasterResult result = RasterizeCase(fixtureCase, state, depth);
  EqaaSurface surface(fixtureCase.width, fixtureCase.height, config, policy, InitialState::Cleared,
                      ToColour(kFixtureClearColour));
  const FragmentCounters fragmentCounters =
      surface.UpdateAll(result, [&](const raster::QuadFragment& quad, int) {
        return ToColour(fixtureCase.triangles[quad.primitiveId].colour);
      });
  FixtureData data{.spec = {config, std::string(patternName), fixtureCase.name, policy.name},
                   .width = fixtureCase.width,
                   .height = fixtureCase.height,
                   .layout = FmaskLayout::For(config.coverageSamples, config.fragments),
                   .pattern = std::move(pattern),
                   .rasterCounters = result.counters,
                   .fragmentCounters = fragmentCounters};
  ExtractFiles(surface, depth, data);
  return data;
}

FixtureData DeriveFixture(const FixtureSpec& spec) {
  return DeriveFixture(CanonicalCase(spec.caseName), spec.config, spec.pattern,
                       PolicyByName(spec.policy));
}

std::uint64_t Fnv1a64(std::span<const std::uint8_t> bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (std::uint8_t byte : bytes) {
    hash ^= byte;
    hash *= 0x100000001b3ull;
  }
  return hash;
}

}  // namespace fmask
