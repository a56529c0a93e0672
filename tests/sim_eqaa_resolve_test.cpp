// The box and fetch-path resolves as kernels (sim/eqaa_resolve.h): bit-identical to the host
// definitions of fmask::EqaaSurface, and what they read of FMASK and fragments is counted.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>

#include "eqaa_frame_util.h"
#include "sim/eqaa_resolve.h"

namespace sim {
namespace {

constexpr fmask::EqaaConfig kResolveModes[] = {{1, 1, 1}, {2, 2, 1}, {4, 4, 2}, {8, 8, 1}, {8, 4, 2}, {8, 8, 8}, {16, 8, 4}};

glm::vec4 HostBox(const fmask::EqaaSurface& surface, int x, int y) { return ToVec4(surface.BoxResolve(x, y)); }

glm::vec4 HostFetch(const fmask::EqaaSurface& surface, int x, int y) {
  glm::vec4 sum(0.0f);
  const int samples = surface.Config().coverageSamples;
  for (int s = 0; s < samples; ++s) sum += ToVec4(surface.FetchSample(x, y, s));
  return sum / static_cast<float>(samples);
}

const ResourceTraffic& TrafficOf(const DispatchReport& report, const std::string& resource) {
  for (const ResourceTraffic& traffic : report.resources) {
    if (traffic.name == resource) return traffic;
  }
  throw std::logic_error("no traffic on " + resource);
}

TEST(EqaaResolveKernel, BoxAndFetchEqualTheHostDefinitionsBitForBit) {
  for (const fmask::EqaaConfig& mode : kResolveModes) {
    const auto frame = testing_eqaa::RenderBuiltin("pixel-crossing", 96, 64, mode);
    const fmask::EqaaSurface& surface = frame->pipeline->Eqaa();
    Texture2D<glm::vec4> box("box", 96, 64, 4), fetch("fetch", 96, 64, 4);
    RunBoxResolve(frame->machine, surface, box, "test/box");
    RunFetchResolve(frame->machine, surface, fetch, "test/fetch");
    int unknownPixels = 0;
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 96; ++x) {
        ASSERT_EQ(box.At(x, y), HostBox(surface, x, y)) << fmask::EqaaName(mode) << " " << x << "," << y;
        ASSERT_EQ(fetch.At(x, y), HostFetch(surface, x, y)) << fmask::EqaaName(mode) << " " << x << "," << y;
        ASSERT_EQ(frame->pipeline->Colour().At(x, y), box.At(x, y));
        unknownPixels += surface.UnknownSamples(x, y) > 0;
      }
    }
    // The scene must leave UNKNOWN samples where the two resolves differ, or the test shows little.
    if (mode.fragments < mode.coverageSamples) {
      EXPECT_GT(unknownPixels, 0) << fmask::EqaaName(mode);
    }
  }
}

// Bytes read are the study's point: one FMASK element per pixel, each named fragment once (box)
// or one fragment per sample (fetch).
TEST(EqaaResolveKernel, CountsFmaskAndFragmentReads) {
  const fmask::EqaaConfig mode{8, 4, 2};
  const auto frame = testing_eqaa::RenderBuiltin("pixel-crossing", 96, 64, mode);
  const fmask::EqaaSurface& surface = frame->pipeline->Eqaa();
  Texture2D<glm::vec4> out("out", 96, 64, 4);
  const DispatchReport box = RunBoxResolve(frame->machine, surface, out, "test/box");
  const DispatchReport fetch = RunFetchResolve(frame->machine, surface, out, "test/fetch");
  std::uint64_t namedFragments = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 96; ++x) {
      std::uint32_t named = 0;
      for (int s = 0; s < 8; ++s) {
        const int code = surface.Layout().Code(surface.Fmask(x, y), s);
        if (code != surface.Layout().UnknownCode()) named |= 1u << code;
      }
      namedFragments += static_cast<std::uint64_t>(std::popcount(named));
    }
  }
  const std::uint64_t pixels = 96 * 64, fmaskBytes = static_cast<std::uint64_t>(surface.Layout().ElementBits() / 8);
  for (const DispatchReport* report : {&box, &fetch}) {
    EXPECT_EQ(TrafficOf(*report, "eqaa/fmask").bytesRead, pixels * fmaskBytes);
    EXPECT_EQ(TrafficOf(*report, "eqaa/fmask").fetches, pixels);
  }
  EXPECT_EQ(TrafficOf(box, "eqaa/fragments").fetches, namedFragments);
  EXPECT_EQ(TrafficOf(fetch, "eqaa/fragments").fetches, pixels * 8);
  EXPECT_LT(namedFragments, pixels * 8);
}

}  // namespace
}  // namespace sim
