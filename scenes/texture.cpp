// Texture decoding (see texture.h). Every encoded value maps through a lookup table built once
// per image, so a 16-bit texture costs 65,536 curve evaluations rather than one per texel.

#include "scenes/texture.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

namespace scenes {

float SrgbToLinear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

namespace {

// Value of every possible code (2^bits of them) under the given encoding.
std::vector<float> DecodeTable(int bitsPerChannel, ColourEncoding encoding) {
  const std::size_t codes = std::size_t{1} << bitsPerChannel;
  const auto maxCode = static_cast<float>(codes - 1);
  std::vector<float> table(codes);
  for (std::size_t code = 0; code < codes; ++code) {
    const float value = static_cast<float>(code) / maxCode;
    table[code] = encoding == ColourEncoding::Srgb ? SrgbToLinear(value) : value;
  }
  return table;
}

constexpr std::array<std::uint8_t, 8> kPngSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
constexpr std::array<std::uint8_t, 3> kJpegSignature = {0xFF, 0xD8, 0xFF};

bool StartsWith(std::span<const std::uint8_t> bytes, std::span<const std::uint8_t> prefix) {
  return bytes.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), bytes.begin());
}

// stb_image takes the length as an int.
int EncodedLength(std::span<const std::uint8_t> encoded, const std::string& name) {
  if (encoded.size() > static_cast<std::size_t>(INT_MAX)) {
    throw SceneError(name + ": " + std::to_string(encoded.size()) +
                     " bytes of image data is more than stb_image reads");
  }
  return static_cast<int>(encoded.size());
}

// stb_image grows its IDAT buffer to whatever length a chunk header declares before it reads
// the chunk, so a 74-byte PNG could make it allocate hundreds of MiB (found by fuzz/image).
// Every chunk must fit in the bytes that are really there.
void CheckPngChunkLengths(std::span<const std::uint8_t> encoded, const std::string& name) {
  constexpr std::size_t kChunkOverhead = 12;  // length, type, CRC
  std::size_t offset = kPngSignature.size();
  while (encoded.size() - offset >= kChunkOverhead) {
    const std::uint32_t length = std::uint32_t{encoded[offset]} << 24 | std::uint32_t{encoded[offset + 1]} << 16 |
                                 std::uint32_t{encoded[offset + 2]} << 8 | std::uint32_t{encoded[offset + 3]};
    const std::size_t left = encoded.size() - offset - kChunkOverhead;
    if (length > left) {
      throw SceneError(name + ": cannot decode: PNG chunk at byte " + std::to_string(offset) + " declares " +
                       std::to_string(length) + " bytes, more than the " + std::to_string(left) +
                       " the file holds after it");
    }
    const bool end = std::equal(encoded.begin() + static_cast<std::ptrdiff_t>(offset + 4),
                                encoded.begin() + static_cast<std::ptrdiff_t>(offset + 8), "IEND");
    if (end) return;
    offset += kChunkOverhead + length;
  }
}

std::string FailureReason() {
  const char* reason = stbi_failure_reason();
  return reason == nullptr ? "unknown reason" : reason;
}

struct StbFree {
  void operator()(void* pixels) const { stbi_image_free(pixels); }
};

}  // namespace

ImageFormat SniffImageFormat(std::span<const std::uint8_t> encoded) {
  if (StartsWith(encoded, kPngSignature)) return ImageFormat::Png;
  if (StartsWith(encoded, kJpegSignature)) return ImageFormat::Jpeg;
  return ImageFormat::Other;
}

ImageSize ReadImageSize(std::span<const std::uint8_t> encoded, const std::string& name) {
  if (SniffImageFormat(encoded) == ImageFormat::Other) {
    throw SceneError(name + ": cannot decode: no PNG or JPEG signature");
  }
  ImageSize size;
  int channels = 0;
  if (stbi_info_from_memory(encoded.data(), EncodedLength(encoded, name), &size.width,
                            &size.height, &channels) == 0) {
    throw SceneError(name + ": cannot decode: " + FailureReason());
  }
  const std::string dimensions = std::to_string(size.width) + "x" + std::to_string(size.height);
  if (size.width <= 0 || size.height <= 0) {
    throw SceneError(name + ": image size " + dimensions + " is empty");
  }
  if (size.width > kMaxImageSide || size.height > kMaxImageSide) {
    throw SceneError(name + ": image size " + dimensions + " exceeds " +
                     std::to_string(kMaxImageSide) + " texels on a side, the most aasim decodes");
  }
  const std::size_t texels =
      static_cast<std::size_t>(size.width) * static_cast<std::size_t>(size.height);
  if (texels > kMaxImageTexels) {
    throw SceneError(name + ": image size " + dimensions + " is " + std::to_string(texels) +
                     " texels, more than the " + std::to_string(kMaxImageTexels) +
                     " aasim decodes");
  }
  // EncodedLength bounded the size by INT_MAX above, so the product cannot overflow.
  if (SniffImageFormat(encoded) == ImageFormat::Jpeg && texels > kMaxJpegTexelsPerByte * encoded.size()) {
    throw SceneError(name + ": JPEG image size " + dimensions + " is " + std::to_string(texels) + " texels in " +
                     std::to_string(encoded.size()) + " bytes, more than the " +
                     std::to_string(kMaxJpegTexelsPerByte) +
                     " texels per byte any JPEG holds (each 8x8 block costs at least one bit): truncated or hostile");
  }
  return size;
}

Texture DecodeImage(std::span<const std::uint8_t> encoded, std::string name,
                    ColourEncoding encoding) {
  const ImageSize size = ReadImageSize(encoded, name);
  if (SniffImageFormat(encoded) == ImageFormat::Png) CheckPngChunkLengths(encoded, name);
  const int length = EncodedLength(encoded, name);
  const bool wide = stbi_is_16_bit_from_memory(encoded.data(), length) != 0;
  int width = 0;
  int height = 0;
  int channels = 0;
  const std::unique_ptr<void, StbFree> pixels(
      wide ? static_cast<void*>(stbi_load_16_from_memory(encoded.data(), length, &width, &height,
                                                         &channels, 0))
           : static_cast<void*>(
                 stbi_load_from_memory(encoded.data(), length, &width, &height, &channels, 0)));
  if (pixels == nullptr) throw SceneError(name + ": cannot decode: " + FailureReason());
  if (width != size.width || height != size.height || channels < 1 || channels > 4) {
    throw SceneError(name + ": decoded to " + std::to_string(width) + "x" +
                     std::to_string(height) + "x" + std::to_string(channels) +
                     ", which its header did not announce");
  }
  const std::size_t bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                            static_cast<std::size_t>(channels) * (wide ? 2u : 1u);
  return DecodeTexels(std::move(name), width, height, channels, wide ? 16 : 8,
                      {static_cast<const unsigned char*>(pixels.get()), bytes}, encoding);
}

Texture DecodeTexels(std::string name, int width, int height, int channels, int bitsPerChannel,
                     std::span<const unsigned char> bytes, ColourEncoding encoding) {
  if (width <= 0 || height <= 0) {
    throw SceneError(name + ": image size " + std::to_string(width) + "x" +
                     std::to_string(height) + " is empty");
  }
  if (channels < 1 || channels > 4) {
    throw SceneError(name + ": " + std::to_string(channels) +
                     " channels per texel; aasim reads 1 to 4");
  }
  if (bitsPerChannel != 8 && bitsPerChannel != 16) {
    throw SceneError(name + ": " + std::to_string(bitsPerChannel) +
                     " bits per channel; aasim reads 8 or 16");
  }
  const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::size_t valueSize = bitsPerChannel == 8 ? 1 : 2;
  const std::size_t expected = texels * static_cast<std::size_t>(channels) * valueSize;
  if (bytes.size() != expected) {
    throw SceneError(name + ": " + std::to_string(bytes.size()) + " bytes of texels, expected " +
                     std::to_string(expected) + " for " + std::to_string(width) + "x" +
                     std::to_string(height) + "x" + std::to_string(channels) + " at " +
                     std::to_string(bitsPerChannel) + " bits");
  }
  const std::vector<float> colourTable = DecodeTable(bitsPerChannel, encoding);
  const std::vector<float> alphaTable = DecodeTable(bitsPerChannel, ColourEncoding::Linear);
  const auto code = [&](std::size_t value) -> std::size_t {
    if (valueSize == 1) return bytes[value];
    std::uint16_t wide = 0;
    std::memcpy(&wide, bytes.data() + 2 * value, sizeof(wide));
    return wide;
  };
  Texture texture;
  texture.name = std::move(name);
  texture.width = width;
  texture.height = height;
  texture.texels.resize(texels);
  const auto perTexel = static_cast<std::size_t>(channels);
  const bool hasAlpha = channels == 2 || channels == 4;
  const std::size_t colourChannels = hasAlpha ? perTexel - 1 : perTexel;
  for (std::size_t t = 0; t < texels; ++t) {
    const std::size_t first = t * perTexel;
    glm::vec4& texel = texture.texels[t];
    if (colourChannels == 1) {
      texel = glm::vec4(glm::vec3(colourTable[code(first)]), 1.0f);
    } else {
      texel = glm::vec4(colourTable[code(first)], colourTable[code(first + 1)],
                        colourTable[code(first + 2)], 1.0f);
    }
    if (hasAlpha) texel.a = alphaTable[code(first + colourChannels)];
  }
  return texture;
}

}  // namespace scenes
