#pragma once
// FMASK fixtures: small canonical scenes rasterized into an EQAA surface and flattened into the
// byte files an outside decoder or resolve shader can be tested against (docs/fixtures.md).

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fmask/eqaa_surface.h"
#include "fmask/layout.h"
#include "raster/counters.h"
#include "raster/rasterizer.h"
#include "raster/sample_pattern.h"

namespace fmask {

// Screen space as in DESIGN.md (pixels, +y down); z is the D3D depth of the vertex, 0..1.
struct FixtureVertex {
  double x = 0.0, y = 0.0;
  float z = 0.5f;
};

struct FixtureTriangle {
  std::array<FixtureVertex, 3> vertices;
  std::array<std::uint8_t, 4> colour{};  // RGBA8 UNORM, linear; the flat fragment colour
};

struct FixtureCase {
  std::string name;       // e.g. "t-junction"
  std::string exercises;  // one sentence for docs and the manifest
  int width = 8, height = 8;
  std::vector<FixtureTriangle> triangles{};  // drawn in this order, one draw
};

std::vector<FixtureCase> CanonicalCases();
// Throws std::invalid_argument listing the case names.
const FixtureCase& CanonicalCase(std::string_view name);

// What identifies a fixture; everything else is derived from it.
struct FixtureSpec {
  EqaaConfig config;
  std::string pattern;  // "standard" or "eqaa" (raster::MakeBuiltinPattern)
  std::string caseName;
  std::string policy = "hraa";  // PolicyByName
};

// "8S4Z2F-standard-t-junction": also the fixture's folder name.
std::string FixtureName(const FixtureSpec& spec);
// Every legal S/Z/F x {standard, eqaa} x every canonical case, policy hraa.
std::vector<FixtureSpec> CanonicalFixtureSet();

// The fixed raster state of every fixture (recorded in the manifest).
inline constexpr int kFixtureMaxZPlanes = 4;
inline constexpr float kFixtureClearDepth = 1.0f;
inline constexpr std::array<std::uint8_t, 4> kFixtureClearColour{0, 0, 0, 255};
// No culling, depth test LESS with writes, hi-Z on, no stencil.
raster::DrawState FixtureDrawState();

// The files of one fixture, each a row-major array over pixels (top row first), little-endian.
struct FixtureData {
  FixtureSpec spec;
  int width = 0, height = 0;
  FmaskLayout layout;
  raster::SamplePattern pattern;
  std::vector<std::uint8_t> fmask{};    // per pixel: ElementBits()/8 bytes, the FMASK element
  std::vector<std::uint8_t> colours{};  // per pixel, per slot 0..F-1: RGBA8
  std::vector<std::uint8_t> depth{};    // per pixel, per sample 0..S-1: float32 tested depth
  std::vector<std::uint8_t> decoded{};  // per pixel, per sample: RGBA8 colour FetchSample reads
  std::vector<std::uint8_t> resolve{};  // per pixel: 4 x float32 RGBA, the box resolve
  // What happened on the way (not written to the files; tests check that each case exercises
  // the rule it is there for).
  raster::RasterCounters rasterCounters{};
  FragmentCounters fragmentCounters{};
};

// Rasterizes the case (FixtureDrawState, kFixtureMaxZPlanes) into a cleared EQAA surface with
// the named pattern and policy and extracts the files. Deterministic. Throws
// std::invalid_argument on an illegal config, pattern or policy name. `state` exists so tests
// can show what a case depends on (e.g. hi-Z off); fixtures always use FixtureDrawState().
FixtureData DeriveFixture(const FixtureCase& fixtureCase, const EqaaConfig& config,
                          std::string_view patternName, const ArbitrationPolicy& policy,
                          const raster::DrawState& state = FixtureDrawState());
FixtureData DeriveFixture(const FixtureSpec& spec);

// 64-bit FNV-1a (offset basis 0xcbf29ce484222325, prime 0x100000001b3), the manifest checksum.
std::uint64_t Fnv1a64(std::span<const std::uint8_t> bytes);

}  // namespace fmask
