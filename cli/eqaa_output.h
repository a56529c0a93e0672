#pragma once
// What `aasim raster --fragments F` shows of its EQAA surface: the flat primitive colours the
// colour block is fed with, and the per-pixel planes behind eqaa.exr, resolve.png and
// fmask.png (formats in docs/cli.md).

#include <cstdint>
#include <filesystem>
#include <vector>

#include "fmask/eqaa_surface.h"

namespace cli {

// Opaque black, what the surface's slots hold before the first draw.
inline constexpr fmask::Colour kClearColour{0.0f, 0.0f, 0.0f, 1.0f};

// A flat, fully saturated colour per primitive (alpha 1): neighbouring primitives differ, so the
// fragment structure of FMASK shows in the resolve.
fmask::Colour PrimitiveColour(std::uint32_t primitiveId);

// The surface read back once per pixel, row-major; every EQAA output is made from these.
struct EqaaPlanes {
  int width = 0;
  int height = 0;
  int samples = 0;
  std::vector<float> red, green, blue, alpha;  // BoxResolve
  std::vector<std::vector<float>> codes;       // [sample][pixel]: stored FMASK code
  std::vector<float> fragments;                // occupied slots
  std::vector<float> unknown;                  // UNKNOWN samples
};

EqaaPlanes ReadEqaaPlanes(const fmask::EqaaSurface& surface);

// Channels R, G, B, A, fmask.s0 .. fmask.s{S-1}, fragments, unknown.
void WriteEqaaExr(const std::filesystem::path& path, const EqaaPlanes& planes);
// 8-bit sRGB RGB of the box resolve.
std::vector<std::uint8_t> ResolveImage(const EqaaPlanes& planes);
// 8-bit sRGB RGB: brightness from the fraction of UNKNOWN samples, tint from the fragment count
// (kFragmentTints in the .cpp; docs/cli.md has the table).
std::vector<std::uint8_t> FmaskImage(const EqaaPlanes& planes);

}  // namespace cli
