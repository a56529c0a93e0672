// Frame images shared by `aasim frame` and `aasim run` (see frame_output.h).

#include "cli/frame_output.h"

#include <glm/vec2.hpp>

#include "cli/image_io.h"
#include "sim/formats.h"

namespace cli {
namespace {

template <typename T, typename Component>
std::vector<float> Plane(const sim::Texture2D<T>& texture, Component&& component) {
  std::vector<float> plane;
  plane.reserve(texture.Texels().size());
  for (const T& texel : texture.Texels()) plane.push_back(component(texel));
  return plane;
}

}  // namespace

std::vector<std::uint8_t> SrgbImage(std::span<const glm::vec4> texels) {
  std::vector<std::uint8_t> pixels;
  pixels.reserve(texels.size() * 3);
  for (const glm::vec4& texel : texels) {
    pixels.push_back(EncodeSrgb8(texel.r));
    pixels.push_back(EncodeSrgb8(texel.g));
    pixels.push_back(EncodeSrgb8(texel.b));
  }
  return pixels;
}

std::vector<std::uint8_t> SrgbAlphaImage(std::span<const glm::vec4> texels) {
  std::vector<std::uint8_t> pixels;
  pixels.reserve(texels.size() * 4);
  for (const glm::vec4& texel : texels) {
    pixels.insert(pixels.end(), {EncodeSrgb8(texel.r), EncodeSrgb8(texel.g), EncodeSrgb8(texel.b),
                                 sim::FloatToUnorm8(texel.a)});
  }
  return pixels;
}

std::vector<std::uint8_t> MaskImage(std::span<const float> mask) {
  std::vector<std::uint8_t> pixels;
  pixels.reserve(mask.size());
  for (const float value : mask) pixels.push_back(EncodeSrgb8(value));
  return pixels;
}

LayerPng LayerPngImage(const passes::PassLayer& layer) {
  const std::size_t channels = layer.channels.size();
  LayerPng png{.channels = channels == 2 ? 3 : static_cast<int>(channels), .pixels = {}};
  png.pixels.reserve(layer.Size() / channels * static_cast<std::size_t>(png.channels));
  for (std::size_t at = 0; at < layer.Size(); at += channels) {
    for (int c = 0; c < png.channels; ++c) {
      png.pixels.push_back(static_cast<std::size_t>(c) < channels
                               ? sim::FloatToUnorm8(layer.Value(at + static_cast<std::size_t>(c)))
                               : 0);
    }
  }
  return png;
}

void WriteLayerPng(const std::filesystem::path& path, const passes::PassLayer& layer) {
  const LayerPng png = LayerPngImage(layer);
  WritePng(path, layer.width, layer.height, png.channels, png.pixels);
}

void WriteLayerExr(const std::filesystem::path& path, const passes::PassLayer& layer) {
  const std::size_t channels = layer.channels.size();
  std::vector<std::vector<float>> planes(channels);
  for (std::size_t c = 0; c < channels; ++c) {
    planes[c].reserve(layer.Size() / channels);
    for (std::size_t at = c; at < layer.Size(); at += channels) planes[c].push_back(layer.Value(at));
  }
  std::vector<ExrChannel> exrChannels;
  for (std::size_t c = 0; c < channels; ++c) exrChannels.push_back({layer.channels[c], planes[c]});
  WriteExr(path, layer.width, layer.height, exrChannels);
}

void WriteFrameExr(const std::filesystem::path& path, const sim::FramePipeline& pipeline) {
  const sim::Texture2D<glm::vec4>& colour = pipeline.Colour();
  const sim::Texture2D<glm::vec4>& normal = pipeline.Normal();
  const sim::Texture2D<glm::vec2>& velocity = pipeline.Velocity();
  const std::vector<float> r = Plane(colour, [](const glm::vec4& c) { return c.r; });
  const std::vector<float> g = Plane(colour, [](const glm::vec4& c) { return c.g; });
  const std::vector<float> b = Plane(colour, [](const glm::vec4& c) { return c.b; });
  const std::vector<float> nx = Plane(normal, [](const glm::vec4& n) { return n.x; });
  const std::vector<float> ny = Plane(normal, [](const glm::vec4& n) { return n.y; });
  const std::vector<float> nz = Plane(normal, [](const glm::vec4& n) { return n.z; });
  // Ids up to 2^24 are exact in a float; the background's kNoObject would round, so it is -1.
  const std::vector<float> objectId = Plane(pipeline.ObjectId(), [](std::uint32_t id) {
    return id == sim::kNoObject ? -1.0f : static_cast<float>(id);
  });
  const std::vector<float> vx = Plane(velocity, [](const glm::vec2& v) { return v.x; });
  const std::vector<float> vy = Plane(velocity, [](const glm::vec2& v) { return v.y; });
  const ExrChannel channels[] = {
      {"R", r},           {"G", g},
      {"B", b},           {"depth", pipeline.Depth().Texels()},
      {"normal.X", nx},   {"normal.Y", ny},
      {"normal.Z", nz},   {"objectId", objectId},
      {"velocity.X", vx}, {"velocity.Y", vy},
  };
  WriteExr(path, colour.Width(), colour.Height(), channels);
}

}  // namespace cli
