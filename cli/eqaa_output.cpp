// EQAA surface outputs of `aasim raster` (see eqaa_output.h).

#include "cli/eqaa_output.h"

#include <algorithm>
#include <array>
#include <string>

#include <oneapi/tbb/parallel_for.h>

#include "cli/image_io.h"
#include "cli/ownership.h"

namespace cli {
namespace {

// fmask.png: linear brightness kFloor + (1 - kFloor) * unknown / S, so a fully known pixel is
// still dark grey and its tint readable, and one with every sample UNKNOWN is full brightness.
constexpr float kFloor = 0.25f;
// Tint by fragment count, indexed by min(count, 4): 0 or 1 neutral, 2 blue, 3 green, 4+ red.
constexpr std::array<std::array<float, 3>, 5> kFragmentTints{{
    {1.0f, 1.0f, 1.0f},
    {1.0f, 1.0f, 1.0f},
    {0.35f, 0.55f, 1.0f},
    {0.35f, 1.0f, 0.35f},
    {1.0f, 0.35f, 0.35f},
}};

}  // namespace

fmask::Colour PrimitiveColour(std::uint32_t primitiveId) {
  // Hue in 6 * 256 integer steps around the colour wheel at full saturation and value: one
  // channel is 1, one 0, and the third ramps within the hue sector.
  const std::uint32_t hue = PrimitiveHash(primitiveId) % (6u * 256u);
  const float ramp = static_cast<float>(hue % 256u) / 255.0f;
  const float rising = ramp, falling = 1.0f - ramp;
  switch (hue / 256u) {
    case 0: return {1.0f, rising, 0.0f, 1.0f};
    case 1: return {falling, 1.0f, 0.0f, 1.0f};
    case 2: return {0.0f, 1.0f, rising, 1.0f};
    case 3: return {0.0f, falling, 1.0f, 1.0f};
    case 4: return {rising, 0.0f, 1.0f, 1.0f};
    default: return {1.0f, 0.0f, falling, 1.0f};
  }
}

EqaaPlanes ReadEqaaPlanes(const fmask::EqaaSurface& surface) {
  const int width = surface.Width(), samples = surface.Config().coverageSamples;
  const std::size_t pixels = static_cast<std::size_t>(width) * surface.Height();
  EqaaPlanes planes{.width = width,
                    .height = surface.Height(),
                    .samples = samples,
                    .red = std::vector<float>(pixels),
                    .green = std::vector<float>(pixels),
                    .blue = std::vector<float>(pixels),
                    .alpha = std::vector<float>(pixels),
                    .codes = std::vector<std::vector<float>>(samples, std::vector<float>(pixels)),
                    .fragments = std::vector<float>(pixels),
                    .unknown = std::vector<float>(pixels)};
  const fmask::FmaskLayout& layout = surface.Layout();
  tbb::parallel_for(0, surface.Height(), [&](int y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
      const fmask::Colour resolved = surface.BoxResolve(x, y);
      planes.red[pixel] = resolved.r;
      planes.green[pixel] = resolved.g;
      planes.blue[pixel] = resolved.b;
      planes.alpha[pixel] = resolved.a;
      const fmask::FmaskElement element = surface.Fmask(x, y);
      for (int s = 0; s < samples; ++s) {
        planes.codes[s][pixel] = static_cast<float>(layout.Code(element, s));
      }
      planes.fragments[pixel] = static_cast<float>(surface.FragmentCount(x, y));
      planes.unknown[pixel] = static_cast<float>(surface.UnknownSamples(x, y));
    }
  });
  return planes;
}

void WriteEqaaExr(const std::filesystem::path& path, const EqaaPlanes& planes) {
  std::vector<ExrChannel> channels{
      {"R", planes.red}, {"G", planes.green}, {"B", planes.blue}, {"A", planes.alpha}};
  for (std::size_t s = 0; s < planes.codes.size(); ++s) {
    channels.push_back({"fmask.s" + std::to_string(s), planes.codes[s]});
  }
  channels.push_back({"fragments", planes.fragments});
  channels.push_back({"unknown", planes.unknown});
  WriteExr(path, planes.width, planes.height, channels);
}

std::vector<std::uint8_t> ResolveImage(const EqaaPlanes& planes) {
  std::vector<std::uint8_t> image(planes.red.size() * 3);
  for (std::size_t pixel = 0; pixel < planes.red.size(); ++pixel) {
    image[pixel * 3 + 0] = EncodeSrgb8(planes.red[pixel]);
    image[pixel * 3 + 1] = EncodeSrgb8(planes.green[pixel]);
    image[pixel * 3 + 2] = EncodeSrgb8(planes.blue[pixel]);
  }
  return image;
}

std::vector<std::uint8_t> FmaskImage(const EqaaPlanes& planes) {
  std::vector<std::uint8_t> image(planes.unknown.size() * 3);
  const float samples = static_cast<float>(planes.samples);
  for (std::size_t pixel = 0; pixel < planes.unknown.size(); ++pixel) {
    const float level = kFloor + (1.0f - kFloor) * planes.unknown[pixel] / samples;
    const std::size_t tint =
        std::min(static_cast<std::size_t>(planes.fragments[pixel]), kFragmentTints.size() - 1);
    for (int channel = 0; channel < 3; ++channel) {
      image[pixel * 3 + channel] = EncodeSrgb8(level * kFragmentTints[tint][channel]);
    }
  }
  return image;
}

}  // namespace cli
