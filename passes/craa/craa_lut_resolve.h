#pragma once
// `craa-lut`: the CRAA LUT resolve of a 1F surface (seed 001, "8xCRAA LUT: In Practice": "Fast
// resolve: neighborhood prefetch, FMask read, LUT[FMask] read, blend").
//
//   resolve/craa-lut   full-screen PS
//     in:  fragment 0 of the pixel and of its up, bottom, left and right neighbours (prefetched
//          whatever the FMASK says, as the slide orders it; clamp addressing at the screen's border),
//          the FMASK of the 1F surface (S bits, 1 = UNKNOWN),
//          the LUT (a buffer of 2^S 16-bit entries per table, U | B<<4 | L<<8 | R<<12; 512 bytes at
//          8S; 4 tables when the pattern differs between quad pixels, indexed by quad pixel)
//     out: colour = (own * (S - U - B - L - R) + U * up + B * bottom + L * left + R * right) / S
//
// The table comes from our generator (craa_lut.h, docs/craa.md "CRAA LUT") for the frame's
// sample pattern, cached as its JSON fixture under ResolveContext::tableCache.

#include <filesystem>
#include <memory>

#include "passes/craa/craa_lut.h"
#include "passes/resolve.h"

namespace passes::craa {

// The table for `pattern`, fitted to `configurations` synthetic configurations (0 = the
// generator's default): read from `cache` when a fixture made for exactly these offsets and that
// count is there, else generated (and written there, atomically). Throws naming the cache file
// when it cannot be read back or written.
CraaLut CachedCraaLut(const raster::SamplePattern& pattern, const std::optional<std::filesystem::path>& cache,
                      std::int64_t configurations = 0);

const ResolveInfo& LutInfo();
std::unique_ptr<Resolve> MakeLut(const ResolveContext& context);
// The resolve with a given table (`aasim` tests, `craa-lut` fixtures of the user's own).
std::unique_ptr<Resolve> MakeLutWith(const raster::SamplePattern& pattern, CraaLut lut);

}  // namespace passes::craa
