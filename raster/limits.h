#pragma once
// Every fixed limit of the coverage model in one place, each with the fact it comes from, and
// the static_asserts that keep the fixed-point arithmetic in range (style.md habit 5).

#include <cstdint>

namespace raster {

// DESIGN.md "Conventions": vertex positions snap to 8 sub-pixel bits.
inline constexpr int kSubPixelBits = 8;
inline constexpr std::int64_t kSubPixelScale = std::int64_t{1} << kSubPixelBits;

// hw-facts §4.2: sample offsets are 4-bit two's-complement fields in 1/16 px, range -8..7.
inline constexpr int kSampleGridBits = 4;
inline constexpr int kSampleOffsetMin = -8;
inline constexpr int kSampleOffsetMax = 7;
inline constexpr std::int64_t kSubPixelPerSampleUnit = kSubPixelScale >> kSampleGridBits;

// hw-facts §1.1: at most 16 coverage samples (MaxMsaaColorSamples), 8 depth samples
// (MaxMsaaDepthSamples); a 2x2 quad has one programmable pattern per pixel (§4.2).
inline constexpr int kMaxCoverageSamples = 16;
inline constexpr int kMaxDepthSamples = 8;
inline constexpr int kQuadPixels = 4;

// hw-facts §5.1: HTILE and hi-Z / hi-stencil work on 8x8-pixel tiles.
inline constexpr int kTileSize = 8;
// hw-facts §5.2: a compressed tile holds at most 16 Z planes.
inline constexpr int kMaxZPlanesPerTile = 16;
// hw-facts §6.1: Tahiti splits the screen among scan converters in 32x32 tiles; aasim bins
// and rasterizes in the same granularity (DESIGN.md "Performance architecture").
inline constexpr int kBinSize = 32;

// D3D11 maximum render-target dimension; larger requests are refused, never clamped.
inline constexpr int kMaxDimension = 16384;
// The quads one draw may collect for the shader stage. Overdraw is unbounded by the screen size
// (200k stacked full-screen triangles at 256x256 are 3.3e9 quads), so the stream is capped and
// a draw past it is refused rather than let run the machine out of memory: 1 GiB is a quarter
// of the 4 GiB a run may use (cli/common_options.h kMaxRunBytes) and holds about 22M quads.
inline constexpr std::uint64_t kMaxQuadStreamBytes = std::uint64_t{1} << 30;

// Guard band in NDC units: triangles are clipped to |x|,|y| <= kGuardBandNdc * w so that
// snapped screen coordinates stay below 2^17 px (see the edge-function bound below).
inline constexpr double kGuardBandNdc = 7.0;

// Edge-function range proof. Screen coordinates are at most (kGuardBandNdc + 1) / 2 *
// kMaxDimension = 65536 = 2^16 px away from the origin, i.e. 2^24 sub-pixel units; edge
// coefficients (coordinate differences) are below 2^25 and sample positions below 2^25, so each
// product is below 2^50 and the three-term sum below 2^52: int64 edge values cannot overflow.
static_assert((kGuardBandNdc + 1.0) / 2.0 * kMaxDimension <= 65536.0);
static_assert(kSubPixelBits + 16 + 1 + kSubPixelBits + 16 + 1 + 2 < 63);
static_assert(kBinSize % (2 * kTileSize) == 0 || kBinSize % kTileSize == 0);
static_assert(kTileSize % 2 == 0, "tiles hold whole 2x2 quads");
static_assert(kMaxCoverageSamples * kQuadPixels == 64, "QuadCoverage packs a quad into 64 bits");

}  // namespace raster
